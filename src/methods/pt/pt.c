/* pt.c: the reference path tracer: the shared path walk (path_walk.c) with every candidate path
 * summed as m f / p, plus emission seen directly. Must never depend on reservoirs. */
#include "methods/pt/pt.h"

#include "core/sobol.h"
#include "render/path_estimate.h"
#include "render/path_walk.h"
#include "render/tiles.h"
#include "scene/scene_env.h"
#include "shading/lights.h"

/* The padded Sobol' dimensions of sample `index` in one pixel and frame (core/sobol.h), each pair or
 * single named by a key hashed from the pixel's key and its dimension number: 0 the pixel position
 * (pair), 1 the lens (pair), 2 the shutter time, then five per path vertex j >= 1 at 3 + 5 (j - 1):
 * the BSDF direction (pair), the BSDF lobe, the NEE point (pair), the NEE light choice, Russian
 * roulette. Vertices past PT_SOBOL_VERTICES draw independent PCG32 numbers from a stream keyed by
 * their first dimension and the sample index: deep bounces gain little from stratification and the
 * scrambles cost (docs/BENCHMARKS.md, pt's samplers). */
#define PT_SOBOL_VERTICES 2
struct sobol_numbers {
    uint64_t pixel_key;
    uint32_t index;
    int rr_bounces; /* render_params.rr_bounces */
};

static uint64_t sobol_dim_key(const struct sobol_numbers *sn, int dim)
{
    return rng_mix64(sn->pixel_key + 0x9e3779b97f4a7c15ull * (uint64_t)(dim + 1));
}

static void sobol_vertex_numbers(const void *ctx, int vertex, struct path_vertex_numbers *u)
{
    const struct sobol_numbers *sn = ctx;
    const int base = 3 + 5 * (vertex - 1);
    if (vertex > PT_SOBOL_VERTICES) { /* deeper vertices: independent numbers, keyed like a dimension */
        pcg32 rng = pcg32_make(sobol_dim_key(sn, base), (uint64_t)sn->index);
        for (int k = 0; k < 3; k++)
            u->bsdf[k] = pcg32_float(&rng);
        for (int k = 0; k < 3; k++)
            u->nee[k] = pcg32_float(&rng);
        u->rr = pcg32_float(&rng);
        return;
    }
    sobol_sample_2d(sn->index, sobol_dim_key(sn, base), &u->bsdf[1]);
    u->bsdf[0] = sobol_sample_1d(sn->index, sobol_dim_key(sn, base + 1));
    sobol_sample_2d(sn->index, sobol_dim_key(sn, base + 2), &u->nee[1]);
    u->nee[0] = sobol_sample_1d(sn->index, sobol_dim_key(sn, base + 3));
    /* the walk reads rr only past rr_bounces (path_walk.c) */
    u->rr = vertex > sn->rr_bounces ? sobol_sample_1d(sn->index, sobol_dim_key(sn, base + 4)) : 0.0f;
}

/* Radiance along (o, d) with the walk's numbers from `numbers`. */
static vec3 pt_trace_numbers(const struct scene *s, vec3 o, vec3 d, int max_bounces, const struct path_numbers *numbers,
                             uint64_t path_seed, struct light_choice lights, int rr_bounces, long long *rays)
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
    const struct path_numbers seeded = path_numbers_seeded(&path_seed);
    *rays += path_walk_run_numbers(s, &x1, numbers ? numbers : &seeded, lights, max_bounces, rr_bounces, &w,
                                   path_sum_candidates, &L);
    return L;
}

vec3 pt_trace(const struct scene *s, vec3 o, vec3 d, int max_bounces, uint64_t path_seed, int rr_bounces,
              long long *rays)
{
    return pt_trace_numbers(s, o, d, max_bounces, NULL, path_seed, LIGHT_CHOICE_POWER_AREA, rr_bounces, rays);
}

/* A pixel's sum of path radiances, in double: summed in float, 4096 paths of a constant sky came
 * out 3.5e-5 too bright (each addition rounds at the running sum's precision, the same way every
 * time for the same value), a bias that a reference's flat regions show at any z. */
