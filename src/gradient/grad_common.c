/* grad_common.c: one-sided differences, emission differences and their combination into forward
 * gradients (see grad_common.h; 002 Eq. 3, 11-13). */
#include "grad_common.h"

#include <string.h>

#include "render/restir_pt.h"
#include "render/tiles.h"
#include "restir/gradient.h"
#include "shading/lights.h"

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
                           const struct pt_domain *from, const struct pt_domain *to, float other[3])
{
    long long rays = 0;
    struct path_sample y;
    float J;
    other[0] = other[1] = other[2] = 0.0f;
    if (path_shift(s, sp, x, from, to, &y, &J, &rays)) {
        other[0] = y.f.x * J;
        other[1] = y.f.y * J;
        other[2] = y.f.z * J;
    }
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
        rays += grad_shift_other(s, sp, x, &from, &to, other);
        restir_grad_one_sided(own, other, diff);
        if (v3_is_finite(v3(diff[0], diff[1], diff[2])))
            add_scaled(grad_os(os, n, d, i), diff, weight);
    }
    return rays;
}

/* Radiance emitted toward the camera by the primary hit at image position (fx, fy). */
static vec3 primary_emission(const struct scene *s, const struct camera_view *view, float fx, float fy)
{
    vec3 d = camera_view_ray(view, fx, fy);
    struct surface_hit hit;
    if (!scene_intersect(s, view->position, d, 0.0f, INFINITY, &hit))
        return v3s(0.0f);
    if (s->tri_emitter[hit.tri] < 0 || !hit.front)
        return v3s(0.0f);
    return lights_radiance(s, hit.tri, v3_neg(d));
}

long long grad_emission_one_sided(const struct scene *s, const struct camera_view *view, int px, int py, int w,
                                  int h, const float u[2], float weight, float *os, size_t i, vec3 *Le)
{
    const size_t n = (size_t)w * (size_t)h;
    vec3 e = primary_emission(s, view, (float)px + u[0], (float)py + u[1]);
    long long rays = 1;
    *Le = e;
    if (!(v3_luminance(e) > 0.0f))
        return rays;
    const float own[3] = {e.x, e.y, e.z};
    for (int d = 0; d < GRAD_DIRS; d++) {
        int ox, oy;
        grad_dir_offset(d, &ox, &oy);
        if (px + ox < 0 || px + ox >= w || py + oy < 0 || py + oy >= h)
            continue;
        vec3 o = primary_emission(s, view, (float)(px + ox) + u[0], (float)(py + oy) + u[1]);
        rays++;
        const float other[3] = {o.x, o.y, o.z};
        float diff[3];
        restir_grad_one_sided(own, other, diff);
        add_scaled(grad_os(os, n, d, i), diff, weight);
    }
    return rays;
}

long long grad_emission_pass(const struct scene *s, const struct camera_view *view, uint64_t seed, int frame,
                             int jitter, int w, int h, float *os)
{
    long long rays = 0;
    const int ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                size_t i = (size_t)y * (size_t)w + (size_t)x;
                pcg32 rng = rng_for(seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_GRAD_EMISSION);
                float u[2] = {0.5f, 0.5f};
                if (jitter) {
                    u[0] = pcg32_float(&rng);
                    u[1] = pcg32_float(&rng);
                }
                vec3 Le;
                rays += grad_emission_one_sided(s, view, x, y, w, h, u, 1.0f, os, i, &Le);
            }
        }
    }
    return rays;
}
