/* restir_pt.c: ReSTIR PT passes (see restir_pt.h): initial path resampling over the candidates of
 * the shared path walk, GRIS merges with shift mappings and Jacobians (004 Eq. 5-7) and
 * selectable resampling MIS (004 Eq. 9-12), temporal and spatial reuse, shading.
 * Must never allocate per pixel. */
#include "methods/restir_pt/restir_pt.h"

#include "render/nonfinite.h"
#include "render/temporal_flags.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "restir/mis.h"
#include "restir/reservoir.h"
#include "scene/scene_env.h"
#include "shading/lights.h"
#include "methods/restir_pt/restir_pt_settings.h"

/* Canonical domain + at most 5 spatial neighbors. */
#define PT_MAX_DOMAINS 6

void pt_shift_params(const struct render_params *p, float scene_diagonal, vec3 camera, struct shift_params *out)
{
    out->kind = p->shift.kind;
    out->min_roughness = p->shift.roughness;
    out->distance_mode = (enum shift_distance_mode)p->shift.distance_mode;
    out->min_distance =
        out->distance_mode == SHIFT_DISTANCE_SCENE ? p->shift.distance * scene_diagonal : p->shift.distance;
    out->distance_factor = p->shift.distance;
    out->camera = camera;
    out->rough = NULL;
}



/* ---- initial sampling ---------------------------------------------------------------------- */

struct initial_ctx {
    const struct scene *s;
    const struct shift_params *shift;
    struct restir_reservoir wrs;
    pcg32 *rng;
    float inv_paths;          /* 1 / number of initial paths: the MIS weight between paths */
    struct path_sample trial; /* u and seed of the path being walked */
    struct pt_reservoir *r;
    float resampling_target; /* p_hat of the selection as the resampling weights saw it */
    int chosen_here;         /* the selection changed during the current walk ... */
    struct path_candidate chosen; /* ... to this candidate */
};

/* Resampling weight m f / p of one candidate (Lin et al. 2022 Sec. 7: resampling along the path,
 * target p_hat = luminance(f)). Only the candidate is kept: the reservoir's sample is built once
 * per walk by keep_chosen, not for every candidate the streaming WRS passes through. */
static void offer_candidate(void *vctx, const struct path_walk *w, const struct path_candidate *c)
{
    (void)w;
    struct initial_ctx *ctx = vctx;
    float target = v3_luminance(c->f);
    float weight = c->pdf > 0.0f ? c->mis * target / c->pdf * ctx->inv_paths : 0.0f;
    if (restir_reservoir_offer(&ctx->wrs, weight, pcg32_float(ctx->rng))) {
        ctx->chosen = *c;
        ctx->chosen_here = 1;
        ctx->resampling_target = target;
    }
}

/* After a walk: the sample of the candidate it selected last, if any. The walk appends vertices
 * and never rewrites those a reported candidate reads, so the finished walk still describes it. */
static void keep_chosen(struct initial_ctx *ctx, const struct path_walk *w)
{
    if (!ctx->chosen_here)
        return;
    ctx->r->y = ctx->trial;
    path_sample_from_candidate(ctx->s, ctx->shift, w, &ctx->chosen, &ctx->r->y);
    ctx->chosen_here = 0;
}

