/* pt_splat.h: temporal reuse of path reservoirs by reservoir splatting (Liu, Lin, Kettunen, Wyman,
 * Ramamoorthi 2025), alone or combined with backprojection by balance MIS (temporal.reuse=splat,
 * both). Derivation of the weights: docs/RESTIR_PT.md, "Reservoir splatting".
 * Must never allocate per pixel or read files. */
#ifndef RESTIR_METHODS_RESTIR_PT_PT_SPLAT_H
#define RESTIR_METHODS_RESTIR_PT_PT_SPLAT_H

#include "methods/restir_pt/restir_pt.h"
#include "render/temporal_flags.h"

/* Buffers of the splat pass, made once per resolution and step count. */
struct pt_splat_buffers {
    int pixels, steps;
    int *land;     /* per (previous pixel, time step): the current pixel it lands in, or -1 */
    int *start;    /* pixels + 1 bucket offsets into entries */
    int *entries;  /* (previous pixel * steps + step), bucket by bucket, in index order */
};

void pt_splat_buffers_init(struct pt_splat_buffers *b, int width, int height, int steps);
void pt_splat_buffers_fini(struct pt_splat_buffers *b);

/* Time strata each previous reservoir is splatted into: temporal.splat_steps with a shutter, else 1. */
int pt_splat_steps(const struct render_params *p);

/* Temporal reuse by splatting (and backprojection with temporal.reuse=both): io holds the initial
 * reservoirs on entry and the merged ones on return; flags (one per pixel) receive TEMPORAL_*
 * bits (temporal_flags.h). Returns rays traced. */
long long pt_temporal_splat_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                                 const struct pt_reservoir *prev_res, struct pt_reservoir *io,
                                 struct pt_splat_buffers *b, unsigned char *flags);

#endif
