/* di_gradient.c: restir-di's temporal gradient for A-SVGF (di_gradient.h). */
#include "methods/restir_di/di_gradient.h"

#include <math.h>

#include "scene/scene_animation.h"
#include "scene/scene_motion.h"

/* A sample's estimate now and before: target x W now, and the same with its emitter at the other
 * frame's strength and, for a moving one, scaled by the unshadowed targets at sp of both frames' poses.
 * now_is_cached: the cached target is this frame's (an initial sample) or the previous frame's (a history
 * sample). */
static void shaded(const struct scene *s, const struct shading_point *sp, const struct di_reservoir *r, int frame,
                   int now_is_cached, float *now, float *before)
{
    *now = *before = 0.0f;
    if (r->y.tri < 0 || !(r->W > 0.0f) || !(r->target > 0.0f))
        return;
    const float cached = r->target * r->W;
    if (r->y.tri == DI_ENV_TRI) { /* the environment does not change */
        *now = *before = cached;
        return;
    }
    float s_now = scene_emission_strength(s, r->y.tri, (float)frame);
    float s_before = scene_emission_strength(s, r->y.tri, (float)(frame - 1));
    if (scene_has_moving_emitters(s) && sp) { /* a moved emitter: the unshadowed targets of both poses */
        struct di_sample y[2] = {r->y, r->y}; /* [0] at this frame, [1] at the previous */
        for (int k = 0; k < 2; k++)
            scene_motion_point_at(s, r->y.tri, r->y.b1, r->y.b2, (float)(frame - k), &y[k].p, &y[k].n);
        s_now *= di_target(sp, &y[0]);
        s_before *= di_target(sp, &y[1]);
    }
    if (now_is_cached) {
        *now = cached;
        *before = s_now > 0.0f ? cached * (s_before / s_now) : 0.0f;
    } else {
        *before = cached;
        *now = s_before > 0.0f ? cached * (s_now / s_before) : 0.0f;
    }
}

/* out[i] = the sum of in over the (2r + 1)^2 window around pixel i, clipped to the image (separable). */
static void box_sum(const float *in, int w, int h, float *row, float *out)
{
    const int r = DI_GRADIENT_RADIUS;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float sum = 0.0f;
            for (int dx = -r; dx <= r; dx++)
                if (x + dx >= 0 && x + dx < w)
                    sum += in[y * w + x + dx];
            row[y * w + x] = sum;
        }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float sum = 0.0f;
            for (int dy = -r; dy <= r; dy++)
                if (y + dy >= 0 && y + dy < h)
                    sum += row[(y + dy) * w + x];
            out[y * w + x] = sum;
        }
}

void di_temporal_gradient(const struct scene *s, const struct gbuffer *g, const struct gbuffer *prev_g,
                          const struct di_reservoir *initial, const struct di_reservoir *prev, int frame, float *grad,
                          float *tmp)
{
    const int w = g->width, h = g->height;
    const size_t n = (size_t)w * (size_t)h;
    float *delta = tmp, *sum_now = tmp + n, *sum_before = tmp + 2 * n, *row = tmp + 3 * n;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < (int)n; i++) {
        float now, before, d = 0.0f, m = 0.0f, b = 0.0f;
        if (g->valid[i]) {
            shaded(s, gbuffer_shading(g, i), &initial[i], frame, 1, &now, &before);
            d += now - before;
            m += now;
            b += before;
            const int q = prev ? gbuffer_motion_pixel(g, i, prev_g) : -1;
            if (q >= 0) {
                shaded(s, gbuffer_shading(prev_g, q), &prev[q], frame, 0, &now, &before);
                d += now - before;
                m += now;
                b += before;
            }
        }
        delta[i] = d;
        sum_now[i] = m;
        sum_before[i] = b;
    }
    box_sum(delta, w, h, row, grad);
    box_sum(sum_now, w, h, row, delta); /* delta's plane now holds the filtered sum of now */
    box_sum(sum_before, w, h, row, sum_now); /* and sum_now's the filtered sum of before */
#pragma omp parallel for schedule(static)
    for (int i = 0; i < (int)n; i++) {
        const float big = fmaxf(delta[i], sum_now[i]);
        const float lambda = big > 0.0f ? fabsf(grad[i]) / big : 0.0f;
        grad[i] = lambda < 1.0f ? lambda : 1.0f;
    }
}

