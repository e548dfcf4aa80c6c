/* pt.c: unidirectional path tracing with next-event estimation and BSDF sampling combined by the
 * power heuristic (Veach 1997, Ch. 9), and throughput-based Russian roulette. Must never depend
 * on reservoirs. */
#include "pt.h"

#include "shading/bsdf.h"
#include "shading/lights.h"
#include "tiles.h"

static float power_heuristic(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/* Next-event estimate at x: one light sample, weighted against BSDF sampling of the same point. */
static vec3 sample_direct(const struct scene *s, const struct surface_hit *h, const struct bsdf *b, vec3 wo,
                          pcg32 *rng, long long *rays)
{
    struct light_sample ls;
    float u0 = pcg32_float(rng), u1 = pcg32_float(rng), u2 = pcg32_float(rng);
    if (!lights_sample(s, u0, u1, u2, &ls))
        return v3s(0.0f);
    vec3 to = v3_sub(ls.p, h->p);
    float d2 = v3_length2(to);
    if (!(d2 > 0.0f))
        return v3s(0.0f);
    vec3 wi = v3_scale(to, 1.0f / sqrtf(d2));
    float cos_l = -v3_dot(ls.n, wi);
    float cos_x = v3_dot(h->ns, wi);
    if (cos_l <= 0.0f || cos_x <= 0.0f)
        return v3s(0.0f);
    vec3 f = bsdf_eval(b, h->ns, wo, wi);
    if (v3_max_component(f) <= 0.0f)
        return v3s(0.0f);
    (*rays)++;
    if (!scene_visible(s, h->p, h->ng, ls.p, ls.n))
        return v3s(0.0f);
    float pdf_light = ls.pdf_area * d2 / cos_l; /* solid angle */
    float pdf_bsdf = bsdf_pdf(b, h->ns, wo, wi);
    float w = power_heuristic(pdf_light, pdf_bsdf);
    return v3_scale(v3_mul(ls.Le, f), cos_x * w / pdf_light);
}

vec3 pt_trace(const struct scene *s, vec3 o, vec3 d, int max_bounces, int rr_bounces, pcg32 *rng,
              long long *rays)
{
    vec3 L = v3s(0.0f), beta = v3s(1.0f);
    float prev_bsdf_pdf = 0.0f; /* solid-angle pdf of the direction that reached this vertex */
    struct surface_hit h;
    for (int bounce = 0;; bounce++) {
        (*rays)++;
        if (!scene_intersect(s, o, d, 0.0f, INFINITY, &h))
            break;
        int emitter = s->tri_emitter[h.tri];
        if (emitter >= 0 && h.front) {
            vec3 Le = lights_radiance(s, h.tri, v3_neg(d));
            float w = 1.0f;
            if (bounce > 0) {
                /* MIS against next-event estimation, which could have produced this point. */
                float cos_l = fabsf(v3_dot(s->tri_normal[h.tri], d));
                float pdf_light = lights_pdf_area(s, h.tri) * h.t * h.t / fmaxf(cos_l, 1e-12f);
                w = power_heuristic(prev_bsdf_pdf, pdf_light);
            }
            L = v3_add(L, v3_scale(v3_mul(beta, Le), w));
        }
        if (bounce >= max_bounces)
            break;
        struct bsdf b;
        bsdf_from_material(&s->materials[h.material], &b);
        vec3 wo = v3_neg(d);
        L = v3_add(L, v3_mul(beta, sample_direct(s, &h, &b, wo, rng, rays)));
        vec3 wi, f;
        float pdf;
        float u0 = pcg32_float(rng), u1 = pcg32_float(rng), u2 = pcg32_float(rng);
        if (!bsdf_sample(&b, h.ns, wo, u0, u1, u2, &wi, &pdf, &f))
            break;
        /* A sampled direction below the geometric surface would leak through it. */
        if (v3_dot(wi, h.ng) <= 0.0f)
            break;
        beta = v3_mul(beta, v3_scale(f, v3_dot(h.ns, wi) / pdf));
        if (bounce + 1 > rr_bounces) {
            float q = fminf(v3_max_component(beta), 0.95f);
            if (pcg32_float(rng) >= q)
                break;
            beta = v3_scale(beta, 1.0f / q);
        }
        prev_bsdf_pdf = pdf;
        o = scene_offset_point(h.p, h.ng, wi);
        d = wi;
    }
    return L;
}

long long pt_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p,
                  int frame, int spp, float *rgb)
{
    long long rays = 0;
    const int w = view->width, hgt = view->height, ntiles = tile_count(w, hgt);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, hgt, t);
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                int i = y * w + x;
                pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_PT);
                vec3 sum = v3s(0.0f);
                for (int k = 0; k < spp; k++) {
                    float jx = p->jitter ? pcg32_float(&rng) : 0.5f, jy = p->jitter ? pcg32_float(&rng) : 0.5f;
                    vec3 d = camera_view_ray(view, (float)x + jx, (float)y + jy);
                    vec3 L = pt_trace(s, view->position, d, p->max_bounces, p->rr_bounces, &rng, &rays);
                    if (v3_is_finite(L))
                        sum = v3_add(sum, L);
                }
                vec3 mean = v3_scale(sum, 1.0f / (float)spp);
                rgb[3 * i] = mean.x;
                rgb[3 * i + 1] = mean.y;
                rgb[3 * i + 2] = mean.z;
            }
        }
    }
    return rays;
}
