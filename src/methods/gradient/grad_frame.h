/* grad_frame.h: the per-frame images of a gradient-domain method (primal, forward gradients, their
 * L2 and L1 screened Poisson reconstructions) and the scratch its passes share. The renderer owns
 * one per gradient method. Must never read or write files. */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_FRAME_H
#define RESTIR_METHODS_GRADIENT_GRAD_FRAME_H

#include "methods/gradient/grestir.h"
#include "render/params.h"
#include "restir/poisson.h"
#include "methods/gradient/grad_settings.h"

struct grad_frame {
    int width, height;
    float *primal, *dx, *dy; /* RGB; dx[a] = F(a + x) - F(a), dy[a] = F(a + y) - F(a) */
    float *l2, *l1;          /* reconstructions; l1 only when recon is l1 or both */
    float *os;               /* one-sided differences (grad_common.h) */
    float *emission;         /* gpt: the part of the primal seen directly (RGB) */
    struct pt_reservoir *base;     /* grestir-pt: this frame's initial paths */
    struct grestir_state *grestir; /* grestir-pt: paired-pixel reservoirs */
    struct restir_poisson_stats l2_stats, l1_stats;
};

/* grestir != 0 allocates the paired-pixel state. */
void grad_frame_init(struct grad_frame *g, const struct render_params *p, int grestir);
void grad_frame_fini(struct grad_frame *g);
/* Zeroes dx, dy and os before a frame's gradient passes. */
void grad_frame_begin(struct grad_frame *g);

/* The L2 solve (recon.solver, alpha = recon.alpha) into g->l2. */
void grad_reconstruct_l2(const struct render_params *p, struct grad_frame *g);
/* The L1 IRLS solve (recon.l1_iterations x recon.l1_cg) into g->l1 (allocated on demand). */
void grad_reconstruct_l1(const struct render_params *p, struct grad_frame *g);

#endif
