/* poisson_ops.c: the right-hand side, residuals and shared helpers of the (weighted) screened
 * Poisson system (recon/poisson_ops.h). Reductions are summed in double per image row, then over
 * rows in order (deterministic). */
#include "recon/poisson_ops.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

double *restir_rp_alloc(size_t n)
{
    if (n == 0 || n > SIZE_MAX / sizeof(double))
        return NULL;
    return malloc(n * sizeof(double));
}

void restir_rp_sum_rows(const struct rp_sys *s, int nv, double *out)
{
    for (int v = 0; v < nv; v++)
        out[v] = 0.0;
    for (int j = 0; j < s->h; j++)
        for (int v = 0; v < nv; v++)
            out[v] += s->rows[(size_t)j * RP_ROW_SUMS + v];
}

int restir_rp_check(int w, int h, const float *primal, const float *dx, const float *dy, float alpha, const float *out)
{
    if (w < 1 || h < 1 || !primal || !dx || !dy || !out || !isfinite(alpha) || !(alpha > 0.0f))
        return -1;
    /* Five 3n double vectors must be addressable, and the loops' int sums of coordinates (i + j,
     * 2 i + 2 on the multigrid levels) must not overflow. */
    if ((size_t)w > SIZE_MAX / (size_t)h / (16 * sizeof(double)) || w > INT_MAX - h)
        return -1;
    return 0;
}

void restir_rp_store(size_t n, const double *x, float *out)
{
    const long m = (long)(3 * n);
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads(n))
    for (long i = 0; i < m; i++)
        out[i] = (float)x[i];
}

/* y = (A x) at pixel (i, j). */
static inline void rp_ax(const struct rp_sys *s, const double *x, int i, int j, double y[3])
{
    rp_apply_at(s->w, s->h, s->a2, s->wp, s->wx, s->wy, x, i, j, y);
}

void restir_rp_rhs(const struct rp_sys *s, const float *primal, const float *dx, const float *dy, double *b)
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
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

/* Per channel: rr[c] = |b - A x|^2, bb[c] = |b|^2. */
static void rp_residual_sq(const struct rp_sys *s, const double *b, const double *x, double rr[3], double bb[3])
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
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
    restir_rp_sum_rows(s, 6, sums);
    rr[0] = sums[0], rr[1] = sums[1], rr[2] = sums[2];
    bb[0] = sums[3], bb[1] = sums[4], bb[2] = sums[5];
}

void restir_rp_residual(const struct rp_sys *s, const double *b, const double *x, double rel[3])
{
    double rr[3], bb[3];
    rp_residual_sq(s, b, x, rr, bb);
    for (int c = 0; c < 3; c++)
        rel[c] = bb[c] > 0.0 ? sqrt(rr[c] / bb[c]) : sqrt(rr[c]);
}

double restir_rp_now_ms(void)
{
    struct timespec ts;
    if (timespec_get(&ts, TIME_UTC) != TIME_UTC)
        return 0.0;
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}
