/* svgf_temporal.h: SVGF's temporal accumulation (Schied et al. 2017 Sec. 4.1), the pass that
 * reprojects the previous frame's colour and luminance moments and blends this frame in. Internal
 * to src/denoise; svgf.c keeps the history planes and calls it once per frame. */
#ifndef RESTIR_DENOISE_SVGF_TEMPORAL_H
#define RESTIR_DENOISE_SVGF_TEMPORAL_H

#include "denoise/denoise_method.h"

/* The previous frame's planes (width x height each, as this frame's). */
struct svgf_history {
    const float *group, *normal[3], *position[3]; /* group: as struct denoise_frame's */
    const int *object;
    const float *value[6]; /* demodulated colour RGB, moments m1 and m2, history length */
};

struct svgf_accumulation {
    struct denoise_frame *f; /* in: this frame; out: f->illum accumulated */
    const struct svgf_history *prev; /* NULL: no history (the first frame) */
    float alpha, moments_alpha;      /* the moving averages' least weights of this frame */
    float normal_min, plane_max;     /* the tests (svgf_normal_min, svgf_plane_max) */
    float *m1, *m2, *len;            /* out: moments and history length (0 on unused pixels) */
};

/* How much of the history a temporal gradient lambda (A-SVGF) discards: 1 - (1 - lambda)^10, Q2RTX's
 * response (its history length N' = N (1 - a)^10 + 1): a 7% change discards half, a 50% one all but
 * 0.1%. Used for the moving averages' weights, the history length and the antialiasing's weight. */
static inline float svgf_gradient_response(float lambda)
{
    const float k = 1.0f - (lambda < 0.0f ? 0.0f : lambda > 1.0f ? 1.0f : lambda);
    const float k2 = k * k, k4 = k2 * k2, k8 = k4 * k4;
    return 1.0f - k8 * k2;
}

/* The pass over every pixel, on all threads. Returns the number of used pixels without history. */
long long svgf_accumulate(const struct svgf_accumulation *a);

#endif
