/* flip.c: LDR-FLIP (Andersson et al. 2020) and HDR-FLIP (Andersson et al. 2021) error maps as declared in
 * restir/metrics.h: the filters, the separable convolutions and the per-pixel error; the colour steps are in
 * flip_color.c (metrics/flip_internal.h). Must never depend on src/ headers outside metrics/, a ray tracer or files. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "metrics/flip_internal.h"
#include "restir/metrics.h"
#include "restir/threads.h"

#define PI 3.14159265358979323846
/* The largest kernel radius RESTIR_METRICS_FLIP_PPD_MAX asks for (CSF 136, features 123 pixels). */
#define FLIP_RADIUS_MAX 160
/* Below this many pixels a call stays on the calling thread (a parallel region costs more than it saves). */
#define FLIP_PARALLEL_MIN 16384

static int ppd_ok(double ppd)
{
    return ppd > 0.0 && ppd <= RESTIR_METRICS_FLIP_PPD_MAX; /* false for NaN too */
}

double restir_metrics_flip_ppd(double distance, double monitor_width, int resolution_x)
{
    if (!(distance > 0.0) || !(monitor_width > 0.0) || !isfinite(distance) || !isfinite(monitor_width) ||
        resolution_x < 1)
        return NAN;
    return distance * ((double)resolution_x / monitor_width) * PI / 180.0;
}

/* A derivative kernel's taps (2 r + 1, tap r at offset 0) scaled so that its positive ones sum to +1 and its
 * negative ones to -1; all zero when a lobe is empty (a one-tap kernel at a tiny PPD). */
static void normalize_lobes(double *v, int r, float *out)
{
    double pos = 0.0, neg = 0.0;
    for (int i = 0; i <= 2 * r; i++) {
        pos += v[i] > 0.0 ? v[i] : 0.0;
        neg -= v[i] < 0.0 ? v[i] : 0.0;
    }
    for (int i = 0; i <= 2 * r; i++)
        out[i] = pos > 0.0 && neg > 0.0 ? (float)(v[i] > 0.0 ? v[i] / pos : v[i] / neg) : 0.0f;
}

int restir_flip_kernels_init(struct restir_flip_kernels *k, double ppd)
{
    memset(k, 0, sizeof *k);
    if (!(ppd > 0.0) || !isfinite(ppd))
        return -1;
    const double sigma = 0.5 * RESTIR_FLIP_WF * ppd;
    const double rc = ceil(3.0 * sqrt(0.04 / (2.0 * PI * PI)) * ppd), rf = ceil(3.0 * sigma);
    if (rc > FLIP_RADIUS_MAX || rf > FLIP_RADIUS_MAX)
        return -1;
    const int r = (int)rc, s = (int)rf, nc = 2 * r + 1, nf = 2 * s + 1;
    k->storage = malloc(sizeof(float) * (size_t)(4 * nc + 3 * nf));
    if (!k->storage)
        return -1;
    k->csf_radius = r;
    k->feature_radius = s;
    for (int j = 0; j < 4; j++)
        k->csf[j] = k->storage + j * nc;
    k->g = k->storage + 4 * nc;
    k->d1 = k->g + nf;
    k->d2 = k->d1 + nf;

    /* CSF: channel Y', Cx, then Cz's two Gaussians; a_j sqrt(pi / b_j) exp(-pi^2 (x / PPD)^2 / b_j) */
    static const double a[4] = {1.0, 1.0, 34.1, 13.5}, b[4] = {0.0047, 0.0053, 0.04, 0.025};
    double sum[4];
    for (int j = 0; j < 4; j++) {
        double g[2 * FLIP_RADIUS_MAX + 1];
        sum[j] = 0.0;
        for (int x = -r; x <= r; x++) {
            const double deg = (double)x / ppd;
            g[x + r] = exp(-PI * PI * deg * deg / b[j]);
            sum[j] += g[x + r];
        }
        for (int i = 0; i < nc; i++)
            k->csf[j][i] = (float)(g[i] / sum[j]);
    }
    /* Cz's 2-D kernel sum_j A_j g_j(x) g_j(y) over its 2-D sum sum_j A_j (sum g_j)^2 */
    const double w2 = a[2] * sqrt(PI / b[2]) * sum[2] * sum[2], w3 = a[3] * sqrt(PI / b[3]) * sum[3] * sum[3];
    k->cz_weight[0] = (float)(w2 / (w2 + w3));
    k->cz_weight[1] = (float)(w3 / (w2 + w3));

    /* features: Gaussian of std sigma (pixels) and its first and second derivatives' shapes */
    double g[2 * FLIP_RADIUS_MAX + 1], d1[2 * FLIP_RADIUS_MAX + 1], d2[2 * FLIP_RADIUS_MAX + 1], gsum = 0.0;
    for (int x = -s; x <= s; x++) {
        const double gx = exp(-(double)x * x / (2.0 * sigma * sigma));
        g[x + s] = gx;
        gsum += gx;
        d1[x + s] = -(double)x * gx;
        d2[x + s] = gx > 0.0 ? ((double)x * x / (sigma * sigma) - 1.0) * gx : 0.0; /* no inf * 0 at tiny sigma */
    }
    for (int i = 0; i < nf; i++)
        k->g[i] = (float)(g[i] / gsum);
    normalize_lobes(d1, s, k->d1);
    normalize_lobes(d2, s, k->d2);
    return 0;
}

