/* path_estimate.h: the path tracer's estimates that methods build from the path walk (path_walk.h):
 * the sum of m f / p over a walk's candidates, the light a camera ray's first hit sends back along it
 * directly (its emission and paths of length 2), the radiance of a path suffix from a secondary vertex
 * with the walk's Russian roulette kept where a full path would have it, and pt's primary ray from
 * independent numbers. pt, restir-gi and ris-gi share them, so their estimates are the same function
 * of the same numbers. Must never hold state. */
#ifndef RESTIR_RENDER_PATH_ESTIMATE_H
#define RESTIR_RENDER_PATH_ESTIMATE_H

#include <stdint.h>

#include "core/rng.h"
#include "render/params.h"
#include "render/path_walk.h"
#include "scene/camera.h"
#include "scene/scene.h"

/* A path_candidate_fn: adds the candidate's m f / p to *(vec3 *)ctx (candidates of zero density add
 * nothing). With path_walk_run this is the path tracer's estimate of the walk. */
void path_sum_candidates(void *ctx, const struct path_walk *w, const struct path_candidate *c);

/* Le + D at hit, the first hit of a camera ray of direction d: the emission it sends back along the
 * ray (front faces of emitters) plus the paths of length 2 through it (next-event estimation and the
 * BSDF-sampled hit, combined by MIS as in pt), walked from seed's streams with p's lights and
 * p->rr_bounces (one scattering event, none when p->max_bounces < 1). A D that is not finite is left
 * out. Adds the rays traced to *rays. */
vec3 path_emission_and_direct(const struct scene *s, const struct render_params *p, const struct surface_hit *hit,
                              vec3 d, uint64_t seed, long long *rays);

/* Lr(x2 -> x1; seed): the radiance leaving secondary vertex x2 toward the previous vertex (x2.wo),
 * walked with the p->max_bounces - 1 scattering events left after x1's and Russian roulette after
 * the same total number of bounces as pt (p->rr_bounces - 1 from x2). x2's own emission is not
 * included (path_walk_run), so this is the radiance of paths of length >= 3 through x1 and x2.
 * Adds the rays traced to *rays. */
vec3 path_suffix_radiance(const struct scene *s, const struct render_params *p, const struct path_vertex *x2,
                          uint64_t seed, long long *rays);

/* pt's primary ray from independent numbers, drawn from rng in this order: the sub-pixel position
 * (when jitter is on; else the pixel's centre), a 64-bit path seed into *path_seed, then the camera's
 * lens point and shutter time (camera_sample_draw). Writes the ray through pixel (x, y) to *o, *d. */
void path_primary_ray(const struct camera_view *view, int jitter, pcg32 *rng, int x, int y, uint64_t *path_seed,
                      vec3 *o, vec3 *d);

#endif
