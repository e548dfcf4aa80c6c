/* poisson_l1.c: L1 screened Poisson reconstruction by IRLS (restir/poisson.h), after the public
 * G-PT solver's "L1D" preset (see the header for where it differs). */
#include <math.h>
#include <stdlib.h>

#include "recon/poisson_cg.h"
#include "recon/poisson_mg.h"
#include "recon/poisson_ops.h"
#include "restir/poisson.h"

static inline double rp_len3(double a, double b, double c)
{
    return sqrt(a * a + b * b + c * c);
}

/* IRLS weights 1 / (|e| + reg) of every row at the current x, scaled to mean 1 over the
 * n + (w-1) h + w (h-1) rows. The ignored last-column / last-row entries are set to 0. */
static void rp_weights(const struct rp_sys *s, double alpha, const float *primal, const float *dx, const float *dy,
                       const double *x, double reg, double *wp, double *wx, double *wy)
{
    const int w = s->w, h = s->h;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (int j = 0; j < h; j++) {
        double sum = 0.0;
        for (int i = 0; i < w; i++) {
            const size_t p = (size_t)j * (size_t)w + (size_t)i;
            const double *xp = x + 3 * p;
            const float *pp = primal + 3 * p;
            double e = alpha * rp_len3(xp[0] - rp_in(pp[0]), xp[1] - rp_in(pp[1]), xp[2] - rp_in(pp[2]));
            wp[p] = 1.0 / (e + reg);
            sum += wp[p];
            wx[p] = wy[p] = 0.0;
            if (i + 1 < w) {
                const double *xq = xp + 3;
                const float *g = dx + 3 * p;
                e = rp_len3(xq[0] - xp[0] - rp_in(g[0]), xq[1] - xp[1] - rp_in(g[1]), xq[2] - xp[2] - rp_in(g[2]));
                wx[p] = 1.0 / (e + reg);
                sum += wx[p];
            }
            if (j + 1 < h) {
                const double *xq = xp + 3 * (size_t)w;
                const float *g = dy + 3 * p;
                e = rp_len3(xq[0] - xp[0] - rp_in(g[0]), xq[1] - xp[1] - rp_in(g[1]), xq[2] - xp[2] - rp_in(g[2]));
                wy[p] = 1.0 / (e + reg);
                sum += wy[p];
            }
        }
        s->rows[(size_t)j * RP_ROW_SUMS] = sum;
    }
    double sum;
    restir_rp_sum_rows(s, 1, &sum);
    const double rows = (double)s->n + (double)(w - 1) * h + (double)w * (h - 1);
    const double scale = rows / sum;
    const long ln = (long)s->n;
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
    for (long k = 0; k < ln; k++) {
        wp[k] *= scale;
        wx[k] *= scale;
        wy[k] *= scale;
    }
}

int restir_poisson_l1(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                      int iterations, enum restir_poisson_precond precond, int cg_steps, float *out,
                      struct restir_poisson_stats *st)
{
    const double t0 = restir_rp_now_ms();
    if (restir_rp_check(w, h, primal, dx, dy, alpha, out) != 0 || iterations < 0 ||
        iterations > RESTIR_POISSON_L1_MAX_ITERATIONS || cg_steps < 1 ||
        (precond != RESTIR_POISSON_PRECOND_MULTIGRID && precond != RESTIR_POISSON_PRECOND_JACOBI))
        return -1;
    struct rp_mg mg = {0};
    struct rp_cg_work work = {0};
    struct rp_mg *pre = precond == RESTIR_POISSON_PRECOND_MULTIGRID ? &mg : NULL;
    const size_t n = (size_t)w * (size_t)h;
    struct rp_sys s = {w, h, n, (double)alpha * (double)alpha, NULL, NULL, NULL,
                       restir_rp_alloc(RP_ROW_SUMS * (size_t)h)};
    double *b = restir_rp_alloc(3 * n), *x = restir_rp_alloc(3 * n);
    double *wp = restir_rp_alloc(n), *wx = restir_rp_alloc(n), *wy = restir_rp_alloc(n);
    int rc = -1, total = 0;
    if (!b || !x || !wp || !wx || !wy || !s.rows || restir_rp_cg_work_alloc(&work, n) != 0)
        goto done;
    restir_rp_rhs(&s, primal, dx, dy, b);
    if (restir_rp_dct_solve(w, h, s.a2, b, x) != 0)
        goto done;
    for (int k = 1; k <= iterations; k++) {
        const double reg = 0.05 * pow(0.5, k - 1);
        rp_weights(&s, alpha, primal, dx, dy, x, reg, wp, wx, wy);
        s.wp = wp, s.wx = wx, s.wy = wy;
        restir_rp_rhs(&s, primal, dx, dy, b);
        if (pre && restir_rp_mg_build(pre, &s, RP_MG_SWEEPS) != 0)
            goto done;
        const int it = restir_rp_cg(&s, b, x, 0.0, cg_steps, pre, &work);
        if (it < 0)
            goto done;
        total += it;
    }
    double rel[3];
    restir_rp_residual(&s, b, x, rel);
    restir_rp_store(n, x, out);
    if (st) {
        st->iterations = total;
        st->residual = fmax(rel[0], fmax(rel[1], rel[2]));
        st->ms = restir_rp_now_ms() - t0;
    }
    rc = 0;
done:;
    restir_rp_mg_free(&mg);
    restir_rp_cg_work_free(&work);
    free(b), free(x), free(wp), free(wx), free(wy), free(s.rows);
    return rc;
}

double restir_poisson_l1_energy(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                                const float *x)
{
    if (restir_rp_check(w, h, primal, dx, dy, alpha, x) != 0)
        return NAN;
    double e = 0.0;
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const size_t k = 3 * ((size_t)j * (size_t)w + (size_t)i), q = k + 3 * (size_t)w;
            e += alpha * rp_len3(rp_in(x[k]) - rp_in(primal[k]), rp_in(x[k + 1]) - rp_in(primal[k + 1]),
                                 rp_in(x[k + 2]) - rp_in(primal[k + 2]));
            if (i + 1 < w)
                e += rp_len3(rp_in(x[k + 3]) - rp_in(x[k]) - rp_in(dx[k]),
                             rp_in(x[k + 4]) - rp_in(x[k + 1]) - rp_in(dx[k + 1]),
                             rp_in(x[k + 5]) - rp_in(x[k + 2]) - rp_in(dx[k + 2]));
            if (j + 1 < h)
                e += rp_len3(rp_in(x[q]) - rp_in(x[k]) - rp_in(dy[k]),
                             rp_in(x[q + 1]) - rp_in(x[k + 1]) - rp_in(dy[k + 1]),
                             rp_in(x[q + 2]) - rp_in(x[k + 2]) - rp_in(dy[k + 2]));
        }
    }
    return e;
}