struct sum3d {
    double x, y, z;
};

static void sum3d_add(struct sum3d *s, vec3 v)
{
    s->x += v.x;
    s->y += v.y;
    s->z += v.z;
}

/* One pixel's spp paths with pt's Sobol' sampler: points first_index .. first_index + spp - 1 of the
 * pixel's padded sequence for (seed, sequence). Owen scrambling makes every point uniform, so each
 * such set is an unbiased randomized quasi-Monte Carlo estimate, and sequences of different seeds or
 * sequence numbers are independent. */
static struct sum3d pixel_sobol(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                        int sequence, uint32_t first_index, int x, int y, int i, int spp, long long *rays)
{
    struct sobol_numbers sn = {rng_key(p->seed, (uint64_t)sequence, (uint64_t)i, RNG_PASS_PT_SOBOL), 0u, p->rr_bounces};
    const struct path_numbers numbers = {sobol_vertex_numbers, &sn};
    struct sum3d sum = {0.0, 0.0, 0.0};
    for (int k = 0; k < spp; k++) {
        sn.index = first_index + (uint32_t)k;
        float jitter[2] = {0.5f, 0.5f};
        if (p->jitter)
            sobol_sample_2d(sn.index, sobol_dim_key(&sn, 0), jitter);
        struct camera_sample cs = {{0.0f, 0.0f}, 0.0f}; /* what camera_sample_draw leaves unset */
        if (view->lens_radius > 0.0f)
            sobol_sample_2d(sn.index, sobol_dim_key(&sn, 1), cs.lens);
        if (view->shutter > 0.0f)
            cs.time = sobol_sample_1d(sn.index, sobol_dim_key(&sn, 2));
        vec3 o, d;
        camera_sample_ray(view, &cs, (float)x + jitter[0], (float)y + jitter[1], &o, &d);
        vec3 L = pt_trace_numbers(s, o, d, p->max_bounces, &numbers, 0u, render_params_light_choice(p), p->rr_bounces,
                                  rays);
        if (v3_is_finite(L))
            sum3d_add(&sum, L);
    }
    return sum;
}

/* One pixel's spp paths with independent numbers: the pixel's PCG32 stream for (seed, frame) gives
 * each path its jitter, seed and camera dimensions; the walk replays from the seed (path_walk.h). */
static struct sum3d pixel_independent(const struct scene *s, const struct camera_view *view,
                                      const struct render_params *p, int frame, int x, int y, int i, int spp,
                                      long long *rays)
{
    pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_PT);
    struct sum3d sum = {0.0, 0.0, 0.0};
    for (int k = 0; k < spp; k++) {
        uint64_t path_seed;
        vec3 o, d;
        path_primary_ray(view, p->jitter, &rng, x, y, &path_seed, &o, &d);
        vec3 L = pt_trace_numbers(s, o, d, p->max_bounces, NULL, path_seed, render_params_light_choice(p),
                                  p->rr_bounces, rays);
        if (v3_is_finite(L))
            sum3d_add(&sum, L);
    }
    return sum;
}

long long pt_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                  int frame, int spp, float *rgb)
{
    return pt_pass_chunk(s, view, p, frame, frame, 0u, spp, rgb);
}

long long pt_pass_chunk(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                        int frame, int sequence, uint32_t first_index, int spp, float *rgb)
{
    long long rays = 0;
    const int w = view->width, hgt = view->height, ntiles = tile_count(w, hgt);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, hgt, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            const struct sum3d sum = p->sampler == PT_SAMPLER_SOBOL
                                         ? pixel_sobol(s, view, p, sequence, first_index, x, y, i, spp, &rays)
                                         : pixel_independent(s, view, p, frame, x, y, i, spp, &rays);
            rgb[3 * i] = (float)(sum.x / spp);
            rgb[3 * i + 1] = (float)(sum.y / spp);
            rgb[3 * i + 2] = (float)(sum.z / spp);
        }
    }
    return rays;
}
