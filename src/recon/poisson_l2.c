/* poisson_l2.c: L2 screened Poisson reconstruction (restir/poisson.h) by the DCT direct solve
 * (poisson_dct.c) or CG. */
#include <math.h>
#include <stdlib.h>

#include "recon/poisson_cg.h"
#include "recon/poisson_ops.h"
#include "restir/poisson.h"

int restir_poisson_l2(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                      enum restir_poisson_solver solver, double tol, int max_iters, float *out,
                      struct restir_poisson_stats *st)
{
    const double t0 = restir_rp_now_ms();
    if (restir_rp_check(w, h, primal, dx, dy, alpha, out) != 0)
        return -1;
    if (solver != RESTIR_POISSON_DCT &&
        (solver != RESTIR_POISSON_CG || !(tol > 0.0) || !isfinite(tol) || max_iters < 1))
        return -1;
    const size_t n = (size_t)w * (size_t)h;
    const struct rp_sys s = {w, h, n, (double)alpha * (double)alpha, NULL, NULL, NULL,
                             restir_rp_alloc(RP_ROW_SUMS * (size_t)h)};
    double *b = restir_rp_alloc(3 * n), *x = restir_rp_alloc(3 * n);
    int iters = 0, rc = -1;
    if (!b || !x || !s.rows)
        goto done;
    restir_rp_rhs(&s, primal, dx, dy, b);
    if (solver == RESTIR_POISSON_DCT) {
        if (restir_rp_dct_solve(w, h, s.a2, b, x) != 0)
            goto done;
    } else {
        const long m = (long)(3 * n);
#pragma omp parallel for schedule(static) num_threads(restir_rp_threads((size_t)w * (size_t)h))
        for (long k = 0; k < m; k++)
            x[k] = rp_in(primal[k]);
        iters = restir_rp_cg(&s, b, x, tol, max_iters, NULL, NULL);
        if (iters < 0)
            goto done;
    }
    double rel[3];
    restir_rp_residual(&s, b, x, rel);
    restir_rp_store(n, x, out);
    if (st) {
        st->iterations = iters;
        st->residual = fmax(rel[0], fmax(rel[1], rel[2]));
        st->ms = restir_rp_now_ms() - t0;
    }
    rc = 0;
done:;
    free(b);
    free(x);
    free(s.rows);
    return rc;
}
