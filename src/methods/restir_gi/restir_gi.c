/* restir_gi.c: ReSTIR GI passes (see restir_gi.h; ReSTIR GI (Ouyang et al. 2021)) in GRIS terms:
 * one BSDF-sampled secondary vertex per pixel with the radiance of its path suffix, the
 * reconnection shift that keeps that vertex and the suffix's seed, GRIS merges with its Jacobian
 * (004 Eq. 5-7) and selectable resampling MIS (004 Eq. 9-12, targets of Eq. 10), temporal and
 * spatial reuse, shading. Must never allocate per pixel or read files. */
#include "methods/restir_gi/restir_gi.h"

#include <math.h>

#include "render/path_estimate.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "restir/mis.h"
#include "restir/reservoir.h"
#include "scene/scene_env.h"
#include "shading/bsdf.h"
#include "shading/lights.h"
#include "methods/restir_gi/gi_settings.h"

/* Canonical domain + at most GI_MAX_NEIGHBORS spatial neighbors. */
#define GI_MAX_DOMAINS (1 + GI_MAX_NEIGHBORS)

/* ---- the integrand --------------------------------------------------------------------------- */

static uint64_t draw_seed(pcg32 *rng)
{
    uint64_t hi = pcg32_next(rng);
    return (hi << 32) | pcg32_next(rng);
}

static int fail(struct gi_sample *y)
{
    y->valid = 0;
    return 0;
}

/* f of sample y in the domain of shading point x1 (restir_gi.h): the straight connection
 * x1 -> x2, the BSDF at x1 with its shading normal bent for x1's own wo (bsdf_shading_normal),
 * the geometric side test of the path walk (w . ng_1 > 0: the initial sampling never produces
 * other directions, so the target vanishes there too), x2 rebuilt from its triangle as a ray
 * x1 -> x2 would hit it (normals facing x1), then visibility when asked for (one ray) and the
 * radiance: traced again by the walk when `walk` is set, else y->Lo as it is. Fills y's x2_ng,
 * cos2, dist2, Lo and f. The initial sample and every shift evaluate f through this one function,
 * so an identity shift reproduces the cached target exactly. Returns 0 (y->valid = 0) where f is
 * zero or not finite. */
static int evaluate(const struct scene *s, const struct render_params *p, const struct path_vertex *x1,
                    struct gi_sample *y, int test_visibility, int walk, long long *rays)
{
    const vec3 to = v3_sub(y->x2_p, x1->p);
    const float d2 = v3_length2(to);
    if (!(d2 > 0.0f) || !isfinite(d2))
        return fail(y);
    const vec3 w = v3_scale(to, 1.0f / sqrtf(d2));
    const vec3 n = bsdf_shading_normal(x1->ns, x1->ng, x1->wo);
    const float cos1 = v3_dot(n, w);
    if (cos1 <= 0.0f || v3_dot(x1->ng, w) <= 0.0f)
        return fail(y);
    struct bsdf b;
    path_vertex_bsdf(s, x1, &b);
    const vec3 fcos = v3_scale(bsdf_eval(&b, n, x1->wo, w), cos1);
    if (!(v3_max_component(fcos) > 0.0f))
        return fail(y);
    struct surface_hit h;
    scene_surface_at(s, y->x2_tri, y->x2_b1, y->x2_b2, y->x2_p, w, &h);
    const float cos2 = -v3_dot(h.ng, w); /* h.ng faces x1 */
    if (!(cos2 > 0.0f))
        return fail(y);
    y->x2_ng = h.ng;
    y->cos2 = cos2;
    y->dist2 = d2;
    if (test_visibility) {
        (*rays)++;
        if (!scene_visible(s, x1->p, x1->ng, y->x2_p, h.ng))
            return fail(y);
    }
    if (walk) {
        const struct path_vertex x2 = path_vertex_from_hit(&h, w);
        y->Lo = path_suffix_radiance(s, p, &x2, y->seed, rays);
    }
    y->f = v3_mul(fcos, y->Lo);
    if (!(v3_max_component(y->f) > 0.0f) || !v3_is_finite(y->f))
        return fail(y);
    y->valid = 1;
    return 1;
}

