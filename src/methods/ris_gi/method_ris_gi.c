/* method_ris_gi.c: the `ris-gi` row (ris_gi.h). Stateless between frames: equal time by paths per pixel. */
#include "methods/renderer.h"
#include "methods/ris_gi/ris_gi.h"

static void *ris_gi_create(const struct renderer *r)
{
    (void)r;
    static char none; /* no state; a non-NULL pointer all the same */
    return &none;
}

static void ris_gi_destroy(void *state) { (void)state; }

static void ris_gi_render_frame(struct renderer *r, void *state, const struct camera_view *view, struct frame_stats *st)
{
    (void)state;
    RENDERER_TIMED(st, PASS_PT, st->rays += ris_gi_pass(r->scene, view, &r->p, r->frame, r->image));
}

const struct method method_ris_gi = {
    .name = "ris-gi",
    .description = "RIS over K BSDF directions at the primary hit, each traced with its path suffix, no reuse (the "
                   "no-reuse baseline of ReSTIR GI)",
    .caps = METHOD_CAMERA_EFFECTS | METHOD_BUDGET_BY_SPP | METHOD_ANIMATED_EMITTERS,
    .blocks = (const struct param_block *const[]){&params_block_spp, &params_block_depth, &params_block_roulette,
                                                  &params_block_lights, &ris_gi_block, NULL},
    .streams = (const char *const[]){RIS_GI_STREAM, NULL},
    .passes = (const char *const[]){"pt", NULL}, /* one path-tracing pass, timed as pt's */
    .variants = "risgi.candidates=1",
    .create = ris_gi_create,
    .destroy = ris_gi_destroy,
    .render_frame = ris_gi_render_frame,
};
