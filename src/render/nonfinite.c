/* nonfinite.c: discarding and counting non-finite reservoirs and radiance (nonfinite.h). */
#include "render/nonfinite.h"

#include <math.h>

/* A reservoir is kept when its W, target and confidence are finite; else it is emptied, keeping a
 * finite confidence (a non-finite one becomes 0: a domain that produced nothing). */
static int reservoir_finite(float W, float target, float c) { return isfinite(W) && isfinite(target) && isfinite(c); }

long long nonfinite_discard_di(struct di_reservoir *res, size_t n)
{
    long long bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (long long i = 0; i < (long long)n; i++) {
        if (!reservoir_finite(res[i].W, res[i].target, res[i].c)) {
            di_reservoir_clear(&res[i], isfinite(res[i].c) ? res[i].c : 0.0f);
            bad++;
        }
    }
    return bad;
}

long long nonfinite_discard_pt(struct pt_reservoir *res, size_t n)
{
    long long bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (long long i = 0; i < (long long)n; i++) {
        if (!reservoir_finite(res[i].W, res[i].target, res[i].c)) {
            pt_reservoir_clear(&res[i], isfinite(res[i].c) ? res[i].c : 0.0f);
            bad++;
        }
    }
    return bad;
}

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