int gi_shift(const struct scene *s, const struct render_params *p, const struct gi_sample *x,
             const struct path_vertex *to_x1, struct gi_sample *y, float *jacobian, long long *rays)
{
    *y = *x;
    *jacobian = 0.0f;
    if (!x->valid || !gi_x1_valid(to_x1) || !(x->cos2 > 0.0f) || !(x->dist2 > 0.0f))
        return fail(y);
    if (!evaluate(s, p, to_x1, y, 1, gi_settings_of(p)->radiance == GI_RADIANCE_REEVALUATE, rays))
        return 0;
    /* ReSTIR GI Eq. 11: the solid angle of x2's surface element seen from the new x1 over the
     * old; the suffix's random numbers are kept (|T'| = 1 there). */
    const float J = (y->cos2 / y->dist2) * (x->dist2 / x->cos2);
    if (!(J > 0.0f) || !isfinite(J))
        return fail(y);
    *jacobian = J;
    return 1;
}

/* ---- initial sampling ------------------------------------------------------------------------ */

/* One candidate (M = 1, as ReSTIR GI's initial sample): a direction w from x1's BSDF with density
 * p(w), its first hit x2 and a fresh seed, resampled with weight p_hat / p(w). res is empty with
 * its confidence set on entry. Its random numbers are drawn before anything can fail, so a
 * pixel's stream is used the same way whatever the scene does. Returns rays traced. */
static long long initial_sample(const struct gi_frame *fr, const struct path_vertex *x1, pcg32 *rng,
                                struct gi_reservoir *res)
{
    const struct scene *s = fr->s;
    long long rays = 0;
    const float u0 = pcg32_float(rng), u1 = pcg32_float(rng), u2 = pcg32_float(rng);
    struct gi_sample y;
    y.seed = draw_seed(rng);
    const float u_wrs = pcg32_float(rng);
    struct bsdf b;
    path_vertex_bsdf(s, x1, &b);
    const vec3 n = bsdf_shading_normal(x1->ns, x1->ng, x1->wo);
    vec3 wi, fs;
    float pdf;
    if (!bsdf_sample(&b, n, x1->wo, u0, u1, u2, &wi, &pdf, &fs) || !(pdf > 0.0f) || v3_dot(wi, x1->ng) <= 0.0f)
        return rays;
    struct surface_hit h;
    rays++;
    if (!scene_intersect(s, scene_offset_point(x1->p, x1->ng, wi), wi, 0.0f, INFINITY, &h))
        return rays; /* the environment seen from x1 is direct light (D) */
    y.x2_p = h.p;
    y.x2_tri = h.tri;
    y.x2_b1 = h.b1;
    y.x2_b2 = h.b2;
    y.Lo = v3s(0.0f);
    /* The hit is the first one along wi: no visibility ray. Lr is traced in both radiance modes
     * (stored keeps this value from now on). */
    if (!evaluate(s, fr->p, x1, &y, 0, 1, &rays))
        return rays;
    const float target = v3_luminance(y.f);
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    if (restir_reservoir_offer(&wrs, target / pdf, u_wrs)) {
        res->y = y;
        res->target = target;
        res->W = restir_gris_contribution_weight(&wrs, target); /* 1 / p(w) */
    }
    if (!(res->W > 0.0f) || !isfinite(res->W))
        gi_reservoir_clear(res, res->c);
    return rays;
}

/* A pixel without a shading point. */
static struct path_vertex no_vertex(void)
{
    struct path_vertex v = {0};
    v.tri = -1;
    v.material = -1;
    return v;
}

