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
