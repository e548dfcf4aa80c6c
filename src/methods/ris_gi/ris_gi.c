/* ris_gi.c: the ris-gi pass and its settings block (ris_gi.h). Must never allocate per pixel. */
#include "methods/ris_gi/ris_gi.h"

#include <math.h>
#include <stddef.h>

#include "render/path_estimate.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "restir/reservoir.h"
#include "scene/scene_env.h"
#include "shading/bsdf.h"

static const struct param_def ris_gi_rows[] = {
    {"risgi.candidates", P_INT, offsetof(struct ris_gi_settings, candidates), 1, 64, "4", NULL,
     "BSDF directions K resampled per primary hit, each traced with its path suffix (K = 1: BSDF sampling)", NULL},
};
struct param_block ris_gi_block = PARAM_METHOD_BLOCK("ris-gi", ris_gi_rows, struct ris_gi_settings, NULL);

/* One candidate's f = f_r(wo, w) cos(n, w) Lr(x2 -> x1) for direction w, given fr = f_r(wo, w) (0 where
 * the direction leaves through x1's geometric surface, escapes to the environment, which x1's paths of
 * length 2 already count, or carries nothing). */
static vec3 candidate_f(const struct scene *s, const struct render_params *p, const struct path_vertex *x1, vec3 n,
                        vec3 w, vec3 fr, uint64_t seed, long long *rays)
{
    const float cos1 = v3_dot(n, w);
    if (!(cos1 > 0.0f) || v3_dot(x1->ng, w) <= 0.0f)
        return v3s(0.0f);
    const vec3 fcos = v3_scale(fr, cos1);
    if (!(v3_max_component(fcos) > 0.0f))
        return v3s(0.0f);
    struct surface_hit h;
    (*rays)++;
    if (!scene_intersect(s, scene_offset_point(x1->p, x1->ng, w), w, 0.0f, INFINITY, &h))
        return v3s(0.0f);
    const struct path_vertex x2 = path_vertex_from_hit(&h, w);
    const vec3 f = v3_mul(fcos, path_suffix_radiance(s, p, &x2, seed, rays));
    return v3_is_finite(f) ? f : v3s(0.0f);
}

/* RIS over K BSDF directions at x1: the kept candidate's f times its contribution weight. Every
 * candidate draws its five numbers before anything can fail, so the stream is used the same way
 * whatever the scene does. */
static vec3 indirect(const struct scene *s, const struct render_params *p, const struct path_vertex *x1, int K,
                     pcg32 *rng, long long *rays)
{
    struct bsdf b;
    path_vertex_bsdf(s, x1, &b);
    const vec3 n = bsdf_shading_normal(x1->ns, x1->ng, x1->wo);
    struct bsdf_frame bf; /* x1's frame and wo terms, once for the K candidates */
    bsdf_frame_init(&bf, &b, n, x1->wo);
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    vec3 kept = v3s(0.0f);
    float kept_target = 0.0f;
    for (int k = 0; k < K; k++) {
        const float u0 = pcg32_float(rng), u1 = pcg32_float(rng), u2 = pcg32_float(rng);
        const uint64_t hi = pcg32_next(rng);
        const uint64_t seed = (hi << 32) | pcg32_next(rng);
        const float u_wrs = pcg32_float(rng);
        vec3 w, fs;
        float pdf;
        if (!bsdf_frame_sample(&bf, u0, u1, u2, &w, &pdf, &fs) || !(pdf > 0.0f)) {
            restir_reservoir_offer(&wrs, 0.0f, u_wrs); /* counts toward K, weight 0 */
            continue;
        }
        const vec3 f = candidate_f(s, p, x1, n, w, fs, seed, rays); /* fs = f_r(wo, w) (bsdf_frame_sample) */
        const float target = v3_luminance(f);
        /* GRIS weight with m_k = 1 / K (004 Eq. 5): the K candidates are i.i.d. */
        if (restir_reservoir_offer(&wrs, target / pdf / (float)K, u_wrs)) {
            kept = f;
            kept_target = target;
        }
    }
    const float W = restir_gris_contribution_weight(&wrs, kept_target);
    return W > 0.0f && isfinite(W) ? v3_scale(kept, W) : v3s(0.0f);
}

long long ris_gi_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p, int frame,
                      float *rgb)
{
    const uint64_t stream = rng_stream_id(RIS_GI_STREAM);
    const int K = ris_gi_settings_of(p)->candidates, spp = p->spp;
    const int w = view->width, hgt = view->height, ntiles = tile_count(w, hgt);
    long long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, hgt, t); px.i >= 0; tile_advance(&px)) {
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)px.i, stream);
            double sum[3] = {0.0, 0.0, 0.0};
            for (int k = 0; k < spp; k++) {
                uint64_t path_seed;
                vec3 o, d;
                path_primary_ray(view, p->jitter, &rng, px.x, px.y, &path_seed, &o, &d);
                struct surface_hit hit;
                vec3 L;
                rays++;
                if (!scene_intersect(s, o, d, 0.0f, INFINITY, &hit)) {
                    L = scene_env_radiance(s, d);
                } else {
                    L = path_emission_and_direct(s, p, &hit, d, path_seed, &rays);
                    if (p->max_bounces > 1) {
                        const struct path_vertex x1 = path_vertex_from_hit(&hit, d);
                        L = v3_add(L, indirect(s, p, &x1, K, &rng, &rays));
                    }
                }
                if (v3_is_finite(L)) {
                    sum[0] += L.x;
                    sum[1] += L.y;
                    sum[2] += L.z;
                }
            }
            for (int c = 0; c < 3; c++)
                rgb[3 * px.i + c] = (float)(sum[c] / spp);
        }
    }
    return rays;
}
