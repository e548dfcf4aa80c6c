/* metrics/flip_internal.h: the steps of FLIP (restir/metrics.h: restir_metrics_flip, restir_metrics_flip_ldr)
 * one by one, for metrics/flip.c and the unit tests that check each step on hand-computed cases. Not installed,
 * not public API. Colours are linear RGB with the sRGB / Rec. 709 primaries and the D65 white. The per-pixel steps
 * are inline float functions: flip.c calls them in loops over a row, which the compiler vectorizes, and float is
 * the precision of FLIP's maps (NVIDIA's FLIP computes in float32 too).
 * Must never depend on anything outside librestir (libm only). */
#ifndef RESTIR_METRICS_FLIP_INTERNAL_H
#define RESTIR_METRICS_FLIP_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* LDR-FLIP's constants (Andersson et al. 2020). */
#define RESTIR_FLIP_QC 0.7   /* exponent of the colour difference (HyAB^q_c) */
#define RESTIR_FLIP_QF 0.5   /* exponent of the feature difference (a square root) */
#define RESTIR_FLIP_PC 0.4   /* the colour remap's knee at p_c c_max ... */
#define RESTIR_FLIP_PT 0.95  /* ... is mapped to p_t */
#define RESTIR_FLIP_WF 0.082 /* feature detector width, degrees: sigma = 0.5 w_f PPD pixels */
#define RESTIR_FLIP_Y_TARGET 0.85 /* HDR-FLIP: the tone-mapped value x_max reaches (2021) */

/* The D65 white as the rows below give it for RGB = (1, 1, 1): (23359437 / 24577794, 1, 80288307 / 73733382). */
#define RESTIR_FLIP_WHITE_X 0.950428545
#define RESTIR_FLIP_WHITE_Z 1.088900371

/* Linear sRGB -> XYZ (D65) as FLIP's exact fractions, each row divided by its white component: XYZ / white. */
#define RESTIR_FLIP_XN(r, g, b)                                                                                  \
    ((float)(10135552.0 / 24577794.0 / RESTIR_FLIP_WHITE_X) * (r) +                                               \
     (float)(8788810.0 / 24577794.0 / RESTIR_FLIP_WHITE_X) * (g) +                                                \
     (float)(4435075.0 / 24577794.0 / RESTIR_FLIP_WHITE_X) * (b))
#define RESTIR_FLIP_YN(r, g, b)                                                                                  \
    ((float)(2613072.0 / 12288897.0) * (r) + (float)(8788810.0 / 12288897.0) * (g) +                              \
     (float)(887015.0 / 12288897.0) * (b))
#define RESTIR_FLIP_ZN(r, g, b)                                                                                  \
    ((float)(1425312.0 / 73733382.0 / RESTIR_FLIP_WHITE_Z) * (r) +                                                \
     (float)(8788810.0 / 73733382.0 / RESTIR_FLIP_WHITE_Z) * (g) +                                                \
     (float)(70074185.0 / 73733382.0 / RESTIR_FLIP_WHITE_Z) * (b))