long long gi_initial_pass(const struct gi_frame *fr, const struct gbuffer *g, struct path_vertex *x1, vec3 *base,
                          struct gi_reservoir *out)
{
    const struct scene *s = fr->s;
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            struct gi_reservoir *res = &out[i];
            gi_reservoir_clear(res, 0.0f);
            x1[i] = no_vertex();
            if (!g->valid[i]) {
                base[i] = g->emission[i]; /* the sky the G-buffer's ray saw */
                continue;
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_GI_INITIAL);
            /* The G-buffer's own ray (pinhole from the camera position), so x1 is its hit. */
            const vec3 o = fr->view->position;
            const vec3 d = camera_view_ray(fr->view, g->sub_pixel[i].x, g->sub_pixel[i].y);
            struct surface_hit hit;
            rays++;
            if (!scene_intersect(s, o, d, 0.0f, INFINITY, &hit)) {
                base[i] = scene_env_radiance(s, d);
                continue;
            }
            /* Le + D: emission and paths of length 2, NEE and BSDF hit MIS'd as in pt. */
            base[i] = path_emission_and_direct(s, p, &hit, d, draw_seed(&rng), &rays);
            const struct path_vertex v = path_vertex_from_hit(&hit, d);
            x1[i] = v;
            res->c = 1.0f;
            if (p->max_bounces > 1)
                rays += initial_sample(fr, &v, &rng, res);
        }
    }
    return rays;
}

/* ---- GRIS merge ------------------------------------------------------------------------------ */

/* A merge's shading points and the rays its shifts trace (restir_gris_shift's ctx). */
struct merge_shift {
    const struct gi_frame *fr;
    const struct path_vertex *const *dom;
    long long rays;
};

static int merge_shift_sample(void *vctx, const void *x, int from, int to, void *y, float *jacobian)
{
    struct merge_shift *m = vctx;
    (void)from; /* the sample carries what the Jacobian needs of the domain it lives in */
    return gi_shift(m->fr->s, m->fr->p, x, m->dom[to], y, jacobian, &m->rays);
}

static float merge_target(void *vctx, const void *y, int domain)
{
    (void)vctx;
    (void)domain;
    return v3_luminance(((const struct gi_sample *)y)->f);
}

/* One GRIS merge into domain dom[0] (canonical, identity shift) of n reservoirs living in the
 * domains dom[j] (004 Eq. 5-7). P[k * n + j] = p_hat_{<-k}(Y_j) (004 Eq. 10): row 0 from the
 * forward shifts, the diagonal from the cached target over the forward Jacobian, the rest by
 * shifting Y_j back into domain k. */
static long long gris_merge(const struct gi_frame *fr, int n, const struct path_vertex *const *dom,
                            const struct gi_reservoir *const *in, pcg32 *rng, struct gi_reservoir *out)
{
    const struct render_params *p = fr->p;
    struct merge_shift ctx = {fr, dom, 0};
    const struct restir_gris_shift shift = {merge_shift_sample, merge_target, &ctx, sizeof(struct gi_sample)};
    float c[GI_MAX_DOMAINS], J[GI_MAX_DOMAINS], P[GI_MAX_DOMAINS * GI_MAX_DOMAINS], cached[GI_MAX_DOMAINS];
    float W[GI_MAX_DOMAINS], u[GI_MAX_DOMAINS], W_Y, c_sum = 0.0f;
    const void *x[GI_MAX_DOMAINS];
    struct gi_sample Y[GI_MAX_DOMAINS], z;
    for (int j = 0; j < n; j++) {
        c[j] = min_f(in[j]->c, p->reuse.confidence_cap); /* fminf is a libm call */
        c_sum += c[j];
        x[j] = gi_reservoir_has_sample(in[j]) ? &in[j]->y : NULL;
        cached[j] = in[j]->target;
    }
    restir_gris_targets(p->reuse.mis, n, &shift, x, cached, Y, P, J, &z); /* 004 Eq. 10 */
    for (int j = 0; j < n; j++) {
        W[j] = in[j]->W;
        u[j] = pcg32_float(rng);
    }
    const int chosen = restir_gris_resample(p->reuse.mis, n, c, P, W, J, u, &W_Y); /* 004 Eq. 5-7 */
    struct gi_reservoir result;
    gi_reservoir_clear(&result, restir_gris_confidence_merge(c_sum, p->reuse.confidence_cap));
    if (chosen >= 0) {
        result.y = Y[chosen];
        result.target = P[chosen];
        result.W = W_Y;
        if (!(result.W > 0.0f) || !isfinite(result.W) || !v3_is_finite(result.y.f))
            gi_reservoir_clear(&result, result.c);
    }
    *out = result;
    return ctx.rays;
}

