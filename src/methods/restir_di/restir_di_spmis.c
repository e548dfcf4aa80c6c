/* restir_di_spmis.c: stochastic pairwise MIS spatial reuse for ReSTIR DI (004 Algorithm 2): the
 * canonical weight m~_c from N_c cell pixels (Eq. 18-19), then a GRIS merge of the canonical light
 * sample and N samples drawn by Eq. 17 (Eq. 14-16). Light samples need no shift (identity, |J| = 1).
 * Both passes queue a tile's targets and evaluate them together, as restir_di.c's reuse does (SIMD across
 * pixels, shadow rays as Embree streams), then finish each pixel in order with its own random stream, so the
 * result is the same as one pixel at a time. Must never allocate per pixel (one queue per thread and pass). */
#include <stdlib.h>

#include "core/check.h"
#include "methods/restir_di/di_visibility.h"
#include "methods/restir_di/restir_di.h"
#include "render/reuse_cells.h"
#include "render/tiles.h"
#include "restir/gris.h"

static int has_sample(const struct di_reservoir *r) { return r->y.tri >= 0 && r->W > 0.0f; }

void di_spmis_weights(const struct render_params *p, const struct gbuffer *g, const struct di_reservoir *in,
                      struct spmis_frame *f)
{
    const int n = g->width * g->height;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        f->conf[i] = fminf(in[i].c, p->reuse.confidence_cap);
        /* 004 Eq. 17: c_i p_hat(X_i) W_i with the target cached in pixel i */
        f->weight[i] = has_sample(&in[i]) ? f->conf[i] * in[i].target * in[i].W : 0.0f;
    }
}

struct di_canonical_ctx {
    const struct scene *s;
    const struct gbuffer *g;
    const struct di_reservoir *in;
    int with_visibility;
};

static int di_canonical_has_sample(const void *ctx, int c)
{
    return has_sample(&((const struct di_canonical_ctx *)ctx)->in[c]);
}

static float di_canonical_target(const void *ctx, int c)
{
    return ((const struct di_canonical_ctx *)ctx)->in[c].target;
}

/* Eq. 19 with p_hat_{<-i}(Y_c) = pixel i's target at the same light point (no shift, |J| = 1) */
static float di_canonical_target_from(const void *ctx, int c, int i, long long *rays)
{
    const struct di_canonical_ctx *k = ctx;
    return di_domain_target(k->s, k->with_visibility, gbuffer_shading(k->g, i), &k->in[c].y, rays);
}

/* di_canonical_target_from for n pairs at once (SIMD across the pairs, shadow rays as streams), in
 * chunks whose scratch fits the stack. */
#define DI_CANONICAL_CHUNK 256
static void di_canonical_targets_from(const void *ctx, int n, const int *c, const int *i, float *out,
                                      long long *rays)
{
    const struct di_canonical_ctx *k = ctx;
    const struct shading_point *sp[DI_CANONICAL_CHUNK];
    const struct di_sample *y[DI_CANONICAL_CHUNK];
    struct ray_query q[DI_CANONICAL_CHUNK];
    int ray_entry[DI_CANONICAL_CHUNK];
    unsigned char occluded[DI_CANONICAL_CHUNK];
    for (int first = 0; first < n; first += DI_CANONICAL_CHUNK) {
        const int m = n - first < DI_CANONICAL_CHUNK ? n - first : DI_CANONICAL_CHUNK;
        for (int e = 0; e < m; e++) {
            sp[e] = gbuffer_shading(k->g, i[first + e]);
            y[e] = &k->in[c[first + e]].y;
        }
        *rays += di_domain_target_many(k->s, k->with_visibility, m, sp, y, out + first, NULL, q, ray_entry, occluded);
    }
}

long long di_spmis_canonical_pass(const struct scene *s, const struct render_params *p, int frame,
                                  const struct gbuffer *g, const struct di_reservoir *in, struct spmis_frame *f)
{
    const struct di_canonical_ctx ctx = {s, g, in, di_targets_visible(p)};
    const struct spmis_canonical_ops ops = {&ctx, di_canonical_has_sample, di_canonical_target,
                                            di_canonical_target_from, di_canonical_targets_from};
    return spmis_canonical_pass(f, p, frame, g, &ops);
}

/* Merges of the reuse pass waiting for their drawn samples' targets p_hat_c(X_z) (Algorithm 2
 * line 15), queued like restir_di.c's merges so that a tile's targets are evaluated together:
 * at most a tile's merges, and draws enough for the largest plan several times over. */
