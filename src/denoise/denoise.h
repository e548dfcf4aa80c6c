/* denoise.h: denoisers that read a rendered frame and the G-buffer features of its primary hits and
 * write a new image: SVGF (Schied et al., HPG 2017, svgf.c) and the edge-avoiding à-trous
 * wavelet filter (Dammertz et al., HPG 2010, atrous.c). A denoiser sits after the estimator and
 * never feeds back into it: its output is BIASED by nature, and the frame it reads stays as it was.
 * Each denoiser is one file with one table row (struct denoise_method); denoise.c lists them.
 * Depends on core only, so that another renderer can lift it with its own buffers.
 * Must never depend on the scene, the ray tracer, reservoirs or methods. */
#ifndef RESTIR_DENOISE_DENOISE_H
#define RESTIR_DENOISE_DENOISE_H

#include "denoise/denoise_types.h"

/* The settings' defaults, method off. */
void denoise_settings_defaults(struct denoise_settings *s);

/* "off", "svgf", "atrous", NULL-terminated: what denoise= spells, in denoise_settings.method order. */
extern const char *const denoise_names[];

struct denoiser;

/* A denoiser of s->method (> 0) for width x height frames, with empty history. Returns NULL for
 * method 0 or an unknown index or size; aborts when memory runs out. Owns its history; one
 * denoiser per frame sequence (not thread-safe: it runs its own OpenMP loops). */
struct denoiser *denoiser_create(const struct denoise_settings *s, int width, int height);
void denoiser_destroy(struct denoiser *d);
/* Denoises rgb (3 floats per pixel, radiance) into out (the same layout, may not alias rgb) with
 * g's features of the same frame, and keeps what the next frame's history needs. Pixels that are
 * not valid, or whose value or features are not finite, are copied from rgb unchanged (counted in
 * st) and never read by a neighbour's filter. Returns 0, or -1 when g's size differs from the
 * denoiser's (out untouched). st may be NULL. */
int denoiser_run(struct denoiser *d, const float *rgb, const struct denoise_guide *g, float *out,
                 struct denoise_stats *st);
/* A plane of the last frame's internals, width * height floats, valid until the next run: for SVGF
 * "variance" (the luminance variance that guided the first iteration, Sec. 4.2) and "history" (the
 * history length in frames, 0 where the pixel was passed through). NULL for another name or method.
 * For debug views and tests. */
const float *denoiser_layer(const struct denoiser *d, const char *name);
/* The name of its method ("svgf", ...). */
const char *denoiser_name(const struct denoiser *d);

#endif
