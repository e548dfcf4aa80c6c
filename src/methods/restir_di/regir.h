/* regir.h: ReGIR, a world-space grid of light reservoirs for ReSTIR DI's initial candidates
 * (di.initial=regir; Boksansky, Jukarainen and Wyman 2021, "Rendering many lights with grid-based
 * reservoirs", Ray Tracing Gems II ch. 23, in the form RTXDI gives it). Each frame a uniform grid
 * is laid over the bounding box of the G-buffer's shading points; every cell some pixel's point
 * falls in gets di.regir_slots slots (fewer when few pixels see it), and each slot is an independent RIS reservoir over
 * di.regir_candidates emitters drawn from a source (power, or a cut through the light BVH at the
 * cell's centre, light_cut.h, mixed with power), resampled toward the cell's target
 *   p_c(y) = lum(Le_e) min(A_e / dbar^2, 2 pi) / A_e      (y a point of emitter e, area measure)
 * with dbar = d + R^3 / (d + 1.1547 R)^2 the fitted mean distance from a ball of radius R (the
 * cell's half-diagonal) around the cell's centre to the emitter's centroid at distance d (RTXDI's
 * volume weight), and 0 only where the whole cell lies behind the emitter's plane. The slot keeps
 * its point y with the contribution weight W = (1/K sum_j p_c(x_j) / p_src(x_j)) / p_c(y)
 * (Talbot's RIS; GRIS, 004 Eq. 7), an unbiased weight for every f that p_c covers.
 *
 * A pixel takes di.light_candidates consecutive slots of its point's cell at a random offset and
 * resamples them with weights (GRIS with the generalized balance heuristic over the light and
 * BSDF strategies, 004 Eq. 11)
 *   w_i = p_hat(X_i) W_i q(X_i) / (N_light q(X_i) + N_bsdf p_bsdf(X_i)),
 *   w_bsdf = p_hat(X) / (N_light q(X) + N_bsdf p_bsdf(X)),
 * where q is the slots' source density (a function of the point alone, as MIS weights must be):
 * the weights' MIS factors sum to 1, every slot's W is unbiased wherever p_c > 0, and p_c covers
 * p_hat for any point in the cell (p_hat is zero behind an emitter), so the pixel's reservoir is
 * unbiased whatever the slots share (the estimator is linear in each candidate's f W). Slots with
 * an environment: with probability env_prob a slot holds a direction from the environment's
 * sampler (W = 1 / (env_prob pdf)), else the emitter reservoir with W / (1 - env_prob), the usual
 * one-sample choice between two unbiased estimators. Must never trace rays. */
#ifndef RESTIR_METHODS_RESTIR_DI_REGIR_H
#define RESTIR_METHODS_RESTIR_DI_REGIR_H

#include <stdint.h>

#include "methods/restir_di/di_settings.h"
#include "methods/restir_di/light_cut.h"
#include "methods/restir_di/light_pool.h"
#include "render/gbuffer.h"

/* The random stream of the fill (the method row's `streams`). */
#define REGIR_STREAM "regir fill"

struct regir_grid {
    vec3 lo;          /* the grid's lower corner */
    float cell;       /* edge of its cubic cells */
    int dims[3];      /* cells per axis, each at most di.regir_grid */
    int *block;       /* per grid cell: its slot block, -1 when no pixel's point falls in it */
    int block_cap;    /* grid cells `block` can index */
    int *cells;       /* per slot block: its grid cell */
    int n_blocks;     /* occupied cells this frame */
    int cells_cap;
    int slots;        /* slots per cell at most (di.regir_slots) */
    int window;       /* the pixel's candidates (di.light_candidates) */
    int *block_first; /* per block: its first store entry */
    int *block_slots; /* per block: its slots, min(di.regir_slots, window x the cell's pixels): a cell
                         seen by few pixels needs no more distinct slots than their windows take. The
                         block is block_slots + window entries long, the tail repeating its first
                         slots so that no window wraps */
    int entries;             /* the store's entries this frame: every block's slots and window tail */
    int max_entries;         /* the most any frame of this size can need: min(grid cells, pixels) x
                                (slots + window), what di.initial's memory check bounds */
    int valid_pixels;        /* this frame's pixels with a shading point */
    struct light_pool store; /* the slots, block after block, with W */
    struct light_cut_order order; /* di.regir_source=bvh: the scene's emitters in tree order (else n = 0) */
    struct light_cut *cuts;       /* and per block the cut through the tree at its cell's centre */
};

/* The grid's fill work this frame over the pixels' own: the slots' candidates (sum of block_slots x
 * di.regir_candidates, after regir_build) over the valid pixels x di.light_candidates (0 without a
 * valid pixel). di.initial=auto compares it with DI_AUTO_REGIR_MAX_FILL_SHARE. */
double regir_fill_share(const struct regir_grid *r, const struct di_settings *ds);

/* Sizes the grid for ds and scene s (the slots are allocated by regir_fill). */
void regir_init(struct regir_grid *r, const struct scene *s, const struct di_settings *ds);
void regir_fini(struct regir_grid *r);
/* Lays this frame's grid over g's valid shading points (di.regir_grid cells along the longest axis of
 * their bounding box) and gives every occupied cell a slot block. Serial (three passes over the
 * pixels: bounds, occupancy, slot counts; one over the grid); counts the store's entries, which
 * regir_fill allocates. */
void regir_build(struct regir_grid *r, const struct gbuffer *g, const struct di_settings *ds);
/* Fills every block's slots for this frame (seeded by seed, frame and block, whatever the thread
 * count), first growing the store to this frame's entries (by half again at least, never past the
 * largest the frame's cells and pixels allow). Threads: OpenMP over blocks. */
void regir_fill(struct regir_grid *r, const struct scene *s, const struct di_settings *ds, uint64_t seed, int frame);
/* The slot block of the cell that holds point p, which must be one of the shading points the grid was
 * built over (another point is clamped to a border cell, whose block may be -1 or not cover it). */
int regir_block_of(const struct regir_grid *r, vec3 p);
/* The first store entry of a pixel's window in block b, for a uniform u in [0, 1). */
static inline int regir_window_first(const struct regir_grid *r, int b, float u)
{
    const int slots = r->block_slots[b];
    int o = (int)(u * (float)slots);
    o = o < slots ? o : slots - 1;
    return r->block_first[b] + o;
}
/* p_c of emitter e for block b's cell times the emitter's area (regir.h's target, per emitter): 0
 * exactly where the cell's slots can never hold a point of e. For tests and diagnostics. */
float regir_cell_weight(const struct regir_grid *r, const struct scene *s, int b, int e);
/* q at a point of emitter triangle tri for a pixel of block b: the density the MIS weights give the
 * light strategy (what the store's pdf holds for a slot on tri), 0 when tri is not an emitter. */
float regir_light_pdf(const struct regir_grid *r, const struct scene *s, const struct di_settings *ds, int b, int tri);

#endif
