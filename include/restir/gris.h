/* restir/gris.h: one GRIS merge (generalized resampled importance sampling, Lin et al. 2022),
 * independent of what a sample is. The caller shifts every input sample into the canonical domain
 * and fills the target matrix; these functions give the resampling weights, pick the output sample
 * and its unbiased contribution weight, and merge confidences.
 *
 * The recipe of a merge of reservoirs j = 0..n-1 into canonical domain 0, each holding sample X_j
 * with contribution weight W_j and confidence c_j:
 *   Y_j = T_j(X_j), J_j = |dT_j/dX_j|          shift into domain 0 (identity for j = 0: J_0 = 1)
 *   m_j = restir_mis_weights(...)              resampling MIS weights, restir/mis.h
 *   w_j = m_j p_hat(Y_j) W_j J_j               restir_gris_resampling_weight (004 Eq. 6)
 *   choose Y = Y_s with probability w_s / sum w  (restir/reservoir.h)
 *   W_Y = sum_j w_j / p_hat(Y)                 restir_gris_contribution_weight (004 Eq. 7)
 *   c_Y = min(sum_j c_j, cap)                  restir_gris_confidence_merge
 * restir_gris_resample does the middle four in one call once the targets are known, and
 * restir_gris_targets computes those targets through the caller's shift and target callbacks.
 * Papers by number (004, ...) are listed in docs/API.md.
 *
 * The RESTIR_HD functions are per-sample code for C, C++ and CUDA device code (restir/hd.h); all
 * functions here are thread-safe on distinct outputs and keep no state. */
#ifndef RESTIR_GRIS_H
#define RESTIR_GRIS_H

#include <stddef.h>

#include "restir/hd.h"
#include "restir/mis.h"
#include "restir/reservoir.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most samples one merge takes. */
#define RESTIR_GRIS_MAX_SAMPLES 64

/* 004 Eq. 6: the resampling weight w = m p_hat W J of a sample shifted into the canonical domain,
 * with m its resampling MIS weight, p_hat its canonical target, W its contribution weight in its
 * own domain and J > 0 the Jacobian of its shift (1 for the canonical sample). Returns 0 when
 * J <= 0 (no shift: the sample does not enter the merge) or the product is not finite and
 * positive (NaN, infinite or negative factors included). */
RESTIR_HD float restir_gris_resampling_weight(float m, float p_hat, float W, float J)
{
    if (!(J > 0.0f))
        return 0.0f;
    return restir_hd_weight(m * p_hat * W * J);
}

/* 004 Eq. 7: the unbiased contribution weight W_Y = sum_j w_j / p_hat(Y) of the sample r selected,
 * given p_hat(Y) (target_of_selected). Returns 0 when r is NULL or selected nothing, or when
 * p_hat(Y) is not finite and positive. With weights that sum to one (004 Eq. 8), classic RIS is
 * the special case m_j = 1/M. */
RESTIR_HD float restir_gris_contribution_weight(const struct restir_reservoir *r, float target_of_selected)
{
    if (!r || r->selected < 0 || !(target_of_selected > 0.0f) || !restir_hd_finite(target_of_selected))
        return 0.0f;
    return r->w_sum / target_of_selected;
}

/* 004 Sec. 2.5: the confidence of a merge's output, the sum of its inputs' confidences c_sum capped
 * at cap (cap <= 0: no cap), so that samples reused again and again do not dominate. A NaN or
 * negative c_sum gives 0. */
RESTIR_HD float restir_gris_confidence_merge(float c_sum, float cap)
{
    if (!(c_sum >= 0.0f))
        return 0.0f;
    if (cap > 0.0f && c_sum > cap)
        return cap;
    return c_sum;
}

/* Resamples n samples Y_j (1 <= n <= RESTIR_GRIS_MAX_SAMPLES) of one merge whose domain 0 is
 * canonical, as the recipe above: m_j = restir_mis_weights(mode, n, c, P), then
 * w_j = restir_gris_resampling_weight(m_j, P[j], W[j], J[j]), streamed through one reservoir with
 * u[j] in [0,1) deciding at sample j. P is the n x n target matrix of restir/mis.h (its row 0 holds
 * the canonical targets p_hat(Y_j)); J[j] <= 0 marks a sample that did not shift in or has none.
 * Returns the chosen index and writes its W_Y (004 Eq. 7) to *W_out; returns -1 with *W_out = 0
 * when no weight is positive, and -1 without writing when an array or W_out is NULL, n is out
 * of range or mode is not one of enum restir_mis. */
RESTIR_HD int restir_gris_resample(enum restir_mis mode, int n, const float *c, const float *P, const float *W,
                                   const float *J, const float *u, float *W_out)
{
    float m[RESTIR_GRIS_MAX_SAMPLES] = {0};
    if (!W_out || !c || !P || !W || !J || !u || n < 1 || n > RESTIR_GRIS_MAX_SAMPLES ||
        restir_mis_weights(mode, n, c, P, m) != 0)
        return -1;
    *W_out = 0.0f;
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    int chosen = -1;
    for (int j = 0; j < n; j++)
        if (restir_reservoir_offer(&wrs, restir_gris_resampling_weight(m[j], P[j], W[j], J[j]), u[j]))
            chosen = j;
    if (chosen >= 0)
        *W_out = restir_gris_contribution_weight(&wrs, P[chosen]);
    return chosen;
}

/* How restir_gris_targets moves the caller's samples between domains (0: the canonical one). */
struct restir_gris_shift {
    /* Shifts sample x, living in domain `from`, into domain `to`: writes the shifted sample to y and
     * |dT/dx| to *jacobian. Returns 1, or 0 when the shift is undefined there or the shifted sample
     * contributes nothing. */
    int (*shift)(void *ctx, const void *x, int from, int to, void *y, float *jacobian);
    /* p_hat of sample y in `domain`, the domain it was shifted into. */
    float (*target)(void *ctx, const void *y, int domain);
    void *ctx;
    size_t sample_size; /* bytes of one sample */
};

/* The targets of one merge of 1 <= n <= RESTIR_GRIS_MAX_SAMPLES samples (004 Eq. 10). x[j] is
 * reservoir j's sample in its own domain j (NULL when it has none) and cached[j] its target
 * p_hat_j(x_j). Writes Y_j = T_{j->0}(x_j) to the j-th sample of Y (Y_0 = x_0), J[j] = |dT/dx| (0
 * where x_j is NULL or its shift failed), and P[k * n + j] = p_hat_{<-k}(Y_j): row 0 from the
 * forward shifts, the diagonal as cached[j] / J[j], the other entries that restir_mis_needs(mode,
 * k, j) asks for by shifting Y_j back into domain k (0 elsewhere). tmp holds one sample (scratch).
 * Calls s->shift in a fixed order: the forward shifts by j, then the back shifts by k and j, on the
 * calling thread. Returns 0, or -1 without writing when a pointer argument (or s->shift, s->target)
 * is NULL, n is out of range or mode is not one of enum restir_mis. */
int restir_gris_targets(enum restir_mis mode, int n, const struct restir_gris_shift *s, const void *const *x,
                        const float *cached, void *Y, float *P, float *J, void *tmp);

#ifdef __cplusplus
}
#endif

#endif
