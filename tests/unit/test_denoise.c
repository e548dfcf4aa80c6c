/* test_denoise.c: the denoisers against values computed here by straightforward scalar
 * code from the papers' equations: SVGF's à-trous weights and variance propagation (Schied et al.
 * 2017 Eq. 1-5) and temporal moments, its 7x7 spatial variance, its history rejection on a mesh id,
 * normal or surface change, the edge-avoiding à-trous weights (Dammertz et al. 2010 Eq. 4-6), the
 * exp2 / log2 approximations the filters vectorise with, that a constant image and a noise-free one
 * pass through unchanged, that no channel of a material takes another material's illumination (a
 * cyan, a black and a white material side by side), and that invalid and non-finite pixels are
 * passed through raw, counted, and never spread into their neighbours. Every instruction-set path
 * runs (simd_limit). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/simd.h"
#include "denoise/denoise.h"
#include "denoise/denoise_kernel.h"
#include "methods/settings.h"
#include "render/params.h"
#include "test_util.h"

#define MAXW 64
#define MAXH 12

/* A frame's features and colour, as a renderer's G-buffer would hold them. */
struct scene_buf {
    int w, h;
    vec3 pos[MAXW * MAXH], nrm[MAXW * MAXH], alb[MAXW * MAXH];
    float depth[MAXW * MAXH], motion[2 * MAXW * MAXH], rgb[3 * MAXW * MAXH];
    int obj[MAXW * MAXH];
    unsigned char valid[MAXW * MAXH];
};

static unsigned rng_state = 12345u;
static float rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (float)(rng_state >> 8) / 16777216.0f;
}

/* A plane facing the camera at a slant: depth linear in x and y, positions on the plane
 * z = depth, with its normal, albedo alb. */
static void plane_scene(struct scene_buf *b, int w, int h, float alb)
{
    memset(b, 0, sizeof(*b));
    b->w = w;
    b->h = h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            b->depth[i] = 2.0f + 0.05f * (float)x + 0.03f * (float)y;
            b->pos[i] = v3((float)x * 0.1f, (float)y * 0.1f, b->depth[i]);
            b->nrm[i] = v3_normalize(v3(-0.5f, -0.3f, 1.0f));
            b->alb[i] = v3s(alb);
            b->obj[i] = 1;
            b->valid[i] = 1;
        }
}

static struct denoise_guide guide_of(const struct scene_buf *b)
{
    struct denoise_guide g = {b->w, b->h, b->pos, b->nrm, b->depth, b->obj, b->alb, NULL, b->motion, b->valid, NULL};
    return g;
}

static float lum_of(const float *c) { return denoise_luminance(c[0], c[1], c[2]); }

/* Depth's derivative as denoise.c defines it: the smaller one-sided difference. */
static float ref_derivative(const struct scene_buf *b, int x, int y, int dx, int dy)
{
    const int i = y * b->w + x;
    float best = 0.0f;
    int found = 0;
    if (x + dx < b->w && y + dy < b->h) {
        best = b->depth[i + dy * b->w + dx] - b->depth[i];
        found = 1;
    }
    if (x - dx >= 0 && y - dy >= 0) {
        const float lo = b->depth[i] - b->depth[i - dy * b->w - dx];
        if (!found || fabsf(lo) < fabsf(best))
            best = lo;
    }
    return best;
}

static const double b3[5] = {1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};

static const double h3[3] = {0.25, 0.5, 0.25};

/* SVGF's à-trous iterations (Eq. 1-5) with steps 1, 2, .., 2^(iterations - 1) on colour I and
 * variance var (filtered by the squared weights, Eq. 2), every pixel used; the kernel is the
 * paper's 5x5 B3 spline (r = 2) or the 3x3 (1 2 1) / 4 of denoise.svgf.kernel=3x3 (r = 1); Eq. 5's
 * deviation the centre's (sym 0, the paper) or the mean of the centre's and the tap's (sym 1). */
