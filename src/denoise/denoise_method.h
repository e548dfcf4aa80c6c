/* denoise_method.h: what a denoiser file implements (one struct denoise_method row) and the frame
 * denoise.c prepares for it: illumination demodulated by albedo (Schied et al. 2017 Sec. 4: the
 * filter never blurs texture), features as planes (structure of arrays, so that the filters'
 * pixel loops vectorise), depth gradients, and which pixels take part. Internal to src/denoise.
 * Must never depend on anything outside src/denoise and src/core. */
#ifndef RESTIR_DENOISE_DENOISE_METHOD_H
#define RESTIR_DENOISE_DENOISE_METHOD_H

#include <stddef.h>

#include "denoise/denoise_types.h"

struct denoise_frame {
    int width, height;
    float *illum[3];           /* in: demodulated illumination, RGB planes; out: the method's result */
    const float *normal[3];    /* shading normal, x y z planes */
    const float *position[3];  /* world position planes */
    const float *depth;        /* distance from the camera; +inf where use is 0, so that every
                                  depth-weighted tap of an unused pixel weighs 0 */
    const float *ddx, *ddy;    /* depth's screen-space derivatives, per pixel (denoise_depth_gradients) */
    const float *use;          /* 1 where the pixel is filtered and may be read, 0 elsewhere */
    const float *group;        /* 0 where use is 0, else 1 + the bits of the albedo channels the
                                  illumination was divided by (bit c: channel c); a filter's tap
                                  counts only where its group is the centre's (denoise.c) */
    const int *object;         /* the guide's mesh ids */
    const float *motion;       /* the guide's motion vectors (2 per pixel) */
    const float *gradient;     /* the guide's temporal gradient (NULL: none, or the setting off) */
    double mean_lum;           /* mean luminance of the used pixels' illumination (0 when none) */
};

struct denoise_method {
    const char *name;
    /* Allocates the method's state for width x height frames; aborts when memory runs out. */
    void *(*create)(const struct denoise_settings *s, int width, int height);
    void (*destroy)(void *state);
    /* Filters f->illum in place where f->use is 1 (elsewhere f->illum may hold anything after it). */
    void (*run)(void *state, const struct denoise_settings *s, struct denoise_frame *f, struct denoise_stats *st);
    /* After remodulation: rgb (width * height * 3, the output so far; pixels with use 0 hold their
     * raw value) may be changed where f->use is 1 (SVGF's temporal antialiasing). NULL: none. */
    void (*post)(void *state, const struct denoise_settings *s, const struct denoise_frame *f, float *rgb);
    /* The last frame's plane of that name (denoiser_layer), or NULL; NULL: none. */
    const float *(*layer)(const void *state, const char *name);
};

/* count planes of n floats, zeroed, in one block (free plane[0]); consecutive planes lie a little
 * more than n floats apart (see denoise.c). */
void denoise_planes_alloc(float **plane, int count, size_t n);

/* Rows of scratch for each OpenMP thread, grown on demand. */
struct denoise_scratch {
    float *data;
    size_t per_thread;
    int threads;
};
/* At least `floats` for each of omp_get_max_threads() threads; call outside a parallel region. */
void denoise_scratch_reserve(struct denoise_scratch *s, size_t floats);
/* The calling thread's scratch (inside the parallel region that follows the reserve). */
float *denoise_scratch_mine(const struct denoise_scratch *s);
void denoise_scratch_free(struct denoise_scratch *s);

/* The rows, in denoise_names order after "off" (denoise.c). */
extern const struct denoise_method denoise_svgf;
extern const struct denoise_method denoise_atrous;

#endif
