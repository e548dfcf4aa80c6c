/* svgf.c: spatiotemporal variance-guided filtering (Schied et al., "Spatiotemporal Variance-Guided
 * Filtering: Real-Time Reconstruction for Path-Traced Global Illumination", HPG 2017) on the
 * demodulated illumination denoise.c prepares:
 *   1. temporal accumulation (Sec. 4.1): the previous frame's colour and luminance moments,
 *      reprojected by the motion vector with a bilinear tap (a 3x3 search when no bilinear tap
 *      passes), each tap tested for the same mesh, normal and surface, blended by an exponential
 *      moving average with weight max(alpha, 1 / history length);
 *   2. variance (Sec. 4.2): from the temporal moments, or, for histories shorter than 4 frames,
 *      from moments filtered by a 7x7 bilateral filter driven by depth and normals;
 *   3. five à-trous iterations (Sec. 4.3, Eq. 1-5) with step 2^i, the B3 kernel, and edge-stopping
 *      weights on depth (by its screen-space gradient), normals (power sigma_n) and luminance (by
 *      the 3x3-blurred variance); the variance is filtered along (Eq. 2); the first iteration's
 *      output becomes the colour history (Sec. 4.3);
 *   4. after remodulation by albedo (denoise.c), temporal antialiasing (svgf_post).
 * Deviations, by necessity: one image (our methods do not separate direct and indirect light); the
 * reprojection's surface test is the plane distance between world positions (what our temporal
 * reuse tests, 001 Sec. 5), since we keep positions rather than a rasteriser's reprojected depth. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/simd.h"
#include "denoise/denoise_kernel.h"
#include "denoise/denoise_method.h"

/* A few per-pixel planes of one frame. */
enum {
    H_C0, H_C1, H_C2, H_M1, H_M2, H_LEN, H_USE, H_P0, H_P1, H_P2, H_N0, H_N1, H_N2, /* history */
    C_M1, C_M2, C_LEN, C_VAR,                                                     /* this frame */
    T_C0, T_C1, T_C2, T_VAR, T_LUM, T_INVL,                                       /* à-trous scratch */
    V_FIRST,                                                                      /* Sec. 4.2's variance */
    A_R, A_G, A_B, A_USE, A_OUT_R, A_OUT_G, A_OUT_B, /* antialiasing: history, its use, this frame's output */
    SVGF_PLANES
};

/* eps of Eq. 3 relative to the pixel's depth, and of Eq. 5 */
#define EPS_DEPTH 1e-3f
#define EPS_LUM 1e-10f
#define MAX_HISTORY 255.0f
/* min and max of finite floats, inline (fminf / fmaxf stay library calls without -ffinite-math-only) */
#define MINF(a, b) ((a) < (b) ? (a) : (b))
#define MAXF(a, b) ((a) > (b) ? (a) : (b))

struct svgf {
    int w, h;
    size_t n;
    float *plane[SVGF_PLANES];
    int *prev_object;
    int has_history;
    int has_taa; /* the antialiasing history holds a frame */
    struct denoise_scratch acc; /* per thread, 6 rows of the image's width */
};

static void *svgf_create(const struct denoise_settings *s, int width, int height)
{
    (void)s;
    struct svgf *v = xcalloc(1, sizeof(*v));
    v->w = width;
    v->h = height;
    v->n = (size_t)width * (size_t)height;
    denoise_planes_alloc(v->plane, SVGF_PLANES, v->n);
    v->prev_object = xcalloc(v->n, sizeof(int));
    return v;
}

static void svgf_destroy(void *state)
{
    struct svgf *v = state;
    free(v->plane[0]);
    free(v->prev_object);
    denoise_scratch_free(&v->acc);
    free(v);
}

