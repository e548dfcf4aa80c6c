/* recon/poisson_ops.h: internal pieces of the Poisson reconstruction (restir/poisson.h): the
 * (weighted) normal-equation operator, its right-hand side, residuals and the DCT direct solve (CG:
 * recon/poisson_cg.h). Vectors are interleaved RGB doubles, 3 n values. */
#ifndef RESTIR_RECON_POISSON_OPS_H
#define RESTIR_RECON_POISSON_OPS_H

#include <math.h>
#include <stddef.h>

#include "restir/threads.h"

/* The system A x = b of one reconstruction:
 *   A = a2 Wp + Dx^T Wx Dx + Dy^T Wy Dy,   b = a2 Wp P + Dx^T Wx Gx + Dy^T Wy Gy.
 * wp / wx / wy are per-row weights (n each; wx[p] weighs the pair (p, p+1), wy[p] the pair
 * (p, p+w); the entries of the ignored last column / row are never read); NULL means all 1. */
struct rp_sys {
    int w, h;
    size_t n;
    double a2;
    const double *wp, *wx, *wy;
    double *rows; /* RP_ROW_SUMS * h scratch doubles for deterministic reductions (restir_rp_alloc) */
};

/* Reductions are summed per image row (a partition that does not depend on the thread count) and
 * then over the rows in order, so every result is bit-identical whatever the number of threads. */
#define RP_ROW_SUMS 9
/* out[v] = sum over rows j in order of s->rows[j * RP_ROW_SUMS + v], v < nv. */
void restir_rp_sum_rows(const struct rp_sys *s, int nv, double *out);

/* A non-finite input value reads as 0. */
static inline double rp_in(float v)
{
    return isfinite(v) ? (double)v : 0.0;
}

/* y += e (xp - xq) over RGB: one weighted edge of the operator. */
static inline void rp_edge(double y[3], const double *xp, const double *xq, double e)
{
    y[0] += e * (xp[0] - xq[0]);
    y[1] += e * (xp[1] - xq[1]);
    y[2] += e * (xp[2] - xq[2]);
}

/* A weight array's entry p; a NULL array weighs everything 1. */
static inline double rp_wgt(const double *wts, size_t p)
{
    return wts ? wts[p] : 1.0;
}

/* The diagonal of A at pixel (i, j): a2 wd_p plus the weights of the pixel's edges. */
static inline double rp_diag_at(int w, int h, double a2, const double *wd, const double *wx, const double *wy,
                                int i, int j)
{
    const size_t W = (size_t)w, p = (size_t)j * W + (size_t)i;
    double d = a2 * rp_wgt(wd, p);
    if (i + 1 < w)
        d += rp_wgt(wx, p);
    if (i > 0)
        d += rp_wgt(wx, p - 1);
    if (j + 1 < h)
        d += rp_wgt(wy, p);
    if (j > 0)
        d += rp_wgt(wy, p - W);
    return d;
}

/* y = (A x) at pixel (i, j) of the w x h operator A = a2 Wd + Dx^T Wx Dx + Dy^T Wy Dy (weight
 * arrays as in struct rp_sys, NULL meaning all 1). */
static inline void rp_apply_at(int w, int h, double a2, const double *wd, const double *wx, const double *wy,
                               const double *x, int i, int j, double y[3])
{
    const size_t W = (size_t)w, p = (size_t)j * W + (size_t)i;
    const double *xp = x + 3 * p;
    if (i > 0 && i + 1 < w && j > 0 && j + 1 < h && wd && wx && wy) {
        /* Interior pixel of a weighted system: no tests per edge (the same sums in the same order * as below). */
        const double d = a2 * wd[p], e0 = wx[p], e1 = wx[p - 1], e2 = wy[p], e3 = wy[p - W];
        const double *x0 = xp + 3, *x1 = xp - 3, *x2 = xp + 3 * W, *x3 = xp - 3 * W;
        for (int c = 0; c < 3; c++)
            y[c] = d * xp[c] + e0 * (xp[c] - x0[c]) + e1 * (xp[c] - x1[c]) + e2 * (xp[c] - x2[c]) +
                   e3 * (xp[c] - x3[c]);
        return;
    }
    const double d = a2 * rp_wgt(wd, p);
    y[0] = d * xp[0];
    y[1] = d * xp[1];
    y[2] = d * xp[2];
    if (i + 1 < w)
        rp_edge(y, xp, xp + 3, rp_wgt(wx, p));
    if (i > 0)
        rp_edge(y, xp, xp - 3, rp_wgt(wx, p - 1));
    if (j + 1 < h)
        rp_edge(y, xp, xp + 3 * W, rp_wgt(wy, p));
    if (j > 0)
        rp_edge(y, xp, xp - 3 * W, rp_wgt(wy, p - W));
}

/* n doubles (malloc), NULL on overflow or failure. */
double *restir_rp_alloc(size_t n);
/* b of the system from the float inputs. */
void restir_rp_rhs(const struct rp_sys *s, const float *primal, const float *dx, const float *dy, double *b);
/* Per channel c: rel[c] = |b - A x| / |b| (|b - A x| where |b| = 0). */
void restir_rp_residual(const struct rp_sys *s, const double *b, const double *x, double rel[3]);
/* Direct solve of the unweighted system (wp = wx = wy = 1) by DCT. Returns 0 or -1. */
int restir_rp_dct_solve(int w, int h, double a2, const double *b, double *x);
/* Shared argument check of the public functions: 0 when usable. */
int restir_rp_check(int w, int h, const float *primal, const float *dx, const float *dy, float alpha, const float *out);
/* Images below this many pixels run their loops on the calling thread: a parallel region's fork
 * and barriers cost more than the loop there (a 48 x 32 CG solve took 330 ms on 2 threads and 1.3
 * ms on 1, docs/BENCHMARKS.md "librestir's thread count"). The multigrid's coarse levels use the
 * same bound. Results do not depend on the thread count (reductions are summed per row, in order). */
#define RP_PARALLEL_MIN 16384

/* Threads for a loop over an image of n pixels: 1 below RP_PARALLEL_MIN, else restir_threads_get(). */
static inline int restir_rp_threads(size_t n)
{
    return n < RP_PARALLEL_MIN ? 1 : restir_threads_get();
}

/* Wall-clock milliseconds since an arbitrary origin (C11 timespec_get), for the stats' ms. */
double restir_rp_now_ms(void);
/* Rounds x to float. */
void restir_rp_store(size_t n, const double *x, float *out);

#endif