long long pt_initial_pass(const struct pt_frame *fr, const struct gbuffer *g, struct pt_reservoir *out,
                          vec3 *emission)
{
    const struct scene *s = fr->s;
    const struct render_params *p = fr->p;
    const int paths = restir_pt_settings_of(p)->candidates;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct path_walk walk;
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            struct pt_reservoir *res = &out[i];
            pt_reservoir_clear(res, 0.0f); /* every pixel samples paths, even where the centre ray misses */
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_PT_INITIAL);
            struct initial_ctx ctx;
            ctx.s = s;
            ctx.shift = &fr->shift;
            restir_reservoir_init(&ctx.wrs);
            ctx.rng = &rng;
            ctx.inv_paths = 1.0f / (float)paths;
            ctx.r = res;
            ctx.chosen_here = 0;
            vec3 Le = v3s(0.0f);
            for (int n = 0; n < paths; n++) {
                ctx.trial.u[0] = p->jitter ? pcg32_float(&rng) : 0.5f;
                ctx.trial.u[1] = p->jitter ? pcg32_float(&rng) : 0.5f;
                const struct camera_sample cs = camera_sample_draw(fr->view, &rng);
                ctx.trial.lens[0] = cs.lens[0];
                ctx.trial.lens[1] = cs.lens[1];
                ctx.trial.time = cs.time;
                float px, py;
                path_image_position(x, y, ctx.trial.u, &px, &py);
                vec3 o, d;
                camera_sample_ray(fr->view, &cs, px, py, &o, &d);
                struct surface_hit hit;
                rays++;
                if (!scene_intersect(s, o, d, 0.0f, INFINITY, &hit)) {
                    Le = v3_add(Le, scene_env_radiance(s, d)); /* the sky seen through the pixel */
                    continue;
                }
                if (s->tri_emitter[hit.tri] >= 0 && hit.front)
                    Le = v3_add(Le, lights_radiance(s, hit.tri, hit.b1, hit.b2, v3_neg(d)));
                struct path_vertex x1 = path_vertex_from_hit(&hit, d);
                ctx.trial.seed = ((uint64_t)pcg32_next(&rng) << 32) | pcg32_next(&rng);
                rays += path_walk_run(s, &x1, ctx.trial.seed, render_params_light_choice(p), p->max_bounces,
                                      p->rr_bounces, &walk, offer_candidate, &ctx);
                keep_chosen(&ctx, &walk);
            }
            emission[i] = v3_scale(Le, ctx.inv_paths);
            res->c = (float)paths;
            if (ctx.wrs.selected >= 0) {
                /* W must divide by the p_hat the weights used (the walk's f); it is then a
                 * UCW for any integrand, and the reservoir caches the target as shifts
                 * evaluate it (path_sample_from_candidate), so reuse sees one definition. */
                res->W = restir_gris_contribution_weight(&ctx.wrs, ctx.resampling_target);
                res->target = v3_luminance(res->y.f);
            }
            if (!(res->W > 0.0f))
                pt_reservoir_clear(res, res->c);
        }
    }
    return rays;
}

/* ---- GRIS merge ------------------------------------------------------------------------------ */

/* A merge's domains and the rays its shifts trace (restir_gris_shift's ctx). */
struct merge_shift {
    const struct pt_frame *fr;
    const struct pt_domain *dom;
    long long rays;
};

static int merge_shift_path(void *vctx, const void *x, int from, int to, void *y, float *jacobian)
{
    struct merge_shift *m = vctx;
    return path_shift(m->fr->s, &m->fr->shift, x, &m->dom[from], &m->dom[to], y, jacobian, &m->rays);
}

/* p_hat = luminance of the path contribution, in whichever domain the path lives. */
static float merge_target(void *vctx, const void *y, int domain)
{
    (void)vctx;
    (void)domain;
    return v3_luminance(((const struct path_sample *)y)->f);
}

/* One GRIS merge into domain dom[0] (canonical, identity shift) of n reservoirs living in the
 * domains dom[j] (004 Eq. 5-7) under resampling MIS `mis`. P[k * n + j] = p_hat_{<-k}(Y_j) (004
 * Eq. 10): row 0 from the forward shifts, the diagonal from the cached target over the forward
 * Jacobian, the rest by shifting Y_j back into domain k. The output's confidence sums the inputs'
 * c_j times share[j] (NULL: 1 each) before the cap. */