/* Whether the previous frame's pixel q shows pixel i's surface (Sec. 4.1's consistency tests). */
static inline int history_tap_ok(const struct svgf *v, const struct denoise_settings *s, const struct denoise_frame *f,
                                 int i, int q)
{
    float *const *P = v->plane;
    if (P[H_USE][q] == 0.0f || v->prev_object[q] != f->object[i])
        return 0;
    const float nd = f->normal[0][i] * P[H_N0][q] + f->normal[1][i] * P[H_N1][q] + f->normal[2][i] * P[H_N2][q];
    if (nd < s->svgf_normal_min)
        return 0;
    const float plane = f->normal[0][i] * (P[H_P0][q] - f->position[0][i]) +
                        f->normal[1][i] * (P[H_P1][q] - f->position[1][i]) +
                        f->normal[2][i] * (P[H_P2][q] - f->position[2][i]);
    return fabsf(plane) <= s->svgf_plane_max * f->depth[i];
}

/* The previous colour, moments and history length at pixel i, reprojected: bilinear over the
 * taps that pass, else the mean of the passing pixels of the 3x3 block around the reprojected
 * position. Returns 0 when none passes. */
static int reproject(const struct svgf *v, const struct denoise_settings *s, const struct denoise_frame *f, int x,
                     int y, float hist[6])
{
    const int i = y * v->w + x;
    const float mx = f->motion[2 * i], my = f->motion[2 * i + 1];
    if (!(mx < DENOISE_NO_MOTION && my < DENOISE_NO_MOTION))
        return 0;
    const float px = (float)x + mx, py = (float)y + my; /* the previous pixel centres' coordinates */
    if (!(px > -2.0f && py > -2.0f && px < (float)v->w + 1.0f && py < (float)v->h + 1.0f))
        return 0;
    const int x0 = (int)floorf(px), y0 = (int)floorf(py);
    const float fx = px - (float)x0, fy = py - (float)y0;
    float wsum = 0.0f;
    for (int k = 0; k < 6; k++)
        hist[k] = 0.0f;
    for (int pass = 0; pass < 2 && wsum <= 1e-4f; pass++) {
        const int r = pass == 0 ? 0 : 1; /* pass 0: the 2x2 bilinear taps; pass 1: 3x3 around the nearest */
        const int bx = pass == 0 ? x0 : (int)floorf(px + 0.5f), by = pass == 0 ? y0 : (int)floorf(py + 0.5f);
        for (int dy = -r; dy <= (pass == 0 ? 1 : r); dy++)
            for (int dx = -r; dx <= (pass == 0 ? 1 : r); dx++) {
                const int qx = bx + dx, qy = by + dy;
                if (qx < 0 || qy < 0 || qx >= v->w || qy >= v->h)
                    continue;
                const int q = qy * v->w + qx;
                if (!history_tap_ok(v, s, f, i, q))
                    continue;
                const float wt = pass == 1 ? 1.0f : (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy);
                if (wt <= 0.0f)
                    continue;
                const float h[6] = {v->plane[H_C0][q], v->plane[H_C1][q], v->plane[H_C2][q],
                                    v->plane[H_M1][q], v->plane[H_M2][q], v->plane[H_LEN][q]};
                for (int k = 0; k < 6; k++)
                    hist[k] += wt * h[k];
                wsum += wt;
            }
        if (wsum <= 1e-4f)
            for (int k = 0; k < 6; k++)
                hist[k] = 0.0f;
    }
    if (wsum <= 1e-4f)
        return 0;
    for (int k = 0; k < 6; k++)
        hist[k] /= wsum;
    return 1;
}

/* Sec. 4.1: colour and moments accumulated into f->illum, C_M1, C_M2, C_LEN. Returns the number of
 * used pixels whose history was rejected. */
