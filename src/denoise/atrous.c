/* atrous.c: the edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika and Lensch,
 * "Edge-Avoiding À-Trous Wavelet Transform for fast Global Illumination Filtering", HPG 2010), the
 * spatial-only baseline SVGF builds on: per iteration i (step 2^i, the B3 kernel h),
 *   c_{i+1}(p) = sum_q h(q) w(p, q) c_i(q) / sum_q h(q) w(p, q),
 *   w = exp(-|c_p - c_q|^2 / sigma_rt,i^2) exp(-|n_p - n_q|^2 / sigma_n^2) exp(-|x_p - x_q|^2 / sigma_x^2)
 * (Sec. 3, Eq. 4-6), with sigma_rt halved after each iteration (Sec. 3.1). No history: each frame
 * on its own. Scales, as our frames are HDR and our scenes of any size: sigma_rt is in units of the
 * frame's mean illumination luminance, sigma_x a fraction of the pixel's distance to the camera.
 * A tap counts only where its group (struct denoise_frame: used, and the same albedo channels
 * demodulated) is the centre's. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/simd.h"
#include "denoise/denoise_kernel.h"
#include "denoise/denoise_method.h"

struct atrous {
    int w, h;
    size_t n;
    float *tmp[3];
    struct denoise_scratch acc; /* per thread, 4 rows of the image's width */
};

static void *atrous_create(const struct denoise_settings *s, int width, int height)
{
    (void)s;
    struct atrous *a = xcalloc(1, sizeof(*a));
    a->w = width;
    a->h = height;
    a->n = (size_t)width * (size_t)height;
    denoise_planes_alloc(a->tmp, 3, a->n);
    return a;
}

static void atrous_destroy(void *state)
{
    struct atrous *a = state;
    free(a->tmp[0]);
    denoise_scratch_free(&a->acc);
    free(a);
}

/* The weight's exponent scales: 1 / sigma^2 of each term, as log2 factors. */
struct atrous_scales {
    float color, normal, position; /* position: per unit of (|dx| / depth_p)^2 */
};

/* One tap (weight hk) over pixels [lo, hi) of a row: p* the centre pixels' planes, q* the taps'
 * (restrict: they never alias the sums, so the pixel loop vectorises). */
struct atrous_segment {
    const float *restrict pz, *restrict pg, *restrict pc[3], *restrict pn[3], *restrict px[3];
    const float *restrict qg, *restrict qc[3], *restrict qn[3], *restrict qx[3];
};

SIMD_INLINE void atrous_tap(const struct atrous_segment *t, const struct atrous_scales *k, int lo, int hi, float hk,
                            float *restrict sw, float *restrict sr, float *restrict sg, float *restrict sb)
{
    const float *restrict pz = t->pz, *restrict pgr = t->pg, *restrict qgr = t->qg;
    const float *restrict pr = t->pc[0], *restrict pg = t->pc[1], *restrict pb = t->pc[2];
    const float *restrict cr = t->qc[0], *restrict cg = t->qc[1], *restrict cb = t->qc[2];
    const float *restrict n0 = t->pn[0], *restrict n1 = t->pn[1], *restrict n2 = t->pn[2];
    const float *restrict m0 = t->qn[0], *restrict m1 = t->qn[1], *restrict m2 = t->qn[2];
    const float *restrict x0 = t->px[0], *restrict x1 = t->px[1], *restrict x2 = t->px[2];
    const float *restrict y0 = t->qx[0], *restrict y1 = t->qx[1], *restrict y2 = t->qx[2];
    const float kc = k->color, kn = k->normal, kx = k->position;
    for (int x = lo; x < hi; x++) {
        const float dr = pr[x] - cr[x], dg = pg[x] - cg[x], db = pb[x] - cb[x];
        const float dn0 = n0[x] - m0[x], dn1 = n1[x] - m1[x], dn2 = n2[x] - m2[x];
        const float dx0 = x0[x] - y0[x], dx1 = x1[x] - y1[x], dx2 = x2[x] - y2[x];
        const float rz = 1.0f / pz[x];
        const float e = kc * (dr * dr + dg * dg + db * db) + kn * (dn0 * dn0 + dn1 * dn1 + dn2 * dn2) +
                        kx * (dx0 * dx0 + dx1 * dx1 + dx2 * dx2) * rz * rz;
        const float wt = qgr[x] == pgr[x] ? hk * denoise_exp2_neg(-e) : 0.0f;
        sw[x] += wt;
        sr[x] += wt * cr[x];
        sg[x] += wt * cg[x];
        sb[x] += wt * cb[x];
    }
}

