/* synthetic_domains.h: synthetic 1-D domains on [0,1) for the GRIS tests: linear densities, inverse-CDF sampling,
 * shifts T (identity / affine / quadratic, 004 Eq. 5), T^{-1}. Must never depend on Embree, files or the renderer. */
#ifndef RESTIR_TEST_SYNTHETIC_DOMAINS_H
#define RESTIR_TEST_SYNTHETIC_DOMAINS_H

#include <math.h>

enum synthetic_shift_kind { SHIFT_IDENTITY, SHIFT_AFFINE, SHIFT_QUADRATIC };

/* One source domain Omega_k = [0,1) with its shift T_k: Omega_k -> Omega_0 into the target domain.
 * The tables (and the target functions that read zero_lo / zero_hi) stay in each test. */
struct synthetic_domain {
    enum synthetic_shift_kind kind;
    double a, b;             /* T(x) = a x + b (affine) or a x^2 + b (quadratic), a > 0 */
    double fail_lo, fail_hi; /* T undefined for x in [fail_lo, fail_hi) */
    double zero_lo, zero_hi; /* the domain's source target vanishes on [zero_lo, zero_hi) */
    double pdf_a, pdf_b;     /* density p(x) = pdf_a + pdf_b x on [0,1), pdf_a + pdf_b / 2 = 1 */
};

/* 1 where the source target of d is 0 by construction: x outside [0,1) or in [zero_lo, zero_hi). */
static inline int synthetic_target_vanishes(const struct synthetic_domain *d, double x)
{
    return x < 0.0 || x >= 1.0 || (x >= d->zero_lo && x < d->zero_hi);
}

static inline double synthetic_pdf(const struct synthetic_domain *d, double x) { return d->pdf_a + d->pdf_b * x; }

/* Inverse CDF of a + b x on [0,1): solves a x + b x^2 / 2 = u in the cancellation-free form. */
static inline double synthetic_pdf_sample(const struct synthetic_domain *d, float u)
{
    double a = d->pdf_a, b = d->pdf_b, uu = (double)u;
    double x = 2.0 * uu / (a + sqrt(a * a + 2.0 * b * uu));
    return x < 1.0 ? x : nextafter(1.0, 0.0);
}

/* The formula of T alone, a x + b or a x^2 + b, without the checks of synthetic_shift_fwd (the
 * identity rows of the tables have a = 1, b = 0, so it is x there). */
static inline double synthetic_shift_map(const struct synthetic_domain *d, double x)
{
    return d->kind == SHIFT_QUADRATIC ? d->a * x * x + d->b : d->a * x + d->b;
}

/* |dT/dx| at x for the affine and quadratic kinds. */
static inline double synthetic_shift_jacobian(const struct synthetic_domain *d, double x)
{
    return d->kind == SHIFT_AFFINE ? d->a : 2.0 * d->a * x;
}

/* T_k (004 Eq. 5). Returns 0 where T_k is undefined, else 1 with y and |dT_k/dx|. */
static inline int synthetic_shift_fwd(const struct synthetic_domain *d, double x, double *y, double *jac)
{
    if (d->kind == SHIFT_IDENTITY) {
        *y = x;
        *jac = 1.0;
        return 1;
    }
    if (x < 0.0 || x >= 1.0 || (x >= d->fail_lo && x < d->fail_hi))
        return 0;
    double v = synthetic_shift_map(d, x);
    if (v < 0.0 || v >= 1.0)
        return 0;
    *y = v;
    *jac = synthetic_shift_jacobian(d, x);
    return 1;
}

/* T_k^{-1}: returns 0 where y is not in the image of T_k, else 1 with x = T_k^{-1}(y) and
 * |dT_k/dx| at x (so |dT_k^{-1}/dy| = 1 / jac, the factor of 004 Eq. 10). */
static inline int synthetic_shift_inv(const struct synthetic_domain *d, double y, double *x, double *jac)
{
    if (y < 0.0 || y >= 1.0)
        return 0;
    if (d->kind == SHIFT_IDENTITY) {
        *x = y;
        *jac = 1.0;
        return 1;
    }
    double v = (y - d->b) / d->a;
    if (d->kind == SHIFT_QUADRATIC) {
        if (v < 0.0)
            return 0;
        v = sqrt(v);
    }
    if (v < 0.0 || v >= 1.0 || (v >= d->fail_lo && v < d->fail_hi))
        return 0;
    *x = v;
    *jac = synthetic_shift_jacobian(d, v);
    return 1;
}

#endif
