/* method_grad_restir.c: the gradient methods on an area-ReSTIR primal (002): `grad-after-restir`
 * (B.1: gradients from shifting each pixel's final path to its neighbors) and `grestir-pt`
 * (ReSTIR over paired-pixel samples with positivization, temporal and adaptive spatial reuse),
 * both reconstructed by screened Poisson. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/gradient/grad_after.h"
#include "methods/gradient/grad_common.h"
#include "methods/gradient/grestir.h"
#include "methods/gradient/grad_method.h"
#include "methods/restir_pt/method_restir_pt.h"
#include "methods/gradient/grad_settings.h"

struct grad_restir_state {
    struct grad_frame grad; /* first: grad_method_output reads the state as its grad_frame */
    struct restir_pt_state primal;
    int paired; /* grestir-pt: ReSTIR over paired-pixel samples; else gradients after ReSTIR */
};

static void *grad_restir_create(const struct renderer *r, int paired)
{
    struct grad_restir_state *g = xcalloc(1, sizeof(*g));
    g->paired = paired;
    grad_frame_init(&g->grad, &r->p, paired);
    restir_pt_state_init(&g->primal, r);
    return g;
}

static void *grad_after_create(const struct renderer *r) { return grad_restir_create(r, 0); }
static void *grestir_create(const struct renderer *r) { return grad_restir_create(r, 1); }

static void grad_restir_destroy(void *state)
{
    struct grad_restir_state *g = state;
    grad_frame_fini(&g->grad);
    restir_pt_state_fini(&g->primal);
    free(g);
}

/* grestir-pt: ReSTIR over paired-pixel samples (002 Sec. 4). */
static void paired_passes(struct renderer *r, struct grad_restir_state *gs_, const struct pt_frame *fr,
                          const struct gbuffer *g, const struct gbuffer *prev_g, struct frame_stats *st)
{
    const struct render_params *p = &r->p;
    struct grad_frame *gf = &gs_->grad;
    struct grestir_state *gs = gf->grestir;
    const int cur = gs_->primal.h.cur, has_history = gs_->primal.h.has_history;
    const size_t n = (size_t)g->width * (size_t)g->height;
    long long accepted = 0;
    RENDERER_TIMED(st, PASS_GRAD_INITIAL, {
        if (!grad_settings_of(p)->base) {
            /* independent initial paths: the same sampler on streams of another seed */
            struct render_params q = *p;
            q.seed = p->seed ^ 0x6772616442617365ull;
            struct pt_frame fb = *fr;
            fb.p = &q;
            st->rays += pt_initial_pass(&fb, g, gf->base, (vec3 *)(void *)gf->emission);
        }
        st->rays += grestir_initial_pass(fr, g, gf->base, gs);
    });
    if (p->reuse.temporal && grad_settings_of(p)->temporal && renderer_history_reusable(r, has_history))
        RENDERER_TIMED(st, PASS_GRAD_TEMPORAL,
                       st->rays += grestir_temporal_pass(fr, g, prev_g, gs, 1 - cur, &accepted));
    RENDERER_TIMED(st, PASS_GRAD_SELECT, grestir_select_pass(fr, g, gs));
    RENDERER_TIMED(st, PASS_GRAD_SPATIAL, st->rays += grestir_spatial_pass(fr, g, gs, cur));
    st->edge_pairs = gs->edge_pairs;
    st->pair_neighbors = gs->neighbors_found;
    RENDERER_TIMED(st, PASS_GRAD_SHADE, grestir_shade_pass(p, gs, cur, gf->dx, gf->dy));
    if (p->reuse.history_temporal && grad_settings_of(p)->spatial != GRAD_SPATIAL_OFF)
        for (int d = 0; d < GRAD_PAIR_DIRS; d++)
            for (int s = 0; s < GRAD_SIGNS; s++)
                memcpy(gs->hist[cur][d][s], gs->work[d][s], sizeof(struct pair_reservoir) * n);
}

_Static_assert(sizeof(vec3) == 3 * sizeof(float), "the primal's emission is read as RGB floats");

