/* method_gpt.c: `gpt`, gradient-domain path tracing (Kettunen et al. 2015; 002 B.2): pt base paths
 * shifted to the 4 neighbors by the hybrid shift, then the screened Poisson reconstruction.
 * Stateless between frames but for its images. */
#include <stddef.h>
#include <stdlib.h>

#include "core/check.h"
#include "methods/gradient/gpt.h"
#include "methods/gradient/grad_common.h"
#include "methods/gradient/grad_method.h"
#include "methods/restir_pt/restir_pt.h"
#include "methods/gradient/grad_settings.h"

struct gpt_state {
    struct grad_frame grad; /* first: grad_method_output reads the state as its grad_frame */
    float scene_diagonal;          /* scales shift.distance */
    unsigned char *material_rough; /* the hybrid shift's roughness class per material */
};

static void *gpt_create(const struct renderer *r)
{
    struct gpt_state *g = xcalloc(1, sizeof(*g));
    grad_frame_init(&g->grad, &r->p, 0);
    g->scene_diagonal = scene_diagonal(r->scene);
    struct shift_params sp; /* for the roughness table only: no camera needed */
    pt_shift_params(&r->p, g->scene_diagonal, v3s(0.0f), &sp);
    g->material_rough = xcalloc((size_t)r->scene->num_materials + 1, 1);
    path_shift_rough_table(r->scene, &sp, g->material_rough);
    return g;
}

static void gpt_destroy(void *state)
{
    struct gpt_state *g = state;
    grad_frame_fini(&g->grad);
    free(g->material_rough);
    free(g);
}

static void gpt_render_frame(struct renderer *r, void *state, const struct camera_view *view, struct frame_stats *st)
{
    struct gpt_state *g = state;
    struct grad_frame *gf = &g->grad;
    struct shift_params sp;
    pt_shift_params(&r->p, g->scene_diagonal, view->position, &sp);
    sp.rough = g->material_rough;
    grad_frame_begin(gf);
    RENDERER_TIMED(st, PASS_GPT, {
        st->rays += gpt_pass(r->scene, &sp, view, &r->p, r->frame, gf->primal, gf->emission, gf->os);
        grad_combine(gf->width, gf->height, gf->os, gf->dx, gf->dy);
        grad_add_image_differences(gf->width, gf->height, gf->emission, gf->dx, gf->dy);
    });
}

static void gpt_reconstruct(struct renderer *r, void *state, struct frame_stats *st)
{
    grad_method_reconstruct(r, &((struct gpt_state *)state)->grad, st);
}

_Static_assert(offsetof(struct gpt_state, grad) == 0, "grad_method_output reads the state as its grad_frame");

const struct method method_gpt = {
    .name = "gpt",
    .description = "gradient-domain path tracing (Kettunen et al. 2015, 002 B.2): pt base paths shifted to the 4 "
                   "neighbors (hybrid shift), Poisson reconstruction",
    .caps = METHOD_GRADIENT | METHOD_BUDGET_BY_SPP | METHOD_ANIMATED_EMITTERS,
    .blocks = (const struct param_block *const[]){&params_block_spp, &params_block_depth, &params_block_roulette,
                                                  &params_block_lights, &params_block_shift, &recon_block, NULL},
    .passes = (const char *const[]){"gpt", GRAD_METHOD_PASSES, NULL},
    .create = gpt_create,
    .destroy = gpt_destroy,
    .render_frame = gpt_render_frame,
    .reconstruct = gpt_reconstruct,
    .outputs = grad_method_outputs,
    .output = grad_method_output,
};