void restir_flip_kernels_fini(struct restir_flip_kernels *k)
{
    free(k->storage);
    memset(k, 0, sizeof *k);
}

/* One 1-D filter pass over w outputs. Tap k (1..r) reads plus[k][x] (the sample at offset +k) and minus[k][x]
 * (offset -k), p0[x] is the sample itself; c points at the kernel's tap for offset 0. The kinds use each kernel's
 * symmetry:
 *   SYM  (Gaussians):         c0 p0 + sum_k c_k (p+k + p-k)
 *   ANTI (first derivative):  sum_k c_k (p+k - p-k), since c_-k = -c_k
 *   ZERO (second derivative): sum_k c_k (p+k + p-k - 2 p0), the symmetric sum with the kernel's zero sum made exact,
 * so that the derivatives of a constant image are exactly 0 (and NaN still spreads over the whole support). */
enum tap_kind { TAP_SYM, TAP_ANTI, TAP_ZERO };

#define TAP(kind, a, b, p0, x)                                                                                         \
    ((kind) == TAP_SYM ? (a)[x] + (b)[x] : (kind) == TAP_ANTI ? (a)[x] - (b)[x] : (a)[x] + (b)[x] - 2.0f * (p0)[x])

/* out[x] += four taps at once (one load and store of out per four taps), or one when a1..a3 are NULL. restrict
 * parameters let the compiler vectorize without overlap checks: out never overlaps the rows read (which may be the
 * same row, only read). */
static inline void taps4(enum tap_kind kind, float *restrict out, const float *restrict p0, const float *restrict a0,
                         const float *restrict b0, const float *restrict a1, const float *restrict b1,
                         const float *restrict a2, const float *restrict b2, const float *restrict a3,
                         const float *restrict b3, const float *c, int w)
{
    if (!a1) {
        for (int x = 0; x < w; x++)
            out[x] += c[0] * TAP(kind, a0, b0, p0, x);
        return;
    }
    for (int x = 0; x < w; x++)
        out[x] += c[0] * TAP(kind, a0, b0, p0, x) + c[1] * TAP(kind, a1, b1, p0, x) +
                  c[2] * TAP(kind, a2, b2, p0, x) + c[3] * TAP(kind, a3, b3, p0, x);
}

