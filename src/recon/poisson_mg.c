/* poisson_mg.c: aggregation multigrid V-cycle for the screened Poisson system (recon/poisson_mg.h).
 */
#include "recon/poisson_mg.h"

#include <stdlib.h>
#include <string.h>

void restir_rp_mg_free(struct rp_mg *mg)
{
    for (int k = 0; k < RP_MG_MAX_LEVELS; k++) {
        struct rp_mg_level *l = &mg->lv[k];
        free(l->own_d), free(l->own_ex), free(l->own_ey), free(l->x), free(l->b), free(l->inv);
    }
    memset(mg, 0, sizeof *mg);
}

/* Galerkin coarse operator of level f onto level c (sizes already set, arrays allocated). */
static void mg_coarsen(const struct rp_mg_level *f, struct rp_mg_level *c)
{
    const int fw = f->w, fh = f->h, cw = c->w, ch = c->h;
#pragma omp parallel for schedule(static) if ((size_t)fw * (size_t)fh > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int J = 0; J < ch; J++) {
        for (int I = 0; I < cw; I++) {
            const size_t q = (size_t)J * (size_t)cw + (size_t)I;
            double d = 0.0, ex = 0.0, ey = 0.0;
            for (int j = 2 * J; j < 2 * J + 2 && j < fh; j++) {
                for (int i = 2 * I; i < 2 * I + 2 && i < fw; i++) {
                    const size_t p = (size_t)j * (size_t)fw + (size_t)i;
                    d += f->a2 * rp_wgt(f->wd, p);
                    if (i == 2 * I + 1 && i + 1 < fw) /* fine x-edge into block I + 1 */
                        ex += rp_wgt(f->ex, p);
                    if (j == 2 * J + 1 && j + 1 < fh)
                        ey += rp_wgt(f->ey, p);
                }
            }
            c->own_d[q] = d;
            c->own_ex[q] = ex;
            c->own_ey[q] = ey;
        }
    }
}

/* inv[p] = 1 / (d_p + sum_q e_pq), the Gauss-Seidel divisor of every pixel of level l. */
static void mg_divisors(struct rp_mg_level *l)
{
    const int w = l->w, h = l->h;
    const size_t W = (size_t)w;
#pragma omp parallel for schedule(static) if (W * (size_t)h > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const size_t p = (size_t)j * W + (size_t)i;
            const double dd = rp_diag_at(w, h, l->a2, l->wd, l->ex, l->ey, i, j);
            l->inv[p] = 1.0 / dd;
        }
    }
}

static inline void mg_add(double s[3], double e, const double *xq)
{
    s[0] += e * xq[0];
    s[1] += e * xq[1];
    s[2] += e * xq[2];
}

int restir_rp_mg_build(struct rp_mg *mg, const struct rp_sys *s, int sweeps)
{
    struct rp_mg_level *l0 = &mg->lv[0];
    if (!l0->inv && !(l0->inv = restir_rp_alloc(s->n))) {
        restir_rp_mg_free(mg);
        return -1;
    }
    l0->w = s->w, l0->h = s->h, l0->a2 = s->a2;
    l0->wd = s->wp, l0->ex = s->wx, l0->ey = s->wy;
    mg->sweeps = sweeps;
    int k = 1;
    while (k < RP_MG_MAX_LEVELS && (mg->lv[k - 1].w > 4 || mg->lv[k - 1].h > 4)) {
        struct rp_mg_level *f = &mg->lv[k - 1], *c = &mg->lv[k];
        c->w = (f->w + 1) / 2, c->h = (f->h + 1) / 2, c->a2 = 1.0;
        const size_t n = (size_t)c->w * (size_t)c->h;
        if (!c->own_d) {
            c->own_d = restir_rp_alloc(n), c->own_ex = restir_rp_alloc(n), c->own_ey = restir_rp_alloc(n);
            c->x = restir_rp_alloc(3 * n), c->b = restir_rp_alloc(3 * n), c->inv = restir_rp_alloc(n);
            if (!c->own_d || !c->own_ex || !c->own_ey || !c->x || !c->b || !c->inv) {
                restir_rp_mg_free(mg);
                return -1;
            }
        }
        c->wd = c->own_d, c->ex = c->own_ex, c->ey = c->own_ey;
        mg_coarsen(f, c);
        k++;
    }
    mg->levels = k;
    for (int t = 0; t < k; t++)
        mg_divisors(&mg->lv[t]);
    return 0;
}

/* One Gauss-Seidel half sweep over the pixels with (i + j) % 2 == colour: x_p = (b_p + sum_q e_pq
 * x_q) / (d_p + sum_q e_pq). */
