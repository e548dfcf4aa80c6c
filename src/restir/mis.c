/* restir/mis.c: resampling MIS weights for GRIS: 1/M, balance (004 Eq. 9), pairwise (004 Eq. 11).
 * Must never depend on a ray tracer, files, the renderer or anything else in src/. */
#include <string.h>

#include "restir/mis.h"

int restir_mis_parse(const char *name, enum restir_mis *out)
{
    if (!name || !out)
        return -1;
    if (strcmp(name, "1/M") == 0 || strcmp(name, "uniform") == 0) {
        *out = RESTIR_MIS_UNIFORM;
        return 0;
    }
    if (strcmp(name, "balance") == 0) {
        *out = RESTIR_MIS_BALANCE;
        return 0;
    }
    if (strcmp(name, "pairwise") == 0) {
        *out = RESTIR_MIS_PAIRWISE;
        return 0;
    }
    return -1;
}

const char *restir_mis_name(enum restir_mis mode)
{
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        return "1/M";
    case RESTIR_MIS_BALANCE:
        return "balance";
    case RESTIR_MIS_PAIRWISE:
        return "pairwise";
    }
    return "unknown";
}

int restir_mis_needs(enum restir_mis mode, int k, int j)
{
    if (k < 0 || j < 0)
        return 0;
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        return 0; /* confidences only */
    case RESTIR_MIS_BALANCE:
        return 1; /* 004 Eq. 9: every p_hat_{<-k}(Y_j), O(M^2) */
    case RESTIR_MIS_PAIRWISE:
        /* 004 Eq. 11a reads (j,j) and (0,j); Eq. 11b reads (0,0) and (j,0): O(M) */
        return k == j || k == 0 || j == 0;
    }
    return 0;
}

/* "1/M" weights m_j = c_j / sum_k c_k. BIASED in general: Eq. 8 needs the weights of the domains
 * that can produce y to sum to one, but constant weights also hand mass to domains that cannot
 * produce y (shift failed, or their target is zero at T_k^{-1}(y)); that mass is simply lost,
 * so the estimate is darkened wherever some domain cannot reach y. */
static void weights_uniform(int n, const float *c, float *m)
{
    double total = 0.0;
    for (int k = 0; k < n; k++)
        total += c[k];
    for (int j = 0; j < n; j++)
        m[j] = total > 0.0 ? (float)(c[j] / total) : 1.0f / (float)n;
}

/* 004 Eq. 9, generalized balance heuristic at Y_j:
 * m_j(Y_j) = c_j p_hat_{<-j}(Y_j) / sum_k c_k p_hat_{<-k}(Y_j).
 * A zero denominator means no domain can produce Y_j (it lies outside every p_hat_{<-k} support,
 * in particular outside supp p_hat), so its weight is irrelevant to Eq. 6 and is set to 0.
 * Wherever some c_k p_hat_{<-k}(y) > 0 the weights are an exact partition of unity (Eq. 8). */
static void weights_balance(int n, const float *c, const float *p, float *m)
{
    for (int j = 0; j < n; j++) {
        double denom = 0.0;
        for (int k = 0; k < n; k++)
            denom += (double)c[k] * (double)p[k * n + j];
        double num = (double)c[j] * (double)p[j * n + j];
        m[j] = denom > 0.0 ? (float)(num / denom) : 0.0f;
    }
}

/* 004 Eq. 11a/11b/12, defensive generalized pairwise MIS, domain 0 canonical.
 * Zero denominators: the pair denominator c_S p_hat_{<-j}(y) + c_0 p_hat(y) is zero only where
 * both targets vanish (given c_0 > 0); such a term contributes 0. This never happens where
 * p_hat(y) = p_hat_{<-0}(y) > 0, so there the weights are an exact partition of unity. The
 * canonical's pair terms c_0 p_hat(Y_0) / (...) are 0 when p_hat(Y_0) = 0 (0/0 included) and its
 * defensive share c_0 / (c_S + c_0) is kept, i.e. Eq. 11b is evaluated literally. Outside
 * supp p_hat no choice makes pairwise weights sum to one, and none is needed: Eq. 8 is only
 * required on supp p_hat, and a sample with p_hat(Y) = 0 has resampling weight 0 in Eq. 6.
 * Degenerate confidences (c_S + c_0 <= 0) give everything to the canonical. Partition of unity
 * needs c_0 > 0 (the canonical is the defensive fallback). */
static void weights_pairwise(int n, const float *c, const float *p, float *m)
{
    double c0 = c[0];
    double cs = 0.0; /* 004 Eq. 12: c_Sigma, the sum of non-canonical confidences */
    for (int k = 1; k < n; k++)
        cs += c[k];
    double ctot = cs + c0;
    if (!(ctot > 0.0)) {
        m[0] = 1.0f;
        for (int j = 1; j < n; j++)
            m[j] = 0.0f;
        return;
    }
    double p00 = p[0]; /* p_hat(Y_0) */
    double m0 = c0 / ctot; /* 004 Eq. 11b: defensive share of the canonical */
    for (int j = 1; j < n; j++) {
        double cj = c[j];
        /* 004 Eq. 11a:
         * (c_S / (c_S + c_0)) c_j p_hat_{<-j}(Y_j) / (c_S p_hat_{<-j}(Y_j) + c_0 p_hat(Y_j)) */
        double pjj = p[j * n + j];
        double p0j = p[0 * n + j];
        double dj = cs * pjj + c0 * p0j;
        m[j] = dj > 0.0 ? (float)((cs / ctot) * cj * pjj / dj) : 0.0f;
        /* 004 Eq. 11b:
         * (c_j / (c_S + c_0)) c_0 p_hat(Y_0) / (c_S p_hat_{<-j}(Y_0) + c_0 p_hat(Y_0)) */
        double pj0 = p[j * n + 0];
        double d0 = cs * pj0 + c0 * p00;
        if (d0 > 0.0)
            m0 += (cj / ctot) * c0 * p00 / d0;
    }
    m[0] = (float)m0;
}

void restir_mis_weights(enum restir_mis mode, int n, const float *c, const float *p, float *m)
{
    if (n <= 0)
        return;
    if (n == 1) {
        m[0] = 1.0f; /* only the canonical: it alone covers p_hat (004 Sec. 2.3.3) */
        return;
    }
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        weights_uniform(n, c, m);
        return;
    case RESTIR_MIS_BALANCE:
        weights_balance(n, c, p, m);
        return;
    case RESTIR_MIS_PAIRWISE:
        weights_pairwise(n, c, p, m);
        return;
    }
    weights_uniform(n, c, m);
}
