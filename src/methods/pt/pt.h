/* pt.h: the unidirectional path tracer (next-event estimation and BSDF sampling combined by
 * MIS, Russian roulette, maximum bounce count), used as method `pt` and for references.
 * Must never depend on reservoirs. */
#ifndef RESTIR_METHODS_PT_PT_H
#define RESTIR_METHODS_PT_PT_H

#include "core/rng.h"
#include "render/params.h"
#include "scene/camera.h"
#include "scene/scene.h"

/* Radiance along the camera ray (o, d): emission seen directly plus up to max_bounces scattering
 * events, with the path's random numbers drawn from path_seed (path_walk.h). *rays counts the
 * rays traced. */
vec3 pt_trace(const struct scene *s, vec3 o, vec3 d, int max_bounces, uint64_t path_seed, int rr_bounces,
              long long *rays);

/* Renders spp paths per pixel into rgb (w*h*3, the mean). Returns the number of rays traced. */
long long pt_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                  int frame, int spp, float *rgb);
/* pt_pass whose sampler=sobol samples are points first_index .. first_index + spp - 1 of the
 * pixels' sequences numbered `sequence` (pt_pass: sequence = frame, first_index = 0), so that
 * chunks of one reference continue one sequence instead of starting independent ones. The
 * independent sampler reads only frame. */
long long pt_pass_chunk(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                        int frame, int sequence, uint32_t first_index, int spp, float *rgb);

#endif