static inline void filter_taps_kind(enum tap_kind kind, const float *c, int r, const float *p0,
                                    const float *const *plus, const float *const *minus, int w, float *out)
{
    const float c0 = kind == TAP_SYM ? c[0] : 0.0f;
    for (int x = 0; x < w; x++)
        out[x] = c0 * p0[x];
    int k = 1;
    for (; k + 3 <= r; k += 4)
        taps4(kind, out, p0, plus[k], minus[k], plus[k + 1], minus[k + 1], plus[k + 2], minus[k + 2], plus[k + 3],
              minus[k + 3], c + k, w);
    for (; k <= r; k++)
        taps4(kind, out, p0, plus[k], minus[k], NULL, NULL, NULL, NULL, NULL, NULL, c + k, w);
}

static void filter_taps(enum tap_kind kind, const float *c, int r, const float *p0, const float *const *plus,
                        const float *const *minus, int w, float *out)
{
    if (kind == TAP_SYM)
        filter_taps_kind(TAP_SYM, c, r, p0, plus, minus, w, out);
    else if (kind == TAP_ANTI)
        filter_taps_kind(TAP_ANTI, c, r, p0, plus, minus, w, out);
    else
        filter_taps_kind(TAP_ZERO, c, r, p0, plus, minus, w, out);
}

/* Horizontal pass: p is a row padded by at least r clamped samples on both sides (p[-r..w+r)). */
static void filter_row(enum tap_kind kind, const float *kern, int r, const float *p, int w, float *out)
{
    const float *plus[FLIP_RADIUS_MAX + 1], *minus[FLIP_RADIUS_MAX + 1];
    for (int k = 1; k <= r; k++) {
        plus[k] = p + k;
        minus[k] = p - k;
    }
    filter_taps(kind, kern + r, r, p, plus, minus, w, out);
}

/* Vertical pass for output row y of a w x h plane, rows clamped at the top and bottom edges. */
static void filter_column(enum tap_kind kind, const float *kern, int r, const float *plane, int w, int h, int y,
                          float *out)
{
    const float *plus[FLIP_RADIUS_MAX + 1], *minus[FLIP_RADIUS_MAX + 1];
    for (int k = 1; k <= r; k++) {
        const int yp = y + k < h ? y + k : h - 1, ym = y - k >= 0 ? y - k : 0;
        plus[k] = plane + (size_t)yp * (size_t)w;
        minus[k] = plane + (size_t)ym * (size_t)w;
    }
    filter_taps(kind, kern + r, r, plane + (size_t)y * (size_t)w, plus, minus, w, out);
}

/* The horizontal passes' planes per image: Y', Cx, Cz by its two Gaussians (CSF), and the feature luminance by
 * g, d1 and d2. */
enum { H_Y, H_CX, H_CZ1, H_CZ2, H_G, H_D1, H_D2, H_PLANES };
#define ROWS_A 4 /* padded rows per thread of the horizontal pass: Y', Cx, Cz, feature luminance */
#define ROWS_B 8 /* rows per image per thread of the vertical pass: Y', Cx, Cz1, Cz2, edge x, y, point x, y */

/* One LDR-FLIP of the two images after the input step (clamp, or HDR's exposure and tone map). */
struct flip_pass {
    int w, h, pad, threads, hdr, first;
    size_t npix, per_thread;
    double scale, cmax; /* hdr: 2^exposure */
    const float *test, *ref;
    const struct restir_flip_kernels *k;
    float *planes;  /* 2 images x H_PLANES planes of npix */
    float *scratch; /* threads x per_thread floats */
    float *map;     /* the output: written (first) or maxed into */
};

