/* method_restir_pt.h: the state and frame of ReSTIR PT's passes (restir-pt, area-restir), exposed
 * so that the gradient methods built on an area-ReSTIR primal (method_grad_restir.c) run the same
 * frame and add their gradient passes. Must never read or write files. */
#ifndef RESTIR_METHODS_RESTIR_PT_METHOD_RESTIR_PT_H
#define RESTIR_METHODS_RESTIR_PT_METHOD_RESTIR_PT_H

#include "methods/screen_history.h"
#include "methods/restir_pt/pt_splat.h"
#include "methods/restir_pt/restir_pt.h"
#include "methods/restir_pt/restir_pt_settings.h"

struct restir_pt_state {
    struct screen_history h;
    struct pt_reservoir *work;      /* initial, then temporal outputs */
    struct pt_reservoir *hist[2];   /* spatial outputs: this frame's and the previous frame's */
    vec3 *emission;                 /* emission seen directly by the initial paths */
    unsigned char *temporal_flags;  /* this frame's TEMPORAL_* bits per pixel (pt_splat.h) */
    struct pt_splat_buffers *splat; /* temporal.reuse=splat|both: landing buckets */
    float scene_diagonal;           /* scales shift.distance */
    unsigned char *material_rough;  /* the hybrid shift's roughness class per material */
    float *boil;                    /* pt.boiling_filter's weights (allocated by its first frame) */
};

/* The settings blocks ReSTIR PT's passes read (struct method.blocks), for its rows and the gradient methods'. */
#define RESTIR_PT_BLOCKS                                                                                          \
    &params_block_depth, &params_block_roulette, &params_block_lights, &params_block_reuse, &params_block_spmis,    \
        &params_block_shift, &restir_pt_block

/* The passes restir_pt_frame times (struct method.passes), for its rows and the gradient methods'. */
#define RESTIR_PT_PASSES                                                                                          \
    "gbuffer", "initial", "temporal", "select", "spatial", "cells", "cell_search", "spmis_canonical", "spmis_reuse", \
        "shade"

void restir_pt_state_init(struct restir_pt_state *t, const struct renderer *r);
void restir_pt_state_fini(struct restir_pt_state *t);

/* Called by restir_pt_frame after the shade pass, before the history is kept: the gradient
 * passes of a method built on the primal (fr: the frame's passes' inputs; res: the final
 * reservoirs of this frame). */
typedef void (*restir_pt_after_shade_fn)(struct renderer *r, void *ctx, struct restir_pt_state *t,
                                        const struct pt_frame *fr, const struct pt_reservoir *res,
                                        struct frame_stats *st);

/* One frame of ReSTIR PT into r->image: G-buffer, initial paths, temporal and spatial reuse,
 * shading; then after_shade (may be NULL), then the history update. base (may be NULL) receives a
 * copy of the initial reservoirs (grestir-pt's shared pair bases). */
void restir_pt_frame(struct renderer *r, struct restir_pt_state *t, const struct camera_view *view,
                     struct pt_reservoir *base, restir_pt_after_shade_fn after_shade, void *ctx,
                     struct frame_stats *st);
/* The history part of renderer_inspect plus the path reservoirs' confidences and temporal flags. */
void restir_pt_inspect(const struct restir_pt_state *t, struct renderer_inspect *out);
/* Area ReSTIR's primal (002 Sec. 5): 1 initial candidate (the default) and 2 spatial neighbors
 * unless spatial.neighbors is set. */
void restir_pt_area_defaults(struct render_params *p);

#endif
