/* gris.c: the resampling step of one GRIS merge (restir/gris.h). */
#include "restir/gris.h"

#include <string.h>

#include "restir/reservoir.h"

void restir_gris_targets(enum restir_mis mode, int n, const struct restir_gris_shift *s, const void *const *x,
                         const float *cached, void *Y, float *P, float *J, void *tmp)
{
    char *y = Y;
    const size_t size = s->sample_size;
    for (int j = 0; j < n * n; j++)
        P[j] = 0.0f;
    for (int j = 0; j < n; j++) {
        J[j] = 0.0f;
        if (!x[j])
            continue;
        if (j == 0) {
            memcpy(y, x[0], size);
            J[0] = 1.0f;
            P[0] = cached[0];
        } else if (s->shift(s->ctx, x[j], j, 0, y + (size_t)j * size, &J[j])) {
            P[j] = s->target(s->ctx, y + (size_t)j * size, 0);
        } else {
            J[j] = 0.0f;
        }
    }
    for (int k = 1; k < n; k++) {
        for (int j = 0; j < n; j++) {
            if (!restir_mis_needs(mode, k, j) || !(J[j] > 0.0f))
                continue;
            if (k == j) {
                P[k * n + j] = cached[j] / J[j]; /* p_hat_j(X_j) |dT^-1/dy| */
            } else {
                float Jb;
                if (s->shift(s->ctx, y + (size_t)j * size, 0, k, tmp, &Jb))
                    P[k * n + j] = s->target(s->ctx, tmp, k) * Jb;
            }
        }
    }
}

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