static void atrous_hand(const struct scene_buf *b, float *I, float *var, int iterations, int r, int sym)
{
    const double *hk = r == 2 ? b3 : h3;
    const int w = b->w, h = b->h;
    static float l[MAXW * MAXH], nI[3 * MAXW * MAXH], nvar[MAXW * MAXH];
    static double sd[MAXW * MAXH];
    for (int it = 0, step = 1; it < iterations; it++, step *= 2) {
        for (int i = 0; i < w * h; i++)
            l[i] = lum_of(&I[3 * i]);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const int p = y * w + x;
                double gs = 0.0, gw = 0.0; /* the 3x3 Gaussian of the variance */
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++) {
                        if (x + dx < 0 || y + dy < 0 || x + dx >= w || y + dy >= h)
                            continue;
                        const double g = (dx ? 0.25 : 0.5) * (dy ? 0.25 : 0.5);
                        gw += g;
                        gs += g * var[p + dy * w + dx];
                    }
                sd[p] = sqrt(gs / gw);
            }
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                const int p = y * w + x;
                const double gx = ref_derivative(b, x, y, 1, 0), gy = ref_derivative(b, x, y, 0, 1);
                double sw = 0.0, sv = 0.0, sc[3] = {0, 0, 0};
                for (int ty = 0; ty <= 2 * r; ty++)
                    for (int tx = 0; tx <= 2 * r; tx++) {
                        const int ox = (tx - r) * step, oy = (ty - r) * step;
                        if (x + ox < 0 || y + oy < 0 || x + ox >= w || y + oy >= h)
                            continue;
                        const int q = p + oy * w + ox;
                        const double den = 1.0 * fabs(gx * ox + gy * oy) + 1e-3 * b->depth[p];
                        const double dev = sym ? 0.5 * (sd[p] + sd[q]) : sd[p];
                        const double a =
                            fabs(b->depth[p] - b->depth[q]) / den + fabs(l[p] - l[q]) / (4.0 * dev + 1e-10);
                        const double nd = fmax(0.0, v3_dot(b->nrm[p], b->nrm[q]));
                        const double wt = hk[ty] * hk[tx] * pow(nd, 128.0) * exp(-a);
                        sw += wt;
                        sv += wt * wt * var[q];
                        for (int c = 0; c < 3; c++)
                            sc[c] += wt * I[3 * q + c];
                    }
                for (int c = 0; c < 3; c++)
                    nI[3 * p + c] = (float)(sc[c] / sw);
                nvar[p] = (float)(sv / (sw * sw));
            }
        memcpy(I, nI, sizeof(float) * 3 * (size_t)(w * h));
        memcpy(var, nvar, sizeof(float) * (size_t)(w * h));
    }
}

/* SVGF after two frames A then B of a static plane, computed by Eq. 1-5 directly: the temporal
 * moments (variance_frames 0), then the à-trous iterations (feedback 0). */
static void svgf_hand(const struct scene_buf *b, const float *A, const float *B, float alb, int iterations, int r,
                      int sym, float *out)
{
    const int n = b->w * b->h;
    static float I[3 * MAXW * MAXH], var[MAXW * MAXH];
    for (int i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++) /* len 2: alpha = max(0.2, 1/2) */
            I[3 * i + c] = 0.5f * (A[3 * i + c] / alb) + 0.5f * (B[3 * i + c] / alb);
        float ia[3] = {A[3 * i] / alb, A[3 * i + 1] / alb, A[3 * i + 2] / alb};
        float ib[3] = {B[3 * i] / alb, B[3 * i + 1] / alb, B[3 * i + 2] / alb};
        const double la = lum_of(ia), lb = lum_of(ib);
        const double m1 = 0.5 * la + 0.5 * lb, m2 = 0.5 * la * la + 0.5 * lb * lb;
        var[i] = (float)fmax(0.0, m2 - m1 * m1);
    }
    atrous_hand(b, I, var, iterations, r, sym);
    for (int i = 0; i < 3 * n; i++)
        out[i] = I[i] * alb;
}

/* Sec. 4.2's 7x7 moments filter of one frame c (history 1): the variance of each pixel's
 * luminance under the weights max(0, n_p . n_q)^128 exp(-|z_p - z_q| / (|grad z_p . (p - q)| +
 * 1e-3 z_p)), every pixel used. */
static void moments_hand(const struct scene_buf *b, const float *c, float *var)
{
    const int w = b->w, h = b->h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int p = y * w + x;
            const double gx = ref_derivative(b, x, y, 1, 0), gy = ref_derivative(b, x, y, 0, 1);
            double sw = 0.0, s1 = 0.0, s2 = 0.0;
            for (int oy = -3; oy <= 3; oy++)
                for (int ox = -3; ox <= 3; ox++) {
                    if (x + ox < 0 || y + oy < 0 || x + ox >= w || y + oy >= h)
                        continue;
                    const int q = p + oy * w + ox;
                    const double den = fabs(gx * ox + gy * oy) + 1e-3 * b->depth[p];
                    const double nd = fmax(0.0, v3_dot(b->nrm[p], b->nrm[q]));
                    const double wt = pow(nd, 128.0) * exp(-fabs(b->depth[p] - b->depth[q]) / den);
                    const double l = lum_of(&c[3 * q]);
                    sw += wt;
                    s1 += wt * l;
                    s2 += wt * l * l;
                }
            var[p] = (float)fmax(0.0, s2 / sw - (s1 / sw) * (s1 / sw));
        }
}

