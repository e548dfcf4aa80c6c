/* restir/spmis.h: stochastic pairwise MIS (004 Sec. 3-4): the stochastic resampling MIS weights
 * of Eq. 15-16 and 18-19, the non-canonical confidence adjustment N / M (Sec. 4.3), and the
 * draws of Algorithm 2 (N_c uniform picks for the canonical weight, N picks by Eq. 17 for the
 * neighbors) from one reuse cell. The sample type stays the caller's: it shifts, evaluates
 * targets and offers w~ to a reservoir; these functions supply the weights.
 * Threads: every function is thread-safe on distinct outputs (the draws only read the cells); the
 * RESTIR_HD weight functions are per-sample code for C, C++ and CUDA device code (restir/hd.h).
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_SPMIS_H
#define RESTIR_SPMIS_H

#include "restir/cells.h"
#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The confidences of one stochastic pairwise merge into canonical pixel c from the M other pixels
 * of a reuse cell. Every non-canonical confidence c_i is multiplied by `scale`, c_sigma included,
 * in every formula below, so the deterministic weights they estimate stay a partition of unity
 * (004 Eq. 8) whatever the scale. */
struct restir_spmis_conf {
    float c_c;     /* canonical confidence */
    float c_sigma; /* 004 Eq. 12 after scaling: scale * sum of the M non-canonical c_i */
    float scale;   /* N / M with the adjustment, else 1 */
};

/* 004 Sec. 4.3: the factor N / M on non-canonical confidences when `adjust` is set, else 1. We cap
 * it at 1 (N >= M gives 1): the paper's aim is c_sigma proportional to N while "degrading to
 * deterministic pairwise MIS as N approaches M", and a factor above 1 would weight neighbors more
 * than deterministic pairwise does. Returns 1 for m <= 0 or n_candidates <= 0. */
RESTIR_HD float restir_spmis_confidence_scale(int n_candidates, int m, int adjust)
{
    if (!adjust || m <= 0 || n_candidates <= 0 || n_candidates >= m)
        return 1.0f;
    return (float)n_candidates / (float)m;
}

/* Fills k: c_c, scale, and c_sigma = scale * c_sigma_raw (the unscaled Eq. 12 sum). Negative, NaN
 * or infinite arguments are read as 0; a NULL k is ignored. */
RESTIR_HD void restir_spmis_conf_set(struct restir_spmis_conf *k, float c_c, float c_sigma_raw, float scale)
{
    if (!k)
        return;
    k->c_c = restir_hd_weight(c_c);
    k->scale = restir_hd_weight(scale);
    k->c_sigma = k->scale * restir_hd_weight(c_sigma_raw);
}

/* What Eq. 11a and Eq. 19 share for domain i: the targets and the scaled c_i (bad values read as 0),
 * c_S + c_c and the pair denominator c_S p_from + c_c p_c. Returns 0 when k is NULL or either sum
 * is not positive (the weight is then 0). */
struct restir_spmis_pair {
    double pf, pc, ci, ctot, d;
};

RESTIR_HD int restir_spmis_pair_terms(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                      struct restir_spmis_pair *t)
{
    if (!k || !t)
        return 0;
    t->pf = restir_hd_weight(p_from);
    t->pc = restir_hd_weight(p_c);
    t->ci = (double)k->scale * restir_hd_weight(c_i); /* c_i and c_sigma scaled alike */
    t->ctot = (double)k->c_sigma + (double)k->c_c;
    t->d = (double)k->c_sigma * t->pf + (double)k->c_c * t->pc;
    return t->ctot > 0.0 && t->d > 0.0;
}

/* 004 Eq. 11a, deterministic defensive pairwise weight of non-canonical domain i at its shifted
 * sample y = T_i(X_i): (c_S / (c_S + c_c)) c_i p_from / (c_S p_from + c_c p_c), with c_i the
 * unscaled confidence (scaled inside), p_from = p_hat_{<-i}(y) (Eq. 10) and p_c = p_hat(y), the
 * canonical target. 0 where a denominator vanishes or k is NULL; negative, NaN or infinite c_i,
 * p_from, p_c are read as 0. */
RESTIR_HD double restir_spmis_pairwise(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c)
{
    struct restir_spmis_pair t;
    if (!restir_spmis_pair_terms(k, c_i, p_from, p_c, &t))
        return 0.0;
    return ((double)k->c_sigma / t.ctot) * t.ci * t.pf / t.d; /* 004 Eq. 11a */
}

/* 004 Eq. 16 for one draw with replacement: m_i^pw(y) / (N P(i)), i.e. Eq. 15 with the
 * multiplicity K(i) accounted for by offering each of the N draws as its own candidate
 * (Algorithm 2 lines 13-18). `factor` is 1 / (N P(i)) from restir_spmis_neighbor_draws (1 for an
 * enumerated, deterministic merge). Bad arguments as restir_spmis_pairwise. */
