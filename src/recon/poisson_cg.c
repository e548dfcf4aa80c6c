/* poisson_cg.c: preconditioned conjugate gradient on the (weighted) screened Poisson system
 * (recon/poisson_cg.h). The three channels are solved in lockstep (one pass over memory per step,
 * per-channel CG scalars); dot products are summed in double per image row, then over rows in order
 * (deterministic for any thread count). */
#include "recon/poisson_cg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "recon/poisson_mg.h"

/* y = A x; dot[c] = x . y per channel. */
static void rp_apply_dot(const struct rp_sys *s, const double *x, double *y, double dot[3])
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int j = 0; j < h; j++) {
        double d0 = 0.0, d1 = 0.0, d2 = 0.0;
        for (int i = 0; i < w; i++) {
            const size_t p = 3 * ((size_t)j * (size_t)w + (size_t)i);
            double *yp = y + p;
            rp_apply_at(w, h, s->a2, s->wp, s->wx, s->wy, x, i, j, yp);
            d0 += x[p] * yp[0];
            d1 += x[p + 1] * yp[1];
            d2 += x[p + 2] * yp[2];
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        row[0] = d0, row[1] = d1, row[2] = d2;
    }
    restir_rp_sum_rows(s, 3, dot);
}

/* Per channel r . z, summed per row then over rows. */
static void rp_dot(const struct rp_sys *s, const double *r, const double *z, double out[3])
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int j = 0; j < h; j++) {
        double d0 = 0.0, d1 = 0.0, d2 = 0.0;
        for (long k = (long)j * w; k < (long)(j + 1) * w; k++) {
            d0 += r[3 * k] * z[3 * k];
            d1 += r[3 * k + 1] * z[3 * k + 1];
            d2 += r[3 * k + 2] * z[3 * k + 2];
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        row[0] = d0, row[1] = d1, row[2] = d2;
    }
    restir_rp_sum_rows(s, 3, out);
}

int restir_rp_cg_work_alloc(struct rp_cg_work *wk, size_t n)
{
    const size_t m = 3 * n;
    wk->r = restir_rp_alloc(m), wk->p = restir_rp_alloc(m), wk->q = restir_rp_alloc(m);
    wk->z = restir_rp_alloc(m), wk->dinv = restir_rp_alloc(n);
    if (wk->r && wk->p && wk->q && wk->z && wk->dinv)
        return 0;
    restir_rp_cg_work_free(wk);
    return -1;
}

void restir_rp_cg_work_free(struct rp_cg_work *wk)
{
    free(wk->r), free(wk->p), free(wk->q), free(wk->z), free(wk->dinv);
    memset(wk, 0, sizeof *wk);
}

int restir_rp_cg(const struct rp_sys *s, const double *b, double *x, double tol, int max_iters, struct rp_mg *mg,
          struct rp_cg_work *work)
{
    const size_t n = s->n;
    const long ln = (long)n;
    struct rp_cg_work own = {0};
    if (!work) {
        if (restir_rp_cg_work_alloc(&own, n) != 0)
            return -1;
        work = &own;
    }
    double *r = work->r, *p = work->p, *q = work->q, *z = work->z, *dinv = work->dinv;
    /* A residual at rounding level is converged: steps past it only add rounding noise to x (L1
     * asks for a fixed number of steps with tol = 0). */
    const double stop = fmax(tol, RP_CG_TOL_FLOOR);
    const int w = s->w, h = s->h;
    /* Jacobi preconditioner: 1 / diag(A). diag(A) >= a2 wp > 0 for positive weights. */
    if (!mg) {
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
        for (int j = 0; j < h; j++) {
            for (int i = 0; i < w; i++) {
                const size_t k = (size_t)j * (size_t)w + (size_t)i;
                const double d = rp_diag_at(w, h, s->a2, s->wp, s->wx, s->wy, i, j);
                dinv[k] = d > 0.0 ? 1.0 / d : 0.0;
            }
        }
    }