static struct denoise_settings settings(int method)
{
    struct denoise_settings s;
    denoise_settings_defaults(&s);
    s.method = method;
    return s;
}

static double max_rel(const float *a, const float *b, int n3)
{
    double worst = 0.0;
    for (int i = 0; i < n3; i++)
        worst = fmax(worst, fabs((double)a[i] - b[i]) / fmax(1e-6, fabs((double)b[i])));
    return worst;
}

static void test_kernels(void)
{
    double worst = 0.0;
    for (double x = -29.99; x <= 0.0; x += 0.0037) {
        const float xf = (float)x;
        worst = fmax(worst, fabs(denoise_exp2_neg(xf) / exp2((double)xf) - 1.0));
    }
    EXPECT(worst < 3e-7, "exp2 relative error %g", worst);
    EXPECT(denoise_exp2_neg(-30.5f) == 0.0f && denoise_exp2_neg(-INFINITY) == 0.0f, "below the cut: exactly 0");
    EXPECT(denoise_exp2_neg(NAN) == 0.0f, "NaN: 0");
    EXPECT(denoise_exp2_neg(0.0f) == 1.0f, "2^0 = %g", (double)denoise_exp2_neg(0.0f));
    worst = 0.0;
    for (double x = 1e-6; x < 100.0; x *= 1.013)
        worst = fmax(worst, fabs(denoise_log2((float)x) - log2(x)));
    EXPECT(worst < 1e-4, "log2 absolute error %g", worst);
}

/* Eq. 1-5 and the temporal moments, by hand, on a slanted plane with a few tilted normals, at a
 * size whose rows hold a vector block inside and blocks at the borders, then one narrower than a
 * block; iterations > 1 take steps past the borders. */
static void svgf_hand_case(int w, int h, int iterations, int kernel3, int paper)
{
    static struct scene_buf b;
    const float alb = 0.5f;
    plane_scene(&b, w, h, alb);
    for (int i = 0; i < b.w * b.h; i += 7)
        b.nrm[i] = v3(0.6f, 0.0f, 0.8f);
    static float A[3 * MAXW * MAXH], B[3 * MAXW * MAXH], out[3 * MAXW * MAXH], want[3 * MAXW * MAXH];
    for (int i = 0; i < 3 * b.w * b.h; i++) {
        A[i] = 0.2f + rnd();
        B[i] = 0.2f + rnd();
    }
    struct denoise_settings s = settings(1);
    s.svgf_iterations = iterations;
    s.svgf_kernel = kernel3;
    s.svgf_lum_weight = paper;
    s.svgf_feedback = 0;
    s.svgf_variance_frames = 0;
    s.svgf_taa_alpha = 1.0f; /* no antialiasing: Eq. 1-5 alone */
    struct denoiser *d = denoiser_create(&s, b.w, b.h);
    const struct denoise_guide g = guide_of(&b);
    struct denoise_stats st;
    EXPECT(denoiser_run(d, A, &g, out, &st) == 0 && st.history_reset == b.w * b.h, "frame 0: every history new");
    EXPECT(denoiser_run(d, B, &g, out, &st) == 0 && st.history_reset == 0, "frame 1: %lld reset", st.history_reset);
    svgf_hand(&b, A, B, alb, iterations, kernel3 ? 1 : 2, !paper, want);
    const double e = max_rel(out, want, 3 * b.w * b.h);
    EXPECT(e < 2e-4, "SVGF (%dx%d, %d iterations, %s, %s) against Eq. 1-5 by hand: worst relative difference %g", w,
           h, iterations, kernel3 ? "3x3" : "5x5", paper ? "paper" : "symmetric", e);
    const float *len = denoiser_layer(d, "history");
    EXPECT(len && len[0] == 2.0f && len[b.w * b.h - 1] == 2.0f, "history length 2 after two frames");
    EXPECT(denoiser_layer(d, "nonsense") == NULL, "an unknown layer is NULL");
    denoiser_destroy(d);
}

