/* restir/grad.h: the arithmetic of gradient-domain reuse (002), independent of what a path is:
 * the inner-shift MIS weight, one-sided differences, the paired-pixel integrand, its positivized
 * targets, and the G-buffer edge-pair test. Colours are RGB float triples.
 *
 * Sign convention. A pixel pair (a, b) has b = a's right (dx) or lower (dy) neighbor, and the
 * gradient images hold forward differences d_ab = F_b - F_a, the convention of the public 002 and
 * G-PT code. 002 Eq. 1 writes Delta_ab = F_a - F_b, so every quantity here is the paper's with the
 * opposite sign; the estimators are otherwise exactly the paper's.
 *
 * Paired-pixel domain (002 Sec. 4.2.1): X = (Omega_a x {0}) u (Omega_b x {1}). A sample (x, k)
 * has its base path x in pixel a (k = 0) or b (k = 1); the inner shift T moves x into the other
 * pixel of the pair. With f_own = f(x) in its pixel and f_other = f(T x) |T'| in the other pixel,
 *   h(x, 0) = -omega_ab(x) (f_a(x) - f_b(T x) |T'|)      (-omega* G of 002 Eq. 15-16, k = 0)
 *   h(x, 1) = +omega_ba(x) (f_b(x) - f_a(T x) |T'|)      (-omega* G, k = 1)
 * and d_ab = int_X h (002 Eq. 14). Per-sample code for C, C++ and CUDA device code (restir/hd.h);
 * thread-safe, no state. */
#ifndef RESTIR_GRAD_H
#define RESTIR_GRAD_H

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Rec. 709 luminance, the scalar every target and MIS weight reads. 0 for a NULL c. */
RESTIR_HD float restir_grad_luminance(const float c[3])
{
    return c ? 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2] : 0.0f;
}

/* Inner-shift MIS weight omega_ab(x) by the generalized balance heuristic (002 Eq. 13):
 * own = p_hat_a(x), other = p_hat_b(T x) |T'| (0 where T is undefined at x). Returns
 * own / (own + other), in [0, 1]; 0 when own is not positive (NaN included), so a one-sided term
 * vanishes wherever its pixel's target does (what makes 002 Eq. 11-12 unbiased with a ReSTIR
 * contribution weight, whose support is that of p_hat_a); 1 when other is not positive. For every
 * x in the shiftable set omega_ab(x) + omega_ba(T x) = 1. */
RESTIR_HD float restir_grad_balance(float own, float other)
{
    if (!(own > 0.0f))
        return 0.0f;
    if (!(other > 0.0f))
        return 1.0f; /* shift undefined or the offset contributes nothing: the base covers alone */
    /* 1 / (1 + other / own): no overflow when own + other exceeds the float range */
    float w = 1.0f / (1.0f + other / own);
    return restir_hd_finite(w) ? w : 0.0f;
}

/* One-sided difference without its contribution weight (002 Eq. 11 / Eq. 3's integrands):
 * out = omega(own, other) (f_own - f_other), omega from the luminances of the two. A NULL
 * argument leaves out untouched. */
RESTIR_HD void restir_grad_one_sided(const float f_own[3], const float f_other[3], float out[3])
{
    if (!f_own || !f_other || !out)
        return;
    float w = restir_grad_balance(restir_grad_luminance(f_own), restir_grad_luminance(f_other));
    for (int c = 0; c < 3; c++)
        out[c] = w > 0.0f ? w * (f_own[c] - f_other[c]) : 0.0f;
}

/* The paired-pixel integrand h(x, k) of the header comment (k = 0: base path in pixel a; else in
 * pixel b) from the two one-sided inputs. A NULL argument leaves h untouched. */
RESTIR_HD void restir_grad_pair_integrand(int k, const float f_own[3], const float f_other[3], float h[3])
{
    if (!f_own || !f_other || !h)
        return;
    restir_grad_one_sided(f_own, f_other, h);
    if (k == 0) /* base in a: -(f_a - f_b) */
        for (int c = 0; c < 3; c++)
            h[c] = -h[c];
}

/* Which part of h a reservoir estimates: all of it with target |h| (002 Eq. 19), or one sign of
 * it (positivization, 002 Eq. 23-26). */
enum restir_grad_sign { RESTIR_GRAD_ABS = 0, RESTIR_GRAD_POS, RESTIR_GRAD_NEG };

/* The part a reservoir of sign s integrates: h (ABS), max(h, 0) (POS) or max(-h, 0) (NEG),
 * per channel. Its target is restir_grad_target. A NULL argument leaves out untouched. */
RESTIR_HD void restir_grad_part(enum restir_grad_sign s, const float h[3], float out[3])
{
    if (!h || !out)
        return;
    for (int c = 0; c < 3; c++) {
        float v = s == RESTIR_GRAD_NEG ? -h[c] : h[c];
        out[c] = s == RESTIR_GRAD_ABS ? v : fmaxf(v, 0.0f);
    }
}

/* Target function: luminance of |h| per channel (Eq. 19), of max(h, 0) (Eq. 25) or of max(-h, 0)
 * (Eq. 26). Positive wherever the part is non-zero, as GRIS needs; 0 when it is not finite or h is
 * NULL. */
RESTIR_HD float restir_grad_target(enum restir_grad_sign s, const float h[3])
{
    if (!h)
        return 0.0f;
    float a[3];
    if (s == RESTIR_GRAD_ABS) {
        for (int c = 0; c < 3; c++)
            a[c] = fabsf(h[c]);
    } else {
        restir_grad_part(s, h, a);
    }
    float t = restir_grad_luminance(a);
    return restir_hd_finite(t) ? t : 0.0f;
}

/* G-buffer thresholds of 002 Sec. 4.3.2. */
struct restir_grad_edge_test {
    float albedo;  /* edge when max_c |albedo_a - albedo_b| > albedo (0.1) */
    float normal;  /* edge when n_a . n_b < normal (0.9). The paper's text says "> 0.9", which marks
                      every flat pair as an edge; its code and Figure 6 mark creases, so "<" */
    float depth;   /* edge when |d_a - d_b| / d_a > depth (0.1) */
};

/* 1 when pixels a and b differ by any of the three tests (an edge pixel pair), else 0. A pixel
 * without a hit (valid 0) differs from one with a hit; two misses are alike. A NULL t or G-buffer
 * pointer of a valid pixel makes the pair an edge. */
RESTIR_HD int restir_grad_edge(const struct restir_grad_edge_test *t, int valid_a, const float albedo_a[3],
                               const float n_a[3], float d_a, int valid_b, const float albedo_b[3],
                               const float n_b[3], float d_b)
{
    if (!valid_a || !valid_b)
        return valid_a != valid_b;
    if (!t || !albedo_a || !n_a || !albedo_b || !n_b)
        return 1;
    float da = 0.0f;
    for (int c = 0; c < 3; c++)
        da = fmaxf(da, fabsf(albedo_a[c] - albedo_b[c]));
    if (da > t->albedo)
        return 1;
    if (n_a[0] * n_b[0] + n_a[1] * n_b[1] + n_a[2] * n_b[2] < t->normal)
        return 1;
    return d_a > 0.0f ? fabsf(d_a - d_b) / d_a > t->depth : d_a != d_b;
}

#ifdef __cplusplus
}
#endif

#endif
