/* restir/cells.h: screen-space reuse cells (004 Sec. 5, Algorithm 1) and the cell search of
 * Sec. 5.1: per-pixel cell keys (PCG hash of tile id, object id and quantized normal), cells
 * built by grouping each tile's pixels by key into flat arrays (the CPU form of the GPU
 * multimap: a counting sort by tile, then by key inside the tile; no allocation per frame), the
 * uniform and Eq. 17 draws from a cell, and the confidence-weighted search for a cell.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_CELLS_H
#define RESTIR_CELLS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest tile edge the cells support (cells of at most 16 x 16 = 256 pixels). */
#define RESTIR_CELL_MAX_TILE 16

/* PCG hash (O'Neill 2014: one step of the 32-bit LCG, then the RXS-M-XS output permutation). */
uint32_t restir_pcg_hash(uint32_t v);

/* 004 Sec. 5: the cell key of a pixel: the PCG hash chained over its tile id, object id and
 * shading normal quantized per component into `bins` buckets of [-1, 1] (floor((n + 1) bins / 2),
 * clamped: negative components never wrap). Pixels with equal keys in one tile share a cell. */
uint32_t restir_cell_key(uint32_t tile, int32_t object, const float normal[3], int bins);

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
    struct restir_cell_tap *tap; /* per pixel: what a search tap reads (restir_cells_pack_taps) */
    int n_cells;
};

/* Everything the cell search reads of a tapped pixel q, in one 32-byte record (one cache line
 * per tap instead of one in each of cell_of, object, normal and conf_sum: the search is 12 random
 * taps per pixel, bound by those misses). */
struct restir_cell_tap {
    int32_t cell;     /* cell_of[q] */
    int32_t object;   /* object id of q */
    float conf_sum;   /* conf_sum of q's cell (0 when q is in no cell) */
    float normal[3];  /* q's shading normal */
    uint32_t pad[2];
};

/* Sizes the arrays for width x height pixels and tile x tile tiles (1 <= tile <= 16).
 * Returns 0, or -1 for bad sizes or no memory (then nothing is left allocated). */
int restir_cells_init(struct restir_cells *c, int width, int height, int tile);
void restir_cells_fini(struct restir_cells *c);

/* 004 Algorithm 1: groups the pixels with valid[i] != 0 by (tile, key[i]); conf[i] >= 0 is the
 * confidence c_i, weight[i] >= 0 the Eq. 17 selection weight c_i p_hat(X_i) W_i (0 for a pixel
 * whose reservoir holds no contributing sample); negative, NaN or infinite values count as 0. Runs
 * in parallel over tiles. */
void restir_cells_build(struct restir_cells *c, const uint32_t *key, const unsigned char *valid, const float *conf,
                        const float *weight);

/* Fills c->tap from the cells just built and the G-buffer's normals (3 floats per pixel) and
 * object ids, for restir_cell_search_packed. Runs in parallel over pixels. */
void restir_cells_pack_taps(struct restir_cells *c, const float *normal, const int *object);

/* M of a merge: the number of pixels of `cell` other than `exclude` (exclude may be -1 or a
 * pixel outside the cell). */
int restir_cells_others(const struct restir_cells *c, int cell, int exclude);
/* 004 Eq. 12 over the cell's pixels other than `exclude`: c_sigma = conf_sum minus conf[exclude]
 * when exclude is in the cell (the canonical domain is never its own neighbor). */
float restir_cells_confidence_others(const struct restir_cells *c, int cell, int exclude, const float *conf);

/* RandomPixelInCell (Algorithm 2 line 9): a pixel of `cell` other than `exclude`, uniform (each
 * with probability 1 / M), from u in [0,1). Returns -1 when M = 0. */
int restir_cells_pick_uniform(const struct restir_cells *c, int cell, int exclude, float u);

/* A pixel of `cell` other than `exclude` with probability c_i / c_sigma (004 Sec. 4.2: "it would
 * be natural to use P_c(i) proportional to c_i"), by inverting the confidence prefix sums with u;
 * *prob receives the probability. Returns -1 (and *prob = 0) when the others' confidences sum
 * to 0. */
int restir_cells_pick_confidence(const struct restir_cells *c, int cell, int exclude, float u, double *prob);

/* ResampleReservoirInCell (004 Eq. 17, Algorithm 2 line 14): a contributing pixel of `cell` other
 * than `exclude`, chosen with probability weight_i / sum over those pixels by inverting the
 * cell's prefix sums with u in [0,1); *prob receives that probability. Returns -1 (and *prob = 0)
 * when no other pixel contributes. */
int restir_cells_pick_weighted(const struct restir_cells *c, int cell, int exclude, float u, double *prob);

/* What an accepted tap's cell weighs in the search. */
enum restir_cell_score {
    RESTIR_CELL_SCORE_CONFIDENCE = 0, /* its confidence sum (004 Sec. 5.1) */
    /* its confidence sum times 000's compatibility (Eq. 14-15) of the tapped pixel's primary hit
     * with the searching pixel's: a variant of ours, in neither paper */
    RESTIR_CELL_SCORE_COMPAT,
};

/* Cell search (004 Sec. 5.1). */
struct restir_cell_search {
    int steps;        /* taps (12) */
    float radius;     /* initial disk radius in pixels (30) */
    float growth;     /* radius factor per tap (1.25) */
    float normal_min; /* a tap is rejected when its shading normal . the pixel's is below */
    enum restir_cell_score score;
    /* RESTIR_CELL_SCORE_COMPAT only: every pixel's primary hit (3 floats) and its distance from the
     * camera, and 000's omega and beta (restir_compat_score) */
    const float *position, *depth;
    float omega, beta;
};

/* Weighted reservoir sampling over s->steps taps: tap t is a pixel uniform in the disk of radius
 * radius * growth^t around `pixel` (u[3t], u[3t+1]); a tap outside the image, in no cell, on
 * another object or with a dissimilar normal is rejected; otherwise its cell is a candidate of
 * weight conf_sum, times the compatibility score of the tapped pixel with `pixel` under
 * RESTIR_CELL_SCORE_COMPAT (u[3t+2] drives the WRS; a weight of 0 rejects the tap). Returns the
 * chosen cell, or the pixel's own cell when no tap is accepted (-1 if the pixel is in no cell).
 * Reads only cells, confidences and G-buffer data (normals, object ids, positions, depths), never
 * samples, so the choice cannot bias GRIS (004 Sec. 5.1). */
int restir_cell_search(const struct restir_cells *c, const struct restir_cell_search *s, int pixel,
                       const float *normal, const int *object, const float *u);
/* The same search reading c->tap (restir_cells_pack_taps after the build) instead of the separate
 * arrays: the same cell for the same u, bit for bit. */
int restir_cell_search_packed(const struct restir_cells *c, const struct restir_cell_search *s, int pixel,
                              const float *u);

#ifdef __cplusplus
}
#endif

#endif