RESTIR_HD double restir_spmis_noncanonical(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                           double factor)
{
    return factor * restir_spmis_pairwise(k, c_i, p_from, p_c);
}

/* 004 Eq. 18, first term: the canonical's defensive share c_c / (c_S + c_c) (1 when both are 0 or k
 * is NULL). */
RESTIR_HD double restir_spmis_canonical_share(const struct restir_spmis_conf *k)
{
    if (!k)
        return 1.0;
    double ctot = (double)k->c_sigma + k->c_c;
    return ctot > 0.0 ? k->c_c / ctot : 1.0;
}

/* 004 Eq. 19 times the draw's factor 1 / (N_c P_c(i)): one term of the sum in Eq. 18,
 * factor * (c_i / (c_S + c_c)) c_c p_c / (c_S p_from + c_c p_c), where p_c = p_hat(Y_c) and
 * p_from = p_hat_{<-i}(Y_c), the canonical sample shifted into domain i (Eq. 10). c_i unscaled. Bad
 * arguments as restir_spmis_pairwise. */
RESTIR_HD double restir_spmis_canonical_term(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                             double factor)
{
    struct restir_spmis_pair t;
    if (!restir_spmis_pair_terms(k, c_i, p_from, p_c, &t))
        return 0.0;
    /* 004 Eq. 19, weighted by the Eq. 18 factor K(i) / (N_c P_c(i)) one draw at a time */
    return factor * (t.ci / t.ctot) * (double)k->c_c * t.pc / t.d;
}

/* Most draws one merge makes (enumerating a whole cell of at most RESTIR_CELLS_MAX_TILE^2 pixels). */
#define RESTIR_SPMIS_MAX_DRAWS (RESTIR_CELLS_MAX_TILE * RESTIR_CELLS_MAX_TILE)

/* The pixels one merge visits, with multiplicity (a pixel drawn twice appears twice), each with
 * the factor 1 / (N P(i)) of Eq. 15-16 and 18. */
struct restir_spmis_draws {
    int count;
    int pixel[RESTIR_SPMIS_MAX_DRAWS];
    double factor[RESTIR_SPMIS_MAX_DRAWS]; /* double: 1 / P can exceed the float range */
};

/* How the canonical draws pick pixels (004 Sec. 4.2). */
enum restir_spmis_pick {
    RESTIR_SPMIS_PICK_UNIFORM = 0, /* P_c(i) = 1 / M: the paper's choice */
    RESTIR_SPMIS_PICK_CONFIDENCE   /* P_c(i) = c_i / c_sigma: the "natural" alternative */
};

/* Canonical draws (004 Eq. 18, Algorithm 2 lines 8-10): n_c picks with replacement over the M
 * pixels of `cell` other than `canonical`, by `pick`, each with factor 1 / (n_c P_c(i)), using
 * u[0..n_c); n_c <= 0 enumerates all M pixels with factor 1 (the exact Eq. 11b sum, 004 Fig. 6d),
 * and u may then be NULL; n_c above RESTIR_SPMIS_MAX_DRAWS counts as that. No draw when M = 0
 * (cell -1 or any index that is not a cell, restir/cells.h), nor, for RESTIR_SPMIS_PICK_CONFIDENCE,
 * when the others' confidences sum to 0. Returns 0 (out->count draws), or -1 without writing for a
 * NULL cells or out, a NULL u with n_c > 0, or an unknown pick. */
int restir_spmis_canonical_draws(const struct restir_cells *cells, int cell, int canonical, int n_c,
                                 enum restir_spmis_pick pick, const float *u, struct restir_spmis_draws *out);

/* Neighbor draws (004 Eq. 15-17, Algorithm 2 lines 13-14): n picks with replacement among the
 * contributing pixels of `cell` other than `canonical`, with P(i) = weight_i / sum (the weights
 * given to restir_cells_build, c_i p_hat(X_i) W_i for Eq. 17; negative, NaN or infinite ones were
 * read as 0 there), factor = 1 / (n P(i)), using u[0..n); n <= 0 enumerates every contributing
 * pixel once with factor 1 (deterministic pairwise over the whole cell, 004 Fig. 7d:
 * non-contributing pixels have w_i = 0 and are skipped exactly), and u may then be NULL; n above
 * RESTIR_SPMIS_MAX_DRAWS counts as that. No draw when no other pixel contributes (or cell is not a
 * cell). Returns 0 (out->count draws), or -1 without writing for a NULL cells or out, or a NULL u
 * with n > 0. */
int restir_spmis_neighbor_draws(const struct restir_cells *cells, int cell, int canonical, int n, const float *u,
                                struct restir_spmis_draws *out);

#ifdef __cplusplus
}
#endif

#endif
