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

/* The pass over every pixel, on all threads. Returns the number of used pixels without history. */
long long svgf_accumulate(const struct svgf_accumulation *a);

#endif
