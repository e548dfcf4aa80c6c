/* restir/mis.h: resampling MIS weights for one GRIS merge (004 Sec. 2.4-2.7): 1/M, generalized
 * balance and defensive generalized pairwise. Pure functions of confidences and target values; the
 * RESTIR_HD ones are per-sample code for C, C++ and CUDA device code (restir/hd.h). Thread-safe.
 *
 * The target matrix. A merge of n reservoirs into canonical domain 0 has samples Y_j = T_j(X_j)
 * shifted into domain 0, and p[k * n + j] = p_hat_{<-k}(Y_j): the target of domain k at Y_j
 * shifted back into domain k, times the Jacobian of that back shift (004 Eq. 10; 0 where Y_j is
 * outside the image of T_k). Row 0 holds the canonical targets p_hat(Y_j). A mode reads only the
 * entries restir_mis_needs names: O(n) for pairwise, O(n^2) for balance, none for 1/M.
 * Confidences c[k] and targets that are negative, NaN or infinite are read as 0. */
#ifndef RESTIR_MIS_H
#define RESTIR_MIS_H

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

enum restir_mis {
    RESTIR_MIS_UNIFORM = 0, /* m_i = c_i / sum c: the "1/M" weights; BIASED when domains differ */
    RESTIR_MIS_BALANCE,     /* generalized balance heuristic, 004 Eq. 9 */
    RESTIR_MIS_PAIRWISE,    /* defensive generalized pairwise MIS, 004 Eq. 11-12 */
    RESTIR_MIS_PAIRWISE_TILED /* the same for non-canonical domains that tile the canonical one
                                 (restir_mis_weights_pairwise_tiled); BIASED where they overlap */
};

/* Parses "1/M" (or "uniform"), "balance", "pairwise" into *out. Returns 0, or -1 (out untouched)
 * for an unknown name or a NULL argument. */
int restir_mis_parse(const char *name, enum restir_mis *out);
/* The name restir_mis_parse reads for mode (a static string), "unknown" for a value outside the
 * enum. */
const char *restir_mis_name(enum restir_mis mode);

/* 1 when mode is one of enum restir_mis, else 0. */
RESTIR_HD int restir_mis_valid(enum restir_mis mode)
{
    return mode == RESTIR_MIS_UNIFORM || mode == RESTIR_MIS_BALANCE || mode == RESTIR_MIS_PAIRWISE ||
           mode == RESTIR_MIS_PAIRWISE_TILED;
}

/* 1 when `mode`'s MIS weights read p[k * n + j] = p_hat_{<-k}(Y_j), else 0 (also for negative k or
 * j). Row 0 (the canonical targets p_hat(Y_j)) is needed in every mode all the same: the resampling
 * weights m_j p_hat(Y_j) W_j J_j of restir/gris.h read it, 1/M included. */
RESTIR_HD int restir_mis_needs(enum restir_mis mode, int k, int j)
{
    if (k < 0 || j < 0)
        return 0;
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        return 0; /* confidences only */
    case RESTIR_MIS_BALANCE:
        return 1; /* 004 Eq. 9: every p_hat_{<-k}(Y_j) */
    case RESTIR_MIS_PAIRWISE:
    case RESTIR_MIS_PAIRWISE_TILED:
        /* 004 Eq. 11a reads (j,j) and (0,j); Eq. 11b reads (0,0) and (j,0) */
        return k == j || k == 0 || j == 0;
    }
    return 0;
}

/* The three modes' weights, which restir_mis_weights dispatches to: each writes m[0..n) and does
 * nothing for n < 1 or a NULL array.
 *
 * "1/M" weights m_j = c_j / sum_k c_k (1/n each when the sum is 0). BIASED in general: Eq. 8 needs
 * the weights of the domains that can produce y to sum to one, but constant weights also hand
 * mass to domains that cannot produce y (shift failed, or their target is zero at T_k^{-1}(y));
 * that mass is lost, darkening the estimate wherever some domain cannot reach y. */