    /* r = b - A x (q = A x), p = z = dinv r (Jacobi), rz = r . z, rr = |r|^2, bb = |b|^2. */
    double rr[3], bb[3], bn[3], rz[3], a[3], beta[3], dot[3];
    int active[3];
    rp_apply_dot(s, x, q, dot);
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int j = 0; j < h; j++) {
        double acc[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        const long k0 = (long)j * w, k1 = (long)(j + 1) * w;
        for (long k = k0; k < k1; k++) {
            double *rk = r + 3 * k;
            const double *bk = b + 3 * k, *qk = q + 3 * k;
            for (int c = 0; c < 3; c++) {
                rk[c] = bk[c] - qk[c];
                acc[3 + c] += rk[c] * rk[c];
                acc[6 + c] += bk[c] * bk[c];
            }
        }
        /* The Jacobi start in its own loop: a conditional read of dinv inside the loop above
         * compiles to masked loads, which on never-written pages (multigrid does not fill dinv)
         * cost a microcode assist each. */
        if (!mg) {
            for (long k = k0; k < k1; k++) {
                double *pk = p + 3 * k;
                const double *rk = r + 3 * k;
                for (int c = 0; c < 3; c++) {
                    pk[c] = dinv[k] * rk[c];
                    acc[c] += rk[c] * pk[c];
                }
            }
        }
        double *row = s->rows + (size_t)j * RP_ROW_SUMS;
        for (int v = 0; v < 9; v++)
            row[v] = acc[v];
    }
    double sums[9];
    restir_rp_sum_rows(s, 9, sums);
    for (int c = 0; c < 3; c++) {
        rz[c] = sums[c], rr[c] = sums[3 + c], bb[c] = sums[6 + c];
        bn[c] = sqrt(bb[c]);
        if (bb[c] == 0.0) { /* x = 0 is exact, and then r = 0 */
            for (size_t k = 0; k < n; k++)
                x[3 * k + c] = r[3 * k + c] = p[3 * k + c] = 0.0;
            rz[c] = 0.0;
            active[c] = 0;
        } else {
            active[c] = sqrt(rr[c]) > stop * bn[c];
        }
    }
    if (mg) { /* z = M^-1 r */
        restir_rp_mg_apply(mg, r, p);
        rp_dot(s, r, p, rz);
    }

    int iters = 0;
    while ((active[0] || active[1] || active[2]) && iters < max_iters) {
        rp_apply_dot(s, p, q, dot); /* q = A p, dot = p . A p */
        for (int c = 0; c < 3; c++) {
            if (active[c] && !(dot[c] > 0.0 && isfinite(rz[c] / dot[c])))
                active[c] = 0; /* breakdown: stop this channel where it is */
            a[c] = active[c] ? rz[c] / dot[c] : 0.0;
        }
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
        for (int j = 0; j < h; j++) {
            double s0 = 0.0, s1 = 0.0, s2 = 0.0, t0 = 0.0, t1 = 0.0, t2 = 0.0;
            const long k0 = (long)j * w, k1 = (long)(j + 1) * w;
            for (long k = k0; k < k1; k++) {
                double *xk = x + 3 * k, *rk = r + 3 * k;
                const double *pk = p + 3 * k, *qk = q + 3 * k;
                for (int c = 0; c < 3; c++) {
                    xk[c] += a[c] * pk[c];
                    rk[c] -= a[c] * qk[c];
                }
                s0 += rk[0] * rk[0];
                s1 += rk[1] * rk[1];
                s2 += rk[2] * rk[2];
            }
            if (!mg) { /* r . dinv r, in its own loop (see the start) */
                for (long k = k0; k < k1; k++) {
                    const double *rk = r + 3 * k;
                    t0 += rk[0] * rk[0] * dinv[k];
                    t1 += rk[1] * rk[1] * dinv[k];
                    t2 += rk[2] * rk[2] * dinv[k];
                }
            }
            double *row = s->rows + (size_t)j * RP_ROW_SUMS;
            row[0] = s0, row[1] = s1, row[2] = s2, row[3] = t0, row[4] = t1, row[5] = t2;
        }
        iters++;
        double sums[6];
        restir_rp_sum_rows(s, 6, sums);
        const double sr[3] = {sums[0], sums[1], sums[2]}, tz[3] = {sums[3], sums[4], sums[5]};
        for (int c = 0; c < 3; c++)
            if (active[c] && sqrt(sr[c]) <= stop * bn[c])
                active[c] = 0;
        if (!(active[0] || active[1] || active[2]) || iters >= max_iters)
            break;
        double rzn[3] = {tz[0], tz[1], tz[2]};
        if (mg) {
            restir_rp_mg_apply(mg, r, z);
            rp_dot(s, r, z, rzn);
        }
        for (int c = 0; c < 3; c++) {
            if (active[c] && !(rz[c] > 0.0 && isfinite(rzn[c] / rz[c])))
                active[c] = 0; /* r . z underflowed: nothing left to solve */
            beta[c] = active[c] ? rzn[c] / rz[c] : 0.0;
            if (active[c])
                rz[c] = rzn[c];
        }
        if (mg) {
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
            for (long k = 0; k < 3 * ln; k++)
                p[k] = z[k] + beta[k % 3] * p[k];
        } else {
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
            for (long k = 0; k < ln; k++) {
                double *pk = p + 3 * k;
                const double *rk = r + 3 * k;
                for (int c = 0; c < 3; c++)
                    pk[c] = dinv[k] * rk[c] + beta[c] * pk[c];
            }
        }
    }
    restir_rp_cg_work_free(&own);
    return iters;
}
