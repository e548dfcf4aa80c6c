/* di_initial.c: ReSTIR DI initial sampling: per pixel, RIS over light-sampled and BSDF-sampled
 * candidates combined by MIS into one reservoir (Bitterli et al. 2020; 001 Sec. 1). Light
 * candidates are windows of the frame's light pool (light_pool.h) or of ReGIR's cell slots
 * (regir.h), evaluated in batches laid out for SIMD. Must never allocate per pixel. */
#include "core/check.h"
#include "core/rng.h"
#include "core/simd.h"
#include "methods/restir_di/di_visibility.h"
#include "methods/restir_di/light_pool.h"
#include "methods/restir_di/regir.h"
#include "methods/restir_di/restir_di.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "scene/env_light.h"
#include "shading/light_tree.h"
#include "shading/lights.h"
#include "methods/restir_di/di_settings.h"

/* Light candidates are evaluated in batches of at most DI_BATCH. */
#define DI_BATCH 64

struct light_batch {
    float wx[DI_BATCH], wy[DI_BATCH], wz[DI_BATCH]; /* unit direction x -> y */
    float geo[DI_BATCH];                            /* cos_x cos_y / d^2, 0 when not facing */
    float to_area[DI_BATCH];                        /* cos_y / d^2: solid angle -> area at y */
    float fr[DI_BATCH], fg[DI_BATCH], fb[DI_BATCH], pdf[DI_BATCH]; /* BSDF value and pdf */
    float w[DI_BATCH];                              /* RIS weight */
};

/* The light point a BSDF ray hit (triangle tri, barycentrics b1, b2) as a DI sample. */
static void sample_at_hit(const struct scene *s, int tri, float b1, float b2, struct di_sample *y)
{
    struct light_sample ls;
    lights_point(s, tri, b1, b2, &ls);
    y->tri = ls.tri;
    y->b1 = ls.b1;
    y->b2 = ls.b2;
    y->p = ls.p;
    y->n = ls.n;
    y->Le = ls.Le;
}

/* RIS weights of the n light candidates at pool entries first .. first + n - 1:
 *   w = p_hat(y) / (N_light p_light(y) + N_bsdf p_bsdf(y))
 * (the balance heuristic over strategies with candidate counts, so W = sum w / p_hat(Y) is an
 * unbiased contribution weight). Every emitter point along a BSDF ray is a candidate (the BSDF
 * strategy traces the emitters-only BVH), so p_bsdf has no visibility term: both strategies are
 * unshadowed, their MIS weights sum to one wherever p_hat > 0, and W is valid on p_hat's whole
 * support (visibility reuse then narrows it to that of p_hat V). The loops read only contiguous
 * arrays, so they vectorize. */
