/* restir/spmis.h: stochastic pairwise MIS (004 Sec. 3-4): the stochastic resampling MIS weights
 * of Eq. 15-16 and 18-19, the non-canonical confidence adjustment N / M (Sec. 4.3), and the
 * draws of Algorithm 2 (N_c uniform picks for the canonical weight, N picks by Eq. 17 for the
 * neighbors) from one reuse cell. The sample type stays the caller's: it shifts, evaluates
 * targets and offers w~ to a reservoir; these functions supply the weights.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_SPMIS_H
#define RESTIR_SPMIS_H

#include "restir/cells.h"

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
 * than deterministic pairwise does. Returns 1 for m <= 0. */
float restir_spmis_confidence_scale(int n_candidates, int m, int adjust);

/* Fills k: c_sigma = scale * c_sigma_raw (the unscaled Eq. 12 sum). */
void restir_spmis_conf_set(struct restir_spmis_conf *k, float c_c, float c_sigma_raw, float scale);

/* 004 Eq. 11a, deterministic defensive pairwise weight of non-canonical domain i at its shifted
 * sample y = T_i(X_i): (c_S / (c_S + c_c)) c_i p_from / (c_S p_from + c_c p_c), with c_i the
 * unscaled confidence (scaled inside), p_from = p_hat_{<-i}(y) (Eq. 10) and p_c = p_hat(y), the
 * canonical target. 0 where the denominator vanishes. */
double restir_spmis_pairwise(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c);

/* 004 Eq. 16 for one draw with replacement: m_i^pw(y) / (N P(i)), i.e. Eq. 15 with the
 * multiplicity K(i) accounted for by offering each of the N draws as its own candidate
 * (Algorithm 2 lines 13-18). `factor` is 1 / (N P(i)) from restir_spmis_draws (1 for an
 * enumerated, deterministic merge). */
double restir_spmis_noncanonical(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                 double factor);

/* 004 Eq. 18, first term: the canonical's defensive share c_c / (c_S + c_c) (1 when both are 0). */
double restir_spmis_canonical_share(const struct restir_spmis_conf *k);

/* 004 Eq. 19 times the draw's factor 1 / (N_c P_c(i)): one term of the sum in Eq. 18,
 * factor * (c_i / (c_S + c_c)) c_c p_c / (c_S p_from + c_c p_c), where p_c = p_hat(Y_c) and
 * p_from = p_hat_{<-i}(Y_c), the canonical sample shifted into domain i (Eq. 10). c_i unscaled. */
double restir_spmis_canonical_term(const struct restir_spmis_conf *k, float c_i, float p_from, float p_c,
                                   double factor);

/* Most draws one merge makes (enumerating a whole cell of at most RESTIR_CELL_MAX_TILE^2 pixels). */
#define RESTIR_SPMIS_MAX_DRAWS (RESTIR_CELL_MAX_TILE * RESTIR_CELL_MAX_TILE)

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
 * u[0..n_c); n_c = 0 enumerates all M pixels with factor 1 (the exact Eq. 11b sum, 004 Fig. 6d).
 * No draw when M = 0. */
void restir_spmis_canonical_draws(const struct restir_cells *cells, int cell, int canonical, int n_c,
                                  enum restir_spmis_pick pick, const float *u, struct restir_spmis_draws *out);

/* Neighbor draws (004 Eq. 15-17, Algorithm 2 lines 13-14): n picks with replacement among the
 * contributing pixels of `cell` other than `canonical`, with P(i) = weight_i / sum (the weights
 * given to restir_cells_build, c_i p_hat(X_i) W_i for Eq. 17), factor = 1 / (n P(i)), using
 * u[0..n); n = 0 enumerates every contributing pixel once with factor 1 (deterministic pairwise
 * over the whole cell, 004 Fig. 7d: non-contributing pixels have w_i = 0 and are skipped
 * exactly). No draw when no other pixel contributes. */
void restir_spmis_neighbor_draws(const struct restir_cells *cells, int cell, int canonical, int n, const float *u,
                                 struct restir_spmis_draws *out);

#ifdef __cplusplus
}
#endif

#endif