static long long accumulate(struct svgf *v, const struct denoise_settings *s, struct denoise_frame *f)
{
    float **P = v->plane;
    long long reset = 0;
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : reset)
    for (int y = 0; y < v->h; y++)
        for (int x = 0; x < v->w; x++) {
            const int i = y * v->w + x;
            P[C_LEN][i] = 0.0f;
            if (f->use[i] == 0.0f)
                continue;
            const float c[3] = {f->illum[0][i], f->illum[1][i], f->illum[2][i]};
            const float l = denoise_luminance(c[0], c[1], c[2]);
            float hist[6];
            const int found = v->has_history && reproject(v, s, f, x, y, hist);
            reset += !found;
            const float len = found ? MINF(hist[5] + 1.0f, MAX_HISTORY) : 1.0f;
            const float a = found ? MAXF(s->svgf_alpha, 1.0f / len) : 1.0f;
            const float am = found ? MAXF(s->svgf_moments_alpha, 1.0f / len) : 1.0f;
            for (int k = 0; k < 3; k++)
                f->illum[k][i] = found ? (1.0f - a) * hist[k] + a * c[k] : c[k];
            P[C_M1][i] = found ? (1.0f - am) * hist[3] + am * l : l;
            P[C_M2][i] = found ? (1.0f - am) * hist[4] + am * l * l : l * l;
            P[C_LEN][i] = len;
        }
    return reset;
}

/* The depth and normal weight of Eq. 3-4 between pixel i and q at offset (ox, oy) (as a log2). */
static inline float depth_normal_log2w(const struct denoise_frame *f, const struct denoise_settings *s, int i, int q,
                                       float ox, float oy)
{
    const float den = s->svgf_sigma_depth * fabsf(f->ddx[i] * ox + f->ddy[i] * oy) + EPS_DEPTH * f->depth[i];
    const float az = fabsf(f->depth[i] - f->depth[q]) / den;
    float nd =
        f->normal[0][i] * f->normal[0][q] + f->normal[1][i] * f->normal[1][q] + f->normal[2][i] * f->normal[2][q];
    nd = nd > 1e-20f ? nd : 1e-20f;
    return s->svgf_sigma_normal * denoise_log2(nd) - az * DENOISE_LOG2E;
}

/* Sec. 4.2: the luminance variance per pixel into C_VAR. */
static void estimate_variance(struct svgf *v, const struct denoise_settings *s, const struct denoise_frame *f)
{
    float **P = v->plane;
    const float short_history = (float)s->svgf_variance_frames;
#pragma omp parallel for schedule(dynamic, 8)
    for (int y = 0; y < v->h; y++)
        for (int x = 0; x < v->w; x++) {
            const int i = y * v->w + x;
            if (f->use[i] == 0.0f) {
                P[C_VAR][i] = 0.0f;
                continue;
            }
            float m1 = P[C_M1][i], m2 = P[C_M2][i];
            if (P[C_LEN][i] < short_history) { /* a 7x7 bilateral estimate of the moments */
                float ws = 0.0f, s1 = 0.0f, s2 = 0.0f;
                for (int dy = -3; dy <= 3; dy++)
                    for (int dx = -3; dx <= 3; dx++) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= v->w || qy >= v->h)
                            continue;
                        const int q = qy * v->w + qx;
                        if (f->use[q] == 0.0f)
                            continue;
                        const float wt = denoise_exp2_neg(depth_normal_log2w(f, s, i, q, (float)dx, (float)dy));
                        ws += wt;
                        s1 += wt * P[C_M1][q];
                        s2 += wt * P[C_M2][q];
                    }
                m1 = s1 / ws; /* ws >= 1: the pixel itself */
                m2 = s2 / ws;
            }
            P[C_VAR][i] = MAXF(0.0f, m2 - m1 * m1);
        }
}

/* The centre pixels' and the taps' planes of one tap over a row segment (restrict: they never
 * alias the outputs, so the pixel loops vectorise). */
struct svgf_segment {
    const float *restrict zp, *restrict gx, *restrict gy, *restrict lp, *restrict ip;
    const float *restrict n0, *restrict n1, *restrict n2;
    const float *restrict zq, *restrict lq, *restrict m0, *restrict m1, *restrict m2;
};