RESTIR_HD void restir_mis_weights_uniform(int n, const float *c, float *m)
{
    if (n < 1 || !c || !m)
        return;
    double total = 0.0;
    for (int k = 0; k < n; k++)
        total += restir_hd_weight(c[k]);
    for (int j = 0; j < n; j++)
        m[j] = total > 0.0 ? (float)(restir_hd_weight(c[j]) / total) : 1.0f / (float)n;
}

/* 004 Eq. 9, the generalized balance heuristic at Y_j:
 * m_j(Y_j) = c_j p_hat_{<-j}(Y_j) / sum_k c_k p_hat_{<-k}(Y_j).
 * A zero denominator means no domain can produce Y_j (it lies outside every p_hat_{<-k} support,
 * in particular outside supp p_hat), so its weight is irrelevant to Eq. 6 and set to 0. Wherever
 * some c_k p_hat_{<-k}(y) > 0 the weights are an exact partition of unity (Eq. 8). */
RESTIR_HD void restir_mis_weights_balance(int n, const float *c, const float *p, float *m)
{
    if (n < 1 || !c || !p || !m)
        return;
    for (int j = 0; j < n; j++) {
        double denom = 0.0;
        for (int k = 0; k < n; k++)
            denom += (double)restir_hd_weight(c[k]) * (double)restir_hd_weight(p[k * n + j]);
        double num = (double)restir_hd_weight(c[j]) * (double)restir_hd_weight(p[j * n + j]);
        m[j] = denom > 0.0 ? (float)(num / denom) : 0.0f;
    }
}

/* 004 Eq. 11a/11b/12, defensive generalized pairwise MIS, domain 0 canonical.
 * The pair denominator c_S p_hat_{<-j}(y) + c_0 p_hat(y) is zero only where both targets vanish
 * (given c_0 > 0); such a term contributes 0. That never happens where p_hat(y) > 0, so there the
 * weights are an exact partition of unity. The canonical's pair terms c_0 p_hat(Y_0) / (...) are 0
 * when p_hat(Y_0) = 0 and its defensive share c_0 / (c_S + c_0) is kept (Eq. 11b literally).
 * Outside supp p_hat no weights sum to one and none need to: a sample with p_hat(Y) = 0 has
 * resampling weight 0 in Eq. 6. Partition of unity needs c_0 > 0, the canonical being the
 * defensive fallback; when c_S + c_0 = 0 everything goes to the canonical. */
RESTIR_HD void restir_mis_weights_pairwise(int n, const float *c, const float *p, float *m)
{
    if (n < 1 || !c || !p || !m)
        return;
    double c0 = restir_hd_weight(c[0]);
    double cs = 0.0; /* 004 Eq. 12: c_Sigma, the sum of non-canonical confidences */
    for (int k = 1; k < n; k++)
        cs += restir_hd_weight(c[k]);
    double ctot = cs + c0;
    if (!(ctot > 0.0)) {
        m[0] = 1.0f;
        for (int j = 1; j < n; j++)
            m[j] = 0.0f;
        return;
    }
    double p00 = restir_hd_weight(p[0]); /* p_hat(Y_0) */
    double m0 = c0 / ctot;               /* 004 Eq. 11b: defensive share of the canonical */
    for (int j = 1; j < n; j++) {
        double cj = restir_hd_weight(c[j]);
        /* 004 Eq. 11a:
         * (c_S / (c_S + c_0)) c_j p_hat_{<-j}(Y_j) / (c_S p_hat_{<-j}(Y_j) + c_0 p_hat(Y_j)) */
        double pjj = restir_hd_weight(p[j * n + j]);
        double p0j = restir_hd_weight(p[0 * n + j]);
        double dj = cs * pjj + c0 * p0j;
        m[j] = dj > 0.0 ? (float)((cs / ctot) * cj * pjj / dj) : 0.0f;
        /* 004 Eq. 11b:
         * (c_j / (c_S + c_0)) c_0 p_hat(Y_0) / (c_S p_hat_{<-j}(Y_0) + c_0 p_hat(Y_0)) */
        double pj0 = restir_hd_weight(p[j * n + 0]);
        double d0 = cs * pj0 + c0 * p00;
        if (d0 > 0.0)
            m0 += (cj / ctot) * c0 * p00 / d0;
    }
    m[0] = (float)m0;
}

