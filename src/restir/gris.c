/* gris.c: the resampling step of one GRIS merge (restir/gris.h). */
#include "restir/gris.h"

#include "restir/reservoir.h"

int restir_gris_resample(enum restir_mis mode, int n, const float *c, const float *P, const float *W, const float *J,
                         const float *u, float *W_out)
{
    float m[RESTIR_GRIS_MAX_SAMPLES] = {0};
    *W_out = 0.0f;
    if (n <= 0 || n > RESTIR_GRIS_MAX_SAMPLES)
        return -1;
    restir_mis_weights(mode, n, c, P, m);
    struct restir_wrs wrs;
    restir_wrs_init(&wrs);
    int chosen = -1;
    for (int j = 0; j < n; j++) {
        const float w = J[j] > 0.0f ? m[j] * P[j] * W[j] * J[j] : 0.0f; /* 004 Eq. 6 */
        if (restir_wrs_offer(&wrs, w, u[j]))
            chosen = j;
    }
    if (chosen >= 0)
        *W_out = restir_gris_contribution_weight(&wrs, P[chosen]); /* 004 Eq. 7 */
    return chosen;
}