/* Eq. 3-5's weight of one tap (B3 weight hk, offset (fox, foy)) for pixels [lo, hi) of a row into
 * wt. Taps that are not used have depth +inf (denoise.c), so their weight is 0. squarings >= 0:
 * sigma_n = 2^squarings, the power taken by squaring (the default 128 = 2^7; nd_min: below it the
 * power is under 2^DENOISE_EXP2_CUT and counts as 0, never a denormal); -1: any sigma_n, by
 * exp2(sigma_n log2(n . n)). Called with constants, so each case compiles to its own loop. */
SIMD_INLINE void svgf_tap_weights(const struct svgf_segment *t, int lo, int hi, float hk, float fox, float foy,
                                  float sz, float sn, int squarings, float nd_min, float *restrict wt)
{
    const float *restrict zp = t->zp, *restrict gx = t->gx, *restrict gy = t->gy, *restrict lp = t->lp;
    const float *restrict ip = t->ip, *restrict n0 = t->n0, *restrict n1 = t->n1, *restrict n2 = t->n2;
    const float *restrict zq = t->zq, *restrict lq = t->lq, *restrict m0 = t->m0;
    const float *restrict m1 = t->m1, *restrict m2 = t->m2;
    for (int x = lo; x < hi; x++) {
        const float den = sz * fabsf(gx[x] * fox + gy[x] * foy) + EPS_DEPTH * zp[x];
        const float a = fabsf(zp[x] - zq[x]) / den + fabsf(lp[x] - lq[x]) * ip[x];
        float nd = n0[x] * m0[x] + n1[x] * m1[x] + n2[x] * m2[x];
        if (squarings >= 0) {
            nd = nd >= nd_min ? nd : 0.0f;
            for (int k = 0; k < squarings; k++)
                nd *= nd;
            wt[x] = hk * nd * denoise_exp2_neg(-a * DENOISE_LOG2E);
        } else {
            nd = nd > 1e-20f ? nd : 1e-20f;
            wt[x] = hk * denoise_exp2_neg(sn * denoise_log2(nd) - a * DENOISE_LOG2E);
        }
    }
}

/* Eq. 1-2's sums of one tap: the weights, weighted colours and squared-weighted variances. */
SIMD_INLINE void svgf_tap_sums(int lo, int hi, const float *restrict wt, const float *restrict cr,
                               const float *restrict cg, const float *restrict cb, const float *restrict cv,
                               float *restrict sw, float *restrict sr, float *restrict sg, float *restrict sb,
                               float *restrict sv)
{
    for (int x = lo; x < hi; x++) {
        const float v = wt[x];
        sw[x] += v;
        sr[x] += v * cr[x];
        sg[x] += v * cg[x];
        sb[x] += v * cb[x];
        sv[x] += v * v * cv[x];
    }
}

/* One row of one à-trous iteration (Eq. 1-5): the sums over the 25 taps into acc[0 .. 5w), with
 * acc[5w .. 6w) for one tap's weights. in[0..2] colour, in[3] variance. */
