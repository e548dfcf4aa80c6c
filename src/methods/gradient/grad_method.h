/* grad_method.h: what the gradient-domain methods (gpt, grad-after-restir, grestir-pt) share: the
 * screened Poisson reconstruction of their primal and gradients into the image (002 Sec. 3), and
 * their declared outputs (struct method_output). Each one's state begins with its struct grad_frame
 * (a base struct, as C spells one), so that one outputs list and one output function serve them all.
 * Must never read or write files. */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_METHOD_H
#define RESTIR_METHODS_GRADIENT_GRAD_METHOD_H

#include "methods/gradient/grad_frame.h"
#include "methods/renderer.h"

/* The L2 reconstruction (and L1 unless recon=l2) of gf into r->image (the one recon selects),
 * timed into st->ms[PASS_RECON_L2 / PASS_RECON_L1], residuals into st. */
void grad_method_reconstruct(struct renderer *r, struct grad_frame *gf, struct frame_stats *st);

/* The passes grad_method_reconstruct times (struct method.passes). */
#define GRAD_METHOD_PASSES "recon_l2", "recon_l1"

/* The outputs every gradient method declares, in the order their EXR layers follow R, G, B: the
 * reconstruction not in R, G, B ("L2" with recon=l1, "L1" with recon=both; derived, so debug), the
 * primal (radiance) and the forward differences "dx", "dy" (signed). */
extern const struct method_output grad_method_outputs[];
/* struct method.output for them: state begins with its struct grad_frame. */
float *grad_method_output(const struct renderer *r, void *state, int k);
/* The grad_frame of r's method, or NULL when it is not a gradient method (for tests and benchmarks
 * that read the reconstructions themselves). */
struct grad_frame *grad_method_frame(const struct renderer *r);

#endif
