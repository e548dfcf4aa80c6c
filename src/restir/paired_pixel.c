/* paired_pixel.c: the paired-pixel (gradient-domain) reuse arithmetic (see restir/paired_pixel.h; 002 Eq. 13-26). */
#include <math.h>

#include "restir/paired_pixel.h"

float restir_grad_luminance(const float c[3]) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

float restir_grad_balance(float own, float other)
{
    if (!(own > 0.0f))
        return 0.0f;
    if (!(other > 0.0f))
        return 1.0f; /* shift undefined or the offset contributes nothing: the base covers alone */
    /* 1 / (1 + other / own): no overflow when own + other exceeds the float range */
    float w = 1.0f / (1.0f + other / own);
    return isfinite(w) ? w : 0.0f;
}

void restir_grad_one_sided(const float f_own[3], const float f_other[3], float out[3])
{
    float w = restir_grad_balance(restir_grad_luminance(f_own), restir_grad_luminance(f_other));
    for (int c = 0; c < 3; c++)
        out[c] = w > 0.0f ? w * (f_own[c] - f_other[c]) : 0.0f;
}

void restir_grad_pair_integrand(int k, const float f_own[3], const float f_other[3], float h[3])
{
    restir_grad_one_sided(f_own, f_other, h);
    if (k == 0) /* base in a: -(f_a - f_b) */
        for (int c = 0; c < 3; c++)
            h[c] = -h[c];
}

void restir_grad_part(enum restir_grad_sign s, const float h[3], float out[3])
{
    for (int c = 0; c < 3; c++) {
        float v = s == RESTIR_GRAD_NEG ? -h[c] : h[c];
        out[c] = s == RESTIR_GRAD_ABS ? v : fmaxf(v, 0.0f);
    }
}

float restir_grad_target(enum restir_grad_sign s, const float h[3])
{
    float a[3];
    if (s == RESTIR_GRAD_ABS) {
        for (int c = 0; c < 3; c++)
            a[c] = fabsf(h[c]);
    } else {
        restir_grad_part(s, h, a);
    }
    float t = restir_grad_luminance(a);
    return isfinite(t) ? t : 0.0f;
}

int restir_grad_edge(const struct restir_grad_edge_test *t, int valid_a, const float albedo_a[3],
                     const float n_a[3], float d_a, int valid_b, const float albedo_b[3], const float n_b[3],
                     float d_b)
{
    if (!valid_a || !valid_b)
        return valid_a != valid_b;
    float da = 0.0f;
    for (int c = 0; c < 3; c++)
        da = fmaxf(da, fabsf(albedo_a[c] - albedo_b[c]));
    if (da > t->albedo)
        return 1;
    if (n_a[0] * n_b[0] + n_a[1] * n_b[1] + n_a[2] * n_b[2] < t->normal)
        return 1;
    return d_a > 0.0f ? fabsf(d_a - d_b) / d_a > t->depth : d_a != d_b;
}
