/* grad_frame.c: gradient-domain frame buffers and the reconstruction calls (see grad_frame.h). */
#include "methods/gradient/grad_frame.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/gradient/grad_common.h"
#include "methods/gradient/grad_settings.h"

void grad_frame_init(struct grad_frame *g, const struct render_params *p, int grestir)
{
    memset(g, 0, sizeof(*g));
    g->width = p->width;
    g->height = p->height;
    size_t n = (size_t)p->width * (size_t)p->height;
    g->primal = xcalloc(3 * n, sizeof(float));
    g->dx = xcalloc(3 * n, sizeof(float));
    g->dy = xcalloc(3 * n, sizeof(float));
    g->l2 = xcalloc(3 * n, sizeof(float));
    g->os = xcalloc(3 * GRAD_DIRS * n, sizeof(float));
    g->emission = xcalloc(3 * n, sizeof(float));
    if (grestir) {
        g->base = xcalloc(n, sizeof(struct pt_reservoir));
        g->grestir = xmalloc(sizeof(*g->grestir));
        grestir_state_init(g->grestir, p->width, p->height);
    }
}

void grad_frame_fini(struct grad_frame *g)
{
    free(g->primal);
    free(g->dx);
    free(g->dy);
    free(g->l2);
    free(g->l1);
    free(g->os);
    free(g->emission);
    free(g->base);
    if (g->grestir) {
        grestir_state_fini(g->grestir);
        free(g->grestir);
    }
    memset(g, 0, sizeof(*g));
}

void grad_frame_begin(struct grad_frame *g)
{
    size_t n = (size_t)g->width * (size_t)g->height;
    memset(g->dx, 0, sizeof(float) * 3 * n);
    memset(g->dy, 0, sizeof(float) * 3 * n);
    grad_os_clear(g->os, n);
}

void grad_reconstruct_l2(const struct render_params *p, struct grad_frame *g)
{
    /* Inputs are sized and alpha is range-checked by the parameter table: this cannot fail. A fixed
     * step count runs CG to a tolerance it cannot reach (DBL_MIN; an exact zero residual still stops
     * it, with the exact solution). */
    const struct recon_settings *rs = recon_settings_of(p);
    const int fixed = rs->iterations > 0;
    int rc = restir_poisson_l2(g->width, g->height, g->primal, g->dx, g->dy, rs->alpha,
                               (enum restir_poisson_solver)rs->solver, fixed ? DBL_MIN : RESTIR_POISSON_TOL,
                               fixed ? rs->iterations : 2000, g->l2, &g->l2_stats);
    RESTIR_CHECK(rc == 0);
}

void grad_reconstruct_l1(const struct render_params *p, struct grad_frame *g)
{
    if (!g->l1)
        g->l1 = xcalloc(3 * (size_t)g->width * (size_t)g->height, sizeof(float));
    const struct recon_settings *rs = recon_settings_of(p);
    const enum restir_poisson_precond pre = (enum restir_poisson_precond)rs->l1_precond;
    const int steps = rs->l1_cg > 0                                 ? rs->l1_cg
                      : pre == RESTIR_POISSON_PRECOND_MULTIGRID ? RESTIR_POISSON_L1_MG_STEPS
                                                                : RESTIR_POISSON_L1_CG_STEPS;
    int rc = restir_poisson_l1(g->width, g->height, g->primal, g->dx, g->dy, rs->alpha, rs->l1_iterations, pre,
                               steps, g->l1, &g->l1_stats);
    RESTIR_CHECK(rc == 0);
}