/* [0, 1] with NaN kept (fminf / fmaxf would turn it into a bound: a broken pixel must not look fine). */
static inline float restir_flip_clamp01(float x)
{
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

/* Linear RGB -> YCxCz (FLIP's "linearized CIELAB": XYZ / white with L*'s affine map but no cube root):
 * Y' = 116 Y/Yw - 16, Cx = 500 (X/Xw - Y/Yw), Cz = 200 (Y/Yw - Z/Zw). */
static inline void restir_flip_rgb_to_ycxcz(const float rgb[3], float ycxcz[3])
{
    const float x = RESTIR_FLIP_XN(rgb[0], rgb[1], rgb[2]), y = RESTIR_FLIP_YN(rgb[0], rgb[1], rgb[2]),
                z = RESTIR_FLIP_ZN(rgb[0], rgb[1], rgb[2]);
    ycxcz[0] = 116.0f * y - 16.0f;
    ycxcz[1] = 500.0f * (x - y);
    ycxcz[2] = 200.0f * (y - z);
}

/* The inverse: YCxCz -> XYZ -> linear RGB (not clamped), with FLIP's inverse matrix rows
 * (3.241003275, -1.537398934, -0.498615861 / -0.969224334, 1.875930071, 0.041554224 / 0.055639423, -0.204011202,
 * 1.057148933) applied to X = Xn Xw, Y = Yn, Z = Zn Zw. */
static inline void restir_flip_ycxcz_to_rgb(const float ycxcz[3], float rgb[3])
{
    const float yn = (ycxcz[0] + 16.0f) * (float)(1.0 / 116.0);
    const float x = (ycxcz[1] * (float)(1.0 / 500.0) + yn) * (float)RESTIR_FLIP_WHITE_X,
                z = (yn - ycxcz[2] * (float)(1.0 / 200.0)) * (float)RESTIR_FLIP_WHITE_Z;
    rgb[0] = 3.241003275f * x - 1.537398934f * yn - 0.498615861f * z;
    rgb[1] = -0.969224334f * x + 1.875930071f * yn + 0.041554224f * z;
    rgb[2] = 0.055639423f * x - 0.204011202f * yn + 1.057148933f * z;
}

/* t^(1/3) for t > 0 (any t gives a finite value, NaN gives NaN): a first guess from the bits (within 3.3%), then
 * two Halley steps y <- y (y^3 + 2 t) / (2 y^3 + t), each cubing the relative error: within 3e-7 of cbrt on
 * CIELAB's range. Branch-free and inline, so that loops over a row vectorize (libm's cbrt is a call and took a
 * third of a map's time). */
static inline float restir_flip_cbrt(float t)
{
    uint32_t bits;
    memcpy(&bits, &t, sizeof bits);
    bits = bits / 3u + 709958130u; /* divides the exponent by 3, biased as float's */
    float y;
    memcpy(&y, &bits, sizeof y);
    for (int i = 0; i < 2; i++) {
        const float y3 = y * y * y;
        y *= (y3 + 2.0f * t) / (2.0f * y3 + t);
    }
    return y;
}

/* CIELAB's f: the cube root above (6/29)^3, the linear segment t / (3 (6/29)^2) + 4/29 below (and for NaN). */
static inline float restir_flip_lab_f(float t)
{
    /* both branches computed, then a select: a loop over a row stays free of branches (vectorized) */
    const float root = restir_flip_cbrt(t), linear = t * (float)(841.0 / 108.0) + (float)(4.0 / 29.0);
    return t > (float)(216.0 / 24389.0) ? root : linear;
}

/* Linear RGB, clamped to [0, 1] first (NaN stays NaN) -> XYZ -> CIELAB (D65) with the Hunt adjustment: a* and b*
 * multiplied by 0.01 L*. */
static inline void restir_flip_rgb_to_lab_hunt(const float rgb[3], float lab[3])
{
    const float r = restir_flip_clamp01(rgb[0]), g = restir_flip_clamp01(rgb[1]), b = restir_flip_clamp01(rgb[2]);
    const float fx = restir_flip_lab_f(RESTIR_FLIP_XN(r, g, b)), fy = restir_flip_lab_f(RESTIR_FLIP_YN(r, g, b)),
                fz = restir_flip_lab_f(RESTIR_FLIP_ZN(r, g, b));
    const float l = 116.0f * fy - 16.0f;
    lab[0] = l;
    lab[1] = 0.01f * l * (500.0f * (fx - fy)); /* Hunt: chroma shrinks with lightness */
    lab[2] = 0.01f * l * (200.0f * (fy - fz));
}

/* HyAB distance of two (Hunt-adjusted) Lab colours: |L1 - L2| + sqrt((a1 - a2)^2 + (b1 - b2)^2). */
static inline float restir_flip_hyab(const float lab1[3], const float lab2[3])
{
    const float da = lab1[1] - lab2[1], db = lab1[2] - lab2[2];
    return fabsf(lab1[0] - lab2[0]) + sqrtf(da * da + db * db);
}

/* ACES (Narkowicz's fit with FLIP's 0.6 pre-exposure), per channel, not clamped:
 * (a x^2 + b x) / (d x^2 + e x + f), a = 0.36 * 2.51, b = 0.6 * 0.03, d = 0.36 * 2.43, e = 0.6 * 0.59, f = 0.14. */
#define RESTIR_FLIP_ACES_A (0.36 * 2.51)
#define RESTIR_FLIP_ACES_B (0.6 * 0.03)
#define RESTIR_FLIP_ACES_D (0.36 * 2.43)
#define RESTIR_FLIP_ACES_E (0.6 * 0.59)
#define RESTIR_FLIP_ACES_F 0.14
static inline float restir_flip_aces(float x)
{
    return ((float)RESTIR_FLIP_ACES_A * x * x + (float)RESTIR_FLIP_ACES_B * x) /
           ((float)RESTIR_FLIP_ACES_D * x * x + (float)RESTIR_FLIP_ACES_E * x + (float)RESTIR_FLIP_ACES_F);
}

/* c_max: HyAB(Hunt(Lab(green)), Hunt(Lab(blue)))^q_c, the largest colour difference of the primaries (41.276). */
double restir_flip_cmax(void);
/* The colour remap of e = HyAB^q_c into [0, 1] with cmax = restir_flip_cmax(): e p_t / (p_c c_max) below the knee
 * p_c c_max, then linear from p_t to 1 at c_max (not clamped above c_max). */
static inline float restir_flip_remap_color(float e, float cmax)
{
    const float knee = (float)RESTIR_FLIP_PC * cmax;
    const float below = e * ((float)RESTIR_FLIP_PT / knee);
    const float above = (float)RESTIR_FLIP_PT + (e - knee) * ((float)(1.0 - RESTIR_FLIP_PT) / (cmax - knee));
    return e < knee ? below : above;
}
/* x_max: the positive root of aces(x) = RESTIR_FLIP_Y_TARGET (about 2.119), in double. */
double restir_flip_aces_xmax(void);

/* The filters at one PPD. Every kernel holds 2 r + 1 taps, tap r being offset 0; the convolutions are separable
 * (one 1-D pass per axis) and clamp at the image's edges. */
struct restir_flip_kernels {
    int csf_radius;     /* ceil(3 sqrt(0.04 / (2 pi^2)) PPD): 10 px at 67 PPD */
    int feature_radius; /* ceil(3 sigma), sigma = 0.5 w_f PPD: 9 px at 67 PPD */
    /* The CSF (2020 Sec. 3.1): each channel's 2-D kernel sum_j A_j g_j(x) g_j(y), A_j = a_j sqrt(pi / b_j),
     * g_j(x) = exp(-pi^2 (x / PPD)^2 / b_j), normalised to unit sum. csf[0] (Y': a 1, b 0.0047) and csf[1]
     * (Cx: a 1, b 0.0053) are g_j / sum g_j; Cz's two Gaussians (34.1, 0.04) and (13.5, 0.025) are csf[2] and
     * csf[3], each of unit sum, weighed cz_weight[j] = A_j (sum g_j)^2 / sum_k A_k (sum g_k)^2 (which sum to 1). */
    float *csf[4];
    float cz_weight[2];
    /* Feature detectors on the luminance: g (Gaussian of std sigma, unit sum), d1 = -x g (edges) and
     * d2 = (x^2 / sigma^2 - 1) g (points), each derivative's positive taps scaled to sum +1 and its negative ones
     * to -1. The 2-D edge (point) kernel along x is d1(x) g(y) (d2(x) g(y)), whose lobes then also sum to +-1. */
    float *g, *d1, *d2;
    float *storage; /* one allocation holding every kernel */
};
/* Fills k for ppd (finite, > 0, radii at most 160 px). Returns 0, or -1 (nothing to free) when ppd is refused or
 * memory is short. */
int restir_flip_kernels_init(struct restir_flip_kernels *k, double ppd);
void restir_flip_kernels_fini(struct restir_flip_kernels *k);

/* HDR-FLIP's exposures from the reference (2021): luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of every pixel
 * whose luminance is finite; start = log2(x_max / Y_max), stop = log2(x_max / Y_median), Y_median being element
 * N / 2 (0-based) of the N finite luminances sorted ascending, zeros included; count = max(2, ceil(stop - start)),
 * the exposures start + i (stop - start) / (count - 1), i < count, both ends included. Our rules where that is
 * undefined: a median <= 0 is replaced by the median (element P / 2) of the P positive luminances; with no
 * positive luminance (or none finite) start = stop = 0 (two exposures of 0). Returns 0, or -1 on no memory. */
int restir_flip_exposures(const float *reference, size_t n_pixels, double *start, double *stop, int *count);

#endif
