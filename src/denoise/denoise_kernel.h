/* denoise_kernel.h: the small inline math every à-trous filter shares: the B3-spline taps
 * (Dammertz et al. 2010 Sec. 3; Schied et al. 2017 Sec. 4.3), luminance, and exp2 / log2
 * approximations made of arithmetic alone, so that the filters' pixel loops vectorise (libm
 * calls do not). Internal to src/denoise. Must never depend on anything but <stdint.h>. */
#ifndef RESTIR_DENOISE_DENOISE_KERNEL_H
#define RESTIR_DENOISE_DENOISE_KERNEL_H

#include <stdint.h>

/* The 5 taps of the cubic B-spline, h = (1, 4, 6, 4, 1) / 16; a 2D tap weighs h[i] * h[j]. */
static const float denoise_b3[5] = {1.0f / 16.0f, 4.0f / 16.0f, 6.0f / 16.0f, 4.0f / 16.0f, 1.0f / 16.0f};

/* Rec. 709 luminance. */
__attribute__((always_inline)) static inline float denoise_luminance(float r, float g, float b)
{
    return 0.2126f * r + 0.7152f * g + 0.0722f * b;
}

/* 2^x for x <= 0, relative error below 3e-7 (2^n by the exponent bits, 2^f for |f| <= 1/2 by its
 * Taylor polynomial to degree 6), and exactly 0 below 2^-30: a weight that small is below float
 * rounding beside the centre tap's, and keeping it would feed denormal products (squared weights
 * times variances) into the sums, which cost x86 cores a microcode assist each. Rounds x to n by
 * adding 1.5 * 2^23 (round to nearest), which vectorises for SSE2 and AVX2 alike where (int)
 * conversions and floorf do not. NaN gives 0. */
#define DENOISE_EXP2_CUT (-30.0f)
__attribute__((always_inline)) static inline float denoise_exp2_neg(float x)
{
    const float keep = x >= DENOISE_EXP2_CUT ? 1.0f : 0.0f;
    x = x >= DENOISE_EXP2_CUT ? x : DENOISE_EXP2_CUT; /* NaN too: a weight of 0, never an integer overflow */
    x = x > 0.0f ? 0.0f : x;
    union {
        float f;
        int32_t i;
    } t = {x + 12582912.0f}; /* the low mantissa bits hold n = round(x) */
    const float f = x - (t.f - 12582912.0f);
    const float p4 = 0.00961812911f + f * (0.00133335581f + f * 0.000154035304f); /* ln2^k / k!, k = 4 .. 6 */
    const float p = 1.0f + f * (0.693147182f + f * (0.240226507f + f * (0.0555041087f + f * p4)));
    union {
        int32_t i;
        float f;
    } u = {(t.i - 0x4B400000 + 127) * (1 << 23)};
    return keep * p * u.f;
}

/* log2(x) for finite x > 0 (normal floats), absolute error below 1e-4. */
__attribute__((always_inline)) static inline float denoise_log2(float x)
{
    union {
        float f;
        int32_t i;
    } u = {x};
    const float e = (float)((u.i >> 23) & 255) - 127.0f;
    u.i = (u.i & 0x007fffff) | 0x3f800000; /* mantissa m in [1, 2) */
    const float m = u.f;
    /* log2(m) = 2 atanh(t) / ln 2 with t = (m - 1) / (m + 1) in [0, 1/3) */
    const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    const float s = t * (2.885390082f + t2 * (0.961796694f + t2 * (0.577078016f + t2 * 0.412198581f)));
    return e + s;
}

#define DENOISE_LOG2E 1.44269504f

/* A reprojected pixel coordinate p moved onto the nearest integer when within 1/1000 pixel of it: a
 * still camera's motion vectors are 0 up to float rounding, which would leave every bilinear
 * lookup with a tap of weight 1 - 1e-7 on a random side of the pixel (and the branch that skips the
 * zero-weight taps unpredictable); snapped, the lookup reads one tap. p outside (-2, 1e7), NaN
 * included, is returned as it is. */
#define DENOISE_SNAP 1e-3f
__attribute__((always_inline)) static inline float denoise_snap(float p)
{
    if (!(p > -2.0f && p < 1e7f))
        return p;
    const float nearest = (float)((int)(p + 2.5f) - 2);
    const float d = p - nearest;
    return d < DENOISE_SNAP && d > -DENOISE_SNAP ? nearest : p;
}

/* min and max of finite floats, inline (fminf / fmaxf stay library calls without -ffinite-math-only) */
#define MINF(a, b) ((a) < (b) ? (a) : (b))
#define MAXF(a, b) ((a) > (b) ? (a) : (b))

#endif