static void test_svgf_hand(void)
{
    for (int paper = DENOISE_LUM_SYMMETRIC; paper <= DENOISE_LUM_PAPER; paper++) { /* luminance_weight= */
        svgf_hand_case(11, 9, 1, 0, paper);
        svgf_hand_case(53, 7, 1, 0, paper);
        svgf_hand_case(61, 12, 3, 0, paper);
        svgf_hand_case(61, 12, 3, 1, paper); /* denoise.svgf.kernel=3x3 */
    }
}

/* The 7x7 moments filter by hand on the first frame (every history short), with tilted normals
 * and a depth step, at a width with inside and border blocks. */
static void test_moments_hand(void)
{
    static struct scene_buf b;
    plane_scene(&b, 47, 9, 1.0f);
    for (int i = 0; i < b.w * b.h; i += 5)
        b.nrm[i] = v3_normalize(v3(-0.45f, -0.3f, 1.0f));
    for (int y = 0; y < b.h; y++)
        for (int x = 30; x < b.w; x++) {
            b.depth[y * b.w + x] += 0.5f; /* a step: the taps across it weigh almost nothing */
            b.pos[y * b.w + x].z += 0.5f;
        }
    static float c[3 * MAXW * MAXH], out[3 * MAXW * MAXH], want[MAXW * MAXH];
    for (int i = 0; i < 3 * b.w * b.h; i++)
        c[i] = 0.1f + rnd();
    struct denoise_settings s = settings(1);
    struct denoiser *d = denoiser_create(&s, b.w, b.h);
    const struct denoise_guide g = guide_of(&b);
    EXPECT(denoiser_run(d, c, &g, out, NULL) == 0, "runs");
    const float *var = denoiser_layer(d, "variance");
    moments_hand(&b, c, want);
    double worst = 0.0;
    for (int i = 0; var && i < b.w * b.h; i++)
        worst = fmax(worst, fabs(var[i] - want[i]) / fmax(1e-6, want[i]));
    EXPECT(var && worst < 2e-4, "7x7 moments' variance against Sec. 4.2 by hand: worst relative difference %g", worst);
    denoiser_destroy(d);
}

static void test_spatial_variance(void)
{
    static struct scene_buf b;
    plane_scene(&b, 7, 7, 1.0f);
    for (int i = 0; i < 49; i++) {
        b.depth[i] = 3.0f;
        b.pos[i].z = 3.0f;
    }
    static float c[3 * 49], out[3 * 49];
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < 49; i++) {
        c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = 0.1f + rnd();
        const double l = lum_of(&c[3 * i]);
        s1 += l;
        s2 += l * l;
    }
    struct denoise_settings s = settings(1);
    struct denoiser *d = denoiser_create(&s, 7, 7);
    const struct denoise_guide g = guide_of(&b);
    EXPECT(denoiser_run(d, c, &g, out, NULL) == 0, "runs");
    const float *var = denoiser_layer(d, "variance");
    const double want = s2 / 49.0 - (s1 / 49.0) * (s1 / 49.0);
    EXPECT(var && fabs(var[24] - want) <= 1e-5 * want, "7x7 spatial variance %.7g vs %.7g", var ? var[24] : -1.0, want);
    denoiser_destroy(d);
}