SIMD_INLINE void light_batch_fill_body(const struct light_pool *lp, int first, const struct shading_point *sp,
                                       int n, int nl, int nb, struct light_batch *lb)
{
    const float *restrict px = lp->px + first, *restrict py = lp->py + first, *restrict pz = lp->pz + first;
    const float *restrict nx = lp->nx + first, *restrict ny = lp->ny + first, *restrict nz = lp->nz + first;
    const float *restrict at_point = lp->at_point + first;
    const vec3 x = sp->p, n_s = sp->n, n_g = sp->ng;
    for (int k = 0; k < n; k++) {
        /* an environment entry (at_point 0) holds its direction: x drops out, d2 ~ 1, cos_y = 1,
         * so to_area is 1 and its weights stay in solid angle, the measure of its pdf */
        const float m = at_point[k];
        float dx = px[k] - x.x * m, dy = py[k] - x.y * m, dz = pz[k] - x.z * m;
        float d2 = max_f(dx * dx + dy * dy + dz * dz, 1e-30f), inv_d = 1.0f / sqrtf(d2);
        dx *= inv_d;
        dy *= inv_d;
        dz *= inv_d;
        float cos_x = n_s.x * dx + n_s.y * dy + n_s.z * dz;
        float cos_g = n_g.x * dx + n_g.y * dy + n_g.z * dz;
        float cos_y = -(nx[k] * dx + ny[k] * dy + nz[k] * dz);
        float facing = (cos_x > 0.0f && cos_y > 0.0f && cos_g > 0.0f) ? 1.0f : 0.0f;
        lb->wx[k] = dx;
        lb->wy[k] = dy;
        lb->wz[k] = dz;
        lb->to_area[k] = facing * cos_y * inv_d * inv_d;
        lb->geo[k] = lb->to_area[k] * cos_x;
    }
    bsdf_frame_eval_batch(&sp->bf, n, lb->wx, lb->wy, lb->wz, lb->fr, lb->fg, lb->fb, lb->pdf);
    const float *restrict Lr = lp->Lr + first, *restrict Lg = lp->Lg + first, *restrict Lb = lp->Lb + first;
    const float *restrict pdf_light = lp->pdf + first;
    const float fnl = (float)nl, fnb = (float)nb;
    if (lp->W) { /* ReGIR's slots: w = p_hat W q / (N_light q + N_bsdf p_bsdf) (regir.h) */
        const float *restrict W = lp->W + first;
        for (int k = 0; k < n; k++) {
            float target = lb->geo[k] * (0.2126f * Lr[k] * lb->fr[k] + 0.7152f * Lg[k] * lb->fg[k] +
                                         0.0722f * Lb[k] * lb->fb[k]);
            float denom = fnl * pdf_light[k] + fnb * lb->pdf[k] * lb->to_area[k];
            /* W q first: W can be large where q is small (a slot of a rarely drawn light) */
            lb->w[k] = target > 0.0f && W[k] > 0.0f ? target * (W[k] * pdf_light[k]) / denom : 0.0f;
        }
        return;
    }
    for (int k = 0; k < n; k++) {
        float target = lb->geo[k] * (0.2126f * Lr[k] * lb->fr[k] + 0.7152f * Lg[k] * lb->fg[k] +
                                     0.0722f * Lb[k] * lb->fb[k]);
        float denom = fnl * pdf_light[k] + fnb * lb->pdf[k] * lb->to_area[k];
        lb->w[k] = target > 0.0f ? target / denom : 0.0f;
    }
}

/* Picks index k with probability w_k / sum w by one uniform (inverse CDF over the prefix sums):
 * the same distribution as streaming reservoir sampling over the batch, with one random number
 * instead of n. Branch-free, since which weights are zero and where u lands are unpredictable:
 * k is the number of prefix sums at or below u * total (a zero weight never ends the count), or
 * the last positive weight when rounding puts u * total past the float sum. Writes the total;
 * returns -1 when it is 0. */
SIMD_INLINE int pick_by_weight_body(const float *w, int n, float u, float *total)
{
    RESTIR_CHECK(n <= DI_BATCH);
    float acc[DI_BATCH], sum = 0.0f;
    int last = -1;
    for (int k = 0; k < n; k++) {
        sum += w[k];
        acc[k] = sum;
        last = w[k] > 0.0f ? k : last;
    }
    *total = sum;
    if (!(sum > 0.0f))
        return -1;
    const float x = u * sum;
    int below = 0;
    for (int k = 0; k < n; k++)
        below += acc[k] <= x;
    return below < n ? below : last;
}

/* The two kernels above for the build's baseline and for AVX2, chosen at run time (core/simd.h):
 * the same operations, so the same bits. */
static void light_batch_fill_baseline(const struct light_pool *lp, int first, const struct shading_point *sp, int n,
                                      int nl, int nb, struct light_batch *lb)
{
    light_batch_fill_body(lp, first, sp, n, nl, nb, lb);
}

