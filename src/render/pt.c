/* pt.c: the reference path tracer: the shared path walk (path_walk.c) with every candidate path
 * summed as m f / p, plus emission seen directly. Must never depend on reservoirs. */
#include "render/pt.h"

#include "render/path_walk.h"
#include "render/tiles.h"
#include "scene/scene_env.h"
#include "shading/lights.h"

static void accumulate(void *ctx, const struct path_walk *w, const struct path_candidate *c)
{
    (void)w;
    vec3 *L = ctx;
    if (c->pdf > 0.0f)
        *L = v3_add(*L, v3_scale(c->f, c->mis / c->pdf));
}

vec3 pt_trace(const struct scene *s, vec3 o, vec3 d, int max_bounces, uint64_t path_seed, int rr_bounces,
              long long *rays)
{
    struct surface_hit h;
    (*rays)++;
    if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h))
        return scene_env_radiance(s, d);
    vec3 L = v3s(0.0f);
    if (s->tri_emitter[h.tri] >= 0 && h.front)
        L = lights_radiance(s, h.tri, h.b1, h.b2, v3_neg(d));
    struct path_walk w;
    struct path_vertex x1 = path_vertex_from_hit(&h, d);
    *rays += path_walk_run(s, &x1, path_seed, max_bounces, rr_bounces, &w, accumulate, &L);
    return L;
}

long long pt_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                  int frame, int spp, float *rgb)
{
    long long rays = 0;
    const int w = view->width, hgt = view->height, ntiles = tile_count(w, hgt);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, hgt, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_PT);
            vec3 sum = v3s(0.0f);
            for (int k = 0; k < spp; k++) {
                float jx = p->jitter ? pcg32_float(&rng) : 0.5f, jy = p->jitter ? pcg32_float(&rng) : 0.5f;
                uint64_t path_seed = ((uint64_t)pcg32_next(&rng) << 32) | pcg32_next(&rng);
                struct camera_sample cs = camera_sample_draw(view, &rng);
                vec3 o, d;
                camera_sample_ray(view, &cs, (float)x + jx, (float)y + jy, &o, &d);
                vec3 L = pt_trace(s, o, d, p->max_bounces, path_seed, p->rr_bounces, &rays);
                if (v3_is_finite(L))
                    sum = v3_add(sum, L);
            }
            vec3 mean = v3_scale(sum, 1.0f / (float)spp);
            rgb[3 * i] = mean.x;
            rgb[3 * i + 1] = mean.y;
            rgb[3 * i + 2] = mean.z;
        }
    }
    return rays;
}
