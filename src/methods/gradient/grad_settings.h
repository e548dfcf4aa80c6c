/* grad_settings.h: the gradient methods' own settings: grestir-pt's paired-pixel reuse (grad.*) and the
 * screened Poisson reconstruction every gradient method runs (recon, recon.*; 002 Sec. 5). */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_SETTINGS_H
#define RESTIR_METHODS_GRADIENT_GRAD_SETTINGS_H

#include "render/params.h"

/* Spatial reuse of paired-pixel samples (002 Sec. 4.3.2, Fig. 10): none, a random similar pair for
 * every pair, or only for edge pairs. */
enum grad_spatial_mode { GRAD_SPATIAL_OFF = 0, GRAD_SPATIAL_DENSE, GRAD_SPATIAL_ADAPTIVE };
/* Which screened Poisson reconstruction fills the image (the other one is written as a layer). */
enum recon_mode { RECON_L2 = 0, RECON_L1, RECON_BOTH };

/* gradient-domain ReSTIR PT (002) */
struct grad_settings {
    enum grad_spatial_mode spatial;
    int temporal;      /* temporal reuse of paired-pixel reservoirs (with temporal on) */
    int base;          /* pairs' initial paths: 0 independent of the primal's, 1 the primal's own */
    int positivize;    /* two reservoirs r+, r- per pair (Eq. 23-26) */
    int cross_sign;    /* r+ and r- also reuse the other sign's neighbor reservoir */
    int search;        /* N: random neighbor pairs tried by the pair search (256) */
    float radius;      /* pair-search neighborhood radius, pixels */
    float inner_jacobian_ratio; /* reject outer shifts whose inner Jacobians differ more (0: off) */
    float edge_albedo, edge_normal, edge_depth; /* edge-pair thresholds (Sec. 4.3.2) */
};

/* the screened Poisson reconstruction */
struct recon_settings {
    enum recon_mode mode;
    float alpha;       /* screened Poisson weight alpha of the primal (0.2) */
    int solver;        /* enum restir_poisson_solver: dct or cg for L2 */
    int iterations;    /* CG steps of L2 from the primal; 0: to the tolerance */
    int l1_iterations, l1_cg; /* IRLS reweightings and CG steps per reweighting (0: default) */
    int l1_precond;    /* enum restir_poisson_precond of the L1 solve's CG */
};

extern struct param_block grad_block, recon_block;
static inline const struct grad_settings *grad_settings_of(const struct render_params *p)
{
    return param_block_in(p, &grad_block);
}
static inline struct grad_settings *grad_settings_mut(struct render_params *p)
{
    return param_block_in_mut(p, &grad_block);
}
static inline const struct recon_settings *recon_settings_of(const struct render_params *p)
{
    return param_block_in(p, &recon_block);
}
static inline struct recon_settings *recon_settings_mut(struct render_params *p)
{
    return param_block_in_mut(p, &recon_block);
}

#endif