SIMD_TARGET_AVX2 static void light_batch_fill_avx2(const struct light_pool *lp, int first,
                                                   const struct shading_point *sp, int n, int nl, int nb,
                                                   struct light_batch *lb)
{
    light_batch_fill_body(lp, first, sp, n, nl, nb, lb);
}

static void light_batch_fill(const struct light_pool *lp, int first, const struct shading_point *sp, int n, int nl,
                             int nb, struct light_batch *lb)
{
    if (simd_isa_active() >= SIMD_ISA_AVX2)
        light_batch_fill_avx2(lp, first, sp, n, nl, nb, lb);
    else
        light_batch_fill_baseline(lp, first, sp, n, nl, nb, lb);
}

static int pick_by_weight_baseline(const float *w, int n, float u, float *total)
{
    return pick_by_weight_body(w, n, u, total);
}

SIMD_TARGET_AVX2 static int pick_by_weight_avx2(const float *w, int n, float u, float *total)
{
    return pick_by_weight_body(w, n, u, total);
}

static int pick_by_weight(const float *w, int n, float u, float *total)
{
    return simd_isa_active() >= SIMD_ISA_AVX2 ? pick_by_weight_avx2(w, n, u, total)
                                              : pick_by_weight_baseline(w, n, u, total);
}

/* di.initial=bvh: a batch of the pixel's own light candidates, drawn down the light BVH at its point
 * with its normal (light_tree.h, the choice pt makes with lights.select=bvh), in the pool's layout so
 * that the same kernel weighs them; pdf holds the mixture's density, (1 - env_prob) P_tree(e) / A_e
 * for an emitter point. */
struct pixel_batch {
    int tri[DI_BATCH];
    float b1[DI_BATCH], b2[DI_BATCH], px[DI_BATCH], py[DI_BATCH], pz[DI_BATCH], nx[DI_BATCH], ny[DI_BATCH],
        nz[DI_BATCH], Lr[DI_BATCH], Lg[DI_BATCH], Lb[DI_BATCH], pdf[DI_BATCH], at_point[DI_BATCH];
};

static struct light_pool pixel_batch_view(struct pixel_batch *pb)
{
    return (struct light_pool){.size = DI_BATCH, .window = DI_BATCH, .tri = pb->tri, .b1 = pb->b1, .b2 = pb->b2,
                               .px = pb->px, .py = pb->py, .pz = pb->pz, .nx = pb->nx, .ny = pb->ny, .nz = pb->nz,
                               .Lr = pb->Lr, .Lg = pb->Lg, .Lb = pb->Lb, .pdf = pb->pdf, .at_point = pb->at_point};
}

/* Draws n candidates into view: with an environment, a direction from its sampler with probability
 * env_prob, else an emitter down the tree (a null candidate where the descent finds none, so that
 * an emitter's probability is light_tree_pmf's, to the resolution one 24-bit uniform gives the
 * whole descent, as in pt) and a point uniform on it. */
static void pixel_batch_draw(struct light_pool *view, const struct scene *s, const struct shading_point *sp, int n,
                             pcg32 *rng)
{
    for (int k = 0; k < n; k++) {
        float u0 = pcg32_float(rng);
        const float u1 = pcg32_float(rng), u2 = pcg32_float(rng);
        if (s->env && u0 < s->env_prob) {
            light_pool_put_env(view, s, k, u1, u2);
            continue;
        }
        if (s->env)
            u0 = min_f((u0 - s->env_prob) / (1.0f - s->env_prob), 0x1.fffffep-1f);
        float pmf = 0.0f;
        const int e = s->num_emitters > 0 ? light_tree_sample(&s->light_bvh, sp->p, sp->n, u0, &pmf) : -1;
        if (e < 0) {
            light_pool_put_empty(view, k, sp->p);
            continue;
        }
        float b1, b2;
        warp_uniform_triangle(u1, u2, &b1, &b2);
        light_pool_put_emitter(view, s, k, &s->emitters[e], b1, b2);
        view->pdf[k] = (1.0f - s->env_prob) * pmf / s->tri_area[s->emitters[e].tri];
    }
}

