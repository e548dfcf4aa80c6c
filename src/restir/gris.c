/* gris.c: the targets of one GRIS merge through the caller's shift callbacks (restir/gris.h). */
#include "restir/gris.h"

#include <string.h>

int restir_gris_targets(enum restir_mis mode, int n, const struct restir_gris_shift *s, const void *const *x,
                        const float *cached, void *Y, float *P, float *J, void *tmp)
{
    if (!s || !s->shift || !s->target || !x || !cached || !Y || !P || !J || !tmp || n < 1 ||
        n > RESTIR_GRIS_MAX_SAMPLES || !restir_mis_valid(mode))
        return -1;
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
    return 0;
}
