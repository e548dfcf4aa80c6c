/* accum.h: running sum / sum of squares of a Monte Carlo estimator, its mean and the sigma of that mean.
 * Must never depend on Embree, files or the renderer: it is pure statistics. */
#ifndef RESTIR_TEST_ACCUM_H
#define RESTIR_TEST_ACCUM_H

#include <math.h>

struct accum {
    double sum, sum2;
    long n;
};

static inline void acc_add(struct accum *a, double v)
{
    a->sum += v;
    a->sum2 += v * v;
    a->n++;
}

/* Adds the samples of b to a (per-chunk partial sums merged in a fixed order stay deterministic). */
static inline void acc_merge(struct accum *a, const struct accum *b)
{
    a->sum += b->sum;
    a->sum2 += b->sum2;
    a->n += b->n;
}

/* Sample mean; 0 for an empty accumulator. */
static inline double acc_mean(const struct accum *a) { return a->n > 0 ? a->sum / (double)a->n : 0.0; }

/* Standard error of the mean: sqrt(s^2 / n) with the unbiased sample variance s^2 (clamped at 0
 * against round-off); 0 for fewer than two samples. */
static inline double acc_sigma(const struct accum *a)
{
    if (a->n < 2)
        return 0.0;
    double m = acc_mean(a);
    double var = (a->sum2 / (double)a->n - m * m) * (double)a->n / (double)(a->n - 1);
    return sqrt(var > 0.0 ? var / (double)a->n : 0.0);
}

#endif
