/* grad_after.c: Gradient after ReSTIR (see grad_after.h; 002 Eq. 10-13). */
#include "grad_after.h"

#include "grad_common.h"
#include "render/tiles.h"

long long grad_after_pass(const struct pt_frame *fr, const struct pt_reservoir *res, float *os)
{
    const int w = fr->view->width, h = fr->view->height, ntiles = tile_count(w, h);
    long long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                if (pt_reservoir_has_sample(&res[i]))
                    rays += grad_one_sided_all(fr->s, &fr->shift, fr->view, &res[i].y, x, y, w, h, res[i].W, os, i);
            }
        }
    }
    return rays;
}