static long long gris_merge(const struct pt_frame *fr, int n, const struct pt_domain *dom,
                            const struct pt_reservoir *const *in, enum restir_mis mis, const float *share, pcg32 *rng,
                            struct pt_reservoir *out, unsigned *shifted)
{
    const struct render_params *p = fr->p;
    struct merge_shift ctx = {fr, dom, 0};
    const struct restir_gris_shift shift = {merge_shift_path, merge_target, &ctx, sizeof(struct path_sample)};
    float c[PT_MAX_DOMAINS], J[PT_MAX_DOMAINS], P[PT_MAX_DOMAINS * PT_MAX_DOMAINS], cached[PT_MAX_DOMAINS];
    float W[PT_MAX_DOMAINS], u[PT_MAX_DOMAINS], W_Y, c_sum = 0.0f;
    const void *x[PT_MAX_DOMAINS];
    struct path_sample Y[PT_MAX_DOMAINS], z;
    for (int j = 0; j < n; j++) {
        c[j] = min_f(in[j]->c, p->reuse.confidence_cap); /* fminf is a libm call */
        c_sum += share ? share[j] * c[j] : c[j];
        x[j] = pt_reservoir_has_sample(in[j]) ? &in[j]->y : NULL;
        cached[j] = in[j]->target;
    }
    restir_gris_targets(mis, n, &shift, x, cached, Y, P, J, &z); /* 004 Eq. 10 */
    if (shifted) {
        *shifted = 0;
        for (int j = 0; j < n; j++)
            *shifted |= J[j] > 0.0f ? 1u << j : 0u;
    }
    for (int j = 0; j < n; j++) {
        W[j] = in[j]->W;
        u[j] = pcg32_float(rng);
    }
    const int chosen = restir_gris_resample(mis, n, c, P, W, J, u, &W_Y); /* 004 Eq. 5-7 */
    struct pt_reservoir result;
    pt_reservoir_clear(&result, restir_gris_confidence_merge(c_sum, p->reuse.confidence_cap));
    if (chosen >= 0) {
        result.y = Y[chosen];
        result.target = P[chosen];
        result.W = W_Y;
        if (!(result.W > 0.0f))
            pt_reservoir_clear(&result, result.c);
    }
    *out = result;
    return ctx.rays;
}

/* ---- temporal and spatial reuse ---------------------------------------------------------------- */

/* temporal.subpixel=search: pixel i's reservoir merged with those of the previous pixels its
 * square overlaps (gbuffer_history_square; Area ReSTIR Sec. 4.3.1). Their domains are translated
 * pixel squares that tile the image, so a path in the current pixel has exactly one previous
 * pixel q(y) that a clipped shift reaches, and p_hat_{<-k}(y) = 0 for every other k. mis=pairwise
 * merges by restir_mis_weights_pairwise_tiled (004 Eq. 11 over the current pixel and q(y)),
 * mis=balance by the balance heuristic over all of them (004 Eq. 9, which reduces to the same two
 * domains); both are partitions of unity wherever p_hat(y) > 0, hence unbiased (1/M stays 1/M,
 * BIASED). The merged confidence adds each previous confidence times its overlap area, what a
 * path drawn uniformly in the pixel meets on average. Returns bit 0: some previous pixel was
 * merged; bit j > 0: the path of merge input j reached pixel i. */
static unsigned temporal_search_merge(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                                      const struct pt_reservoir *prev_res, int i, struct pt_reservoir *io,
                                      long long *rays)
{
    const struct render_params *p = fr->p;
    struct gbuffer_history_cell cells[4];
    const int m = gbuffer_history_square(g, i, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane, cells);
    if (m == 0)
        return 0;
    struct pt_domain dom[5];
    const struct pt_reservoir *in[5] = {io};
    float share[5] = {1.0f};
    dom[0] = pt_pixel_domain(fr->view, i % g->width, i / g->width);
    dom[0].clip = 1;
    for (int k = 0; k < m; k++) {
        const int q = cells[k].q;
        dom[k + 1] = pt_pixel_domain(fr->prev_view, q % g->width, q / g->width);
        dom[k + 1].origin[0] = cells[k].origin[0];
        dom[k + 1].origin[1] = cells[k].origin[1];
        dom[k + 1].clip = 1;
        in[k + 1] = &prev_res[q];
        share[k + 1] = cells[k].area;
    }
    pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_PT_TEMPORAL);
    unsigned shifted;
    *rays += gris_merge(fr, m + 1, dom, in, render_params_tiled_mis(p), share, &rng, io, &shifted);
    return 1u | (shifted & ~1u);
}

