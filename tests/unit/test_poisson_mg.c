/* test_poisson_mg.c: unit tests for the multigrid preconditioner of the Poisson solves
 * (recon/poisson_mg.h) on weighted systems like IRLS's (weights spanning eight decades): the
 * V-cycle is symmetric and positive definite (what CG needs), it reduces the error as a solver on
 * its own, and CG preconditioned by it reaches a tight residual in far fewer steps than
 * Jacobi-preconditioned CG, to the same solution. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "recon/poisson_cg.h"
#include "recon/poisson_mg.h"
#include "recon/poisson_ops.h"
#include "test_util.h"

static uint64_t rng_state = 0x2545f4914f6cdd1dull;

static double rnd(void) /* uniform [0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static double *dalloc(size_t n)
{
    double *p = calloc(n, sizeof(double));
    if (!p) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return p;
}

static double dot(const double *a, const double *b, size_t m)
{
    double s = 0.0;
    for (size_t i = 0; i < m; i++)
        s += a[i] * b[i];
    return s;
}

/* y = A x, straight from the definition in recon/poisson_ops.h. */
static void apply(const struct rp_sys *s, const double *x, double *y)
{
    for (int j = 0; j < s->h; j++)
        for (int i = 0; i < s->w; i++)
            rp_apply_at(s->w, s->h, s->a2, s->wp, s->wx, s->wy, x, i, j, y + 3 * ((size_t)j * s->w + i));
}

/* Weights 10^(4 t - 2) spanning four decades (t in [0, 1]). rough: t independent per row, every
 * neighbour unrelated (the worst case for aggregation); else t smooth over the image with 3% of the
 * rows outliers at 1e-4 (IRLS's weights: residuals vary smoothly, a failed shift's row gets a tiny
 * weight). */
static double weight(int rough, int i, int j, int which)
{
    const double t = rough ? rnd() : 0.5 + 0.5 * sin(0.21 * i + 1.3 * which) * cos(0.17 * j);
    if (!rough && rnd() < 0.03)
        return 1e-4;
    return pow(10.0, 4.0 * t - 2.0);
}

static void check_size(int w, int h, int rough)
{
    const size_t n = (size_t)w * h, m = 3 * n;
    double *wp = dalloc(n), *wx = dalloc(n), *wy = dalloc(n);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            const size_t k = (size_t)j * w + i;
            wp[k] = weight(rough, i, j, 0), wx[k] = weight(rough, i, j, 1), wy[k] = weight(rough, i, j, 2);
        }
    double *rows = dalloc(RP_ROW_SUMS * (size_t)h);
    const struct rp_sys s = {w, h, n, 0.04, wp, wx, wy, rows};
    struct rp_mg mg = {0};
    EXPECT(restir_rp_mg_build(&mg, &s, RP_MG_SWEEPS) == 0, "build %dx%d", w, h);
    EXPECT(mg.levels >= 1 && mg.lv[mg.levels - 1].w <= 4 && mg.lv[mg.levels - 1].h <= 4, "%dx%d: %d levels", w, h,
           mg.levels);

    /* Symmetric, positive definite. */
    double *u = dalloc(m), *v = dalloc(m), *mu = dalloc(m), *mv = dalloc(m);
    for (int t = 0; t < 4; t++) {
        for (size_t i = 0; i < m; i++)
            u[i] = rnd() - 0.5, v[i] = rnd() - 0.5;
        restir_rp_mg_apply(&mg, u, mu);
        restir_rp_mg_apply(&mg, v, mv);
        const double a = dot(u, mv, m), b = dot(v, mu, m);
        EXPECT(fabs(a - b) <= 1e-11 * (fabs(a) + fabs(b)), "%dx%d: u.Mv %.17g != v.Mu %.17g", w, h, a, b);
        EXPECT(dot(v, mv, m) > 0.0 && dot(u, mu, m) > 0.0, "%dx%d: not positive", w, h);
    }

    /* As a stationary solver x += M (b - A x): the error shrinks. */
    double *xs = dalloc(m), *b = dalloc(m), *x = dalloc(m), *r = dalloc(m), *ax = dalloc(m), *e = dalloc(m);
    for (size_t i = 0; i < m; i++)
        xs[i] = rnd() - 0.5;
    apply(&s, xs, b);
    double first = 0.0, err = 0.0;
    for (int cycle = 0; cycle < 10; cycle++) {
        apply(&s, x, ax);
        for (size_t i = 0; i < m; i++)
            r[i] = b[i] - ax[i];
        restir_rp_mg_apply(&mg, r, e);
        for (size_t i = 0; i < m; i++)
            x[i] += e[i];
        double d2 = 0.0;
        for (size_t i = 0; i < m; i++)
            d2 += (x[i] - xs[i]) * (x[i] - xs[i]);
        err = sqrt(d2 / dot(xs, xs, m));
        if (cycle == 0)
            first = err;
    }
    printf("%dx%d %s weights: %d levels, error after 1 V-cycle %.3g, after 10 %.3g\n", w, h,
           rough ? "rough" : "smooth", mg.levels, first, err);
    EXPECT(err <= first && first < 1.0, "%dx%d: V-cycles do not reduce the error (%g, %g)", w, h, first, err);

    /* Preconditioned CG: same solution, far fewer steps than Jacobi. */
    double *xj = dalloc(m), *xm = dalloc(m);
    struct rp_mg *none = NULL;
    const int ij = restir_rp_cg(&s, b, xj, 1e-10, 100000, none, NULL);
    const int im = restir_rp_cg(&s, b, xm, 1e-10, 100000, &mg, NULL);
    double dj = 0.0, dm = 0.0;
    for (size_t i = 0; i < m; i++)
        dj += (xj[i] - xs[i]) * (xj[i] - xs[i]), dm += (xm[i] - xs[i]) * (xm[i] - xs[i]);
    printf("%dx%d %s weights: CG to 1e-10: Jacobi %d steps, multigrid %d\n", w, h, rough ? "rough" : "smooth", ij,
           im);
    EXPECT(im > 0 && ij > 0, "cg failed %d %d", ij, im);
    EXPECT(sqrt(dm / dot(xs, xs, m)) < 1e-6 && sqrt(dj / dot(xs, xs, m)) < 1e-6, "%dx%d: CG solutions off", w, h);
    if (n >= 256)
        EXPECT(2 * im < ij, "%dx%d: multigrid %d steps vs Jacobi %d", w, h, im, ij);

    restir_rp_mg_free(&mg);
    free(wp), free(wx), free(wy), free(rows), free(u), free(v), free(mu), free(mv);
    free(xs), free(b), free(x), free(r), free(ax), free(e), free(xj), free(xm);
}

int main(void)
{
    const int sizes[6][2] = {{1, 1}, {1, 17}, {23, 1}, {5, 3}, {37, 23}, {130, 67}};
    for (int k = 0; k < 6; k++)
        for (int rough = 0; rough < 2; rough++)
            check_size(sizes[k][0], sizes[k][1], rough);
    return test_finish();
}