/* Defensive pairwise MIS when the non-canonical domains 1..n-1 tile the canonical one: each reaches
 * a part of it disjoint from the others' (the previous pixels that a moved pixel overlaps, with
 * shifts that are undefined outside the pixel: temporal.subpixel=search). A sample y can then come
 * from the canonical and from at most one other domain r(y), and 004 Eq. 11 is applied to the two
 * domains {0, r(y)} with c_S = c_r:
 *   m_j(Y_j) = c_j / (c_0 + c_j) * c_j p_hat_{<-j}(Y_j) / (c_j p_hat_{<-j}(Y_j) + c_0 p_hat(Y_j)),
 *   m_0(Y_0) = c_0 / (c_0 + c_r) + c_r / (c_0 + c_r) * c_0 p_hat(Y_0) / (c_r p_hat_{<-r}(Y_0) + c_0 p_hat(Y_0)),
 * with r the first k >= 1 where p_hat_{<-k}(Y_0) > 0 (m_0 = 1 when there is none: nothing else
 * reaches Y_0). For each y the weights of the domains that can produce it, 0 and r(y), sum to one
 * wherever p_hat(y) > 0 (004 Eq. 8). Plain pairwise MIS is unbiased here too, but it divides the
 * non-canonical share among n - 1 domains of which only one reaches y; balance has no defensive
 * share, which measured heavier tails for grestir-pt's signed gradient targets. BIASED where the
 * domains overlap, which the caller must rule out. Reads the entries restir_mis_needs(PAIRWISE)
 * names; zero denominators as restir_mis_weights_pairwise. */
RESTIR_HD void restir_mis_weights_pairwise_tiled(int n, const float *c, const float *p, float *m)
{
    if (n < 1 || !c || !p || !m)
        return;
    const double c0 = restir_hd_weight(c[0]), p00 = restir_hd_weight(p[0]);
    int r = 0;
    for (int k = 1; k < n && !r; k++)
        if (restir_hd_weight(p[k * n]) > 0.0f)
            r = k;
    double m0 = 1.0;
    if (r) {
        const double cr = restir_hd_weight(c[r]), ct = c0 + cr, d0 = cr * restir_hd_weight(p[r * n]) + c0 * p00;
        m0 = ct > 0.0 ? c0 / ct + (d0 > 0.0 ? (cr / ct) * c0 * p00 / d0 : 0.0) : 1.0;
    }
    m[0] = (float)m0;
    for (int j = 1; j < n; j++) {
        const double cj = restir_hd_weight(c[j]), ct = c0 + cj, pjj = restir_hd_weight(p[j * n + j]);
        const double dj = cj * pjj + c0 * restir_hd_weight(p[j]);
        m[j] = ct > 0.0 && dj > 0.0 ? (float)((cj / ct) * cj * pjj / dj) : 0.0f;
    }
}

/* Resampling MIS weights m_j(Y_j), j = 0..n-1, of one merge whose domain 0 is canonical, from the
 * confidences c[0..n) and the target matrix p (may be NULL for RESTIR_MIS_UNIFORM). n = 1 gives
 * m_0 = 1. Returns 0, or -1 without writing for n < 1, a NULL array or an unknown mode. */
RESTIR_HD int restir_mis_weights(enum restir_mis mode, int n, const float *c, const float *p, float *m)
{
    if (n < 1 || !c || !m || (mode != RESTIR_MIS_UNIFORM && !p) || !restir_mis_valid(mode))
        return -1;
    if (n == 1) {
        m[0] = 1.0f; /* only the canonical: it alone covers p_hat (004 Sec. 2.3.3) */
        return 0;
    }
    switch (mode) {
    case RESTIR_MIS_UNIFORM:
        restir_mis_weights_uniform(n, c, m);
        return 0;
    case RESTIR_MIS_BALANCE:
        restir_mis_weights_balance(n, c, p, m);
        return 0;
    case RESTIR_MIS_PAIRWISE:
        restir_mis_weights_pairwise(n, c, p, m);
        return 0;
    case RESTIR_MIS_PAIRWISE_TILED:
        restir_mis_weights_pairwise_tiled(n, c, p, m);
        return 0;
    }
    return -1;
}

#ifdef __cplusplus
}
#endif

#endif
