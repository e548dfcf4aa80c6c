/* reuse_cells.c: SPMIS reuse cells, cell search and the canonical weight pass (see reuse_cells.h;
 * 004 Sec. 5, Algorithms 1-2, Sec. 5.1). Must never allocate per frame or see a sample type. */
#include "render/reuse_cells.h"

#include <stdlib.h>

#include "core/check.h"
#include "render/tiles.h"
#include "restir/gris.h"

/* n uniforms into u, n clamped to cap (the size of u): params.c bounds every count by it already. */
static void uniforms(pcg32 *rng, int n, float *u, int cap)
{
    if (n > cap)
        n = cap;
    for (int j = 0; j < n; j++)
        u[j] = pcg32_float(rng);
}

void spmis_frame_init(struct spmis_frame *f, const struct render_params *p)
{
    size_t n = (size_t)p->width * (size_t)p->height;
    RESTIR_CHECK(restir_cells_init(&f->cells, p->width, p->height, p->spmis.tile) == 0);
    f->key = xcalloc(n, sizeof(uint32_t));
    f->conf = xcalloc(n, sizeof(float));
    f->weight = xcalloc(n, sizeof(float));
    f->cell = xcalloc(n, sizeof(int));
    f->m_c = xcalloc(n, sizeof(float));
}

void spmis_frame_fini(struct spmis_frame *f)
{
    restir_cells_fini(&f->cells);
    free(f->key);
    free(f->conf);
    free(f->weight);
    free(f->cell);
    free(f->m_c);
}

void spmis_cells_pass(struct spmis_frame *f, const struct render_params *p, const struct gbuffer *g)
{
    const int w = g->width, n = g->width * g->height, tile = p->spmis.tile;
    const int tiles_x = f->cells.tiles_x;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        if (!g->valid[i])
            continue;
        int x = i % w, y = i / w;
        uint32_t t = (uint32_t)((y / tile) * tiles_x + x / tile);
        const float n3[3] = {g->normal[i].x, g->normal[i].y, g->normal[i].z};
        f->key[i] = restir_cells_key(t, g->object[i], n3, p->spmis.normal_bins);
    }
    restir_cells_build(&f->cells, f->key, g->valid, f->conf, f->weight);
    restir_cells_pack_taps(&f->cells, (const float *)(const void *)g->normal, g->object); /* vec3: 3 floats */
}

void spmis_search_pass(struct spmis_frame *f, const struct render_params *p, const struct gbuffer *g, int frame)
{
    const struct restir_cells *cells = &f->cells;
    const struct restir_cells_search s = {p->spmis.search_steps,
                                         p->spmis.search_radius,
                                         p->spmis.search_growth,
                                         p->spmis.search_normal,
                                         p->spmis.search_score,
                                         (const float *)(const void *)g->position, /* vec3: 3 floats */
                                         g->depth,
                                         p->reuse.spatial_omega,
                                         p->reuse.spatial_beta};
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    /* In tiles (64 x 4 pixels), so that neighbouring pixels' near taps share cache lines; each
     * pixel's draws come from its own stream, so the order changes no result. */
#pragma omp parallel for schedule(dynamic, 1)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i, own = cells->cell_of[i];
            if (own < 0 || s.steps == 0) {
                f->cell[i] = own;
                continue;
            }
            if (p->spmis.search == SPMIS_SEARCH_SPARSE && cells->contributing[own] > p->spmis.sparse_count) {
                f->cell[i] = own; /* BIASED: the count depends on the samples (params help) */
                continue;
            }
            if (p->spmis.search == SPMIS_SEARCH_LOW_CONFIDENCE &&
                cells->conf_sum[own] >= p->spmis.search_confidence * (float)cells->count[own]) {
                f->cell[i] = own; /* the own cell holds history: no need to look farther (reads c only) */
                continue;
            }
            float u[3 * SPMIS_MAX_SEARCH_STEPS];
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_CELL_SEARCH);
            uniforms(&rng, 3 * s.steps, u, 3 * SPMIS_MAX_SEARCH_STEPS);
            f->cell[i] = restir_cells_search_packed(cells, &s, i, u);
        }
    }
}

/* Returns M, the number of the cell's other pixels. */
/* The confidences of pixel c's merge; *merged (may be NULL) gets the confidence its output
 * reservoir keeps (see spmis_neighbor_plan). */
static void spmis_pixel_conf(const struct spmis_frame *f, const struct render_params *p, int c,
                             struct restir_spmis_conf *k, float *merged)
{
    int cell = f->cell[c];
    int m = restir_cells_others(&f->cells, cell, c);
    float c_sigma = restir_cells_confidence_others(&f->cells, cell, c, f->conf);
    float scale = restir_spmis_confidence_scale(p->spmis.candidates, m, p->spmis.confidence_adjust);
    restir_spmis_conf_set(k, f->conf[c], c_sigma, scale);
    if (merged) {
        float evaluated = restir_spmis_confidence_scale(p->spmis.candidates, m, 1); /* min(1, N / M) */
        *merged = restir_gris_confidence_merge(f->conf[c] + evaluated * c_sigma, p->reuse.confidence_cap);
    }
}

void spmis_canonical_plan(const struct spmis_frame *f, const struct render_params *p, int frame, int c,
                          struct restir_spmis_conf *k, struct restir_spmis_draws *draws)
{
    spmis_pixel_conf(f, p, c, k, NULL);
    pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)c, RNG_PASS_SPMIS_CANONICAL);
    float u[RESTIR_SPMIS_MAX_DRAWS];
    uniforms(&rng, p->spmis.canonical_candidates, u, RESTIR_SPMIS_MAX_DRAWS);
    restir_spmis_canonical_draws(&f->cells, f->cell[c], c, p->spmis.canonical_candidates,
                                 (enum restir_spmis_pick)p->spmis.canonical_pick, u, draws);
}