/* Sec. 4.1: history is rejected where the mesh id, the normal or the surface changes. */
static void test_history_rejection(void)
{
    static struct scene_buf b;
    plane_scene(&b, 5, 4, 1.0f);
    static float c[3 * 20], out[3 * 20];
    for (int i = 0; i < 60; i++)
        c[i] = 0.5f;
    struct denoise_settings s = settings(1);
    struct denoiser *d = denoiser_create(&s, 5, 4);
    struct denoise_guide g = guide_of(&b);
    struct denoise_stats st;
    denoiser_run(d, c, &g, out, &st);
    b.obj[0] = 7;                                                 /* another mesh */
    b.nrm[2] = v3(0.866f, 0.0f, 0.5f);                            /* n . n_prev = 0.5 < 0.9 */
    b.pos[4] = v3_madd(b.pos[4], b.nrm[4], 0.05f * b.depth[4]);   /* 5% of the depth off its plane */
    b.pos[12] = v3_madd(b.pos[12], b.nrm[12], 0.002f * b.depth[12]); /* within the 1% tolerance */
    g = guide_of(&b);
    denoiser_run(d, c, &g, out, &st);
    const float *len = denoiser_layer(d, "history");
    EXPECT(len[0] == 1.0f && len[2] == 1.0f && len[4] == 1.0f, "rejected: id %g normal %g plane %g", len[0], len[2],
           len[4]);
    EXPECT(len[12] == 2.0f && len[6] == 2.0f, "kept: %g %g", len[12], len[6]);
    EXPECT(st.history_reset == 3, "%lld histories reset", st.history_reset);
    denoiser_destroy(d);
    /* a motion vector moves the history with the surface: one mesh per column, shifted right by
     * one pixel, is found one pixel to the left; the left column's mesh is new */
    plane_scene(&b, 5, 4, 1.0f);
    for (int i = 0; i < 20; i++)
        b.obj[i] = i % 5;
    d = denoiser_create(&s, 5, 4);
    g = guide_of(&b);
    denoiser_run(d, c, &g, out, &st);
    for (int i = 0; i < 20; i++) {
        b.obj[i] = i % 5 - 1;
        b.motion[2 * i] = -1.0f;
    }
    g = guide_of(&b);
    denoiser_run(d, c, &g, out, &st);
    len = denoiser_layer(d, "history");
    EXPECT(len[1] == 2.0f && len[4] == 2.0f && len[19] == 2.0f, "moved histories: %g %g %g", len[1], len[4], len[19]);
    EXPECT(len[0] == 1.0f && len[15] == 1.0f && st.history_reset == 4, "the left column is new: %g %g, %lld reset",
           len[0], len[15], st.history_reset);
    denoiser_destroy(d);
}

/* Dammertz et al. Eq. 4-6 with sigma_rt in units of the mean illumination, one iteration. */
static void test_atrous_hand(void)
{
    static struct scene_buf b;
    plane_scene(&b, 9, 8, 1.0f);
    for (int i = 0; i < 72; i += 5)
        b.nrm[i] = v3(0.0f, 0.6f, 0.8f);
    static float c[3 * 72], out[3 * 72], want[3 * 72];
    double mean = 0.0;
    for (int i = 0; i < 72; i++) {
        for (int k = 0; k < 3; k++)
            c[3 * i + k] = 0.2f + rnd();
        mean += lum_of(&c[3 * i]) / 72.0;
    }
    struct denoise_settings s = settings(2);
    s.atrous_iterations = 1;
    const double sc = s.atrous_sigma_color * mean, sn = s.atrous_sigma_normal, sx = s.atrous_sigma_position;
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 9; x++) {
            const int p = y * 9 + x;
            double sw = 0.0, acc[3] = {0, 0, 0};
            for (int ty = 0; ty < 5; ty++)
                for (int tx = 0; tx < 5; tx++) {
                    const int qx = x + tx - 2, qy = y + ty - 2;
                    if (qx < 0 || qy < 0 || qx >= 9 || qy >= 8)
                        continue;
                    const int q = qy * 9 + qx;
                    double dc = 0.0;
                    for (int k = 0; k < 3; k++)
                        dc += ((double)c[3 * p + k] - c[3 * q + k]) * ((double)c[3 * p + k] - c[3 * q + k]);
                    const double dn = v3_length2(v3_sub(b.nrm[p], b.nrm[q]));
                    const double dx = v3_length2(v3_sub(b.pos[p], b.pos[q]));
                    const double sxp = sx * b.depth[p];
                    const double wt = b3[ty] * b3[tx] * exp(-dc / (sc * sc) - dn / (sn * sn) - dx / (sxp * sxp));
                    sw += wt;
                    for (int k = 0; k < 3; k++)
                        acc[k] += wt * c[3 * q + k];
                }
            for (int k = 0; k < 3; k++)
                want[3 * p + k] = (float)(acc[k] / sw);
        }
    struct denoiser *d = denoiser_create(&s, 9, 8);
    const struct denoise_guide g = guide_of(&b);
    EXPECT(denoiser_run(d, c, &g, out, NULL) == 0, "runs");
    const double e = max_rel(out, want, 216);
    EXPECT(e < 2e-4, "a-trous against Eq. 4-6 by hand: worst relative difference %g", e);
    denoiser_destroy(d);
}

/* A constant image through both filters over moving frames, and a noise-free one (two flat
 * regions split by a crease) through SVGF once its history holds (variance from the moments). */
