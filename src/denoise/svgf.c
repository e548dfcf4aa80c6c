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
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "denoise/denoise_kernel.h"
#include "denoise/denoise_method.h"
#include "denoise/svgf_kernels.h"
#include "denoise/svgf_temporal.h"

/* A few per-pixel planes of one frame. */
/* The kinds of pixel the antialiasing keeps apart: a surface the filter used, and the sky (a pixel that
 * sees nothing, with its direction's motion), whose history never blends into the other's. */
#define TAA_SURFACE 1.0f
#define TAA_SKY 2.0f

enum {
    H_C0, H_C1, H_C2, H_M1, H_M2, H_LEN, H_GROUP, H_P0, H_P1, H_P2, H_N0, H_N1, H_N2, /* history */
    C_M1, C_M2, C_LEN, C_VAR,                                                     /* this frame */
    T_C0, T_C1, T_C2, T_VAR, T_LUM, T_INVL, T_WS, T_TMP,                          /* à-trous scratch */
    V_FIRST,                                                                      /* Sec. 4.2's variance */
    A_USE, /* antialiasing: each pixel's kind in its history (taa_rgb): TAA_SURFACE, TAA_SKY or 0 (none) */
    A_LEN, /* antialiasing: frames its history holds at each pixel */
    R_LO0, R_LO1, R_LO2, R_HI0, R_HI1, R_HI2, /* antialiasing: this frame's 3x3 range */
    SVGF_PLANES
};

/* eps of Eq. 3 relative to the pixel's depth, and of Eq. 5 */
#define EPS_DEPTH 1e-3f
#define EPS_LUM 1e-10f

struct svgf {
    int w, h;
    size_t n;
    float *plane[SVGF_PLANES];
    int *prev_object;
    int has_history;
    float *taa_rgb; /* the antialiasing history: the last output, RGB interleaved */
    int has_taa;    /* it holds a frame */
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
    v->taa_rgb = xcalloc(3 * v->n, sizeof(float));
    return v;
}

static void svgf_destroy(void *state)
{
    struct svgf *v = state;
    free(v->plane[0]);
    free(v->prev_object);
    free(v->taa_rgb);
    free(v);
}

/* Sec. 4.1: colour and moments accumulated into f->illum, C_M1, C_M2, C_LEN (svgf_temporal.c).
 * Returns the number of used pixels whose history was rejected. */
static long long accumulate(struct svgf *v, const struct denoise_settings *s, struct denoise_frame *f)
{
    float **P = v->plane;
    const struct svgf_history prev = {P[H_GROUP],
                                      {P[H_N0], P[H_N1], P[H_N2]},
                                      {P[H_P0], P[H_P1], P[H_P2]},
                                      v->prev_object,
                                      {P[H_C0], P[H_C1], P[H_C2], P[H_M1], P[H_M2], P[H_LEN]}};
    const struct svgf_accumulation a = {f,
                                        v->has_history ? &prev : NULL,
                                        s->svgf_alpha,
                                        s->svgf_moments_alpha,
                                        s->svgf_normal_min,
                                        s->svgf_plane_max,
                                        P[C_M1],
                                        P[C_M2],
                                        P[C_LEN]};
    return svgf_accumulate(&a);
}

#define LN2 0.693147181f

/* The kernels' settings from Sec. 4.2-4.3's parameters. */
static struct svgf_pass pass_settings(const struct denoise_settings *s, const struct denoise_frame *f)
{
    struct svgf_pass p = {0};
    p.f = f;
    p.sz_ln2 = s->svgf_sigma_depth * LN2;
    p.eps_ln2 = EPS_DEPTH * LN2;
    p.nd_min = exp2f(DENOISE_EXP2_CUT / s->svgf_sigma_normal);
    p.sn = s->svgf_sigma_normal;
    return p;
}

/* Sec. 4.2: the luminance variance per pixel into C_VAR: from the temporal moments, or, where the
 * history is shorter than svgf_variance_frames, from the moments filtered by the 7x7 kernel. */
