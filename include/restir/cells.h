/* restir/cells.h: screen-space reuse cells (004 Sec. 5, Algorithm 1) and the cell search of
 * Sec. 5.1: per-pixel cell keys (PCG hash of tile id, object id and quantized normal), cells
 * built by grouping each tile's pixels by key into flat arrays (the CPU form of the GPU
 * multimap: a counting sort by tile, then by key inside the tile; no allocation per frame), the
 * uniform and Eq. 17 draws from a cell, and the confidence-weighted search for a cell.
 * Ownership and threads: struct restir_cells is the caller's; restir_cells_init allocates its arrays
 * and restir_cells_fini frees them. restir_cells_build and restir_cells_pack_taps write it, running
 * on restir_threads_get() threads (restir/threads.h), and must not overlap any other call on the
 * same cells; the draws and searches only read it and may run concurrently from any threads. The
 * RESTIR_HD functions are per-sample code for C, C++ and CUDA device code (restir/hd.h). Nothing
 * here aborts or writes to stdout or stderr.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_CELLS_H
#define RESTIR_CELLS_H

#include <stdint.h>

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest tile edge the cells support (cells of at most 16 x 16 = 256 pixels). */
#define RESTIR_CELLS_MAX_TILE 16

/* PCG hash (O'Neill 2014: one step of the 32-bit LCG, then the RXS-M-XS output permutation). */
RESTIR_HD uint32_t restir_cells_hash(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* One normal component n in [-1, 1] quantized to floor((n + 1) bins / 2), clamped to
 * [0, bins - 1]: a negative component must not wrap around when cast (the pitfall of one public
 * implementation); NaN gives 0, bins < 1 counts as 1. */
RESTIR_HD int restir_cells_quantize(float n, int bins)
{
    if (bins < 1)
        bins = 1;
    float q = floorf((n + 1.0f) * 0.5f * (float)bins);
    if (!(q >= 0.0f))
        return 0;
    return q >= (float)bins ? bins - 1 : (int)q;
}

/* 004 Sec. 5: the cell key of a pixel: the PCG hash chained over its tile id, object id and
 * shading normal quantized per component into `bins` buckets of [-1, 1] (restir_cells_quantize;
 * bins < 1 counts as 1, a NULL normal as (0, 0, 0)). Pixels with equal keys in one tile share a
 * cell. */
RESTIR_HD uint32_t restir_cells_key(uint32_t tile, int32_t object, const float normal[3], int bins)
{
    if (bins < 1)
        bins = 1;
    const float zero[3] = {0.0f, 0.0f, 0.0f};
    const float *n = normal ? normal : zero;
    uint32_t h = restir_cells_hash(tile);
    h = restir_cells_hash(h ^ (uint32_t)object);
    uint32_t nq = (uint32_t)(restir_cells_quantize(n[0], bins) +
                             bins * (restir_cells_quantize(n[1], bins) + bins * restir_cells_quantize(n[2], bins)));
    return restir_cells_hash(h ^ nq);
}

/* Cells of one frame. A cell is named by the index of its first entry in `entry`; its pixels are
 * entry[cell .. cell + count[cell]), the contributing ones (Eq. 17 weight > 0) first, then the
 * others, each group in increasing pixel order. Per-cell values are stored at the cell's index. */
struct restir_cells {
    int width, height, tile;
    int tiles_x, tiles_y;
    int *tile_base;     /* per tile: index of its first entry */
    int *entry;         /* pixel indices grouped by cell */
    int *cell_of;       /* per pixel: its cell, -1 for pixels in no cell (not valid) */
    int *slot_of;       /* per pixel: its index in entry, -1 for pixels in no cell */
    int *count;         /* per cell: number of pixels */
    int *contributing;  /* per cell: number of contributing pixels */
    float *conf_sum;    /* per cell: sum of the pixels' confidences (before any exclusion) */
    double *cdf;        /* per entry of a contributing pixel: inclusive prefix sum of the Eq. 17
                           weights within its cell */
    double *conf_cdf;   /* per entry: inclusive prefix sum of the confidences within its cell */
    uint32_t *key;      /* per cell: the key its pixels share */
    struct restir_cells_tap *tap; /* per pixel: what a search tap reads (restir_cells_pack_taps) */
    int n_cells;
};

/* Everything the cell search reads of a tapped pixel q, in one 32-byte record (one cache line
 * per tap instead of one in each of cell_of, object, normal and conf_sum: the search is 12 random
 * taps per pixel, bound by those misses). */
struct restir_cells_tap {
    int32_t cell;     /* cell_of[q] */
    int32_t object;   /* object id of q */
    float conf_sum;   /* conf_sum of q's cell (0 when q is in no cell) */
    float normal[3];  /* q's shading normal */
    uint32_t pad[2];
};

/* Sizes the arrays for width x height pixels (w h <= INT_MAX - 16) and tile x tile tiles
 * (1 <= tile <= 16); no pixel is in a cell until the first build. Returns 0, or -1 for a NULL c,
 * bad sizes or no memory (then c is zeroed and nothing is left allocated). */
int restir_cells_init(struct restir_cells *c, int width, int height, int tile);
/* Frees the arrays and zeroes c (initialized by restir_cells_init, successful or not, or zeroed);
 * a NULL c is ignored. */
void restir_cells_fini(struct restir_cells *c);

/* Bad arguments of the functions below. A cell is named by an index the last build gave (cell_of,
 * or a search): any other index, -1 included, is no cell, with no pixel, M = 0 and no draw. An
 * `exclude` outside the cell (-1, another cell's pixel, an index outside the image) excludes
 * nothing. A draw's u outside [0,1) is clamped into it (NaN reads as 0). */

/* 004 Algorithm 1: groups the pixels with valid[i] != 0 by (tile, key[i]); conf[i] >= 0 is the
 * confidence c_i, weight[i] >= 0 the Eq. 17 selection weight c_i p_hat(X_i) W_i (0 for a pixel
 * whose reservoir holds no contributing sample); negative, NaN or infinite values count as 0, and
 * a cell's confidence sum past the float range saturates at FLT_MAX. Runs in parallel over tiles.
 * Returns 0, or -1 without writing for a NULL array or a c that restir_cells_init did not size. */
int restir_cells_build(struct restir_cells *c, const uint32_t *key, const unsigned char *valid, const float *conf,
                       const float *weight);

/* Fills c->tap from the cells just built (call it after every build) and the G-buffer's normals
 * (3 floats per pixel) and object ids, for restir_cells_search_packed. Runs in parallel over
 * pixels. Returns 0, or -1 without writing for a NULL array or a c that restir_cells_init did not
 * size. */
int restir_cells_pack_taps(struct restir_cells *c, const float *normal, const int *object);

/* M of a merge: the number of pixels of `cell` other than `exclude`; 0 for a NULL c or no cell. */
int restir_cells_others(const struct restir_cells *c, int cell, int exclude);
/* 004 Eq. 12 over the cell's pixels other than `exclude`: c_sigma = conf_sum minus conf[exclude]
 * when exclude is in the cell (the canonical domain is never its own neighbor), at least 0, with
 * conf[exclude] read as in the build. 0 for a NULL c or conf, or no cell. */
float restir_cells_confidence_others(const struct restir_cells *c, int cell, int exclude, const float *conf);

/* RandomPixelInCell (Algorithm 2 line 9): a pixel of `cell` other than `exclude`, uniform (each
 * with probability 1 / M), from u in [0,1). Returns -1 when M = 0 (also for a NULL c). */
int restir_cells_pick_uniform(const struct restir_cells *c, int cell, int exclude, float u);

/* A pixel of `cell` other than `exclude` with probability c_i / c_sigma (004 Sec. 4.2: "it would
 * be natural to use P_c(i) proportional to c_i"), by inverting the confidence prefix sums with u;
 * *prob (prob may be NULL) receives the probability. Returns -1 (and *prob = 0) when the others'
 * confidences sum to 0 (also for a NULL c). */
int restir_cells_pick_confidence(const struct restir_cells *c, int cell, int exclude, float u, double *prob);

/* ResampleReservoirInCell (004 Eq. 17, Algorithm 2 line 14): a contributing pixel of `cell` other
 * than `exclude`, chosen with probability weight_i / sum over those pixels by inverting the
 * cell's prefix sums with u in [0,1); *prob (prob may be NULL) receives that probability. Returns
 * -1 (and *prob = 0) when no other pixel contributes (also for a NULL c). */
int restir_cells_pick_weighted(const struct restir_cells *c, int cell, int exclude, float u, double *prob);

/* What an accepted tap's cell weighs in the search. */
enum restir_cells_score {
    RESTIR_CELLS_SCORE_CONFIDENCE = 0, /* its confidence sum (004 Sec. 5.1) */
    /* its confidence sum times 000's compatibility (Eq. 14-15) of the tapped pixel's primary hit
     * with the searching pixel's: a variant of ours, in neither paper */
    RESTIR_CELLS_SCORE_COMPAT,
};

/* Cell search (004 Sec. 5.1). */
struct restir_cells_search {
    int steps;        /* taps (12) */
    float radius;     /* initial disk radius in pixels (30) */
    float growth;     /* radius factor per tap (1.25) */
    float normal_min; /* a tap is rejected when its shading normal . the pixel's is below */
    enum restir_cells_score score;
    /* RESTIR_CELLS_SCORE_COMPAT only: every pixel's primary hit (3 floats) and its distance from the
     * camera, and 000's omega and beta (restir_neighbors_compat) */
    const float *position, *depth;
    float omega, beta;
};

/* Weighted reservoir sampling over s->steps taps: tap t is a pixel uniform in the disk of radius
 * radius * growth^t around `pixel` (u[3t], u[3t+1]); a tap outside the image, in no cell, on
 * another object or with a dissimilar normal is rejected; otherwise its cell is a candidate of
 * weight conf_sum, times the compatibility score of the tapped pixel with `pixel` under
 * RESTIR_CELLS_SCORE_COMPAT (u[3t+2] drives the WRS; a weight of 0 rejects the tap). Returns the
 * chosen cell, or the pixel's own cell when no tap is accepted (-1 if the pixel is in no cell).
 * Reads only cells, confidences and G-buffer data (normals, object ids, positions, depths), never
 * samples, so the choice cannot bias GRIS (004 Sec. 5.1). u holds 3 s->steps values (steps <= 0:
 * no tap). u outside [0,1) (NaN included) or a NaN or infinite radius or growth only moves taps
 * (anywhere, or outside the image: rejected); a NaN normal or normal_min rejects no tap by normal.
 * Also returns -1 for a NULL c, s, normal, object or u, a pixel outside the image, or
 * RESTIR_CELLS_SCORE_COMPAT with a NULL position or depth; any other score weighs as
 * RESTIR_CELLS_SCORE_CONFIDENCE. */
int restir_cells_search(const struct restir_cells *c, const struct restir_cells_search *s, int pixel,
                       const float *normal, const int *object, const float *u);
/* The same search reading c->tap (restir_cells_pack_taps after the build) instead of the separate
 * arrays: the same cell for the same u, bit for bit. Before the first restir_cells_pack_taps every
 * tap is rejected. Bad arguments as restir_cells_search. */
int restir_cells_search_packed(const struct restir_cells *c, const struct restir_cells_search *s, int pixel,
                              const float *u);

#ifdef __cplusplus
}
#endif

#endif
