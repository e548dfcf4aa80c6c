/* recon/poisson_mg.h: a multigrid V-cycle that preconditions CG on the (weighted) screened Poisson
 * system of recon/poisson_ops.h, so that IRLS L1 reconstruction needs a few CG steps per
 * reweighting instead of tens. Hierarchy: aggregation of 2x2 pixel blocks (odd sizes
 * keep a 1-wide last block) down to a grid of at most 4 x 4. The coarse operator is the Galerkin
 * product P^T A P with P the piecewise constant prolongation, which for A = diag + weighted grid
 * Laplacian is again one: the coarse diagonal is the sum of the block's diagonal terms, a coarse
 * edge weight the sum of the fine edge weights that cross between the two blocks, and edges inside
 * a block drop out. The V-cycle smooths with red-black Gauss-Seidel, `sweeps` (red, black) pairs
 * before the coarse correction and as many (black, red) pairs after it, and runs
 * RP_MG_COARSE_SWEEPS pairs each way on the coarsest grid, so the preconditioner is a fixed
 * symmetric positive definite linear operator, as CG requires. Every loop runs over rows with a
 * thread-count independent partition (red-black updates of one colour do not read each other), so
 * results are bit-identical for any number of threads. */
#ifndef RESTIR_RECON_POISSON_MG_H
#define RESTIR_RECON_POISSON_MG_H

#include "recon/poisson_ops.h"

#define RP_MG_MAX_LEVELS 16
#define RP_MG_COARSE_SWEEPS 20
#define RP_MG_SWEEPS 1 /* smoothing pairs per level each way */

struct rp_mg_level {
    int w, h;
    double a2;                  /* diagonal = a2 * wd[p] (wd NULL: 1) */
    const double *wd, *ex, *ey; /* level 0: the system's wp / wx / wy; coarser: own arrays */
    double *own_d, *own_ex, *own_ey;
    double *x, *b; /* 3 n each (coarser levels only; level 0 uses the caller's vectors) */
    double *inv;   /* n: 1 / (diagonal + sum of the pixel's edge weights) */
};

struct rp_mg {
    int levels, sweeps;
    struct rp_mg_level lv[RP_MG_MAX_LEVELS];
};

/* Builds (or rebuilds, for the same w x h) the hierarchy for s's current weights. The level-0
 * coefficients are read from s at apply time, so s and its weights must outlive the applies.
 * Returns 0, or -1 on allocation failure (mg is then freed). mg must start zeroed. */
int restir_rp_mg_build(struct rp_mg *mg, const struct rp_sys *s, int sweeps);
/* z = M^-1 r: one V-cycle from z = 0. r and z are 3 n interleaved RGB doubles, not aliased. */
void restir_rp_mg_apply(struct rp_mg *mg, const double *r, double *z);
void restir_rp_mg_free(struct rp_mg *mg);

#endif