static void test_unchanged(void)
{
    static struct scene_buf b;
    static float c[3 * MAXW * MAXH], out[3 * MAXW * MAXH];
    for (int m = 1; m <= 2; m++) {
        plane_scene(&b, 16, 12, 0.7f);
        struct denoise_settings s = settings(m);
        struct denoiser *d = denoiser_create(&s, 16, 12);
        double worst = 0.0;
        for (int f = 0; f < 5; f++) {
            for (int i = 0; i < 192; i++) {
                b.depth[i] = 1.0f + 3.0f * rnd();
                b.pos[i] = v3(rnd(), rnd(), b.depth[i]);
                b.nrm[i] = v3_normalize(v3(rnd() - 0.5f, rnd() - 0.5f, 1.0f));
                b.motion[2 * i] = 2.0f * rnd() - 1.0f;
                b.motion[2 * i + 1] = 2.0f * rnd() - 1.0f;
                c[3 * i] = 0.3f, c[3 * i + 1] = 0.6f, c[3 * i + 2] = 0.9f;
            }
            const struct denoise_guide g = guide_of(&b);
            denoiser_run(d, c, &g, out, NULL);
            worst = fmax(worst, max_rel(out, c, 576));
        }
        EXPECT(worst < 1e-6, "%s: a constant image changes by %g", denoise_names[m], worst);
        denoiser_destroy(d);
    }
    plane_scene(&b, 16, 12, 0.5f);
    for (int y = 0; y < 12; y++)
        for (int x = 0; x < 16; x++) {
            const int i = y * 16 + x;
            const float v = x < 7 ? 0.25f : 0.8f + 0.01f * (float)y;
            c[3 * i] = v, c[3 * i + 1] = 0.5f * v, c[3 * i + 2] = 0.25f * v;
        }
    struct denoise_settings s = settings(1);
    struct denoiser *d = denoiser_create(&s, 16, 12);
    const struct denoise_guide g = guide_of(&b);
    /* the first frames estimate variance spatially and blur the crease; their output is the colour
     * history (Sec. 4.3), which the moving average forgets at 0.8 per frame, and the antialiasing's
     * history, forgotten at 0.9 per frame */
    for (int f = 0; f < 200; f++)
        denoiser_run(d, c, &g, out, NULL);
    const double e = max_rel(out, c, 576);
    EXPECT(e < 1e-5, "svgf: a noise-free image changes by %g once its history holds", e);
    denoiser_destroy(d);
}

/* Cyan (red albedo 0), black and white materials side by side on one plane, lit by the same noisy
 * illumination: the channels an albedo does not divide by hold radiance, not illumination, so no
 * filter may average them with another material's: cyan keeps red 0, black stays black, and white
 * keeps R = G = B (with them averaged, cyan turned red and white cyan beside it). */
static void test_material_groups(void)
{
    static struct scene_buf b;
    static float c[3 * MAXW * MAXH], out[3 * MAXW * MAXH];
    const int w = 24, h = 12;
    for (int m = 1; m <= 2; m++) {
        plane_scene(&b, w, h, 0.8f);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < 14; x++)
                b.alb[y * w + x] = x < 10 ? v3(0.0f, 0.6f, 0.6f) : v3s(0.0f);
        struct denoise_settings s = settings(m);
        struct denoiser *d = denoiser_create(&s, w, h);
        double cyan_red = 0.0, black = 0.0, white_tint = 0.0;
        for (int f = 0; f < 4; f++) {
            for (int i = 0; i < w * h; i++) {
                const float illum = 0.5f + rnd();
                c[3 * i] = b.alb[i].x * illum, c[3 * i + 1] = b.alb[i].y * illum, c[3 * i + 2] = b.alb[i].z * illum;
            }
            const struct denoise_guide g = guide_of(&b);
            denoiser_run(d, c, &g, out, NULL);
            for (int i = 0; i < w * h; i++) {
                const int x = i % w;
                const float *o = &out[3 * i];
                if (x < 10)
                    cyan_red = fmax(cyan_red, fabs(o[0]));
                else if (x < 14)
                    black = fmax(black, fabs(o[0]) + fabs(o[1]) + fabs(o[2]));
                else
                    white_tint = fmax(white_tint, fmax(fabs(o[0] - o[1]), fabs(o[2] - o[1])) / o[1]);
            }
        }
        EXPECT(cyan_red == 0.0, "%s: the cyan material's red is %g, not 0", denoise_names[m], cyan_red);
        EXPECT(black == 0.0, "%s: the black material shows %g", denoise_names[m], black);
        EXPECT(white_tint < 1e-5, "%s: the white material is tinted by %g beside cyan", denoise_names[m], white_tint);
        denoiser_destroy(d);
    }
}

/* A NaN colour, an infinite normal and an invalid pixel are left as they came and counted; no
 * neighbour reads them. */
