/* method_pt.c: `pt`, unidirectional path tracing (render/pt.h), the reference every other method is
 * measured against. Stateless between frames. */
#include "methods/renderer.h"
#include "methods/pt/pt.h"

static void *pt_create(const struct renderer *r)
{
    (void)r;
    static char none; /* no state; a non-NULL pointer all the same */
    return &none;
}

static void pt_destroy(void *state) { (void)state; }

static void pt_render_frame(struct renderer *r, void *state, const struct camera_view *view, struct frame_stats *st)
{
    (void)state;
    RENDERER_TIMED(st, PASS_PT, st->rays += pt_pass(r->scene, view, &r->p, r->frame, r->p.spp, r->image));
}

const struct method method_pt = {
    .name = "pt",
    .description = "path tracing: NEE + BSDF sampling with MIS, Russian roulette (the reference method)",
    .caps = METHOD_CAMERA_EFFECTS | METHOD_BUDGET_BY_SPP | METHOD_ANIMATED_EMITTERS,
    .viewer_order = 3,
    .blocks = (const struct param_block *const[]){&params_block_spp, &params_block_depth, &params_block_roulette,
                                                  &params_block_sampler, &params_block_lights, NULL},
    .passes = (const char *const[]){"pt", NULL},
    .roles = "reference",
    .create = pt_create,
    .destroy = pt_destroy,
    .render_frame = pt_render_frame,
};