/* The light density that the MIS weights of a BSDF candidate on emitter triangle tri use: the pool's
 * (power sampling), with ReGIR the source density of the pixel's cell (regir_light_pdf), with bvh
 * the tree's at the pixel's point (pixel_batch_draw's). */
static float light_pdf_for_bsdf_hit(const struct scene *s, const struct regir_grid *rg, const struct di_settings *ds,
                                    const struct shading_point *sp, int block, int tri)
{
    if (rg)
        return regir_light_pdf(rg, s, ds, block, tri);
    if (ds->initial == DI_INITIAL_BVH) {
        const int e = tri >= 0 && tri < s->num_tris ? s->tri_emitter[tri] : -1;
        if (e < 0)
            return 0.0f;
        return (1.0f - s->env_prob) * light_tree_pmf(&s->light_bvh, sp->p, sp->n, e) / s->tri_area[tri];
    }
    return lights_pdf_area(s, tri) * (1.0f - s->env_prob);
}

static void initial_pixel(const struct scene *s, const struct light_pool *pool, const struct regir_grid *rg,
                          const struct render_params *p, const struct shading_point *sp, pcg32 *rng,
                          struct di_reservoir *r, long long *rays)
{
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    di_reservoir_clear(r, 1.0f);
    const struct di_settings *ds = di_settings_of(p);
    const int nl = s->num_emitters > 0 || s->env ? ds->light_candidates : 0, nb = ds->bsdf_candidates;
    struct light_batch lb;
    /* this pixel's nl candidates: a window of the pool, of its cell's slots, or its own draws */
    const int own = ds->initial == DI_INITIAL_BVH && !rg;
    struct pixel_batch pb;
    struct light_pool own_view = pixel_batch_view(&pb);
    const int block = rg ? regir_block_of(rg, sp->p) : -1;
    const struct light_pool *lp = rg ? &rg->store : own ? &own_view : pool;
    int offset = 0;
    if (nl && !own)
        offset = rg ? regir_window_first(rg, block, pcg32_float(rng)) : light_pool_offset(pcg32_float(rng));
    for (int done = 0; done < nl; done += DI_BATCH) {
        int n = nl - done < DI_BATCH ? nl - done : DI_BATCH, first = offset + done;
        if (own) {
            pixel_batch_draw(&own_view, s, sp, n, rng);
            first = 0;
        }
        light_batch_fill(lp, first, sp, n, nl, nb, &lb);
        struct restir_reservoir batch;
        restir_reservoir_init(&batch);
        batch.offered = n;
        batch.selected = pick_by_weight(lb.w, n, pcg32_float(rng), &batch.w_sum);
        if (restir_reservoir_merge(&wrs, &batch, pcg32_float(rng))) {
            struct di_sample *y = &r->y;
            light_pool_entry(lp, first + batch.selected, &y->tri, &y->b1, &y->b2, &y->p, &y->n, &y->Le);
        }
    }
    for (int k = 0; k < nb; k++) {
        vec3 wi, f;
        float pdf;
        float u0 = pcg32_float(rng), u1 = pcg32_float(rng), u2 = pcg32_float(rng);
        if (!bsdf_frame_sample(&sp->bf, u0, u1, u2, &wi, &pdf, &f) || v3_dot(wi, sp->ng) <= 0.0f)
            continue;
        vec3 o = scene_offset_point(sp->p, sp->ng, wi);
        float tmin = 0.0f;
        struct surface_hit h;
        /* Every emitter point along the ray is a candidate of this strategy, however many lie in
         * front of it: the light candidates' MIS weights count p_bsdf for all of them, so a cap on the
         * hits would drop the far ones' share (a bias wherever reuse carries them to a pixel that sees
         * them). tmin grows strictly, so the walk ends after at most one hit per emitter triangle. */
        while (scene_intersect_emitters(s, o, wi, tmin, INFINITY, &h)) {
            (*rays)++;
            tmin = h.t * (1.0f + 1e-5f) + 1e-6f;
            if (!h.front)
                continue;
            struct di_sample y;
            sample_at_hit(s, h.tri, h.b1, h.b2, &y);
            float p_bsdf;
            float target = v3_luminance(di_unshadowed_pdf(sp, &y, &p_bsdf));
            if (target <= 0.0f)
                continue;
            float p_light = nl ? light_pdf_for_bsdf_hit(s, rg, ds, sp, block, h.tri) : 0.0f;
            float w = target / ((float)nl * p_light + (float)nb * p_bsdf);
            if (restir_reservoir_offer(&wrs, w, pcg32_float(rng)))
                r->y = y;
        }
        (*rays)++; /* the final ray that left the emitters */
        if (s->env) { /* the direction itself is the BSDF strategy's environment candidate */
            struct di_sample y;
            y.tri = DI_ENV_TRI;
            y.b1 = y.b2 = 0.0f;
            y.p = wi;
            y.n = v3_neg(wi);
            y.Le = environment_radiance(s->env, wi);
            float p_bsdf;
            float target = v3_luminance(di_unshadowed_pdf(sp, &y, &p_bsdf));
            if (target > 0.0f) {
                float p_light = nl ? s->env_prob * env_pdf(s->env_sampler, wi) : 0.0f;
                float w = target / ((float)nl * p_light + (float)nb * p_bsdf);
                if (restir_reservoir_offer(&wrs, w, pcg32_float(rng)))
                    r->y = y;
            }
        }
    }
    if (wrs.selected < 0)
        return;
    /* The selected sample's target is evaluated once more by the scalar path that reuse uses,
     * so the cached value and every later evaluation agree exactly. */
    r->target = di_target(sp, &r->y);
    r->W = restir_gris_contribution_weight(&wrs, r->target);
    if (r->W <= 0.0f)
        di_reservoir_clear(r, 1.0f);
}