SIMD_INLINE void atrous_row_body(const struct denoise_frame *f, const struct denoise_settings *s,
                                 const float *const in[4], const float *lum, const float *invl, int y, int step,
                                 float *acc)
{
    const int w = f->width, h = f->height;
    float *sw = acc, *sr = acc + w, *sg = acc + 2 * w, *sb = acc + 3 * w, *sv = acc + 4 * w, *wt = acc + 5 * w;
    for (int x = 0; x < w; x++)
        sw[x] = sr[x] = sg[x] = sb[x] = sv[x] = 0.0f;
    const int row = y * w;
    const float sz = s->svgf_sigma_depth, sn = s->svgf_sigma_normal;
    const float nd_min = exp2f(DENOISE_EXP2_CUT / sn);
    for (int ty = 0; ty < 5; ty++) {
        const int oy = (ty - 2) * step, yq = y + oy;
        if (yq < 0 || yq >= h)
            continue;
        for (int tx = 0; tx < 5; tx++) {
            const int ox = (tx - 2) * step;
            const int xlo = ox < 0 ? -ox : 0, xhi = ox > 0 ? w - ox : w;
            const int q = yq * w + ox; /* tap of pixel x: q + x */
            const struct svgf_segment t = {f->depth + row,      f->ddx + row,       f->ddy + row,
                                           lum + row,           invl + row,         f->normal[0] + row,
                                           f->normal[1] + row,  f->normal[2] + row, f->depth + q,
                                           lum + q,             f->normal[0] + q,   f->normal[1] + q,
                                           f->normal[2] + q};
            const float hk = denoise_b3[ty] * denoise_b3[tx];
            if (sn == 128.0f)
                svgf_tap_weights(&t, xlo, xhi, hk, (float)ox, (float)oy, sz, sn, 7, nd_min, wt);
            else
                svgf_tap_weights(&t, xlo, xhi, hk, (float)ox, (float)oy, sz, sn, -1, nd_min, wt);
            svgf_tap_sums(xlo, xhi, wt, in[0] + q, in[1] + q, in[2] + q, in[3] + q, sw, sr, sg, sb, sv);
        }
    }
}

static void atrous_row_base(const struct denoise_frame *f, const struct denoise_settings *s, const float *const in[4],
                            const float *lum, const float *invl, int y, int step, float *acc)
{
    atrous_row_body(f, s, in, lum, invl, y, step, acc);
}

#if RESTIR_SIMD_DISPATCH
SIMD_TARGET_AVX2 static void atrous_row_avx2(const struct denoise_frame *f, const struct denoise_settings *s,
                                             const float *const in[4], const float *lum, const float *invl, int y,
                                             int step, float *acc)
{
    atrous_row_body(f, s, in, lum, invl, y, step, acc);
}
#endif

/* Per iteration: the luminance of the input colour and 1 / (sigma_l sqrt(g_3x3(Var)) + eps) of Eq. 5,
 * the variance blurred by the 3x3 Gaussian over the used pixels. */
static void luminance_terms(const struct denoise_frame *f, const struct denoise_settings *s, const float *const in[4],
                            float *lum, float *invl)
{
    const int w = f->width, h = f->height;
    static const float g3[3] = {0.25f, 0.5f, 0.25f};
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            lum[i] = denoise_luminance(in[0][i], in[1][i], in[2][i]);
            float ws = 0.0f, vs = 0.0f;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const int qx = x + dx, qy = y + dy;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h)
                        continue;
                    const int q = qy * w + qx;
                    const float wt = g3[dx + 1] * g3[dy + 1] * f->use[q];
                    ws += wt;
                    vs += wt * in[3][q];
                }
            const float var = ws > 0.0f ? vs / ws : 0.0f;
            invl[i] = 1.0f / (s->svgf_sigma_lum * sqrtf(var) + EPS_LUM);
        }
}

/* Sec. 4.3: the à-trous iterations on f->illum with the variance C_VAR, the colour history from
 * iteration svgf_feedback. */
