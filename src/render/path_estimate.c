/* path_estimate.c: the path tracer's estimates built from the path walk (path_estimate.h). */
#include "render/path_estimate.h"

#include <math.h>

#include "shading/lights.h"

void path_sum_candidates(void *ctx, const struct path_walk *w, const struct path_candidate *c)
{
    (void)w;
    vec3 *L = ctx;
    if (c->pdf > 0.0f)
        *L = v3_add(*L, v3_scale(c->f, c->mis / c->pdf));
}

vec3 path_emission_and_direct(const struct scene *s, const struct render_params *p, const struct surface_hit *hit,
                              vec3 d, uint64_t seed, long long *rays)
{
    vec3 Le = v3s(0.0f);
    if (s->tri_emitter[hit->tri] >= 0 && hit->front)
        Le = lights_radiance(s, hit->tri, hit->b1, hit->b2, v3_neg(d));
    const struct path_vertex v = path_vertex_from_hit(hit, d);
    struct path_walk walk;
    vec3 D = v3s(0.0f);
    const int direct_bounces = p->max_bounces < 1 ? p->max_bounces : 1;
    *rays += path_walk_run(s, &v, seed, render_params_light_choice(p), direct_bounces, p->rr_bounces, &walk,
                           path_sum_candidates, &D);
    return v3_is_finite(D) ? v3_add(Le, D) : Le;
}

vec3 path_suffix_radiance(const struct scene *s, const struct render_params *p, const struct path_vertex *x2,
                          uint64_t seed, long long *rays)
{
    struct path_walk walk;
    vec3 L = v3s(0.0f);
    const int rr = p->rr_bounces > 1 ? p->rr_bounces - 1 : 0;
    *rays += path_walk_run(s, x2, seed, render_params_light_choice(p), p->max_bounces - 1, rr, &walk,
                           path_sum_candidates, &L);
    return L;
}

void path_primary_ray(const struct camera_view *view, int jitter, pcg32 *rng, int x, int y, uint64_t *path_seed,
                      vec3 *o, vec3 *d)
{
    const float jx = jitter ? pcg32_float(rng) : 0.5f, jy = jitter ? pcg32_float(rng) : 0.5f;
    const uint64_t hi = pcg32_next(rng);
    *path_seed = (hi << 32) | pcg32_next(rng);
    const struct camera_sample cs = camera_sample_draw(view, rng);
    camera_sample_ray(view, &cs, (float)x + jx, (float)y + jy, o, d);
}
