/* poisson_l2.c: L2 screened Poisson reconstruction (restir/poisson.h): the DCT direct solve and
 * the CG path. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>

#include "recon/poisson_cg.h"
#include "recon/poisson_ops.h"
#include "restir/poisson.h"

#ifdef RESTIR_HAVE_FFTW
#include <fftw3.h>
#endif

/* The Neumann grid Laplacian is Lx (+) Ly with Lx the path-graph Laplacian of w nodes, whose
 * eigenvectors cos(pi k (i + 1/2) / w) are the DCT-II basis, eigenvalue 2 - 2 cos(pi k / w).
 * FFTW's REDFT10 (DCT-II) followed by REDFT01 (DCT-III) multiplies by 2w per dimension, hence
 * the 1 / (4 w h). Channels are planar copies so one plan serves all three (fftw_execute_r2r on
 * equally aligned fftw_malloc arrays, which is thread-safe; the planner is not). */
int restir_rp_dct_solve(int w, int h, double a2, const double *b, double *x)
{
#ifndef RESTIR_HAVE_FFTW
    (void)w, (void)h, (void)a2, (void)b, (void)x;
    return -1; /* librestir built without FFTW: the DCT solve is not there (restir/poisson.h) */
#else
    const size_t n = (size_t)w * (size_t)h;
    double *ch[3] = {fftw_alloc_real(n), fftw_alloc_real(n), fftw_alloc_real(n)};
    double *lx = restir_rp_alloc((size_t)w), *ly = restir_rp_alloc((size_t)h);
    fftw_plan fwd = NULL, inv = NULL;
    int rc = -1;
    if (!ch[0] || !ch[1] || !ch[2] || !lx || !ly)
        goto done;
#pragma omp critical(restir_fftw_planner)
    {
        fwd = fftw_plan_r2r_2d(h, w, ch[0], ch[0], FFTW_REDFT10, FFTW_REDFT10, FFTW_ESTIMATE);
        inv = fftw_plan_r2r_2d(h, w, ch[0], ch[0], FFTW_REDFT01, FFTW_REDFT01, FFTW_ESTIMATE);
    }
    if (!fwd || !inv)
        goto done;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < w; i++)
        lx[i] = 2.0 - 2.0 * cos(pi * i / w);
    for (int j = 0; j < h; j++)
        ly[j] = 2.0 - 2.0 * cos(pi * j / h);
    const long ln = (long)n;
#pragma omp parallel for schedule(static)
    for (long k = 0; k < ln; k++)
        for (int c = 0; c < 3; c++)
            ch[c][k] = b[3 * k + c];
#pragma omp parallel for schedule(static, 1)
    for (int c = 0; c < 3; c++)
        fftw_execute_r2r(fwd, ch[c], ch[c]);
    const double norm = 4.0 * (double)n;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < h; j++) {
        for (int i = 0; i < w; i++) {
            const double f = 1.0 / ((a2 + lx[i] + ly[j]) * norm);
            const size_t k = (size_t)j * (size_t)w + (size_t)i;
            for (int c = 0; c < 3; c++)
                ch[c][k] *= f;
        }
    }
#pragma omp parallel for schedule(static, 1)
    for (int c = 0; c < 3; c++)
        fftw_execute_r2r(inv, ch[c], ch[c]);
#pragma omp parallel for schedule(static)
    for (long k = 0; k < ln; k++)
        for (int c = 0; c < 3; c++)
            x[3 * k + c] = ch[c][k];
    rc = 0;
done:;
#pragma omp critical(restir_fftw_planner)
    {
        if (fwd)
            fftw_destroy_plan(fwd);
        if (inv)
            fftw_destroy_plan(inv);
    }
    for (int c = 0; c < 3; c++)
        fftw_free(ch[c]);
    free(lx);
    free(ly);
    return rc;
#endif
}

int restir_poisson_l2(int w, int h, const float *primal, const float *dx, const float *dy, float alpha,
                      enum restir_poisson_solver solver, double tol, int max_iters, float *out,
                      struct restir_poisson_stats *st)
{
    const double t0 = omp_get_wtime();
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
#pragma omp parallel for schedule(static)
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
        st->ms = 1e3 * (omp_get_wtime() - t0);
    }
    rc = 0;
done:;
    free(b);
    free(x);
    free(s.rows);
    return rc;
}
