/* svgf_temporal.c: SVGF's temporal accumulation (Schied et al. 2017 Sec. 4.1; svgf_temporal.h).
 * Each used pixel's previous position (its motion vector) is read bilinearly from the previous
 * frame's pixels that pass the consistency tests (the same mesh and group of demodulated albedo
 * channels, normals within svgf_normal_min, and its surface: the plane distance between world
 * positions within svgf_plane_max of the depth);
 * where none of the four passes, the passing pixels of the 3x3 block around the nearest one, each
 * alike. Colour and moments are blended by exponential moving averages with weight max(alpha,
 * 1 / history length). */
#include "denoise/svgf_temporal.h"

#include <math.h>

#include "denoise/denoise_kernel.h"

#define MAX_HISTORY 255.0f
#define MIN_WEIGHT 1e-4f /* a bilinear sum of weights below it counts as no history */

/* Whether the previous frame's pixel q shows pixel i's surface. */
static inline int tap_ok(const struct svgf_accumulation *a, int i, int q)
{
    const struct denoise_frame *f = a->f;
    const struct svgf_history *h = a->prev;
    const float nd = f->normal[0][i] * h->normal[0][q] + f->normal[1][i] * h->normal[1][q] +
                     f->normal[2][i] * h->normal[2][q];
    const float pl = f->normal[0][i] * (h->position[0][q] - f->position[0][i]) +
                     f->normal[1][i] * (h->position[1][q] - f->position[1][i]) +
                     f->normal[2][i] * (h->position[2][q] - f->position[2][i]);
    return (h->group[q] == f->group[i]) & (h->object[q] == f->object[i]) & (nd >= a->normal_min) &
           (fabsf(pl) <= a->plane_max * f->depth[i]);
}

/* The bilinear sums at the previous position (px, py) of pixel (x, y), px, py > -1: the six values
 * into acc[0..5], their weight into acc[6]. Taps of weight 0 are skipped (a snapped position,
 * denoise_snap, has three). */
static inline void bilinear(const struct svgf_accumulation *a, int x, int y, float px, float py, float acc[7])
{
    const int w = a->f->width, h = a->f->height, i = y * w + x;
    const int x0 = (int)(px + 1.0f) - 1, y0 = (int)(py + 1.0f) - 1; /* floor, as px, py > -1 */
    const float fx = px - (float)x0, fy = py - (float)y0;
    for (int c = 0; c < 7; c++)
        acc[c] = 0.0f;
    for (int k = 0; k < 4; k++) {
        const int qx = x0 + (k & 1), qy = y0 + (k >> 1), q = qy * w + qx;
        const float wt = ((k & 1) ? fx : 1.0f - fx) * ((k >> 1) ? fy : 1.0f - fy);
        if (wt == 0.0f || qx < 0 || qy < 0 || qx >= w || qy >= h || !tap_ok(a, i, q))
            continue;
        for (int c = 0; c < 6; c++)
            acc[c] += wt * a->prev->value[c][q];
        acc[6] += wt;
    }
}

/* Where no bilinear tap passed: the sums over the passing pixels of the 3x3 block around the
 * nearest previous pixel, each weighing 1, at (px, py) > (-2, -2). */
static void search_3x3(const struct svgf_accumulation *a, int x, int y, float px, float py, float acc[7])
{
    const int w = a->f->width, h = a->f->height, i = y * w + x;
    const int bx = (int)(px + 2.5f) - 2, by = (int)(py + 2.5f) - 2; /* the nearest pixel */
    for (int c = 0; c < 7; c++)
        acc[c] = 0.0f;
    for (int qy = by - 1; qy <= by + 1; qy++)
        for (int qx = bx - 1; qx <= bx + 1; qx++) {
            if (qx < 0 || qy < 0 || qx >= w || qy >= h || !tap_ok(a, i, qy * w + qx))
                continue;
            for (int c = 0; c < 6; c++)
                acc[c] += a->prev->value[c][qy * w + qx];
            acc[6] += 1.0f;
        }
}

/* The previous values of pixel (x, y), averaged (hist[0..5]); 0 when none passes. */
static int reproject(const struct svgf_accumulation *a, int x, int y, float hist[6])
{
    const struct denoise_frame *f = a->f;
    const int w = f->width, h = f->height, i = y * w + x;
    const float mx = f->motion[2 * i], my = f->motion[2 * i + 1];
    if (!(mx < DENOISE_NO_MOTION && my < DENOISE_NO_MOTION))
        return 0;
    /* the previous pixel centres' coordinates */
    const float px = denoise_snap((float)x + mx), py = denoise_snap((float)y + my);
    if (!(px > -2.0f && py > -2.0f && px < (float)w + 1.0f && py < (float)h + 1.0f))
        return 0;
    float acc[7] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    if (px > -1.0f && py > -1.0f)
        bilinear(a, x, y, px, py, acc);
    if (acc[6] <= MIN_WEIGHT)
        search_3x3(a, x, y, px, py, acc);
    if (acc[6] <= MIN_WEIGHT)
        return 0;
    for (int c = 0; c < 6; c++)
        hist[c] = acc[c] / acc[6];
    return 1;
}

long long svgf_accumulate(const struct svgf_accumulation *a)
{
    struct denoise_frame *f = a->f;
    const int w = f->width, h = f->height;
    long long reset = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : reset)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            if (f->use[i] == 0.0f) {
                a->len[i] = 0.0f;
                continue;
            }
            const float c[3] = {f->illum[0][i], f->illum[1][i], f->illum[2][i]};
            const float l = denoise_luminance(c[0], c[1], c[2]);
            float hist[6];
            const int found = a->prev && reproject(a, x, y, hist);
            reset += !found;
            /* A-SVGF: a stale history (gradient g) counts for less and weighs less */
            const float g = f->gradient ? svgf_gradient_response(f->gradient[i]) : 0.0f;
            const float len = found ? MINF(hist[5] * (1.0f - g) + 1.0f, MAX_HISTORY) : 1.0f;
            float al = found ? MAXF(a->alpha, 1.0f / len) : 1.0f;
            float am = found ? MAXF(a->moments_alpha, 1.0f / len) : 1.0f;
            al += g * (1.0f - al);
            am += g * (1.0f - am);
            for (int k = 0; k < 3; k++)
                f->illum[k][i] = found ? (1.0f - al) * hist[k] + al * c[k] : c[k];
            a->m1[i] = found ? (1.0f - am) * hist[3] + am * l : l;
            a->m2[i] = found ? (1.0f - am) * hist[4] + am * l * l : l * l;
            a->len[i] = len;
        }
    return reset;
}