static void test_passthrough(void)
{
    static struct scene_buf b;
    static float c[3 * 80], out[3 * 80];
    for (int m = 1; m <= 2; m++) {
        plane_scene(&b, 10, 8, 1.0f);
        for (int i = 0; i < 240; i++)
            c[i] = 0.2f + rnd();
        c[3 * 33 + 1] = NAN;
        b.nrm[44] = v3(INFINITY, 0.0f, 0.0f);
        b.valid[55] = 0;
        c[3 * 55] = 1e30f; /* an invalid pixel's value, however large, stays out of the filter */
        struct denoise_settings s = settings(m);
        struct denoiser *d = denoiser_create(&s, 10, 8);
        const struct denoise_guide g = guide_of(&b);
        struct denoise_stats st;
        for (int f = 0; f < 2; f++)
            denoiser_run(d, c, &g, out, &st);
        EXPECT(st.passed_through == 2, "%s: %lld passed through (NaN colour, infinite normal)", denoise_names[m],
               st.passed_through);
        EXPECT(isnan(out[3 * 33 + 1]) && out[3 * 33] == c[3 * 33], "%s: the NaN pixel is passed through raw",
               denoise_names[m]);
        EXPECT(out[3 * 44] == c[3 * 44] && out[3 * 55] == 1e30f, "%s: the others too", denoise_names[m]);
        int finite = 1;
        for (int i = 0; i < 80; i++)
            if (i != 33)
                for (int k = 0; k < 3; k++)
                    finite &= isfinite(out[3 * i + k]) && (i == 55 || out[3 * i + k] < 2.0f);
        EXPECT(finite, "%s: no neighbour took the NaN or the invalid pixel's value", denoise_names[m]);
        denoiser_destroy(d);
    }
}

static void test_bad_arguments(void)
{
    struct denoise_settings s = settings(0);
    EXPECT(denoiser_create(&s, 4, 4) == NULL, "method off: no denoiser");
    s.method = 3;
    EXPECT(denoiser_create(&s, 4, 4) == NULL, "unknown method: no denoiser");
    s.method = 1;
    EXPECT(denoiser_create(&s, 0, 4) == NULL, "empty image: no denoiser");
    struct denoiser *d = denoiser_create(&s, 4, 4);
    static struct scene_buf b;
    plane_scene(&b, 5, 4, 1.0f);
    const struct denoise_guide g = guide_of(&b);
    float out[60] = {0};
    EXPECT(denoiser_run(d, b.rgb, &g, out, NULL) == -1 && out[0] == 0.0f, "a guide of another size is refused");
    EXPECT(!strcmp(denoiser_name(d), "svgf"), "name");
    denoiser_destroy(d);
    denoiser_destroy(NULL);
}

/* Temporal antialiasing (svgf.taa): a pixel whose jittered sample lands on one mesh in one frame
 * and on its neighbour in the next keeps no feature-tested history; the antialiasing averages it:
 * the same mean over frames, a fraction of the flicker. */
static void test_taa(void)
{
    static struct scene_buf b;
    static float c[3 * 25], out[3 * 25];
    double mean[2] = {0, 0}, flicker[2] = {0, 0};
    for (int on = 0; on < 2; on++) {
        struct denoise_settings s = settings(1);
        s.svgf_taa_alpha = on ? 0.1f : 1.0f;
        struct denoiser *d = denoiser_create(&s, 5, 5);
        float last = 0.0f;
        for (int f = 0; f < 120; f++) {
            plane_scene(&b, 5, 5, 1.0f);
            for (int i = 0; i < 25; i++) {
                const int right = i % 5 >= 3 || (i == 12 && f % 2); /* pixel (2, 2) alternates */
                b.obj[i] = right ? 2 : 1;
                c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = right ? 1.0f : 0.2f;
            }
            const struct denoise_guide g = guide_of(&b);
            denoiser_run(d, c, &g, out, NULL);
            if (f >= 80) {
                mean[on] += out[3 * 12] / 40.0;
                flicker[on] += fabs(out[3 * 12] - last) / 40.0;
            }
            last = out[3 * 12];
        }
        denoiser_destroy(d);
    }
    EXPECT(fabs(mean[1] - mean[0]) < 0.02, "the antialiased mean %g against %g without", mean[1], mean[0]);
    EXPECT(flicker[0] > 0.3 && flicker[1] < 0.1 * flicker[0], "flicker %g with antialiasing, %g without", flicker[1],
           flicker[0]);
}

