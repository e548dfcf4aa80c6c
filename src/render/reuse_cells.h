/* reuse_cells.h: the method-independent passes of stochastic pairwise MIS (004 Sec. 5): reuse
 * cells built from the G-buffer with each pixel's confidence and Eq. 17 weight (Algorithm 1), the
 * per-pixel cell search (Sec. 5.1) and the canonical weight pass (Algorithm 2 lines 6-12), which
 * reads samples only through the method's callbacks. Must never depend on a sample type: methods
 * fill conf and weight, supply those callbacks and run their own reuse passes
 * (restir_di_spmis.c, restir_pt_spmis.c). */
#ifndef RESTIR_RENDER_REUSE_CELLS_H
#define RESTIR_RENDER_REUSE_CELLS_H

#include "core/rng.h"
#include "render/gbuffer.h"
#include "render/params.h"
#include "restir/spmis.h"

/* What SPMIS keeps per frame; made once per resolution. */
struct spmis_frame {
    struct restir_cells cells;
    uint32_t *key; /* per pixel: cell key (tile, object, quantized normal) */
    float *conf;   /* per pixel: capped confidence c_i (filled by the method) */
    float *weight; /* per pixel: Eq. 17 weight c_i p_hat(X_i) W_i (filled by the method) */
    int *cell;     /* per pixel: the cell it reuses from (search output), -1 for invalid pixels */
    float *m_c;    /* per pixel: stochastic canonical MIS weight m~_c (Eq. 18) */
};

void spmis_frame_init(struct spmis_frame *f, const struct render_params *p);
void spmis_frame_fini(struct spmis_frame *f);

/* 004 Algorithm 1: cell keys from the G-buffer, then the cells over f->conf and f->weight. */
void spmis_cells_pass(struct spmis_frame *f, const struct render_params *p, const struct gbuffer *g);

/* 004 Sec. 5.1 for every valid pixel into f->cell (spmis.search: always, sparse or low-confidence). */
void spmis_search_pass(struct spmis_frame *f, const struct render_params *p, const struct gbuffer *g, int frame);

/* In both plans, k holds the confidences of pixel c's merge from its chosen cell: 004 Eq. 12 over
 * the cell's other pixels, scaled by spmis.candidates / M when spmis.confidence_adjust (Sec. 4.3). */

/* The canonical draws of pixel c (004 Algorithm 2 lines 8-10: spmis.canonical_candidates picks by
 * spmis.canonical_pick from its chosen cell) and the confidences k of its merge. */
void spmis_canonical_plan(const struct spmis_frame *f, const struct render_params *p, int frame, int c,
                          struct restir_spmis_conf *k, struct restir_spmis_draws *draws);
/* The neighbor draws of pixel c (lines 13-14: spmis.candidates picks by Eq. 17), the confidences
 * k of its merge, and in *merged the confidence its output keeps (004 leaves it open): min(cap, c_c
 * + min(1, N / M) c_sigma), the cell's mean confidence per evaluated draw, or with
 * spmis.confidence_update=drawn min(cap, c_c + the confidences of the distinct pixels drawn).
 * It does not depend on spmis.confidence_adjust, which changes only the MIS weights, so the
 * Fig. 2 ablation changes one thing. Returns the pixel's stream, to drive the merge's WRS. */
pcg32 spmis_neighbor_plan(const struct spmis_frame *f, const struct render_params *p, int frame, int c,
                          struct restir_spmis_conf *k, float *merged, struct restir_spmis_draws *draws);

/* Starts loading the drawn pixels' records (reservoirs of `stride` bytes from `base`): the cell
 * search puts draws up to hundreds of pixels away, and the misses then overlap with the
 * canonical sample's work (restir-pt's reuse pass: 136 -> 120 ms at 640x360). */
static inline void spmis_prefetch_draws(const struct restir_spmis_draws *draws, const void *base, size_t stride)
{
    for (int d = 0; d < draws->count; d++) {
        const char *r = (const char *)base + (size_t)draws->pixel[d] * stride;
        for (size_t b = 0; b < stride; b += 64)
            __builtin_prefetch(r + b);
    }
}

/* What the canonical pass asks of a method's samples. */
struct spmis_canonical_ops {
    const void *ctx;
    /* pixel c's reservoir holds a sample (Algorithm 2 line 6: only those need m~_c) */
    int (*has_sample)(const void *ctx, int c);
    /* p_hat(Y_c): the target cached with pixel c's sample */
    float (*target)(const void *ctx, int c);
    /* p_hat_{<-i}(Y_c) of Eq. 19: pixel i's target for pixel c's sample brought into i's domain
     * (with the shift's Jacobian), adding the rays it traces to *rays */
    float (*target_from)(const void *ctx, int c, int i, long long *rays);
    /* Optional (NULL: target_from one pair at a time): out[e] = target_from(ctx, c[e], i[e]) for
     * n pairs at once, the same values, so that a method can evaluate them across pixels with
     * vector instructions and trace their rays as streams (restir_di_spmis.c) */
    void (*targets_from)(const void *ctx, int n, const int *c, const int *i, float *out, long long *rays);
};

/* 004 Algorithm 2 lines 6-12 for every pixel: the stochastic canonical weight m~_c from
 * spmis.canonical_candidates draws of the pixel's cell (Eq. 18-19) into f->m_c (1 where the pixel
 * is invalid or has no sample). The draws of many pixels (a tile's, at most) are queued and their
 * p_hat_{<-i}(Y_c) evaluated together before each pixel's sum is taken in draw order, the same sum
 * as one pixel at a time. Returns the rays traced. */
long long spmis_canonical_pass(struct spmis_frame *f, const struct render_params *p, int frame,
                               const struct gbuffer *g, const struct spmis_canonical_ops *ops);

#endif
