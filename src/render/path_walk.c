/* path_walk.c: the path generator shared by `pt` and ReSTIR PT: NEE and BSDF sampling combined by
 * the power heuristic (Veach 1997, Ch. 9) and throughput-based Russian roulette, reporting every
 * complete path as a candidate. Must never depend on reservoirs. */
#include "render/path_walk.h"

#include "scene/env_light.h"
#include "shading/bsdf.h"
#include "shading/lights.h"

static float power_heuristic(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

struct path_vertex path_vertex_from_hit(const struct surface_hit *h, vec3 ray_dir)
{
    struct path_vertex v = {0};
    v.p = h->p;
    v.ns = h->ns;
    v.ng = h->ng;
    v.wo = v3_neg(ray_dir);
    v.material = h->material;
    v.tri = h->tri;
    v.b1 = h->b1;
    v.b2 = h->b2;
    return v;
}

void path_vertex_bsdf(const struct scene *s, const struct path_vertex *v, struct bsdf *b)
{
    struct material tmp;
    bsdf_from_material(scene_material_at(s, v->tri, v->b1, v->b2, &tmp), b);
}

/* Reports the NEE path ending at light point (or direction) light_p with the given radiance and
 * densities: f = prefix f_s cos Le, pdf = prefix * light pdf, power heuristic against the BSDF. */
static void emit_nee(const struct path_walk *w, int at_env, vec3 light_p, vec3 light_n, vec3 Le, vec3 wi, vec3 f,
                     float cos_x, vec3 prefix_f, float prefix_pdf, float pdf_light, float pdf_bsdf,
                     path_candidate_fn emit, void *ctx)
{
    struct path_candidate c;
    c.length = w->nv + 1;
    c.via_nee = 1;
    c.at_env = at_env;
    c.light_p = light_p;
    c.light_n = light_n;
    c.Le = Le;
    c.w_last = wi;
    c.fcos_last = v3_scale(f, cos_x);
    c.f = v3_mul(v3_mul(prefix_f, c.fcos_last), Le);
    c.pdf = prefix_pdf * pdf_light;
    c.mis = power_heuristic(pdf_light, pdf_bsdf);
    emit(ctx, w, &c);
}

/* The environment's NEE strategy under `lights`: its sampler and the probability that a light
 * sample takes it rather than an emitter (none without an environment). Compensated falls back to
 * the map's own distribution where nothing is above the mean (a constant sky, as pbrt-v4 does):
 * measured on a constant sky, BSDF sampling alone had 1.2x the variance per sample for 0.83x the
 * cost (docs/BENCHMARKS.md). NEE and the MIS weights of BSDF hits both ask here. */
struct walk_env {
    const struct env_sampler *sampler;
    float share;
};

static struct walk_env walk_env_of(const struct scene *s, struct light_choice lights)
{
    struct walk_env e = {NULL, 0.0f};
    if (!s->env)
        return e;
    e.sampler = lights.env == LIGHT_ENV_COMPENSATED && s->env_sampler_compensated ? s->env_sampler_compensated
                                                                                   : s->env_sampler;
    e.share = s->env_prob;
    return e;
}

/* NEE toward the environment: a direction from its importance sampler, chosen with
 * probability env.share; reported like a light point at infinity (no distance term). */
static long long next_event_env(const struct scene *s, const struct path_walk *w, const struct bsdf_frame *bf, vec3 n,
                                vec3 prefix_f, float prefix_pdf, float u1, float u2, struct walk_env env,
                                path_candidate_fn emit, void *ctx)
{
    const struct path_vertex *x = &w->v[w->nv - 1];
    float pdf_env;
    vec3 wi = env_sample(env.sampler, u1, u2, &pdf_env);
    const float pdf_light = env.share * pdf_env, cos_x = v3_dot(n, wi);
    if (!(pdf_light > 0.0f) || cos_x <= 0.0f || v3_dot(x->ng, wi) <= 0.0f)
        return 0;
    float pdf_bsdf;
    vec3 f = bsdf_frame_eval(bf, wi, &pdf_bsdf);
    if (v3_max_component(f) <= 0.0f)
        return 0;
    if (scene_occluded(s, scene_offset_point(x->p, x->ng, wi), wi, 0.0f, INFINITY))
        return 1;
    emit_nee(w, 1, v3_add(x->p, wi), v3_neg(wi), environment_radiance(s->env, wi), wi, f, cos_x, prefix_f, prefix_pdf,
             pdf_light, pdf_bsdf, emit, ctx);
    return 1;
}

/* NEE at x (the last vertex of the walk, BSDF prepared for x->wo in bf): one light point,
 * reported as a candidate of length nv + 1 when it contributes. prefix_f / prefix_pdf describe
 * x_1 .. x. */
static long long next_event(const struct scene *s, const struct path_walk *w, const struct bsdf_frame *bf, vec3 n,
                            vec3 prefix_f, float prefix_pdf, const float u[3], struct light_choice lights,
                            path_candidate_fn emit, void *ctx)
{
    const struct path_vertex *x = &w->v[w->nv - 1];
    struct light_sample ls;
    float u0 = u[0], u1 = u[1], u2 = u[2];
    float emitter_share = 1.0f; /* the probability of sampling an emitter rather than the environment */
    const struct walk_env env = walk_env_of(s, lights);
    if (env.share > 0.0f) {
        if (u0 < env.share)
            return next_event_env(s, w, bf, n, prefix_f, prefix_pdf, u1, u2, env, emit, ctx);
        emitter_share = 1.0f - env.share;
        u0 = (u0 - env.share) / emitter_share;
    }
    if (!lights_sample_at(s, lights, x->p, n, u0, u1, u2, &ls))
        return 0;
    vec3 to = v3_sub(ls.p, x->p);
    float d2 = v3_length2(to);
    if (!(d2 > 0.0f))
        return 0;
    vec3 wi = v3_scale(to, 1.0f / sqrtf(d2));
    float cos_l = -v3_dot(ls.n, wi), cos_x = v3_dot(n, wi);
    if (cos_l <= 0.0f || cos_x <= 0.0f || v3_dot(x->ng, wi) <= 0.0f)
        return 0;
    float pdf_bsdf;
    vec3 f = bsdf_frame_eval(bf, wi, &pdf_bsdf);
    if (v3_max_component(f) <= 0.0f)
        return 0;
    if (!scene_visible(s, x->p, x->ng, ls.p, ls.n))
        return 1;
    float pdf_light = ls.pdf_area * d2 / cos_l * emitter_share;
    emit_nee(w, 0, ls.p, ls.n, ls.Le, wi, f, cos_x, prefix_f, prefix_pdf, pdf_light, pdf_bsdf, emit, ctx);
    return 1;
}

/* The replayable numbers: vertex j's stream path_rng(seed, j), drawn in the order of path_walk.h. */
static void numbers_from_seed(const void *ctx, int vertex, struct path_vertex_numbers *u)
{
    pcg32 rng = path_rng(*(const uint64_t *)ctx, vertex);
    for (int k = 0; k < 3; k++)
        u->bsdf[k] = pcg32_float(&rng);
    for (int k = 0; k < 3; k++)
        u->nee[k] = pcg32_float(&rng);
    u->rr = pcg32_float(&rng);
}

long long path_walk_run(const struct scene *s, const struct path_vertex *x1, uint64_t seed, struct light_choice lights,
                        int max_bounces, int rr_bounces, struct path_walk *w, path_candidate_fn emit, void *ctx)
{
    const struct path_numbers numbers = path_numbers_seeded(&seed);
    return path_walk_run_numbers(s, x1, &numbers, lights, max_bounces, rr_bounces, w, emit, ctx);
}

struct path_numbers path_numbers_seeded(const uint64_t *seed)
{
    const struct path_numbers numbers = {numbers_from_seed, seed};
    return numbers;
}

long long path_walk_run_numbers(const struct scene *s, const struct path_vertex *x1, const struct path_numbers *numbers,
                                struct light_choice lights, int max_bounces, int rr_bounces, struct path_walk *w,
                                path_candidate_fn emit, void *ctx)
{
    long long rays = 0;
    if (max_bounces > PATH_MAX_VERTICES)
        max_bounces = PATH_MAX_VERTICES;
    w->nv = 1;
    w->v[0] = *x1;
    vec3 prefix_f = v3s(1.0f); /* prod of fcos over x_1 .. x_{nv-1} */
    float prefix_pdf = 1.0f;
    const struct walk_env env = walk_env_of(s, lights);
    for (;;) {
        struct path_vertex *x = &w->v[w->nv - 1];
        const int j = w->nv;
        if (j > max_bounces)
            break;
        struct path_vertex_numbers u;
        numbers->fill(numbers->ctx, j, &u);
        /* One frame for NEE and the continuation: f and pdf of both strategies come from
         * bsdf_frame_eval, so their MIS weights see the same densities. */
        struct bsdf b;
        struct bsdf_frame bf;
        path_vertex_bsdf(s, x, &b);
        const vec3 n = bsdf_shading_normal(x->ns, x->ng, x->wo);
        bsdf_frame_init(&bf, &b, n, x->wo);
        rays += next_event(s, w, &bf, n, prefix_f, prefix_pdf, u.nee, lights, emit, ctx);
        const float u_rr = u.rr;
        vec3 wi, f;
        float pdf;
        if (!bsdf_frame_sample(&bf, u.bsdf[0], u.bsdf[1], u.bsdf[2], &wi, &pdf, &f))
            break;
        /* A sampled direction below the geometric surface would leak through it. */
        if (v3_dot(wi, x->ng) <= 0.0f)
            break;
        x->w_next = wi;
        x->fcos = v3_scale(f, v3_dot(n, wi));
        x->pdf_dir = pdf;
        prefix_f = v3_mul(prefix_f, x->fcos);
        prefix_pdf *= pdf;
        if (j > rr_bounces) {
            vec3 beta = v3_scale(prefix_f, 1.0f / prefix_pdf);
            float q = min_f(v3_max_component(beta), 0.95f); /* fminf is a libm call */
            if (!(u_rr < q))
                break;
            prefix_pdf *= q;
        }
        if (!(prefix_pdf > 0.0f) || !isfinite(prefix_pdf))
            break;
        struct surface_hit h;
        rays++;
        vec3 o = scene_offset_point(x->p, x->ng, wi);
        if (!scene_intersect(s, o, wi, 0.0f, INFINITY, &h)) {
            if (s->env) { /* the path escapes to the environment: its BSDF-sampled light strategy */
                struct path_candidate c;
                c.length = j + 1;
                c.via_nee = 0;
                c.at_env = 1;
                c.light_p = v3_add(x->p, wi);
                c.light_n = v3_neg(wi);
                c.Le = environment_radiance(s->env, wi);
                c.w_last = wi;
                c.fcos_last = x->fcos;
                c.f = v3_mul(prefix_f, c.Le);
                c.pdf = prefix_pdf;
                c.mis = power_heuristic(pdf, env.share * env_pdf(env.sampler, wi));
                emit(ctx, w, &c);
            }
            break;
        }
        int emitter = s->tri_emitter[h.tri];
        if (emitter >= 0 && h.front) {
            struct path_candidate c;
            c.length = j + 1;
            c.via_nee = 0;
            c.at_env = 0;
            c.light_p = h.p;
            c.light_n = s->tri_normal[h.tri];
            c.Le = lights_radiance(s, h.tri, h.b1, h.b2, v3_neg(wi));
            c.w_last = wi;
            c.fcos_last = x->fcos;
            c.f = v3_mul(prefix_f, c.Le);
            c.pdf = prefix_pdf;
            float cos_l = fabsf(v3_dot(c.light_n, wi));
            /* x and n as next_event saw them, so both strategies' densities agree */
            float pdf_light = lights_pdf_at(s, lights, x->p, n, h.tri, h.t, cos_l) * (1.0f - env.share);
            c.mis = power_heuristic(pdf, pdf_light);
            emit(ctx, w, &c);
        }
        if (w->nv >= PATH_MAX_VERTICES)
            break;
        w->v[w->nv++] = path_vertex_from_hit(&h, wi);
    }
    return rays;
}