/* One row of one iteration: sum of weights and weighted colours into acc[0 .. 4w). */
SIMD_INLINE void atrous_row_body(const struct denoise_frame *f, const struct atrous_scales *k, const float *const in[3],
                                 int y, int step, float *acc)
{
    const int w = f->width, h = f->height;
    float *sw = acc, *sr = acc + w, *sg = acc + 2 * w, *sb = acc + 3 * w;
    for (int x = 0; x < w; x++)
        sw[x] = sr[x] = sg[x] = sb[x] = 0.0f;
    const int row = y * w;
    for (int ty = 0; ty < 5; ty++) {
        const int yq = y + (ty - 2) * step;
        if (yq < 0 || yq >= h)
            continue;
        for (int tx = 0; tx < 5; tx++) {
            const int ox = (tx - 2) * step;
            const int xlo = ox < 0 ? -ox : 0, xhi = ox > 0 ? w - ox : w;
            const int q = yq * w + ox; /* tap of pixel x: q + x */
            struct atrous_segment t = {f->depth + row, f->group + row, {0}, {0}, {0}, f->group + q, {0}, {0}, {0}};
            for (int c = 0; c < 3; c++) {
                t.pc[c] = in[c] + row;
                t.qc[c] = in[c] + q;
                t.pn[c] = f->normal[c] + row;
                t.qn[c] = f->normal[c] + q;
                t.px[c] = f->position[c] + row;
                t.qx[c] = f->position[c] + q;
            }
            atrous_tap(&t, k, xlo, xhi, denoise_b3[ty] * denoise_b3[tx], sw, sr, sg, sb);
        }
    }
}

static void atrous_row_base(const struct denoise_frame *f, const struct atrous_scales *k, const float *const in[3],
                            int y, int step, float *acc)
{
    atrous_row_body(f, k, in, y, step, acc);
}

#if RESTIR_SIMD_DISPATCH
SIMD_TARGET_AVX2 static void atrous_row_avx2(const struct denoise_frame *f, const struct atrous_scales *k,
                                             const float *const in[3], int y, int step, float *acc)
{
    atrous_row_body(f, k, in, y, step, acc);
}
#endif

static void atrous_run(void *state, const struct denoise_settings *s, struct denoise_frame *f, struct denoise_stats *st)
{
    (void)st;
    struct atrous *a = state;
    const int w = a->w, h = a->h;
    denoise_scratch_reserve(&a->acc, 4 * (size_t)w);
#if RESTIR_SIMD_DISPATCH
    void (*row)(const struct denoise_frame *, const struct atrous_scales *, const float *const[3], int, int, float *) =
        simd_isa_active() >= SIMD_ISA_AVX2 ? atrous_row_avx2 : atrous_row_base;
#else
    void (*row)(const struct denoise_frame *, const struct atrous_scales *, const float *const[3], int, int, float *) =
        atrous_row_base;
#endif
    const float unit = f->mean_lum > 0.0 ? (float)f->mean_lum : 1.0f;
    float sigma_c = s->atrous_sigma_color * unit;
    float *src[3] = {f->illum[0], f->illum[1], f->illum[2]}, *dst[3] = {a->tmp[0], a->tmp[1], a->tmp[2]};
    for (int it = 0; it < s->atrous_iterations; it++, sigma_c *= 0.5f) {
        const struct atrous_scales k = {
            DENOISE_LOG2E / (sigma_c * sigma_c), DENOISE_LOG2E / (s->atrous_sigma_normal * s->atrous_sigma_normal),
            DENOISE_LOG2E / (s->atrous_sigma_position * s->atrous_sigma_position)};
        const float *const in[3] = {src[0], src[1], src[2]};
        const int step = 1 << it;
#pragma omp parallel for schedule(dynamic, 4)
        for (int y = 0; y < h; y++) {
            float *acc = denoise_scratch_mine(&a->acc);
            row(f, &k, in, y, step, acc);
            for (int x = 0; x < w; x++) {
                const int i = y * w + x;
                const int used = f->use[i] != 0.0f;
                for (int c = 0; c < 3; c++)
                    dst[c][i] = used ? acc[(c + 1) * w + x] / acc[x] : 0.0f;
            }
        }
        for (int c = 0; c < 3; c++) {
            float *t = src[c];
            src[c] = dst[c];
            dst[c] = t;
        }
    }
    if (src[0] != f->illum[0])
        for (int c = 0; c < 3; c++)
            memcpy(f->illum[c], src[c], sizeof(float) * a->n);
}

const struct denoise_method denoise_atrous = {"atrous", atrous_create, atrous_destroy, atrous_run, NULL, NULL};