static void mg_gs(const struct rp_mg_level *l, const double *b, double *x, int colour)
{
    const int w = l->w, h = l->h;
    const size_t W = (size_t)w;
    const double *ex = l->ex, *ey = l->ey;
#pragma omp parallel for schedule(static) if (W * (size_t)h > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int j = 0; j < h; j++) {
        for (int i = (j + colour) & 1; i < w; i += 2) {
            const size_t p = (size_t)j * W + (size_t)i;
            const double *xp = x + 3 * p;
            double sum[3] = {b[3 * p], b[3 * p + 1], b[3 * p + 2]};
            if (i + 1 < w)
                mg_add(sum, rp_wgt(ex, p), xp + 3);
            if (i > 0)
                mg_add(sum, rp_wgt(ex, p - 1), xp - 3);
            if (j + 1 < h)
                mg_add(sum, rp_wgt(ey, p), xp + 3 * W);
            if (j > 0)
                mg_add(sum, rp_wgt(ey, p - W), xp - 3 * W);
            const double inv = l->inv[p];
            x[3 * p] = sum[0] * inv;
            x[3 * p + 1] = sum[1] * inv;
            x[3 * p + 2] = sum[2] * inv;
        }
    }
}

/* The first half sweep from x = 0: red pixels get b_p / (d_p + sum e), black ones 0. */
static void mg_gs_from_zero(const struct rp_mg_level *l, const double *b, double *x)
{
    const int w = l->w, h = l->h;
    const size_t W = (size_t)w;
#pragma omp parallel for schedule(static) if (W * (size_t)h > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const size_t p = (size_t)j * W + (size_t)i;
            const double f = ((i + j) & 1) ? 0.0 : l->inv[p];
            x[3 * p] = b[3 * p] * f;
            x[3 * p + 1] = b[3 * p + 1] * f;
            x[3 * p + 2] = b[3 * p + 2] * f;
        }
    }
}

/* c->b = R (b - A x): the fine residual summed over each 2x2 block. */
static void mg_restrict_residual(const struct rp_mg_level *f, const double *b, const double *x,
                                 struct rp_mg_level *c)
{
    const int fw = f->w, fh = f->h, cw = c->w;
    const size_t W = (size_t)fw;
#pragma omp parallel for schedule(static) if (W * (size_t)fh > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int J = 0; J < c->h; J++) {
        for (int I = 0; I < cw; I++) {
            double acc[3] = {0.0, 0.0, 0.0};
            for (int j = 2 * J; j < 2 * J + 2 && j < fh; j++) {
                for (int i = 2 * I; i < 2 * I + 2 && i < fw; i++) {
                    const size_t p = (size_t)j * W + (size_t)i;
                    double y[3];
                    rp_apply_at(fw, fh, f->a2, f->wd, f->ex, f->ey, x, i, j, y);
                    for (int ch = 0; ch < 3; ch++)
                        acc[ch] += b[3 * p + ch] - y[ch];
                }
            }
            double *cb = c->b + 3 * ((size_t)J * (size_t)cw + (size_t)I);
            cb[0] = acc[0], cb[1] = acc[1], cb[2] = acc[2];
        }
    }
}

/* x += P c->x: each fine pixel gets its block's coarse value. */
static void mg_prolong_add(const struct rp_mg_level *f, const struct rp_mg_level *c, double *x)
{
    const int fw = f->w, cw = c->w;
#pragma omp parallel for schedule(static) if ((size_t)fw * (size_t)f->h > RP_PARALLEL_MIN) num_threads(restir_threads_get())
    for (int j = 0; j < f->h; j++) {
        for (int i = 0; i < fw; i++) {
            const double *cx = c->x + 3 * ((size_t)(j / 2) * (size_t)cw + (size_t)(i / 2));
            double *xp = x + 3 * ((size_t)j * (size_t)fw + (size_t)i);
            xp[0] += cx[0], xp[1] += cx[1], xp[2] += cx[2];
        }
    }
}

static void mg_vcycle(struct rp_mg *mg, int k, const double *b, double *x)
{
    const struct rp_mg_level *l = &mg->lv[k];
    const int last = k + 1 == mg->levels;
    const int pairs = last ? RP_MG_COARSE_SWEEPS : mg->sweeps;
    for (int t = 0; t < pairs; t++) {
        if (t == 0)
            mg_gs_from_zero(l, b, x); /* the red half sweep from x = 0 */
        else
            mg_gs(l, b, x, 0);
        mg_gs(l, b, x, 1);
    }
    if (!last) {
        struct rp_mg_level *c = &mg->lv[k + 1];
        mg_restrict_residual(l, b, x, c);
        mg_vcycle(mg, k + 1, c->b, c->x);
        mg_prolong_add(l, c, x);
    }
    for (int t = 0; t < pairs; t++) {
        mg_gs(l, b, x, 1);
        mg_gs(l, b, x, 0);
    }
}

void restir_rp_mg_apply(struct rp_mg *mg, const double *r, double *z)
{
    mg_vcycle(mg, 0, r, z);
}
