/* restir/gris.h: the resampling step of one GRIS merge (004 Eq. 5-7), independent of what a sample
 * is: once the caller has shifted every input sample into the canonical domain and filled the
 * target matrix, this picks the output sample and its contribution weight. Every ReSTIR pass of
 * the renderer (light samples, paths, paired-pixel samples, ReSTIR GI's sample points) ends its
 * merges here. Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_GRIS_H
#define RESTIR_GRIS_H

#include <stddef.h>

#include "restir/mis.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most samples one merge takes. */
#define RESTIR_GRIS_MAX_SAMPLES 64

/* How a merge moves the caller's samples between its domains (0: the canonical one). */
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

/* The targets of one merge of n <= RESTIR_GRIS_MAX_SAMPLES samples (004 Eq. 10). x[j] is reservoir
 * j's sample in its own domain j (NULL when it has none) and cached[j] its target p_hat_j(x_j).
 * Writes Y_j = T_{j->0}(x_j) to the j-th sample of Y (Y_0 = x_0), J[j] = |dT/dx| (0 where x_j is
 * NULL or its shift failed), and P[k * n + j] = p_hat_{<-k}(Y_j): row 0 from the forward shifts,
 * the diagonal as cached[j] / J[j], the other entries that restir_mis_needs(mode, k, j) asks for by
 * shifting Y_j back into domain k (0 elsewhere). tmp holds one sample (scratch). Calls s->shift in
 * a fixed order: the forward shifts by j, then the back shifts by k and j. */
void restir_gris_targets(enum restir_mis mode, int n, const struct restir_gris_shift *s, const void *const *x,
                         const float *cached, void *Y, float *P, float *J, void *tmp);

/* Resamples n <= RESTIR_GRIS_MAX_SAMPLES samples Y_j of one merge whose domain 0 is canonical:
 *   m_j  = restir_mis_weights(mode, n, c, P)            (004 Eq. 9-12; P as mis.h documents it)
 *   w_j  = m_j * P[j] * W[j] * J[j]                     (004 Eq. 6; 0 where J[j] <= 0)
 * with W[j] the contribution weight of Y_j in its own domain and J[j] > 0 the Jacobian of its shift
 * into domain 0 (1 for the canonical sample and for shifts that keep the sample; J[j] <= 0 marks a
 * sample that did not shift in or has none). The output is chosen by streaming WRS, u[j] in [0,1)
 * deciding at sample j. Returns the chosen index, or -1 when no weight is positive, and writes its
 * contribution weight W_Y = sum_j w_j / P[chosen] (004 Eq. 7; 0 for none) to *W_out. Thread-safe;
 * non-finite weights are offered and never chosen (restir_wrs_offer). */
int restir_gris_resample(enum restir_mis mode, int n, const float *c, const float *P, const float *W, const float *J,
                         const float *u, float *W_out);

#ifdef __cplusplus
}
#endif

#endif
