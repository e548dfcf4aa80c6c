/* restir/poisson.h: screened Poisson reconstruction for gradient-domain rendering (002 Sec. 5
 * "Reconstruction"; the solver of Kettunen et al. 2015 G-PT). Must never depend on a ray tracer,
 * files or the renderer.
 *
 * Images are interleaved RGB floats, row-major, w*h*3 values. The gradient images hold forward
 * differences, the convention of restir/grad.h:
 *   dx[p] ~ I(x+1, y) - I(x, y)   (the last column of dx is ignored)
 *   dy[p] ~ I(x, y+1) - I(x, y)   (the last row of dy is ignored)
 * Per channel the reconstruction I minimizes, over the rows r of the stacked system
 *   r = alpha (I - P)   (one per pixel),   Dx I - Gx,   Dy I - Gy   (one per pixel pair),
 * the energy
 *   L2:  E(I) = alpha^2 |I - P|^2 + sum |Dx I - Gx|^2 + sum |Dy I - Gy|^2
 *   L1:  the same rows in the L1 norm (approximated by IRLS, below),
 * with P the primal image, Gx = dx, Gy = dy. L2's minimizer solves the normal equations
 *   A I = b,   A = alpha^2 Id + Dx^T Dx + Dy^T Dy,   b = alpha^2 P + Dx^T Gx + Dy^T Gy,
 * where Dx^T Dx + Dy^T Dy is the grid Laplacian with Neumann (reflective) boundaries.
 *
 * Shared conventions: a non-finite primal or gradient value (NaN, +-inf) is read as 0, so it
 * cannot spread through the solve. The solves run in double precision; per-pixel loops use
 * OpenMP. Every function returns 0, or -1 on bad input (w or h < 1, w + h > INT_MAX or w*h too
 * large to address, alpha <= 0 or not finite, a NULL image pointer, bad solver parameters or an
 * enum value outside its enum) or allocation failure; out is then left untouched and st
 * (optional, may be NULL) is not written. out may not alias the inputs.
 *
 * Threading: the per-pixel loops run on restir_threads_get() threads (restir/threads.h); every
 * function may be called from several threads at once on distinct outputs. The DCT path
 * (RESTIR_POISSON_DCT, and the start of restir_poisson_l1) keeps the FFTW plans of the last 8 image
 * sizes (FFTW_ESTIMATE, no wisdom), made and destroyed under a mutex of librestir's own, so the
 * first solve of a size plans and later ones reuse. FFTW's planner is global to the process: an
 * application that itself plans FFTW transforms while a librestir DCT solve may run must make
 * FFTW's planner thread-safe (fftw_make_planner_thread_safe, FFTW >= 3.3.5). The CG solver does
 * not use FFTW. Nothing here writes to stdout or stderr or aborts. */
#ifndef RESTIR_POISSON_H
#define RESTIR_POISSON_H