/* The confidences of the distinct pixels among the draws (with replacement, a pixel may repeat). */
static float drawn_confidence(const struct spmis_frame *f, const struct restir_spmis_draws *draws)
{
    float sum = 0.0f;
    for (int d = 0; d < draws->count; d++) {
        int seen = 0;
        for (int e = 0; e < d && !seen; e++)
            seen = draws->pixel[e] == draws->pixel[d];
        if (!seen)
            sum += f->conf[draws->pixel[d]];
    }
    return sum;
}

pcg32 spmis_neighbor_plan(const struct spmis_frame *f, const struct render_params *p, int frame, int c,
                          struct restir_spmis_conf *k, float *merged, struct restir_spmis_draws *draws)
{
    spmis_pixel_conf(f, p, c, k, merged);
    pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)c, RNG_PASS_SPMIS_REUSE);
    float u[RESTIR_SPMIS_MAX_DRAWS];
    uniforms(&rng, p->spmis.candidates, u, RESTIR_SPMIS_MAX_DRAWS);
    restir_spmis_neighbor_draws(&f->cells, f->cell[c], c, p->spmis.candidates, u, draws);
    /* The drawn pixels depend on the samples (Eq. 17), but a confidence only weights later merges,
     * whose pairwise weights sum to 1 for any confidences: unbiased either way. */
    if (merged && p->spmis.confidence_update == SPMIS_CONFIDENCE_DRAWN)
        *merged = restir_gris_confidence_merge(f->conf[c] + drawn_confidence(f, draws), p->reuse.confidence_cap);
    return rng;
}

/* Pixels waiting for their Eq. 19 targets in the canonical pass: at most a tile's pixels, and
 * draws enough for the largest plan (RESTIR_SPMIS_MAX_DRAWS) several times over. */
#define CANONICAL_QUEUE_PIXELS (RESTIR_TILE_W * RESTIR_TILE_H)
#define CANONICAL_QUEUE_DRAWS (4 * RESTIR_SPMIS_MAX_DRAWS)
struct canonical_queue {
    int pixels, draws;
    int pixel[CANONICAL_QUEUE_PIXELS], end[CANONICAL_QUEUE_PIXELS]; /* pixel j's draws end at end[j] */
    struct restir_spmis_conf k[CANONICAL_QUEUE_PIXELS];
    int c[CANONICAL_QUEUE_DRAWS], i[CANONICAL_QUEUE_DRAWS]; /* draw e: p_hat_{<-i[e]}(Y_{c[e]}) */
    double factor[CANONICAL_QUEUE_DRAWS];
    float p_from[CANONICAL_QUEUE_DRAWS];
};

/* Evaluates the queued draws' targets, then m~_c of each queued pixel (Eq. 18, the terms of Eq. 19
 * summed in draw order). Returns the rays traced. */
static long long canonical_flush(struct canonical_queue *q, struct spmis_frame *f,
                                 const struct spmis_canonical_ops *ops)
{
    long long rays = 0;
    if (ops->targets_from)
        ops->targets_from(ops->ctx, q->draws, q->c, q->i, q->p_from, &rays);
    else
        for (int e = 0; e < q->draws; e++)
            q->p_from[e] = ops->target_from(ops->ctx, q->c[e], q->i[e], &rays);
    for (int j = 0, e = 0; j < q->pixels; j++) {
        const int c = q->pixel[j];
        const float p_c = ops->target(ops->ctx, c);
        double m_c = restir_spmis_canonical_share(&q->k[j]);
        for (; e < q->end[j]; e++) /* Eq. 19 */
            m_c += restir_spmis_canonical_term(&q->k[j], f->conf[q->i[e]], q->p_from[e], p_c, q->factor[e]);
        f->m_c[c] = (float)m_c; /* Eq. 18 */
    }
    q->pixels = q->draws = 0;
    return rays;
}

long long spmis_canonical_pass(struct spmis_frame *f, const struct render_params *p, int frame,
                               const struct gbuffer *g, const struct spmis_canonical_ops *ops)
{
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel reduction(+ : rays)
    {
        struct canonical_queue *q = xmalloc(sizeof(*q)); /* one per thread and pass */
        q->pixels = q->draws = 0;
        struct restir_spmis_draws draws;
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < ntiles; t++) {
            for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
                const int c = px.i;
                f->m_c[c] = 1.0f;
                if (!g->valid[c] || !ops->has_sample(ops->ctx, c))
                    continue;
                struct restir_spmis_conf k;
                spmis_canonical_plan(f, p, frame, c, &k, &draws);
                if (q->pixels == CANONICAL_QUEUE_PIXELS || q->draws + draws.count > CANONICAL_QUEUE_DRAWS)
                    rays += canonical_flush(q, f, ops);
                for (int d = 0; d < draws.count; d++) {
                    q->c[q->draws] = c;
                    q->i[q->draws] = draws.pixel[d];
                    q->factor[q->draws++] = draws.factor[d];
                }
                q->pixel[q->pixels] = c;
                q->k[q->pixels] = k;
                q->end[q->pixels++] = q->draws;
            }
            rays += canonical_flush(q, f, ops);
        }
        free(q);
    }
    return rays;
}
