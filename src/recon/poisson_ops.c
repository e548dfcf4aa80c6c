/* poisson_ops.c: the normal-equation operator of the (weighted) screened Poisson system, its
 * right-hand side, residuals and Jacobi-preconditioned CG (recon/poisson_ops.h). The three
 * channels are solved in lockstep (one pass over memory per step, per-channel CG scalars); dot
 * products are summed in double per image row, then over rows in order (deterministic). */
#include "recon/poisson_ops.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

double *rp_alloc(size_t n)
{
    if (n == 0 || n > SIZE_MAX / sizeof(double))
        return NULL;
    return malloc(n * sizeof(double));
}

void rp_sum_rows(const struct rp_sys *s, int nv, double *out)
{
    for (int v = 0; v < nv; v++)
        out[v] = 0.0;
    for (int j = 0; j < s->h; j++)
        for (int v = 0; v < nv; v++)
            out[v] += s->rows[(size_t)j * RP_ROW_SUMS + v];
}

int rp_check(int w, int h, const float *primal, const float *dx, const float *dy, float alpha, const float *out)
{
    if (w < 1 || h < 1 || !primal || !dx || !dy || !out || !isfinite(alpha) || !(alpha > 0.0f))
        return -1;
    /* Five 3n double vectors must be addressable. */
    if ((size_t)w > SIZE_MAX / (size_t)h / (16 * sizeof(double)))
        return -1;
    return 0;
}

void rp_store(size_t n, const double *x, float *out)
{
    const long m = (long)(3 * n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < m; i++)
        out[i] = (float)x[i];
}

static inline double rp_wgt(const double *wts, size_t p)
{
    return wts ? wts[p] : 1.0;
}

static inline void rp_edge(double y[3], const double *xp, const double *xq, double e)
{
    y[0] += e * (xp[0] - xq[0]);
    y[1] += e * (xp[1] - xq[1]);
    y[2] += e * (xp[2] - xq[2]);
}

/* y = (A x) at pixel (i, j). */
static inline void rp_ax(const struct rp_sys *s, const double *x, int i, int j, double y[3])
{
    const size_t w = (size_t)s->w, p = (size_t)j * w + (size_t)i;
    const double *xp = x + 3 * p;
    const double d = s->a2 * rp_wgt(s->wp, p);
    y[0] = d * xp[0];
    y[1] = d * xp[1];
    y[2] = d * xp[2];
    if (i + 1 < s->w)
        rp_edge(y, xp, xp + 3, rp_wgt(s->wx, p));
    if (i > 0)
        rp_edge(y, xp, xp - 3, rp_wgt(s->wx, p - 1));
    if (j + 1 < s->h)
        rp_edge(y, xp, xp + 3 * w, rp_wgt(s->wy, p));
    if (j > 0)
        rp_edge(y, xp, xp - 3 * w, rp_wgt(s->wy, p - w));
}

void rp_rhs(const struct rp_sys *s, const float *primal, const float *dx, const float *dy, double *b)
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const size_t p = (size_t)j * (size_t)w + (size_t)i;
            const double d = s->a2 * rp_wgt(s->wp, p);
            for (int c = 0; c < 3; c++) {
                double v = d * rp_in(primal[3 * p + c]);
                if (i + 1 < w)
                    v -= rp_wgt(s->wx, p) * rp_in(dx[3 * p + c]);
                if (i > 0)
                    v += rp_wgt(s->wx, p - 1) * rp_in(dx[3 * (p - 1) + c]);
                if (j + 1 < h)
                    v -= rp_wgt(s->wy, p) * rp_in(dy[3 * p + c]);
                if (j > 0)
                    v += rp_wgt(s->wy, p - (size_t)w) * rp_in(dy[3 * (p - (size_t)w) + c]);
                b[3 * p + c] = v;
            }
        }
    }
}

/* y = A x; dot[c] = x . y per channel. */
static void rp_apply_dot(const struct rp_sys *s, const double *x, double *y, double dot[3])
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        double d0 = 0.0, d1 = 0.0, d2 = 0.0;
        for (int i = 0; i < w; i++) {
            const size_t p = 3 * ((size_t)j * (size_t)w + (size_t)i);
            double *yp = y + p;
            rp_ax(s, x, i, j, yp);
            d0 += x[p] * yp[0];
            d1 += x[p + 1] * yp[1];
            d2 += x[p + 2] * yp[2];
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        row[0] = d0, row[1] = d1, row[2] = d2;
    }
    rp_sum_rows(s, 3, dot);
}

/* Per channel: rr[c] = |b - A x|^2, bb[c] = |b|^2. */
static void rp_residual_sq(const struct rp_sys *s, const double *b, const double *x, double rr[3], double bb[3])
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        double r0 = 0.0, r1 = 0.0, r2 = 0.0, b0 = 0.0, b1 = 0.0, b2 = 0.0;
        for (int i = 0; i < w; i++) {
            const size_t p = 3 * ((size_t)j * (size_t)w + (size_t)i);
            double y[3];
            rp_ax(s, x, i, j, y);
            const double e0 = b[p] - y[0], e1 = b[p + 1] - y[1], e2 = b[p + 2] - y[2];
            r0 += e0 * e0;
            r1 += e1 * e1;
            r2 += e2 * e2;
            b0 += b[p] * b[p];
            b1 += b[p + 1] * b[p + 1];
            b2 += b[p + 2] * b[p + 2];
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        row[0] = r0, row[1] = r1, row[2] = r2, row[3] = b0, row[4] = b1, row[5] = b2;
    }
    double sums[6];
    rp_sum_rows(s, 6, sums);
    rr[0] = sums[0], rr[1] = sums[1], rr[2] = sums[2];
    bb[0] = sums[3], bb[1] = sums[4], bb[2] = sums[5];
}

