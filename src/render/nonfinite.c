/* nonfinite.c: discarding and counting non-finite radiance (nonfinite.h). */
#include "render/nonfinite.h"

#include <math.h>

long long nonfinite_discard_rgb(float *rgb, size_t n_pixels)
{
    long long bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (long long i = 0; i < 3 * (long long)n_pixels; i++) {
        if (!isfinite(rgb[i])) {
            rgb[i] = 0.0f;
            bad++;
        }
    }
    return bad;
}
