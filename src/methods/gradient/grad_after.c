/* grad_after.c: Gradient after ReSTIR (see grad_after.h; 002 Eq. 10-13). */
#include "methods/gradient/grad_after.h"

#include "methods/gradient/grad_common.h"
#include "render/tiles.h"

long long grad_after_pass(const struct pt_frame *fr, const struct pt_reservoir *res, float *os)
{
    const int w = fr->view->width, h = fr->view->height, ntiles = tile_count(w, h);
    long long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y;
            const size_t i = (size_t)px.i;
            if (pt_reservoir_has_sample(&res[i]))
                rays += grad_one_sided_all(fr->s, &fr->shift, fr->view, &res[i].y, x, y, w, h, res[i].W, os, i);
        }
    }
    return rays;
}