static void filter(struct svgf *v, const struct denoise_settings *s, struct denoise_frame *f)
{
    float **P = v->plane;
    const int w = v->w, h = v->h;
    denoise_scratch_reserve(&v->acc, 6 * (size_t)w);
    float *src[4] = {f->illum[0], f->illum[1], f->illum[2], P[C_VAR]};
    float *dst[4] = {P[T_C0], P[T_C1], P[T_C2], P[T_VAR]};
#if RESTIR_SIMD_DISPATCH
    void (*row)(const struct denoise_frame *, const struct denoise_settings *, const float *const[4], const float *,
                const float *, int, int, float *) =
        simd_isa_active() == SIMD_ISA_AVX2 ? atrous_row_avx2 : atrous_row_base;
#else
    void (*row)(const struct denoise_frame *, const struct denoise_settings *, const float *const[4], const float *,
                const float *, int, int, float *) = atrous_row_base;
#endif
    if (s->svgf_feedback == 0)
        for (int k = 0; k < 3; k++)
            memcpy(P[H_C0 + k], f->illum[k], sizeof(float) * v->n);
    for (int it = 0; it < s->svgf_iterations; it++) {
        const float *const in[4] = {src[0], src[1], src[2], src[3]};
        luminance_terms(f, s, in, P[T_LUM], P[T_INVL]);
        const int step = 1 << it;
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < h; y++) {
            float *acc = denoise_scratch_mine(&v->acc);
            row(f, s, in, P[T_LUM], P[T_INVL], y, step, acc);
            for (int x = 0; x < w; x++) {
                const int i = y * w + x;
                const float sw = acc[x];
                const int used = f->use[i] != 0.0f;
                dst[0][i] = used ? acc[w + x] / sw : 0.0f;
                dst[1][i] = used ? acc[2 * w + x] / sw : 0.0f;
                dst[2][i] = used ? acc[3 * w + x] / sw : 0.0f;
                dst[3][i] = used ? acc[4 * w + x] / (sw * sw) : 0.0f;
            }
        }
        for (int k = 0; k < 4; k++) { /* the output is the next iteration's input */
            float *t = src[k];
            src[k] = dst[k];
            dst[k] = t;
        }
        if (it + 1 == s->svgf_feedback)
            for (int k = 0; k < 3; k++)
                memcpy(P[H_C0 + k], src[k], sizeof(float) * v->n);
    }
    if (src[0] != f->illum[0])
        for (int k = 0; k < 3; k++)
            memcpy(f->illum[k], src[k], sizeof(float) * v->n);
}

/* What the next frame reprojects: moments, history length and the features of the used pixels. */
static void keep_history(struct svgf *v, const struct denoise_frame *f)
{
    float **P = v->plane;
    memcpy(P[H_M1], P[C_M1], sizeof(float) * v->n);
    memcpy(P[H_M2], P[C_M2], sizeof(float) * v->n);
    memcpy(P[H_LEN], P[C_LEN], sizeof(float) * v->n);
    memcpy(P[H_USE], f->use, sizeof(float) * v->n);
    for (int k = 0; k < 3; k++) {
        memcpy(P[H_P0 + k], f->position[k], sizeof(float) * v->n);
        memcpy(P[H_N0 + k], f->normal[k], sizeof(float) * v->n);
    }
    memcpy(v->prev_object, f->object, sizeof(int) * v->n);
    v->has_history = 1;
}

static void svgf_run(void *state, const struct denoise_settings *s, struct denoise_frame *f, struct denoise_stats *st)
{
    struct svgf *v = state;
    st->history_reset += accumulate(v, s, f);
    estimate_variance(v, s, f);
    memcpy(v->plane[V_FIRST], v->plane[C_VAR], sizeof(float) * v->n);
    filter(v, s, f);
    keep_history(v, f);
}

/* The 3x3 neighbourhood's per-channel range of this frame's output over used pixels (Karis 2014's
 * colour clamp). */
static void neighbourhood_range(const struct denoise_frame *f, const float *rgb, int x, int y, float lo[3],
                                float hi[3])
{
    for (int c = 0; c < 3; c++) {
        lo[c] = INFINITY;
        hi[c] = -INFINITY;
    }
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= f->width || qy >= f->height)
                continue;
            const int q = qy * f->width + qx;
            if (f->use[q] == 0.0f)
                continue;
            for (int c = 0; c < 3; c++) {
                lo[c] = MINF(lo[c], rgb[3 * q + c]);
                hi[c] = MAXF(hi[c], rgb[3 * q + c]);
            }
        }
}