/* Where the antialiasing clamps its history (svgf_taa_clamp): a uniform image that drops from 1 to
 * 0.2 at frame 10, every pixel still or moving 0.3 pixels a frame (under taa_motion). Where it
 * clamps, the frame after the drop is the frame without antialiasing (the 3x3 range is one value);
 * where it does not, it lags above it. */
static void test_taa_clamp(void)
{
    static struct scene_buf b;
    static float c[3 * 25], out[3 * 25];
    for (int moving = 0; moving < 2; moving++) {
        float after[4]; /* clamp moving, always, off (DENOISE_TAA_CLAMP_*); then no antialiasing */
        for (int mode = 0; mode < 4; mode++) {
            struct denoise_settings s = settings(1);
            s.svgf_taa_clamp = mode < 3 ? mode : 0;
            s.svgf_taa_alpha = mode < 3 ? 0.1f : 1.0f;
            struct denoiser *d = denoiser_create(&s, 5, 5);
            for (int f = 0; f <= 10; f++) {
                plane_scene(&b, 5, 5, 1.0f);
                for (int i = 0; i < 25; i++) {
                    b.motion[2 * i] = moving ? 0.3f : 0.0f;
                    c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = f < 10 ? 1.0f : 0.2f;
                }
                const struct denoise_guide g = guide_of(&b);
                denoiser_run(d, c, &g, out, NULL);
            }
            after[mode] = out[3 * 12];
            denoiser_destroy(d);
        }
        const int clamps[3] = {moving, 1, 0};
        for (int mode = 0; mode < 3; mode++)
            EXPECT(clamps[mode] ? fabsf(after[mode] - after[3]) < 1e-5f : after[mode] > after[3] + 0.05f,
                   "taa_clamp %d, %s pixels: %g after the drop, %g without antialiasing", mode,
                   moving ? "moving" : "still", after[mode], after[3]);
    }
}

/* The antialiasing skips pixels that moved more than svgf_taa_motion: with every pixel moving one
 * pixel a frame, its output is the one without antialiasing, bit for bit, and differs once the
 * limit lets it run. */
static void test_taa_motion(void)
{
    static struct scene_buf b;
    static float c[3 * 25], out[3][3 * 25];
    const float alpha[3] = {1.0f, 0.1f, 0.1f}, limit[3] = {0.5f, 0.5f, 2.0f};
    for (int k = 0; k < 3; k++) {
        struct denoise_settings s = settings(1);
        s.svgf_taa_alpha = alpha[k];
        s.svgf_taa_motion = limit[k];
        struct denoiser *d = denoiser_create(&s, 5, 5);
        for (int f = 0; f < 6; f++) {
            plane_scene(&b, 5, 5, 1.0f);
            for (int i = 0; i < 25; i++) {
                b.motion[2 * i] = -1.0f; /* the scene slides one pixel right per frame */
                c[3 * i] = c[3 * i + 1] = c[3 * i + 2] = (float)((i + f) % 5) * 0.2f + 0.1f;
            }
            const struct denoise_guide g = guide_of(&b);
            denoiser_run(d, c, &g, out[k], NULL);
        }
        denoiser_destroy(d);
    }
    EXPECT(memcmp(out[0], out[1], sizeof(out[0])) == 0, "moving 1 px > 0.5: antialiasing skipped");
    EXPECT(memcmp(out[0], out[2], sizeof(out[0])) != 0, "limit 2 px: antialiasing runs");
}

/* The library's defaults are the settings table's (denoise.* keys). */
static void test_defaults_agree(void)
{
    struct render_params p;
    render_params_defaults(&p);
    struct denoise_settings s;
    denoise_settings_defaults(&s);
    EXPECT(memcmp(&p.denoise, &s, sizeof s) == 0, "denoise_settings_defaults equals the denoise.* keys' defaults");
}

int main(void)
{
    test_defaults_agree();
    for (int isa = SIMD_ISA_BASELINE; isa <= SIMD_ISA_AVX512; isa++) {
        simd_limit((enum simd_isa)isa);
        printf("denoisers on the %s path\n", simd_isa_name(simd_isa_active()));
        test_kernels();
        test_svgf_hand();
        test_spatial_variance();
        test_moments_hand();
        test_history_rejection();
        test_atrous_hand();
        test_unchanged();
        test_material_groups();
        test_passthrough();
        test_taa();
        test_taa_clamp();
        test_taa_motion();
    }
    test_bad_arguments();
    return test_finish();
}