#ifdef __cplusplus
extern "C" {
#endif

#define RESTIR_POISSON_ALPHA 0.2f   /* G-PT's primal weight */
#define RESTIR_POISSON_TOL 1e-6     /* CG relative residual */
#define RESTIR_POISSON_L1_ITERATIONS 20
#define RESTIR_POISSON_L1_MAX_ITERATIONS 1000 /* more would take reg_k below the double range */
#define RESTIR_POISSON_L1_CG_STEPS 50 /* per reweighting, Jacobi preconditioner */
#define RESTIR_POISSON_L1_MG_STEPS 4  /* per reweighting, multigrid preconditioner */

/* 1 when this librestir has the DCT solve (it was built with FFTW), else 0. Thread-safe. */
int restir_poisson_has_dct(void);

/* Destroys the cached FFTW plans no solve is using (all of them when none runs), e.g. before the
 * application unloads librestir or calls fftw_cleanup. Thread-safe; a no-op without FFTW. */
void restir_poisson_release_plans(void);

struct restir_poisson_stats {
    int iterations;  /* CG iterations (the maximum over channels); 0 for the DCT solve; for L1 the
                        CG steps of all reweightings together */
    double residual; /* relative residual |b - A x| / |b| of the (last, for L1 the reweighted)
                        normal equations, in double before rounding to float, max over channels
                        (|b - A x| itself where |b| = 0) */
    double ms;       /* wall time of the call */
};

enum restir_poisson_solver {
    /* Direct solve: A is diagonalized by the 2D DCT-II (the Neumann path-graph Laplacian's
     * eigenvectors are cos(pi k (j + 1/2) / n), eigenvalues 2 - 2 cos(pi k / n)), so
     * I = DCT-III(DCT-II(b) / (alpha^2 + lambda_x + lambda_y)) with FFTW's REDFT10 / REDFT01.
     * Exact up to rounding; tol and max_iters are ignored. In a librestir built without FFTW the
     * solve is not there: restir_poisson_l2 returns -1 (and so does restir_poisson_l1, which starts
     * from it); use RESTIR_POISSON_CG. */
    RESTIR_POISSON_DCT = 0,
    /* Jacobi-preconditioned conjugate gradient from x0 = primal until every channel's relative
     * residual is <= tol or max_iters iterations ran. */
    RESTIR_POISSON_CG
};

/* L2 reconstruction (the energy above). tol > 0 and max_iters >= 1 are required for CG
 * (RESTIR_POISSON_TOL, e.g. 1000). Writes w*h*3 floats to out. */
int restir_poisson_l2(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                      enum restir_poisson_solver solver, double tol, int max_iters, float *out,
                      struct restir_poisson_stats *st);

/* Preconditioner of the L1 solve's inner CG. */
enum restir_poisson_precond {
    /* One multigrid V-cycle per CG step: 2x2 aggregation down to 4 x 4, Galerkin coarse
     * operators (sums of the fine weights), one red-black Gauss-Seidel pair before and after the
     * coarse correction. Smooth error, which Jacobi removes one pixel per
     * step, is corrected on the coarse grids: 3-4x fewer steps to a given residual. */
    RESTIR_POISSON_PRECOND_MULTIGRID = 0,
    /* 1 / diag(A), the public G-PT solver's choice (there without preconditioning at all). */
    RESTIR_POISSON_PRECOND_JACOBI
};

/* L1 reconstruction by iteratively reweighted least squares, after the public G-PT solver
 * (Kettunen et al. 2015, preset "L1D"): starting from the exact L2 solution (DCT), `iterations`
 * reweightings k = 1..iterations; each sets on every row (primal and gradient rows) the weight
 *   w_r = 1 / (|e_r| + reg_k),   reg_k = 0.05 * 0.5^(k-1),
 * with e_r the row's current residual (the primal row's includes the factor alpha) and |e_r| its
 * Euclidean length over RGB, so one weight is shared by the three channels; weights are then
 * scaled to mean 1 over all rows. The weighted normal equations
 *   (alpha^2 Wp + Dx^T Wx Dx + Dy^T Wy Dy) I = alpha^2 Wp P + Dx^T Wx Gx + Dy^T Wy Gy
 * get cg_steps preconditioned CG steps (precond) warm-started from the previous solution (fewer
 * where a channel's residual reaches rounding level, 1e-14 relative).
 * Differences from the public code: it counts its first, unweighted CG solve (50 steps from the
 * primal) as IRLS iteration 1, so its 20 iterations are 19 reweightings, and it uses plain CG
 * and averages the weights over its 3N rows including the ignored last-column / last-row ones.
 * Defaults: RESTIR_POISSON_L1_ITERATIONS and RESTIR_POISSON_L1_MG_STEPS (multigrid) or
 * RESTIR_POISSON_L1_CG_STEPS (Jacobi); 0 <= iterations <= RESTIR_POISSON_L1_MAX_ITERATIONS (0 gives
 * the L2 solution), cg_steps >= 1. Both preconditioners converge to the same IRLS iterates; at the
 * defaults, on a rendered 640x360 frame, they reached the same L1 energy to 0.03-0.15%. */
int restir_poisson_l1(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                      int iterations, enum restir_poisson_precond precond, int cg_steps, float *out,
                      struct restir_poisson_stats *st);

/* The L1 energy restir_poisson_l1 minimizes, of the image x: alpha |x_p - P_p| summed over the
 * pixels plus |x_q - x_p - G_p| over the pixel pairs, |.| the Euclidean length over RGB (non-
 * finite inputs read as 0, as in the solves). For comparing L1 solves. Returns the energy, or
 * NaN on bad input (the argument rules of the solves). */
double restir_poisson_l1_energy(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                                const float *x);

#ifdef __cplusplus
}
#endif

#endif
