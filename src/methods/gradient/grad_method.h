/* grad_method.h: what the gradient-domain methods (gpt, grad-after-restir, grestir-pt) share: the
 * screened Poisson reconstruction of their primal and gradients into the image (002 Sec. 3).
 * Must never read or write files. */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_METHOD_H
#define RESTIR_METHODS_GRADIENT_GRAD_METHOD_H

#include "methods/gradient/grad_frame.h"
#include "methods/renderer.h"

/* The L2 reconstruction (and L1 unless recon=l2) of gf into r->image (the one recon selects),
 * timed into st->ms[PASS_RECON_L2 / PASS_RECON_L1], residuals into st. */
void grad_method_reconstruct(struct renderer *r, struct grad_frame *gf, struct frame_stats *st);

#endif
