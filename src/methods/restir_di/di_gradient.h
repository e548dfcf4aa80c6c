/* di_gradient.h: restir-di's temporal gradient for A-SVGF (Schied et al. 2018), from the
 * samples its reuse already holds instead of re-shaded strata: per pixel, the history sample (the
 * previous frame's reservoir under the backward motion vector) and the current initial sample, each
 * shaded unshadowed (target x W, visibility as the targets have it) under the previous and under this
 * frame's lights; delta = sum (now - before) and the sums of now and of before, box-filtered over
 * 7 x 7 pixels, lambda = min(1, |delta| / max(now, before)): the relative change of the window's
 * lighting (A-SVGF's |delta| / max(L_cur, L_prev) with both frames' samples). It sees what changes the lights make (animated
 * emitters, scene/scene_animation.h); a scene whose lights stand still gives 0. Must never trace rays. */
#ifndef RESTIR_METHODS_RESTIR_DI_DI_GRADIENT_H
#define RESTIR_METHODS_RESTIR_DI_DI_GRADIENT_H

#include "methods/restir_di/di_sample.h"
#include "scene/scene.h"

#define DI_GRADIENT_RADIUS 3 /* the box filter's half width: 7 x 7 */

/* lambda per pixel into grad (w x h), with tmp (4 w h floats) as scratch. initial: this frame's initial
 * reservoirs; prev: the previous frame's final ones (NULL: no history); frame: this frame's number. */
void di_temporal_gradient(const struct scene *s, const struct gbuffer *g, const struct gbuffer *prev_g,
                          const struct di_reservoir *initial, const struct di_reservoir *prev, int frame, float *grad,
                          float *tmp);

#endif