#define REUSE_QUEUE_MERGES (RESTIR_TILE_W * RESTIR_TILE_H)
#define REUSE_QUEUE_DRAWS (4 * RESTIR_SPMIS_MAX_DRAWS)
struct reuse_merge {
    int c, end; /* the canonical pixel; its draws end at entry `end` */
    float merged_c;
    struct restir_spmis_conf k;
    pcg32 rng; /* the pixel's stream after its draws: it drives the merge's WRS as before */
};
struct reuse_queue {
    int merges, draws;
    struct reuse_merge mg[REUSE_QUEUE_MERGES];
    int z[REUSE_QUEUE_DRAWS];
    double factor[REUSE_QUEUE_DRAWS];
    const struct shading_point *sp[REUSE_QUEUE_DRAWS];
    const struct di_sample *y[REUSE_QUEUE_DRAWS];
    float p_c[REUSE_QUEUE_DRAWS];
    struct ray_query q[REUSE_QUEUE_DRAWS]; /* scratch of di_domain_target_many */
    int ray_entry[REUSE_QUEUE_DRAWS];
    unsigned char occluded[REUSE_QUEUE_DRAWS];
};

/* Algorithm 2 lines 11-19 for one queued merge whose targets are final. */
static void reuse_merge_end(struct reuse_merge *mg, const struct reuse_queue *q, int first,
                            const struct di_reservoir *in, const struct spmis_frame *f, struct di_reservoir *out)
{
    const int c = mg->c;
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    struct di_reservoir result;
    di_reservoir_clear(&result, mg->merged_c);
    /* Lines 11-12: w~_c = m~_c p_hat(X_c) W_c (Eq. 14) */
    if (has_sample(&in[c]) &&
        restir_reservoir_offer(&wrs, restir_gris_resampling_weight(f->m_c[c], in[c].target, in[c].W, 1.0f),
                               pcg32_float(&mg->rng))) {
        result.y = in[c].y;
        result.target = in[c].target;
    }
    for (int e = first; e < mg->end; e++) {
        /* Lines 13-18 (line 15: the drawn neighbor's own sample X_z comes to pixel c) */
        const int z = q->z[e];
        const float p_c = q->p_c[e]; /* p_hat(y) */
        float wz = (float)(restir_spmis_noncanonical(&mg->k, f->conf[z], in[z].target, p_c, q->factor[e]) * p_c *
                           in[z].W);
        if (restir_reservoir_offer(&wrs, wz, pcg32_float(&mg->rng))) {
            result.y = in[z].y;
            result.target = p_c;
        }
    }
    result.W = restir_gris_contribution_weight(&wrs, result.target); /* line 19, Eq. 7 */
    if (!(result.W > 0.0f))
        di_reservoir_clear(&result, result.c);
    out[c] = result;
}

/* Evaluates the queued draws' targets across the merges at once (SIMD, shadow rays as streams),
 * then finishes the merges in order. Returns the rays counted. */
static long long reuse_flush(struct reuse_queue *q, const struct scene *s, int with_visibility,
                             const struct di_reservoir *in, const struct spmis_frame *f, struct di_reservoir *out)
{
    long long rays = di_domain_target_many(s, with_visibility, q->draws, q->sp, q->y, q->p_c, NULL, q->q, q->ray_entry,
                                           q->occluded);
    for (int j = 0, first = 0; j < q->merges; first = q->mg[j++].end)
        reuse_merge_end(&q->mg[j], q, first, in, f, out);
    q->merges = q->draws = 0;
    return rays;
}

long long di_spmis_reuse_pass(const struct scene *s, const struct render_params *p, int frame, const struct gbuffer *g,
                              const struct di_reservoir *in, const struct spmis_frame *f, struct di_reservoir *out)
{
    const int with_visibility = di_targets_visible(p);
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel reduction(+ : rays)
    {
        struct reuse_queue *q = xmalloc(sizeof(*q)); /* one per thread and pass */
        q->merges = q->draws = 0;
        struct restir_spmis_draws draws;
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < ntiles; t++) {
            for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
                const int c = px.i;
                if (!g->valid[c]) {
                    out[c] = in[c];
                    continue;
                }
                struct reuse_merge mg;
                mg.c = c;
                mg.rng = spmis_neighbor_plan(f, p, frame, c, &mg.k, &mg.merged_c, &draws);
                spmis_prefetch_draws(&draws, in, sizeof in[0]);
                if (q->merges == REUSE_QUEUE_MERGES || q->draws + draws.count > REUSE_QUEUE_DRAWS)
                    rays += reuse_flush(q, s, with_visibility, in, f, out);
                const struct shading_point *sp = gbuffer_shading(g, c);
                for (int d = 0; d < draws.count; d++) {
                    q->z[q->draws] = draws.pixel[d];
                    q->factor[q->draws] = draws.factor[d];
                    q->sp[q->draws] = sp;
                    q->y[q->draws++] = &in[draws.pixel[d]].y;
                }
                mg.end = q->draws;
                q->mg[q->merges++] = mg;
            }
            rays += reuse_flush(q, s, with_visibility, in, f, out);
        }
        free(q);
    }
    return rays;
}