long long di_initial_pass(const struct scene *s, const struct light_pool *lp, const struct regir_grid *rg,
                          const struct render_params *p, int frame, const struct gbuffer *g, struct di_reservoir *out)
{
    const struct di_settings *ds = di_settings_of(p);
    /* the pool's (or the cells') windows are that long */
    RESTIR_CHECK(ds->light_candidates <= (rg ? rg->window : lp->window));
    long long rays = 0;
    const int ntiles = tile_count(g->width, g->height);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        int pixel[RESTIR_TILE_W * RESTIR_TILE_H], n = 0;
        struct ray_query q[RESTIR_TILE_W * RESTIR_TILE_H];
        for (struct tile_pixel px = tile_first_pixel(g->width, g->height, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            const struct shading_point *sp = gbuffer_shading(g, i);
            if (!sp->valid) {
                di_reservoir_clear(&out[i], 0.0f);
                continue;
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_DI_INITIAL);
            initial_pixel(s, lp, rg, p, sp, &rng, &out[i], &rays);
            /* Visibility reuse (Bitterli et al. 2020, Alg. 5): a one-candidate resampling step to
             * the target p_hat V. A visible Y keeps W (p_hat V = p_hat there); an occluded one is
             * dropped while the confidence stays 1, so W remains an unbiased contribution weight
             * for p_hat V. The tile's shadow rays are traced together, as one stream, below. */
            if (ds->visibility_reuse && out[i].W > 0.0f) {
                rays++;
                if (di_visibility_query(sp, &out[i].y, &q[n]))
                    pixel[n++] = i;
            }
        }
        unsigned char occluded[RESTIR_TILE_W * RESTIR_TILE_H];
        scene_occluded_batch(s, q, n, occluded);
        for (int k = 0; k < n; k++)
            if (occluded[k])
                di_reservoir_clear(&out[pixel[k]], 1.0f);
    }
    return rays;
}
