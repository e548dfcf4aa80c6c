/* grad_common.c: one-sided differences, emission differences and their combination into forward
 * gradients (see grad_common.h; 002 Eq. 3, 11-13). */
#include "methods/gradient/grad_common.h"

#include <string.h>

#include "methods/restir_pt/restir_pt.h"
#include "render/tiles.h"
#include "restir/grad.h"

void grad_os_clear(float *os, size_t n) { memset(os, 0, sizeof(float) * 3 * GRAD_DIRS * n); }

void grad_combine(int w, int h, const float *os, float *dx, float *dy)
{
    const size_t n = (size_t)w * (size_t)h;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            size_t a = (size_t)y * (size_t)w + (size_t)x;
            const float *right = os + ((size_t)GRAD_RIGHT * n + a) * 3, *down = os + ((size_t)GRAD_DOWN * n + a) * 3;
            for (int c = 0; c < 3; c++) {
                /* d_ab = F_b - F_a = <Delta'_ba> - <Delta'_ab> (Eq. 12, forward sign) */
                if (x + 1 < w)
                    dx[3 * a + c] += os[((size_t)GRAD_LEFT * n + a + 1) * 3 + c] - right[c];
                if (y + 1 < h)
                    dy[3 * a + c] += os[((size_t)GRAD_UP * n + a + (size_t)w) * 3 + c] - down[c];
            }
        }
    }
}

long long grad_shift_other(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
                           const struct pt_domain *from, const struct pt_domain *to, float other[3], float *jacobian)
{
    long long rays = 0;
    struct path_sample y;
    float J;
    other[0] = other[1] = other[2] = 0.0f;
    if (path_shift(s, sp, x, from, to, &y, &J, &rays)) {
        other[0] = y.f.x * J;
        other[1] = y.f.y * J;
        other[2] = y.f.z * J;
    } else {
        J = 0.0f;
    }
    if (jacobian)
        *jacobian = J;
    return rays;
}

static void add_scaled(float *dst, const float *v, float weight)
{
    for (int c = 0; c < 3; c++)
        dst[c] += weight * v[c];
}

long long grad_one_sided_all(const struct scene *s, const struct shift_params *sp, const struct camera_view *view,
                             const struct path_sample *x, int px, int py, int w, int h, float weight, float *os,
                             size_t i)
{
    const size_t n = (size_t)w * (size_t)h;
    const float own[3] = {x->f.x, x->f.y, x->f.z};
    if (!(restir_grad_luminance(own) > 0.0f) || !(weight > 0.0f))
        return 0; /* omega = 0 where the base contributes nothing (Eq. 13) */
    struct pt_domain from = pt_pixel_domain(view, px, py);
    long long rays = 0;
    for (int d = 0; d < GRAD_DIRS; d++) {
        int ox, oy;
        grad_dir_offset(d, &ox, &oy);
        if (px + ox < 0 || px + ox >= w || py + oy < 0 || py + oy >= h)
            continue;
        struct pt_domain to = pt_pixel_domain(view, px + ox, py + oy);
        float other[3], diff[3];
        rays += grad_shift_other(s, sp, x, &from, &to, other, NULL);
        restir_grad_one_sided(own, other, diff);
        if (v3_is_finite(v3(diff[0], diff[1], diff[2])))
            add_scaled(grad_os(os, n, d, i), diff, weight);
    }
    return rays;
}

void grad_add_image_differences(int w, int h, const float *E, float *dx, float *dy)
{
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            for (int c = 0; c < 3; c++) {
                if (x + 1 < w)
                    dx[3 * i + c] += E[3 * (i + 1) + c] - E[3 * i + c];
                if (y + 1 < h)
                    dy[3 * i + c] += E[3 * (i + (size_t)w) + c] - E[3 * i + c];
            }
        }
    }
}