static void estimate_variance(struct svgf *v, const struct denoise_settings *s, const struct denoise_frame *f)
{
    float **P = v->plane;
    struct svgf_pass p = pass_settings(s, f);
    p.val[0] = P[C_M1];
    p.val[1] = P[C_M2];
    p.len = P[C_LEN];
    p.short_history = (float)s->svgf_variance_frames;
    p.out[0] = P[C_VAR];
    const svgf_row_fn row = svgf_moments_row();
#pragma omp parallel for schedule(dynamic, 4)
    for (int y = 0; y < v->h; y++)
        row(&p, y);
}

/* The 3x3 binomial blur (1 2 1) x (1 2 1) of a plane, unnormalised, zero outside the image: the
 * horizontal pass into tmp, the vertical into out. */
static void blur3(const float *restrict in, float *restrict tmp, float *restrict out, int w, int h)
{
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        const float *restrict r = in + (size_t)y * w;
        float *restrict t = tmp + (size_t)y * w;
        t[0] = 2.0f * r[0] + (w > 1 ? r[1] : 0.0f);
        for (int x = 1; x < w - 1; x++)
            t[x] = r[x - 1] + 2.0f * r[x] + r[x + 1];
        if (w > 1)
            t[w - 1] = r[w - 2] + 2.0f * r[w - 1];
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        const float *restrict up = tmp + (size_t)(y > 0 ? y - 1 : y) * w, *restrict mid = tmp + (size_t)y * w;
        const float *restrict dn = tmp + (size_t)(y < h - 1 ? y + 1 : y) * w;
        const float ku = y > 0 ? 1.0f : 0.0f, kd = y < h - 1 ? 1.0f : 0.0f;
        float *restrict o = out + (size_t)y * w;
        for (int x = 0; x < w; x++)
            o[x] = ku * up[x] + 2.0f * mid[x] + kd * dn[x];
    }
}

/* Per iteration: the luminance of the input colour and log2(e) / (sigma_l sqrt(g_3x3(Var)) + eps) of
 * Eq. 5, g_3x3 the 3x3 Gaussian over the used pixels: the blur of the variance (0 on unused pixels)
 * over the blur of the use mask (ws, once per frame). */
static void luminance_terms(const struct denoise_frame *f, const struct denoise_settings *s, const float *const in[4],
                            const float *ws, float *tmp, float *lum, float *invl)
{
    const int w = f->width, h = f->height;
    blur3(in[3], tmp, invl, w, h);
    const float sl = s->svgf_sigma_lum;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        const size_t row = (size_t)y * w;
        const float *restrict r = in[0] + row, *restrict g = in[1] + row, *restrict b = in[2] + row;
        const float *restrict wr = ws + row;
        float *restrict l = lum + row, *restrict il = invl + row;
        for (int x = 0; x < w; x++) {
            l[x] = denoise_luminance(r[x], g[x], b[x]);
            const float var = wr[x] > 0.0f ? il[x] / wr[x] : 0.0f;
            il[x] = DENOISE_LOG2E / (sl * sqrtf(var) + EPS_LUM);
        }
    }
}

/* Sec. 4.3: the à-trous iterations on f->illum with the variance C_VAR, the colour history from
 * iteration svgf_feedback. */