/* The gradient passes after the area-ReSTIR primal (r->image), from its final reservoirs res. */
static void gradient_passes(struct renderer *r, void *ctx, struct restir_pt_state *t, const struct pt_frame *fr,
                            const struct pt_reservoir *res, struct frame_stats *st)
{
    struct grad_restir_state *gs = ctx;
    struct grad_frame *gf = &gs->grad;
    const struct gbuffer *g = screen_history_gbuffer(&t->h), *prev_g = screen_history_prev_gbuffer(&t->h);
    const size_t n = (size_t)g->width * (size_t)g->height;
    memcpy(gf->primal, r->image, sizeof(float) * 3 * n);
    grad_frame_begin(gf);
    if (!gs->paired)
        RENDERER_TIMED(st, PASS_GRAD_INITIAL, st->rays += grad_after_pass(fr, res, gf->os));
    else
        paired_passes(r, gs, fr, g, prev_g, st);
    /* Emission seen directly (restir-pt's paths start after the primary hit): the differences of
     * the primal's own estimate of it (grad_add_image_differences). */
    RENDERER_TIMED(st, PASS_GRAD_SHADE, {
        grad_combine(g->width, g->height, gf->os, gf->dx, gf->dy);
        grad_add_image_differences(g->width, g->height, &t->emission[0].x, gf->dx, gf->dy);
    });
}

static void grad_restir_render_frame(struct renderer *r, void *state, const struct camera_view *view,
                                     struct frame_stats *st)
{
    struct grad_restir_state *gs = state;
    /* grad.base=shared: the pairs' candidates are the primal's initial paths */
    struct pt_reservoir *base = gs->paired && grad_settings_of(&r->p)->base ? gs->grad.base : NULL;
    restir_pt_frame(r, &gs->primal, view, base, gradient_passes, gs, st);
}

static void grad_restir_reconstruct(struct renderer *r, void *state, struct frame_stats *st)
{
    grad_method_reconstruct(r, &((struct grad_restir_state *)state)->grad, st);
}

static void grad_restir_inspect(const void *state, struct renderer_inspect *out)
{
    restir_pt_inspect(&((const struct grad_restir_state *)state)->primal, out);
}

_Static_assert(offsetof(struct grad_restir_state, grad) == 0, "grad_method_output reads the state as its grad_frame");

/* What the two rows share: gradients beside the area-ReSTIR primal, one state, frame, reconstruction and
 * set of outputs. */
#define GRAD_RESTIR_SHARED                                                                                        \
    .caps = METHOD_GRADIENT | METHOD_HISTORY | METHOD_PATH_RESERVOIRS | METHOD_ANIMATED_EMITTERS,                  \
    .defaults = restir_pt_area_defaults,                                                                           \
    .destroy = grad_restir_destroy, .render_frame = grad_restir_render_frame,                                      \
    .reconstruct = grad_restir_reconstruct, .inspect = grad_restir_inspect, .outputs = grad_method_outputs,        \
    .output = grad_method_output

const struct method method_grad_after_restir = {
    .name = "grad-after-restir",
    .description = "Gradient after ReSTIR (002 B.1): area-ReSTIR primal, gradients from shifting each "
                   "pixel's final path to its neighbors, Poisson reconstruction",
    .blocks = (const struct param_block *const[]){RESTIR_PT_BLOCKS, &recon_block, NULL},
    .passes = (const char *const[]){RESTIR_PT_PASSES, "grad_initial", "grad_shade", GRAD_METHOD_PASSES, NULL},
    .create = grad_after_create,
    GRAD_RESTIR_SHARED,
};

const struct method method_grestir_pt = {
    .name = "grestir-pt",
    .description = "gradient-domain ReSTIR PT (002): area-ReSTIR primal, ReSTIR over paired-pixel samples with "
                   "positivization, temporal and adaptive spatial reuse, Poisson reconstruction",
    .blocks = (const struct param_block *const[]){RESTIR_PT_BLOCKS, &recon_block, &grad_block, NULL},
    .passes = (const char *const[]){RESTIR_PT_PASSES, "grad_initial", "grad_temporal", "grad_select", "grad_spatial",
                                    "grad_shade", GRAD_METHOD_PASSES, NULL},
    .variants = "recon=both grad.base=shared",
    .create = grestir_create,
    GRAD_RESTIR_SHARED,
};
