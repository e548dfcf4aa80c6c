/* gpt.h: gradient-domain path tracing (Kettunen et al. 2015; 002 baseline B.2): per pixel and
 * sample a base path from the `pt` walk, every candidate path of it (NEE and BSDF, each with its
 * density p and NEE/BSDF weight m) shifted into the four neighbors by the inner shift (hybrid by
 * default), the symmetric estimator of 002 Eq. 3. Must never depend on reservoirs. */
#ifndef RESTIR_METHODS_GRADIENT_GPT_H
#define RESTIR_METHODS_GRADIENT_GPT_H

#include "render/params.h"
#include "render/path_shift.h"

/* spp samples per pixel: primal (RGB, the pt estimate of the same paths), its part seen directly
 * (emission, RGB; its gradients are its forward differences, grad_add_image_differences) and the
 * one-sided differences of the paths of length >= 2 in os (grad_common.h, cleared by the caller).
 * Returns rays traced. */
long long gpt_pass(const struct scene *s, const struct shift_params *sp, const struct camera_view *view,
                   const struct render_params *p, int frame, float *primal, float *emission, float *os);

#endif