/* The antialiasing history at pixel i's reprojected position: bilinear over the previous frame's
 * used pixels. Returns 0 where none is there. */
static int taa_history(const struct svgf *v, const struct denoise_frame *f, int x, int y, float h[3])
{
    const int i = y * v->w + x;
    const float mx = f->motion[2 * i], my = f->motion[2 * i + 1];
    if (!(mx < DENOISE_NO_MOTION && my < DENOISE_NO_MOTION))
        return 0;
    const float px = (float)x + mx, py = (float)y + my;
    if (!(px > -1.0f && py > -1.0f && px < (float)v->w && py < (float)v->h))
        return 0;
    const int x0 = (int)floorf(px), y0 = (int)floorf(py);
    const float fx = px - (float)x0, fy = py - (float)y0;
    float wsum = 0.0f;
    h[0] = h[1] = h[2] = 0.0f;
    for (int dy = 0; dy <= 1; dy++)
        for (int dx = 0; dx <= 1; dx++) {
            const int qx = x0 + dx, qy = y0 + dy;
            if (qx < 0 || qy < 0 || qx >= v->w || qy >= v->h)
                continue;
            const int q = qy * v->w + qx;
            const float wt = v->plane[A_USE][q] * (dx ? fx : 1.0f - fx) * (dy ? fy : 1.0f - fy);
            if (wt <= 0.0f)
                continue;
            for (int c = 0; c < 3; c++)
                h[c] += wt * v->plane[A_R + c][q];
            wsum += wt;
        }
    if (wsum <= 1e-4f)
        return 0;
    for (int c = 0; c < 3; c++)
        h[c] /= wsum;
    return 1;
}

/* Schied et al.'s last step, temporal antialiasing (Karis 2014): each used pixel's reprojected
 * output, clamped to its 3x3 neighbourhood's range in this frame, blended with this frame's output
 * by svgf_taa_alpha. Where a jittered pixel straddles an edge, its sample lands on one surface in one
 * frame and on the other in the next; the feature-tested history (Sec. 4.1) cannot average the two,
 * this can, and the neighbourhood holds both, so the clamp lets it. */
static void svgf_post(void *state, const struct denoise_settings *s, const struct denoise_frame *f, float *rgb)
{
    struct svgf *v = state;
    float **P = v->plane;
    const float a = s->svgf_taa_alpha;
    const int has = v->has_taa;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < v->h; y++)
        for (int x = 0; x < v->w; x++) {
            const int i = y * v->w + x;
            float h[3], lo[3], hi[3];
            const int found = f->use[i] != 0.0f && a < 1.0f && has && taa_history(v, f, x, y, h);
            if (found)
                neighbourhood_range(f, rgb, x, y, lo, hi);
            for (int c = 0; c < 3; c++) {
                const float cur = rgb[3 * i + c];
                const float hc = found ? MINF(MAXF(h[c], lo[c]), hi[c]) : cur;
                P[A_OUT_R + c][i] = found ? hc + a * (cur - hc) : cur;
            }
        }
    for (int i = 0; i < (int)v->n; i++) {
        for (int c = 0; c < 3; c++) {
            P[A_R + c][i] = P[A_OUT_R + c][i];
            if (f->use[i] != 0.0f)
                rgb[3 * i + c] = P[A_OUT_R + c][i];
        }
        P[A_USE][i] = f->use[i];
    }
    v->has_taa = 1;
}

static const float *svgf_layer(const void *state, const char *name)
{
    const struct svgf *v = state;
    if (!strcmp(name, "variance"))
        return v->plane[V_FIRST];
    if (!strcmp(name, "history"))
        return v->plane[H_LEN];
    return NULL;
}

const struct denoise_method denoise_svgf = {"svgf", svgf_create, svgf_destroy, svgf_run, svgf_post, svgf_layer};
