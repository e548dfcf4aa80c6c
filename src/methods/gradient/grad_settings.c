/* grad_settings.c: the gradient methods' settings blocks (grad_settings.h). */
#include "methods/gradient/grad_settings.h"

#include <stddef.h>
#include <stdio.h>

#include "core/check.h"
#include "restir/poisson.h"

static const char *const grad_spatial_names[] = {"off", "dense", "adaptive", NULL};
static const char *const base_names[] = {"independent", "shared", NULL};
static const char *const recon_names[] = {"l2", "l1", "both", NULL};
static const char *const solver_names[] = {"dct", "cg", NULL};
static const char *const precond_names[] = {"multigrid", "jacobi", NULL}; /* enum restir_poisson_precond */
_Static_assert(sizeof(enum grad_spatial_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(enum recon_mode) == sizeof(int), "enum size");

#define G(field) offsetof(struct grad_settings, field)
static const struct param_def grad_rows[] = {
    {"grad.spatial", P_NAMES, G(spatial), 0, 0, "adaptive", NULL,
     "spatial reuse of paired-pixel samples: off, dense (a similar random pair for every pair) "
     "or adaptive (edge pairs only, 002 Sec. 4.3.2); the search reads only the G-buffer (unbiased)",
     grad_spatial_names},
    {"grad.temporal", P_BOOL, G(temporal), 0, 1, "on", NULL,
     "temporal reuse of paired-pixel reservoirs (needs temporal=on; off isolates the gradient "
     "pass's history from the primal's)", NULL},
    {"grad.base", P_NAMES, G(base), 0, 0, "independent", NULL,
     "the pairs' initial paths: independent (their own initial pass, as the public 002 code) or "
     "shared (the primal's initial paths: no extra paths, but primal and gradient errors correlate, which the "
     "solve does not smooth away); unbiased either way",
     base_names},
    {"grad.positivize", P_BOOL, G(positivize), 0, 1, "on", NULL,
     "separate reservoirs for the positive and negative gradient parts (002 Eq. 23-26)", NULL},
    {"grad.cross_sign", P_BOOL, G(cross_sign), 0, 1, "off", NULL,
     "r+ and r- also resample the neighbor's reservoir of the other sign (002 Sec. 4.4 ablation)",
     NULL},
    {"grad.search", P_INT, G(search), 1, 4096, "256", NULL, "random neighbor pairs tried per pair (N)", NULL},
    {"grad.radius", P_FLOAT, G(radius), 1, 512, "4", NULL, "pair-search radius in pixels", NULL},
    {"grad.inner_jacobian_ratio", P_FLOAT, G(inner_jacobian_ratio), 0, 1e30, "0", NULL,
     "reject an outer shift when the path's inner-shift Jacobians before and after it differ by more "
     "than this factor or one of them is undefined, as 002's public code does with 10 (0: off); the rule is "
     "symmetric, so the reverse shift is rejected too and reuse stays unbiased (render.gradient_unbiased)", NULL},
    {"grad.edge_albedo", P_FLOAT, G(edge_albedo), 0, 1e30, "0.1", NULL, "edge pair: max albedo difference above", NULL},
    {"grad.edge_normal", P_FLOAT, G(edge_normal), -1, 1, "0.9", NULL,
     "edge pair: n_a . n_b below this (the paper's text says '>', which cannot mark an edge)", NULL},
    {"grad.edge_depth", P_FLOAT, G(edge_depth), 0, 1e30, "0.1", NULL, "edge pair: |d_a - d_b| / d_a above", NULL},
};
#undef G

#define C(field) offsetof(struct recon_settings, field)
static const struct param_def recon_rows[] = {
    {"recon", P_NAMES, C(mode), 0, 0, "l2", "l1",
     "which screened Poisson solve fills the image: l2 (unbiased: linear in unbiased "
     "inputs), l1 (BIASED: iteratively reweighted, robust to outliers) or both (image = L2, L1 as a layer)",
     recon_names},
    {"recon.alpha", P_FLOAT, C(alpha), 1e-6, 1e6, "0.2", NULL, "screened Poisson: weight alpha of the primal term",
     NULL},
    {"recon.solver", P_NAMES, C(solver), 0, 0, "dct", NULL,
     "L2 solver: dct (direct, exact) or cg (conjugate gradient to a relative residual of 1e-6, or recon.iterations "
     "steps)",
     solver_names},
    {"recon.iterations", P_INT, C(iterations), 0, 100000, "0", NULL,
     "L2 with recon.solver=cg: 0 solves to a relative residual of 1e-6; N stops after exactly N CG steps from the "
     "primal, as 002's public code and Kettunen et al. do (BIASED: a truncated CG is not linear in its noisy "
     "inputs; measured in docs/BENCHMARKS.md)",
     NULL},
    {"recon.l1_iterations", P_INT, C(l1_iterations), 1, 1000, "20", NULL, "L1: IRLS reweighting iterations", NULL},
    {"recon.l1_precond", P_NAMES, C(l1_precond), 0, 0, "multigrid", NULL,
     "L1: preconditioner of the inner CG: multigrid (V-cycle) or jacobi (the public G-PT solver's kind)",
     precond_names},
    {"recon.l1_cg", P_INT, C(l1_cg), 0, 100000, "0", NULL,
     "L1: conjugate-gradient steps per reweighting; 0: the preconditioner's default (multigrid 4, jacobi 50)", NULL},
};
#undef C

static int grad_validate(const struct render_params *p, const void *block, char *msg)
{
    (void)p;
    const struct grad_settings *g = block;
    if (g->inner_jacobian_ratio > 0.0f && g->inner_jacobian_ratio < 1.0f) {
        snprintf(msg, RESTIR_MSG_LEN, "grad.inner_jacobian_ratio = %g: 0 (off) or a factor of at least 1",
                 (double)g->inner_jacobian_ratio);
        return -1;
    }
    return 0;
}

static int recon_validate(const struct render_params *p, const void *block, char *msg)
{
    (void)p;
    const struct recon_settings *c = block;
    if (c->iterations > 0 && c->solver != RESTIR_POISSON_CG) {
        snprintf(msg, RESTIR_MSG_LEN, "recon.iterations = %d needs recon.solver=cg (dct solves exactly)",
                 c->iterations);
        return -1;
    }
    return 0;
}

struct param_block grad_block = PARAM_METHOD_BLOCK("grad", grad_rows, struct grad_settings, grad_validate);
struct param_block recon_block = PARAM_METHOD_BLOCK("recon", recon_rows, struct recon_settings, recon_validate);