static void filter(struct svgf *v, const struct denoise_settings *s, struct denoise_frame *f)
{
    float **P = v->plane;
    const int h = v->h;
    float *src[4] = {f->illum[0], f->illum[1], f->illum[2], P[C_VAR]};
    float *dst[4] = {P[T_C0], P[T_C1], P[T_C2], P[T_VAR]};
    const svgf_row_fn row = svgf_atrous_row();
    if (s->svgf_feedback == 0)
        for (int k = 0; k < 3; k++)
            memcpy(P[H_C0 + k], f->illum[k], sizeof(float) * v->n);
    blur3(f->use, P[T_TMP], P[T_WS], v->w, h);
    for (int it = 0; it < s->svgf_iterations; it++) {
        const float *const in[4] = {src[0], src[1], src[2], src[3]};
        luminance_terms(f, s, in, P[T_WS], P[T_TMP], P[T_LUM], P[T_INVL]);
        struct svgf_pass pass = pass_settings(s, f);
        for (int k = 0; k < 4; k++) {
            pass.val[k] = src[k];
            pass.out[k] = dst[k];
        }
        pass.lum = P[T_LUM];
        pass.invl = P[T_INVL];
        pass.lum_symmetric = s->svgf_lum_weight == DENOISE_LUM_SYMMETRIC;
        pass.step = 1 << it;
        pass.radius = s->svgf_kernel == 1 ? 1 : 2;
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < h; y++)
            row(&pass, y);
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
    memcpy(P[H_GROUP], f->group, sizeof(float) * v->n);
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

/* The antialiasing history at pixel i's reprojected position: bilinear over the previous frame's
 * pixels of the same kind (TAA_SURFACE or TAA_SKY), and into *len the frames it holds (the least of
 * the taps'). Returns 0 where none is there. */
static int taa_history(const struct svgf *v, const struct denoise_frame *f, int x, int y, float kind, float h[3],
                       float *len)
{
    const int i = y * v->w + x;
    const float mx = f->motion[2 * i], my = f->motion[2 * i + 1];
    if (!(mx < DENOISE_NO_MOTION && my < DENOISE_NO_MOTION))
        return 0;
    const float px = denoise_snap((float)x + mx), py = denoise_snap((float)y + my);
    if (!(px > -1.0f && py > -1.0f && px < (float)v->w && py < (float)v->h))
        return 0;
    const int x0 = (int)(px + 1.0f) - 1, y0 = (int)(py + 1.0f) - 1; /* floor: px, py > -1 */
    const float fx = px - (float)x0, fy = py - (float)y0;
    const float *restrict hu = v->plane[A_USE], *restrict hl = v->plane[A_LEN];
    float wsum = 0.0f;
    h[0] = h[1] = h[2] = 0.0f;
    *len = INFINITY;
    for (int t = 0; t < 4; t++) {
        const int qx = x0 + (t & 1), qy = y0 + (t >> 1), q = qy * v->w + qx;
        const float bw = ((t & 1) ? fx : 1.0f - fx) * ((t >> 1) ? fy : 1.0f - fy);
        if (bw == 0.0f || qx < 0 || qy < 0 || qx >= v->w || qy >= v->h) /* (snapped: three taps) */
            continue;
        const float wt = hu[q] == kind ? bw : 0.0f;
        for (int c = 0; c < 3; c++)
            h[c] += wt * v->taa_rgb[3 * q + c];
        wsum += wt;
        if (wt > 0.0f)
            *len = MINF(*len, hl[q]);
    }
    if (wsum <= 1e-4f)
        return 0;
    for (int c = 0; c < 3; c++)
        h[c] /= wsum;
    return 1;
}

/* The per-channel minimum and maximum of this frame's output over the used pixels of each pixel's
 * 3x3 neighbourhood (+inf and -inf where none is used), separably: rows into tmp[0..5], then
 * columns into range[0..5] (minima, then maxima). */
static void neighbourhood_range(const struct denoise_frame *f, const float *rgb, float *const tmp[6],
                                float *const range[6])
{
    const int w = f->width, h = f->height;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            float l[3] = {INFINITY, INFINITY, INFINITY}, u[3] = {-INFINITY, -INFINITY, -INFINITY};
            for (int q = i - (x > 0); q <= i + (x < w - 1); q++)
                if (f->use[q] != 0.0f)
                    for (int c = 0; c < 3; c++) {
                        l[c] = MINF(l[c], rgb[3 * q + c]);
                        u[c] = MAXF(u[c], rgb[3 * q + c]);
                    }
            for (int c = 0; c < 3; c++) {
                tmp[c][i] = l[c];
                tmp[3 + c][i] = u[c];
            }
        }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        const size_t row = (size_t)y * w, up = y > 0 ? row - w : row, dn = y < h - 1 ? row + w : row;
        for (int k = 0; k < 6; k++) {
            const float *restrict a = tmp[k] + up, *restrict b = tmp[k] + row, *restrict c = tmp[k] + dn;
            float *restrict o = range[k] + row;
            if (k < 3)
                for (int x = 0; x < w; x++)
                    o[x] = MINF(MINF(a[x], b[x]), c[x]);
            else
                for (int x = 0; x < w; x++)
                    o[x] = MAXF(MAXF(a[x], b[x]), c[x]);
        }
    }
}

