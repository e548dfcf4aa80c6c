/* chi2_util.h: Pearson chi-square goodness-of-fit helpers for the statistical tests (the
 * chi-square survival function via the regularized incomplete gamma function, cell pooling).
 * Must never depend on renderer code: it is pure statistics. */
#ifndef RESTIR_TEST_CHI2_UTIL_H
#define RESTIR_TEST_CHI2_UTIL_H

#include <math.h>

/* Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a): the power series of
 * P(a, x) for x < a + 1 and the continued fraction for Q otherwise, evaluated with the modified
 * Lentz method (Press et al., Numerical Recipes 3rd ed., sec. 6.2; Lentz 1976). Each converges
 * fast in its own region. */
static inline double chi2_gamma_q(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    double log_prefix = -x + a * log(x) - lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 100000; n++) {
            term *= x / (a + n);
            sum += term;
            if (fabs(term) < fabs(sum) * 1e-16)
                break;
        }
        return 1.0 - sum * exp(log_prefix);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; i++) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (fabs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1.0) < 1e-16)
            break;
    }
    return exp(log_prefix) * h;
}

/* Probability that a chi-square variable with dof degrees of freedom exceeds stat. */
static inline double chi2_pvalue(double stat, int dof)
{
    if (!(stat < INFINITY)) /* infinite or NaN: reject */
        return 0.0;
    return chi2_gamma_q(0.5 * dof, 0.5 * stat);
}

/* Pearson statistic over n cells. Cells with expected count below 5 are pooled into one cell
 * (the usual validity rule for the chi-square approximation, Cochran 1954); if the pooled cell
 * is itself below 5 it is merged into the smallest remaining cell, so a handful of samples where
 * the expected count rounds to 0 (e.g. float ties at the horizon) is tolerated, while many of
 * them still blow up that cell's term. Returns the statistic and writes the degrees of
 * freedom (cells - 1, because the total count is fixed). */
static inline double chi2_pooled(const double *observed, const double *expected, int n, int *dof)
{
    double pool_o = 0.0, pool_e = 0.0, stat = 0.0;
    int cells = 0, smallest = -1;
    for (int i = 0; i < n; i++) {
        if (expected[i] < 5.0) {
            pool_o += observed[i];
            pool_e += expected[i];
        } else {
            if (smallest < 0 || expected[i] < expected[smallest])
                smallest = i;
        }
    }
    double merge_o = 0.0, merge_e = 0.0;
    if (pool_e >= 5.0) {
        double d = pool_o - pool_e;
        stat += d * d / pool_e;
        cells++;
    } else if (pool_e > 0.0 || pool_o > 0.0) {
        if (smallest < 0) {
            /* Nothing to merge into: only "impossible" observations can be judged. */
            *dof = 1;
            return pool_o > 0.0 && pool_e <= 0.0 ? INFINITY : 0.0;
        }
        merge_o = pool_o;
        merge_e = pool_e;
    }
    for (int i = 0; i < n; i++) {
        if (expected[i] < 5.0)
            continue;
        double o = observed[i], e = expected[i];
        if (i == smallest) {
            o += merge_o;
            e += merge_e;
        }
        double d = o - e;
        stat += d * d / e;
        cells++;
    }
    *dof = cells > 1 ? cells - 1 : 1;
    return stat;
}

/* Sidak-corrected per-test significance so that the family of num_tests tests rejects a
 * correct implementation with probability alpha overall. */
/* p-value of observed counts against probabilities prob[0..n) over `trials` draws (n <= 512),
 * cells with expected count < 5 pooled. */
static inline double chi2_counts(const double *observed, const double *prob, int n, double trials, int *dof)
{
    double expected[512];
    for (int i = 0; i < n; i++)
        expected[i] = prob[i] * trials;
    double stat = chi2_pooled(observed, expected, n, dof);
    return chi2_pvalue(stat, *dof);
}

static inline double chi2_sidak(double alpha, int num_tests) { return 1.0 - pow(1.0 - alpha, 1.0 / num_tests); }

#endif