void rp_residual(const struct rp_sys *s, const double *b, const double *x, double rel[3])
{
    double rr[3], bb[3];
    rp_residual_sq(s, b, x, rr, bb);
    for (int c = 0; c < 3; c++)
        rel[c] = bb[c] > 0.0 ? sqrt(rr[c] / bb[c]) : sqrt(rr[c]);
}

int rp_cg(const struct rp_sys *s, const double *b, double *x, double tol, int max_iters)
{
    const size_t n = s->n, m = 3 * n;
    const long ln = (long)n;
    double *r = rp_alloc(m), *p = rp_alloc(m), *q = rp_alloc(m), *dinv = rp_alloc(n);
    if (!r || !p || !q || !dinv) {
        free(r), free(p), free(q), free(dinv);
        return -1;
    }
    const int w = s->w, h = s->h;
    /* Jacobi preconditioner: 1 / diag(A). diag(A) >= a2 wp > 0 for positive weights. */
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const size_t k = (size_t)j * (size_t)w + (size_t)i;
            double d = s->a2 * rp_wgt(s->wp, k);
            if (i + 1 < w)
                d += rp_wgt(s->wx, k);
            if (i > 0)
                d += rp_wgt(s->wx, k - 1);
            if (j + 1 < h)
                d += rp_wgt(s->wy, k);
            if (j > 0)
                d += rp_wgt(s->wy, k - (size_t)w);
            dinv[k] = d > 0.0 ? 1.0 / d : 0.0;
        }
    }

    double rr[3], bb[3], bn[3], rz[3], a[3], beta[3];
    int active[3];
    rp_residual_sq(s, b, x, rr, bb);
    for (int c = 0; c < 3; c++) {
        bn[c] = sqrt(bb[c]);
        if (bb[c] == 0.0) { /* x = 0 is exact */
            for (size_t k = 0; k < n; k++)
                x[3 * k + c] = 0.0;
            active[c] = 0;
        } else {
            active[c] = sqrt(rr[c]) > tol * bn[c];
        }
    }
    /* r = b - A x (q = A x), p = z = dinv r, rz = r . z. */
    double dot[3];
    rp_apply_dot(s, x, q, dot);
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        double z0 = 0.0, z1 = 0.0, z2 = 0.0;
        for (long k = (long)j * w; k < (long)(j + 1) * w; k++) {
            double *rk = r + 3 * k, *pk = p + 3 * k;
            const double *bk = b + 3 * k, *qk = q + 3 * k;
            for (int c = 0; c < 3; c++) {
                rk[c] = bk[c] - qk[c];
                pk[c] = dinv[k] * rk[c];
            }
            z0 += rk[0] * pk[0];
            z1 += rk[1] * pk[1];
            z2 += rk[2] * pk[2];
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        row[0] = z0, row[1] = z1, row[2] = z2;
    }
    rp_sum_rows(s, 3, rz);

    int iters = 0;
    while ((active[0] || active[1] || active[2]) && iters < max_iters) {
        rp_apply_dot(s, p, q, dot); /* q = A p, dot = p . A p */
        for (int c = 0; c < 3; c++) {
            if (active[c] && !(dot[c] > 0.0 && isfinite(rz[c] / dot[c])))
                active[c] = 0; /* breakdown: stop this channel where it is */
            a[c] = active[c] ? rz[c] / dot[c] : 0.0;
        }
#pragma omp parallel for schedule(static)
        for (int j = 0; j < h; j++) {
            double s0 = 0.0, s1 = 0.0, s2 = 0.0, t0 = 0.0, t1 = 0.0, t2 = 0.0;
            for (long k = (long)j * w; k < (long)(j + 1) * w; k++) {
                double *xk = x + 3 * k, *rk = r + 3 * k;
                const double *pk = p + 3 * k, *qk = q + 3 * k;
                for (int c = 0; c < 3; c++) {
                    xk[c] += a[c] * pk[c];
                    rk[c] -= a[c] * qk[c];
                }
                s0 += rk[0] * rk[0];
                s1 += rk[1] * rk[1];
                s2 += rk[2] * rk[2];
                t0 += rk[0] * rk[0] * dinv[k];
                t1 += rk[1] * rk[1] * dinv[k];
                t2 += rk[2] * rk[2] * dinv[k];
            }
            double *row = s->rows + (size_t)j * RP_ROW_SUMS;
            row[0] = s0, row[1] = s1, row[2] = s2, row[3] = t0, row[4] = t1, row[5] = t2;
        }
        iters++;
        double sums[6];
        rp_sum_rows(s, 6, sums);
        const double sr[3] = {sums[0], sums[1], sums[2]}, tz[3] = {sums[3], sums[4], sums[5]};
        for (int c = 0; c < 3; c++) {
            if (active[c] && sqrt(sr[c]) <= tol * bn[c])
                active[c] = 0;
            beta[c] = active[c] ? tz[c] / rz[c] : 0.0;
            if (active[c])
                rz[c] = tz[c];
        }
        if (!(active[0] || active[1] || active[2]) || iters >= max_iters)
            break;
#pragma omp parallel for schedule(static)
        for (long k = 0; k < ln; k++) {
            double *pk = p + 3 * k;
            const double *rk = r + 3 * k;
            for (int c = 0; c < 3; c++)
                pk[c] = dinv[k] * rk[c] + beta[c] * pk[c];
        }
    }
    free(r), free(p), free(q), free(dinv);
    return iters;
}