/* Schied et al.'s last step, temporal antialiasing (Karis 2014): each used pixel's reprojected
 * output, and each sky pixel's (one that sees nothing: its history from sky pixels only, through its
 * direction's motion; a silhouette against it otherwise flickers with the jitter: pillars' lit wall
 * edge was 0.0086 of its per-pixel flicker at 320x180, docs/BENCHMARKS.md), blended with this frame's output by
 * max(svgf_taa_alpha, 1 / frames), so that a short
 * history is the plain mean of its frames (as Sec. 4.1's moving average). Where a jittered pixel
 * straddles an edge, its sample lands on one surface in one frame and on the other in the next; the
 * feature-tested history (Sec. 4.1) cannot average the two, this can. Only where the pixel moved at
 * most svgf_taa_motion pixels: under camera motion the history lets the light behind a moving
 * silhouette into the surface in front of it for ~1 / alpha frames (measured, docs/DENOISE.md).
 * Karis's clamp of the history to the 3x3 neighbourhood's range in this frame runs by default only
 * where the pixel moved (svgf_taa_clamp): under a still pixel of a static scene nothing changes for
 * it to guard against, and where no sample of the 3x3 block hits a sub-pixel emitter it clamps the
 * emitter's light away. */
static void svgf_post(void *state, const struct denoise_settings *s, const struct denoise_frame *f, float *rgb)
{
    struct svgf *v = state;
    float **P = v->plane;
    const float a = s->svgf_taa_alpha;
    const int on = a < 1.0f && v->has_taa, clamp = s->svgf_taa_clamp, w = v->w, h = v->h;
    const float moved2 = DENOISE_SNAP * DENOISE_SNAP; /* below 1/1000 pixel a pixel is still (denoise_snap) */
    float *const tmp[6] = {P[T_C0], P[T_C1], P[T_C2], P[T_VAR], P[T_LUM], P[T_INVL]}; /* free after run */
    float *const range[6] = {P[R_LO0], P[R_LO1], P[R_LO2], P[R_HI0], P[R_HI1], P[R_HI2]};
    float *restrict len = P[T_TMP]; /* this frame's history lengths (free after run, too) */
    if (on && clamp != DENOISE_TAA_CLAMP_OFF)
        neighbourhood_range(f, rgb, tmp, range);
    float *restrict taa_kind = P[T_C0]; /* each pixel's kind for the next frame (tmp is free again) */
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            float hc[3], frames;
            const float mx = f->motion[2 * i], my = f->motion[2 * i + 1];
            const float m2 = mx * mx + my * my;
            const int still = m2 <= s->svgf_taa_motion * s->svgf_taa_motion;
            len[i] = 1.0f;
            /* the sky too (a pixel that sees nothing: svgf_taa_sky): its silhouettes alias as the surfaces' do */
            const int sky = s->svgf_taa_sky && mx < DENOISE_NO_MOTION &&
                            isfinite(rgb[3 * i] + rgb[3 * i + 1] + rgb[3 * i + 2]);
            const float kind = f->use[i] != 0.0f ? TAA_SURFACE : sky ? TAA_SKY : 0.0f;
            taa_kind[i] = kind;
            if (!(on && still && kind != 0.0f && taa_history(v, f, x, y, kind, hc, &frames)))
                continue; /* the output stays this frame's */
            len[i] = MINF(frames + 1.0f, 1e6f);
            float weight = MAXF(a, 1.0f / len[i]);
            if (f->gradient) /* A-SVGF: a stale history weighs less here too */
                weight += svgf_gradient_response(f->gradient[i]) * (1.0f - weight);
            /* (the range is the used surfaces': the sky's history, a function of direction, is not clamped) */
            const int clamped = kind == TAA_SURFACE && (clamp == DENOISE_TAA_CLAMP_ALWAYS ||
                                                        (clamp == DENOISE_TAA_CLAMP_MOVING && m2 > moved2));
            for (int c = 0; c < 3; c++) {
                const float old = clamped ? MINF(MAXF(hc[c], range[c][i]), range[3 + c][i]) : hc[c];
                rgb[3 * i + c] = old + weight * (rgb[3 * i + c] - old);
            }
        }
    memcpy(v->taa_rgb, rgb, sizeof(float) * 3 * v->n); /* this frame's output is the next one's history */
    memcpy(P[A_USE], taa_kind, sizeof(float) * v->n);
    memcpy(P[A_LEN], len, sizeof(float) * v->n);
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