long long pt_temporal_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct pt_reservoir *prev_res, struct pt_reservoir *io, long long *accepted,
                           unsigned char *flags)
{
    const struct render_params *p = fr->p;
    long long rays = 0, acc = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    int ox = 0, oy = 0; /* temporal.permutation (wrap only: permutation_validate): this frame's tile offset */
    const int permute = p->reuse.temporal_permutation;
    if (permute)
        gbuffer_permutation_offset(p->seed, fr->frame, &ox, &oy);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays, acc)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            flags[i] = 0;
            if (p->reuse.temporal_subpixel == TEMPORAL_SUBPIXEL_SEARCH) {
                unsigned shifted = temporal_search_merge(fr, g, prev_g, prev_res, i, &io[i], &rays);
                flags[i] = (unsigned char)(shifted & 1u ? TEMPORAL_BP_RECEIVED : 0) |
                           (unsigned char)(shifted & ~1u ? TEMPORAL_BP_ACCEPTED : 0);
                acc += shifted & 1u;
                continue;
            }
            const float nmin = p->reuse.temporal_normal, plane = p->reuse.temporal_plane;
            /* a permuted neighbour's domain is its own pixel square, moved by pixel i's motion as the
             * reprojected one's: a translation like a spatial neighbour's */
            int q = permute ? gbuffer_history_pixel_permuted(g, i, prev_g, nmin, plane, ox, oy)
                            : gbuffer_history_pixel(g, i, prev_g, nmin, plane);
            if (q < 0)
                continue;
            struct pt_domain dom[2];
            dom[0] = pt_pixel_domain(fr->view, x, y);
            dom[1] = pt_pixel_domain(fr->prev_view, q % w, q / w);
            if (p->jitter) {
                /* Area ReSTIR: a previous-frame offset moves with the fractional backward
                 * motion, a translation of the sub-pixel square (|T'| = 1). */
                dom[1].origin[0] -= g->motion[2 * i];
                dom[1].origin[1] -= g->motion[2 * i + 1];
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_PT_TEMPORAL);
            const struct pt_reservoir *in[2] = {&io[i], &prev_res[q]};
            unsigned shifted;
            rays += gris_merge(fr, 2, dom, in, p->reuse.mis, NULL, &rng, &io[i], &shifted);
            flags[i] = (unsigned char)(TEMPORAL_BP_RECEIVED | (shifted & 2u ? TEMPORAL_BP_ACCEPTED : 0));
            acc++;
        }
    }
    *accepted = acc;
    return rays;
}

/* Neighbors' reservoirs are read at random within the reuse radius, two cache lines each, and
 * their loads stalled the merge (half of this pass's own time in perf). Issuing them one pixel
 * ahead hides the latency behind the current pixel's shifts. */
static void prefetch_neighbors(const struct pt_reservoir *in, const int *list, int m)
{
    for (int k = 0; k < m; k++) {
        if (list[k] < 0)
            continue;
        const char *r = (const char *)&in[list[k]];
        __builtin_prefetch(r);
        __builtin_prefetch(r + sizeof(struct pt_reservoir) - 1);
    }
}

long long pt_spatial_pass(const struct pt_frame *fr, const struct gbuffer *g, const int *neighbors,
                          const struct pt_reservoir *in, struct pt_reservoir *out)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const int m = render_params_spatial_neighbors(p, 1); /* at most 5 = PT_MAX_DOMAINS - 1 (params.c) */
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            int next = tile_peek(&px);
            if (next >= 0)
                prefetch_neighbors(in, &neighbors[(size_t)next * m], m);
            if (!g->valid[i]) {
                out[i] = in[i];
                continue;
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_PT_SPATIAL);
            struct pt_domain dom[PT_MAX_DOMAINS];
            const struct pt_reservoir *src[PT_MAX_DOMAINS];
            dom[0] = pt_pixel_domain(fr->view, x, y);
            src[0] = &in[i];
            int n = 1;
            for (int k = 0; k < m; k++) {
                int j = neighbors[(size_t)i * m + k];
                if (j < 0)
                    continue;
                dom[n] = pt_pixel_domain(fr->view, j % w, j / w);
                src[n++] = &in[j];
            }
            rays += gris_merge(fr, n, dom, src, p->reuse.mis, NULL, &rng, &out[i], NULL);
        }
    }
    return rays;
}

void pt_shade_pass(const struct gbuffer *g, const struct pt_reservoir *res, const vec3 *emission, float *rgb)
{
    const int n = g->width * g->height;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        vec3 L = emission[i];
        if (pt_reservoir_has_sample(&res[i]))
            L = v3_add(L, v3_scale(res[i].y.f, res[i].W)); /* f(Y) W_Y */
        rgb[3 * i] = L.x;
        rgb[3 * i + 1] = L.y;
        rgb[3 * i + 2] = L.z;
    }
}

NONFINITE_DEFINE_DISCARD(nonfinite_discard_pt, struct pt_reservoir, pt_reservoir_clear)
