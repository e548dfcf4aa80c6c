/* recon/poisson_cg.h: preconditioned conjugate gradient on the screened Poisson system of
 * recon/poisson_ops.h, with a Jacobi or multigrid (recon/poisson_mg.h) preconditioner. */
#ifndef RESTIR_RECON_POISSON_CG_H
#define RESTIR_RECON_POISSON_CG_H

#include "recon/poisson_ops.h"

/* CG's work vectors for an n-pixel system, allocated once for a sequence of solves (fresh pages for
 * every solve cost a fifth of an L1 reconstruction's time in page faults). */
struct rp_cg_work {
    double *r, *p, *q, *z; /* 3 n each */
    double *dinv;          /* n */
};
/* 0, or -1 on allocation failure (nothing is then held). */
int restir_rp_cg_work_alloc(struct rp_cg_work *wk, size_t n);
void restir_rp_cg_work_free(struct rp_cg_work *wk);

#define RP_CG_TOL_FLOOR 1e-14 /* relative residuals below this count as converged */

struct rp_mg;
/* Preconditioned CG on A x = b from the given x, per channel until |r| <= max(tol, RP_CG_TOL_FLOOR)
 * |b| or max_iters. The preconditioner is mg's V-cycle (recon/poisson_mg.h, built for s) or, with
 * mg NULL, Jacobi (1 / diag A). work: vectors for s->n pixels, or NULL to allocate them for this
 * call. Returns the iterations run (max over channels), -1 on allocation failure. */
int restir_rp_cg(const struct rp_sys *s, const double *b, double *x, double tol, int max_iters, struct rp_mg *mg,
          struct rp_cg_work *work);

#endif
