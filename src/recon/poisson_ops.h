/* recon/poisson_ops.h: internal pieces of the Poisson reconstruction (restir/poisson.h): the
 * (weighted) normal-equation operator, its right-hand side, residuals, Jacobi-preconditioned CG
 * and the DCT direct solve. Vectors are interleaved RGB doubles, 3 n values. */
#ifndef RESTIR_RECON_POISSON_OPS_H
#define RESTIR_RECON_POISSON_OPS_H

#include <math.h>
#include <stddef.h>

/* The system A x = b of one reconstruction:
 *   A = a2 Wp + Dx^T Wx Dx + Dy^T Wy Dy,   b = a2 Wp P + Dx^T Wx Gx + Dy^T Wy Gy.
 * wp / wx / wy are per-row weights (n each; wx[p] weighs the pair (p, p+1), wy[p] the pair
 * (p, p+w); the entries of the ignored last column / row are never read); NULL means all 1. */
struct rp_sys {
    int w, h;
    size_t n;
    double a2;
    const double *wp, *wx, *wy;
    double *rows; /* RP_ROW_SUMS * h scratch doubles for deterministic reductions (rp_alloc) */
};

/* Reductions are summed per image row (a partition that does not depend on the thread count) and
 * then over the rows in order, so every result is bit-identical whatever the number of threads. */
#define RP_ROW_SUMS 6
/* out[v] = sum over rows j in order of s->rows[j * RP_ROW_SUMS + v], v < nv. */
void rp_sum_rows(const struct rp_sys *s, int nv, double *out);

/* A non-finite input value reads as 0. */
static inline double rp_in(float v)
{
    return isfinite(v) ? (double)v : 0.0;
}

/* n doubles (malloc), NULL on overflow or failure. */
double *rp_alloc(size_t n);
/* b of the system from the float inputs. */
void rp_rhs(const struct rp_sys *s, const float *primal, const float *dx, const float *dy, double *b);
/* Per channel c: rel[c] = |b - A x| / |b| (|b - A x| where |b| = 0). */
void rp_residual(const struct rp_sys *s, const double *b, const double *x, double rel[3]);
/* Jacobi-preconditioned CG on A x = b from the given x, per channel until |r| <= tol |b| or
 * max_iters. Returns the iterations run (max over channels), -1 on allocation failure. */
int rp_cg(const struct rp_sys *s, const double *b, double *x, double tol, int max_iters);
/* Direct solve of the unweighted system (wp = wx = wy = 1) by DCT. Returns 0 or -1. */
int rp_dct_solve(int w, int h, double a2, const double *b, double *x);
/* Shared argument check of the public functions: 0 when usable. */
int rp_check(int w, int h, const float *primal, const float *dx, const float *dy, float alpha, const float *out);
/* Rounds x to float. */
void rp_store(size_t n, const double *x, float *out);

#endif