static int thread_id(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

/* n input values as LDR-FLIP reads them: NaN for a NaN or infinite one; HDR: negative values as 0 (ACES's rational
 * function would show a large negative value bright), times 2^exposure (in double, then capped at 1e6, where ACES
 * is long past 1, so float never overflows), tone-mapped; then clamped to [0, 1]. Branch-free: vectorized. */
static void row_input(const float *restrict src, float *restrict out, int n, int hdr, double scale)
{
    if (!hdr) {
        for (int i = 0; i < n; i++)
            out[i] = fabsf(src[i]) <= FLT_MAX ? restir_flip_clamp01(src[i]) : NAN;
        return;
    }
    for (int i = 0; i < n; i++) {
        const float v = src[i];
        const double scaled = (double)v * scale;
        const float x = (float)(scaled < 1e6 ? scaled : 1e6);
        const float t = restir_flip_clamp01(restir_flip_aces(v > 0.0f ? x : 0.0f));
        out[i] = fabsf(v) <= FLT_MAX ? t : NAN;
    }
}

/* Horizontal passes of one row of one image into its planes. */
static void pass_horizontal(const struct flip_pass *fp, int img, int y, float *scratch)
{
    const int w = fp->w, R = fp->pad;
    const size_t pw = (size_t)w + 2 * (size_t)R;
    float *row[ROWS_A], *in = scratch + ROWS_A * pw; /* 3 w input values */
    for (int q = 0; q < ROWS_A; q++)
        row[q] = scratch + q * pw + R; /* row[q][-R .. w + R) */
    row_input((img ? fp->ref : fp->test) + 3 * (size_t)w * (size_t)y, in, 3 * w, fp->hdr, fp->scale);
    for (int x = 0; x < w; x++) {
        const float rgb[3] = {in[3 * x], in[3 * x + 1], in[3 * x + 2]};
        float ycc[3];
        restir_flip_rgb_to_ycxcz(rgb, ycc);
        row[0][x] = ycc[0];
        row[1][x] = ycc[1];
        row[2][x] = ycc[2];
        row[3][x] = RESTIR_FLIP_YN(rgb[0], rgb[1], rgb[2]); /* the features' luminance (Y' + 16) / 116 in [0, 1] */
    }
    for (int q = 0; q < ROWS_A; q++)
        for (int i = 1; i <= R; i++) { /* clamp at the left and right edges */
            row[q][-i] = row[q][0];
            row[q][w - 1 + i] = row[q][w - 1];
        }
    const struct restir_flip_kernels *k = fp->k;
    const int rc = k->csf_radius, rf = k->feature_radius;
    float *out = fp->planes + (size_t)img * H_PLANES * fp->npix + (size_t)y * (size_t)w;
    filter_row(TAP_SYM, k->csf[0], rc, row[0], w, out + H_Y * fp->npix);
    filter_row(TAP_SYM, k->csf[1], rc, row[1], w, out + H_CX * fp->npix);
    filter_row(TAP_SYM, k->csf[2], rc, row[2], w, out + H_CZ1 * fp->npix);
    filter_row(TAP_SYM, k->csf[3], rc, row[2], w, out + H_CZ2 * fp->npix);
    filter_row(TAP_SYM, k->g, rf, row[3], w, out + H_G * fp->npix);
    filter_row(TAP_ANTI, k->d1, rf, row[3], w, out + H_D1 * fp->npix);
    filter_row(TAP_ZERO, k->d2, rf, row[3], w, out + H_D2 * fp->npix);
}

/* NaN when either is NaN, else the larger. */
static float max_nan(float a, float b)
{
    return a >= b || isnan(a) ? a : b;
}

/* One image's row after the vertical passes: Y' (l), Cx (a) and Cz's two parts (b, cz2) become the Hunt-adjusted
 * Lab (l, a, b), the edge (e, ey) and point (p, py) responses along x and y their magnitudes (e, p). A loop of
 * inline float steps over restrict parameters (the compiler honours those, not block-scope ones): vectorized. */
static void row_lab_features(float *restrict l, float *restrict a, float *restrict b, const float *restrict cz2,
                             float *restrict e, const float *restrict ey, float *restrict p, const float *restrict py,
                             float w0, float w1, int w)
{
    for (int x = 0; x < w; x++) {
        const float ycc[3] = {l[x], a[x], w0 * b[x] + w1 * cz2[x]};
        float rgb[3], lab[3];
        restir_flip_ycxcz_to_rgb(ycc, rgb);
        restir_flip_rgb_to_lab_hunt(rgb, lab); /* clamps the filtered colour to [0, 1] first */
        l[x] = lab[0];
        a[x] = lab[1];
        b[x] = lab[2];
        e[x] = sqrtf(e[x] * e[x] + ey[x] * ey[x]);
        p[x] = sqrtf(p[x] * p[x] + py[x] * py[x]);
    }
}

/* The colour difference HyAB of the two images' Lab rows into hyab, and the feature difference
 * dE_f = (max(|edge0 - edge1|, |point0 - point1|) / sqrt 2)^q_f into feature (q_f = 0.5: a square root). */
static void row_differences(const float *restrict l0, const float *restrict a0, const float *restrict b0,
                            const float *restrict l1, const float *restrict a1, const float *restrict b1,
                            const float *restrict e0, const float *restrict e1, const float *restrict p0,
                            const float *restrict p1, float *restrict hyab, float *restrict feature, int w)
{
    for (int x = 0; x < w; x++) {
        const float lab0[3] = {l0[x], a0[x], b0[x]}, lab1[3] = {l1[x], a1[x], b1[x]};
        hyab[x] = restir_flip_hyab(lab0, lab1);
        feature[x] = sqrtf(max_nan(fabsf(e0[x] - e1[x]), fabsf(p0[x] - p1[x])) * (float)(1.0 / 1.4142135623730951));
    }
}

/* Vertical passes and the per-pixel error of one row. */
static void pass_vertical(const struct flip_pass *fp, int y, float *scratch)
{
    const int w = fp->w, h = fp->h;
    const struct restir_flip_kernels *k = fp->k;
    const int rc = k->csf_radius, rf = k->feature_radius;
    float *o[2][ROWS_B];
    for (int img = 0; img < 2; img++) {
        const float *hp = fp->planes + (size_t)img * H_PLANES * fp->npix;
        for (int q = 0; q < ROWS_B; q++)
            o[img][q] = scratch + ((size_t)img * ROWS_B + (size_t)q) * (size_t)w;
        filter_column(TAP_SYM, k->csf[0], rc, hp + H_Y * fp->npix, w, h, y, o[img][0]);
        filter_column(TAP_SYM, k->csf[1], rc, hp + H_CX * fp->npix, w, h, y, o[img][1]);
        filter_column(TAP_SYM, k->csf[2], rc, hp + H_CZ1 * fp->npix, w, h, y, o[img][2]);
        filter_column(TAP_SYM, k->csf[3], rc, hp + H_CZ2 * fp->npix, w, h, y, o[img][3]);
        filter_column(TAP_SYM, k->g, rf, hp + H_D1 * fp->npix, w, h, y, o[img][4]);  /* edges along x */
        filter_column(TAP_ANTI, k->d1, rf, hp + H_G * fp->npix, w, h, y, o[img][5]); /* edges along y */
        filter_column(TAP_SYM, k->g, rf, hp + H_D2 * fp->npix, w, h, y, o[img][6]);  /* points along x */
        filter_column(TAP_ZERO, k->d2, rf, hp + H_G * fp->npix, w, h, y, o[img][7]); /* points along y */
        row_lab_features(o[img][0], o[img][1], o[img][2], o[img][3], o[img][4], o[img][5], o[img][6], o[img][7],
                         k->cz_weight[0], k->cz_weight[1], w);
    }
    /* the rows of Cz's second part are free now: the colour and feature differences go there */
    row_differences(o[0][0], o[0][1], o[0][2], o[1][0], o[1][1], o[1][2], o[0][4], o[1][4], o[0][6], o[1][6], o[0][3],
                    o[1][3], w);
    float *map = fp->map + (size_t)y * (size_t)w;
    const float *hyab = o[0][3], *feature = o[1][3], cmax = (float)fp->cmax;
    for (int x = 0; x < w; x++) {
        /* the powers in float (the map's precision): powf is several times faster than pow */
        const float dc = restir_flip_remap_color(powf(hyab[x], (float)RESTIR_FLIP_QC), cmax), df = feature[x];
        /* powf(x, NaN) is 1 for x = 1 and powf(NaN, 0) is 1: a NaN must stay one */
        const float e = isnan(dc) || isnan(df) ? NAN : powf(dc, 1.0f - df);
        map[x] = fp->first ? e : max_nan(map[x], e);
    }
}

static void flip_pass_run(struct flip_pass *fp)
{
    const int h = fp->h;
#pragma omp parallel for schedule(static) num_threads(fp->threads)
    for (int t = 0; t < 2 * h; t++)
        pass_horizontal(fp, t / h, t % h, fp->scratch + (size_t)thread_id() * fp->per_thread);
#pragma omp parallel for schedule(static) num_threads(fp->threads)
    for (int y = 0; y < h; y++)
        pass_vertical(fp, y, fp->scratch + (size_t)thread_id() * fp->per_thread);
}

/* The shared body of the public functions: hdr 0 = LDR-FLIP, 1 = HDR-FLIP. */
static int flip_compute(const float *test, const float *reference, int width, int height, double ppd, float *map_out,
                        double *mean_out, int hdr)
{
    if (!test || !reference || !mean_out || width < 1 || height < 1 || !ppd_ok(ppd))
        return -1;
    const size_t npix = (size_t)width * (size_t)height;
    /* the planes: 2 H_PLANES + 1 floats a pixel; 3 floats a pixel of input */
    if ((size_t)width > SIZE_MAX / (sizeof(float) * (2 * H_PLANES + 4)) / (size_t)height ||
        width > (INT_MAX - 2 * FLIP_RADIUS_MAX) / 3 || height > INT_MAX / 2) /* row and loop indices are int */
        return -1;
    struct restir_flip_kernels k;
    if (restir_flip_kernels_init(&k, ppd) != 0)
        return -1;
    double start = 0.0, stop = 0.0;
    int count = 1;
    if (hdr && restir_flip_exposures(reference, npix, &start, &stop, &count) != 0) {
        restir_flip_kernels_fini(&k);
        return -1;
    }
    struct flip_pass fp = {.w = width, .h = height, .hdr = hdr, .npix = npix, .test = test, .ref = reference,
                           .k = &k, .cmax = restir_flip_cmax(), .scale = 1.0};
    fp.pad = k.csf_radius > k.feature_radius ? k.csf_radius : k.feature_radius;
    fp.threads = npix < FLIP_PARALLEL_MIN ? 1 : restir_threads_get();
    const size_t a = ROWS_A * ((size_t)width + 2 * (size_t)fp.pad) + 3 * (size_t)width, b = 2 * ROWS_B * (size_t)width;
    fp.per_thread = a > b ? a : b;
    fp.planes = malloc(sizeof(float) * 2 * H_PLANES * npix);
    fp.scratch = malloc(sizeof(float) * fp.per_thread * (size_t)fp.threads);
    float *own = map_out ? NULL : malloc(sizeof(float) * npix);
    int rc = -1;
    if (fp.planes && fp.scratch && (map_out || own)) {
        fp.map = map_out ? map_out : own;
        for (int i = 0; i < count; i++) {
            fp.first = i == 0;
            if (hdr) /* the exposures from start to stop, both included */
                fp.scale = exp2(count > 1 ? start + (stop - start) * i / (count - 1) : start);
            flip_pass_run(&fp);
        }
        double sum = 0.0;
        for (size_t i = 0; i < npix; i++)
            sum += (double)fp.map[i];
        *mean_out = sum / (double)npix;
        rc = 0;
    }
    free(own);
    free(fp.scratch);
    free(fp.planes);
    restir_flip_kernels_fini(&k);
    return rc;
}

int restir_metrics_flip_ldr(const float *test, const float *reference, int width, int height, double ppd,
                            float *map_out, double *mean_out)
{
    return flip_compute(test, reference, width, height, ppd, map_out, mean_out, 0);
}

int restir_metrics_flip(const float *test, const float *reference, int width, int height, double ppd, float *map_out,
                        double *mean_out)
{
    return flip_compute(test, reference, width, height, ppd, map_out, mean_out, 1);
}
