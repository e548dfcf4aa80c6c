/* grad_method.c: the gradient methods' shared reconstruction (grad_method.h). */
#include "methods/gradient/grad_method.h"
#include "methods/gradient/grad_settings.h"

#include <string.h>

void grad_method_reconstruct(struct renderer *r, struct grad_frame *gf, struct frame_stats *st)
{
    const size_t n = (size_t)gf->width * (size_t)gf->height;
    RENDERER_TIMED(st, PASS_RECON_L2, grad_reconstruct_l2(&r->p, gf));
    st->l2_residual = gf->l2_stats.residual;
    if (recon_settings_of(&r->p)->mode != RECON_L2) {
        RENDERER_TIMED(st, PASS_RECON_L1, grad_reconstruct_l1(&r->p, gf));
        st->l1_residual = gf->l1_stats.residual;
    }
    memcpy(r->image, recon_settings_of(&r->p)->mode == RECON_L1 ? gf->l1 : gf->l2, sizeof(float) * 3 * n);
}

const struct method_output grad_method_outputs[] = {
    {"L2", 3, METHOD_OUTPUT_DEBUG},
    {"L1", 3, METHOD_OUTPUT_DEBUG},
    {"primal", 3, METHOD_OUTPUT_RADIANCE},
    {"dx", 3, METHOD_OUTPUT_SIGNED},
    {"dy", 3, METHOD_OUTPUT_SIGNED},
    {NULL, 0, METHOD_OUTPUT_RADIANCE},
};

float *grad_method_output(const struct renderer *r, void *state, int k)
{
    struct grad_frame *g = state;
    const enum recon_mode mode = recon_settings_of(&r->p)->mode;
    switch (k) {
    case 0: return mode == RECON_L1 ? g->l2 : NULL;
    case 1: return mode == RECON_BOTH ? g->l1 : NULL;
    case 2: return g->primal;
    case 3: return g->dx;
    case 4: return g->dy;
    default: return NULL;
    }
}

struct grad_frame *grad_method_frame(const struct renderer *r)
{
    return r->method->output == grad_method_output ? r->state : NULL;
}