/* ---- temporal and spatial reuse -------------------------------------------------------------- */

long long gi_temporal_pass(const struct gi_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct path_vertex *x1, const struct path_vertex *prev_x1,
                           const struct gi_reservoir *prev_res, struct gi_reservoir *io, long long *accepted)
{
    const struct render_params *p = fr->p;
    long long rays = 0, acc = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays, acc)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            if (!gi_x1_valid(&x1[i]))
                continue;
            /* Reads G-buffers only, so the domain pair does not depend on the samples. */
            int q = gbuffer_history_pixel(g, i, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane);
            if (q < 0 || !gi_x1_valid(&prev_x1[q]))
                continue;
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_GI_TEMPORAL);
            const struct path_vertex *dom[2] = {&x1[i], &prev_x1[q]};
            const struct gi_reservoir *in[2] = {&io[i], &prev_res[q]};
            rays += gris_merge(fr, 2, dom, in, &rng, &io[i]);
            acc++;
        }
    }
    *accepted = acc;
    return rays;
}

/* Neighbors' reservoirs and shading points are read at random within the reuse radius; issuing
 * their loads one pixel ahead hides the latency behind the current pixel's shifts (as
 * restir_pt.c does). */
static void prefetch_neighbors(const struct gi_reservoir *in, const struct path_vertex *x1, const int *list, int m)
{
    for (int k = 0; k < m; k++) {
        if (list[k] < 0)
            continue;
        prefetch_bytes(&in[list[k]], (unsigned)sizeof(struct gi_reservoir));
        prefetch_bytes(&x1[list[k]], (unsigned)sizeof(struct path_vertex));
    }
}

long long gi_spatial_pass(const struct gi_frame *fr, const struct gbuffer *g, const int *neighbors,
                          const struct path_vertex *x1, const struct gi_reservoir *in, struct gi_reservoir *out)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const int m = render_params_spatial_neighbors(p, 1); /* the list's stride */
    const int m_read = m < GI_MAX_NEIGHBORS ? m : GI_MAX_NEIGHBORS;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            int next = tile_peek(&px);
            if (next >= 0)
                prefetch_neighbors(in, x1, &neighbors[(size_t)next * m], m_read);
            if (!g->valid[i] || !gi_x1_valid(&x1[i])) {
                out[i] = in[i];
                continue;
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_GI_SPATIAL);
            const struct path_vertex *dom[GI_MAX_DOMAINS];
            const struct gi_reservoir *src[GI_MAX_DOMAINS];
            dom[0] = &x1[i];
            src[0] = &in[i];
            int n = 1;
            for (int k = 0; k < m_read; k++) {
                /* Skipping a neighbor without a shading point depends on the G-buffer's ray only. */
                int j = neighbors[(size_t)i * m + k];
                if (j < 0 || !gi_x1_valid(&x1[j]))
                    continue;
                dom[n] = &x1[j];
                src[n++] = &in[j];
            }
            rays += gris_merge(fr, n, dom, src, &rng, &out[i]);
        }
    }
    return rays;
}

/* ---- shading and the non-finite guard -------------------------------------------------------- */

void gi_shade_pass(const struct gbuffer *g, const vec3 *base, const struct gi_reservoir *res, float *rgb)
{
    const int n = g->width * g->height;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        vec3 L = base[i];
        if (gi_reservoir_has_sample(&res[i]))
            L = v3_add(L, v3_scale(res[i].y.f, res[i].W)); /* f(Y) W_Y */
        rgb[3 * i] = L.x;
        rgb[3 * i + 1] = L.y;
        rgb[3 * i + 2] = L.z;
    }
}

long long gi_nonfinite_discard(struct gi_reservoir *res, size_t n)
{
    long long bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
    for (long long i = 0; i < (long long)n; i++) {
        struct gi_reservoir *r = &res[i];
        int finite = isfinite(r->W) && isfinite(r->target) && isfinite(r->c);
        if (finite && r->y.valid)
            finite = v3_is_finite(r->y.f);
        if (!finite) {
            gi_reservoir_clear(r, isfinite(r->c) ? r->c : 0.0f);
            bad++;
        }
    }
    return bad;
}
