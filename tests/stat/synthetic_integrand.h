/* synthetic_integrand.h: the target-domain integrand of the synthetic GRIS tests on [0,1),
 * f_0(y) = 0.25 + sin^2(pi y) + a tent spike, with its closed-form integral. Must never depend on
 * Embree, files or the renderer. */
#ifndef RESTIR_TEST_SYNTHETIC_INTEGRAND_H
#define RESTIR_TEST_SYNTHETIC_INTEGRAND_H

#include <math.h>

#define SYNTHETIC_PI 3.14159265358979323846
#define SPIKE_C 0.8  /* tent centre */
#define SPIKE_H 0.03 /* tent half-width */
#define SPIKE_A 6.0  /* tent height: area SPIKE_A * SPIKE_H = 0.18 */

static inline double synthetic_tent(double y)
{
    double d = fabs(y - SPIKE_C);
    return d < SPIKE_H ? SPIKE_A * (1.0 - d / SPIKE_H) : 0.0;
}

static inline double synthetic_tent_cdf(double y)
{
    double lo = SPIKE_C - SPIKE_H, hi = SPIKE_C + SPIKE_H;
    if (y <= lo)
        return 0.0;
    if (y >= hi)
        return SPIKE_A * SPIKE_H;
    if (y <= SPIKE_C)
        return SPIKE_A * (y - lo) * (y - lo) / (2.0 * SPIKE_H);
    return SPIKE_A * SPIKE_H - SPIKE_A * (hi - y) * (hi - y) / (2.0 * SPIKE_H);
}

static inline double synthetic_sin2(double y)
{
    double s = sin(SYNTHETIC_PI * y);
    return s * s;
}

/* f_0 on [0,1), 0 outside. */
static inline double synthetic_f0(double y)
{
    return (y < 0.0 || y >= 1.0) ? 0.0 : 0.25 + synthetic_sin2(y) + synthetic_tent(y);
}

/* int_a^b f_0 for 0 <= a <= b <= 1, from the antiderivative 0.75 y - sin(2 pi y) / (4 pi) + tent CDF. */
static inline double synthetic_f0_int(double a, double b)
{
    const double k = 4.0 * SYNTHETIC_PI;
    double Fb = 0.75 * b - sin(2.0 * SYNTHETIC_PI * b) / k + synthetic_tent_cdf(b);
    double Fa = 0.75 * a - sin(2.0 * SYNTHETIC_PI * a) / k + synthetic_tent_cdf(a);
    return Fb - Fa;
}

#endif
