/* unbiased_util.h: the per-pixel unbiasedness check shared by render tests: K independently
 * seeded runs of a method against K runs of the path-traced reference, a Welch t-test per pixel
 * with a Sidak-corrected level, and a pooled whole-image z-test that sees small global biases.
 * Must never depend on a specific method: callers pass the images. */
#ifndef RESTIR_TEST_UNBIASED_UTIL_H
#define RESTIR_TEST_UNBIASED_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/vec3.h"

/* Running per-pixel mean and variance of luminance (Welford), over independent runs. */
struct pixel_stats {
    int n_pixels;
    int runs;
    double *mean, *m2;
    int *nonzero; /* runs in which the pixel's value was not 0 */
};

static inline void pixel_stats_init(struct pixel_stats *s, int n_pixels)
{
    s->n_pixels = n_pixels;
    s->runs = 0;
    s->mean = calloc((size_t)n_pixels, sizeof(double));
    s->m2 = calloc((size_t)n_pixels, sizeof(double));
    s->nonzero = calloc((size_t)n_pixels, sizeof(int));
}

static inline void pixel_stats_free(struct pixel_stats *s)
{
    free(s->mean);
    free(s->m2);
    free(s->nonzero);
}

static inline void pixel_stats_add(struct pixel_stats *s, const float *rgb)
{
    s->runs++;
    for (int i = 0; i < s->n_pixels; i++) {
        double v = v3_luminance(v3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]));
        double d = v - s->mean[i];
        s->mean[i] += d / s->runs;
        s->m2[i] += d * (v - s->mean[i]);
        s->nonzero[i] += v != 0.0;
    }
}

/* Two-sided standard normal quantile: z with P(|Z| > z) = alpha (bisection on erfc). With more
 * than 100 runs per side, Welch's t is normal to within the precision a test needs. */
static inline double normal_two_sided_quantile(double alpha)
{
    double lo = 0.0, hi = 40.0;
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (erfc(mid / sqrt(2.0)) > alpha)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

struct unbiased_report {
    int pixels_tested;
    int pixels_rare;      /* not judged: both sides saw fewer than UNBIASED_MIN_EVENTS nonzero runs */
    int pixels_failed;
    double worst_t;
    double pooled_z;      /* whole-image: sum of differences over its standard deviation */
    double mean_rel_bias; /* (sum method - sum reference) / sum reference */
};

/* Differences below this fraction of the reference's image-mean luminance count as agreement: at
 * 1e-9 no bias worth seeing hides under it, and it keeps rare-event pixels of essentially zero
 * radiance (1e-17 against an image mean of 0.1, seen on pillars' top rows with standard and spmis
 * reuse alike, where the method's runs never hit the event and have zero variance) from failing
 * a t-test whose variance estimate cannot see events that did not occur. */
#define UNBIASED_ABS_FLOOR 1e-9

/* A pixel whose value was nonzero in fewer runs than this on both sides is a rare event (e.g. a
 * jittered primary ray landing on a sliver that sees the light, 3e-7 against 3e-3 next to it on
 * cornell): a mean of a handful of heavy-tailed values is not near normal and the t-test's
 * variance estimate cannot see events that did not occur, so such pixels are counted, not
 * judged. A method that misses what the reference sees in this many runs is still caught. */
#define UNBIASED_MIN_EVENTS 10

/* Per-pixel Welch t-test at family-wise level alpha (Sidak over the tested pixels) and the pooled
 * z of the image sum. Pixels where both sides have zero variance are tested for equality. */
static inline struct unbiased_report unbiased_compare(const struct pixel_stats *a, const struct pixel_stats *b,
                                                      double alpha)
{
    struct unbiased_report r = {0, 0, 0, 0.0, 0.0, 0.0};
    double alpha_pixel = 1.0 - pow(1.0 - alpha, 1.0 / a->n_pixels);
    double t_crit = normal_two_sided_quantile(alpha_pixel);
    double sum_d = 0.0, sum_var = 0.0, sum_a = 0.0, sum_b = 0.0, ref_mean = 0.0;
    for (int i = 0; i < b->n_pixels; i++)
        ref_mean += b->mean[i] / b->n_pixels;
    for (int i = 0; i < a->n_pixels; i++) {
        double va = a->runs > 1 ? a->m2[i] / (a->runs - 1) : 0.0;
        double vb = b->runs > 1 ? b->m2[i] / (b->runs - 1) : 0.0;
        double se2 = va / a->runs + vb / b->runs;
        double d = a->mean[i] - b->mean[i];
        sum_d += d;
        sum_var += se2;
        sum_a += a->mean[i];
        sum_b += b->mean[i];
        if (a->nonzero[i] < UNBIASED_MIN_EVENTS && b->nonzero[i] < UNBIASED_MIN_EVENTS && d != 0.0) {
            r.pixels_rare++;
            continue;
        }
        r.pixels_tested++;
        if (fabs(d) <= UNBIASED_ABS_FLOOR * ref_mean)
            continue;
        if (se2 <= 0.0) {
            if (fabs(d) > 1e-6 * (fabs(a->mean[i]) + 1e-6)) {
                r.pixels_failed++;
            }
            continue;
        }
        double t = fabs(d) / sqrt(se2);
        if (t > r.worst_t)
            r.worst_t = t;
        if (t > t_crit) {
            r.pixels_failed++;
            printf("  pixel %d: method %.5g (sd %.3g), reference %.5g (sd %.3g), t %.2f\n", i, a->mean[i], sqrt(va),
                   b->mean[i], sqrt(vb), t);
        }
    }
    r.pooled_z = sum_var > 0.0 ? sum_d / sqrt(sum_var) : 0.0;
    r.mean_rel_bias = sum_b > 0.0 ? (sum_a - sum_b) / sum_b : 0.0;
    printf("  %d pixels (+%d rare-event pixels not judged), Sidak per-pixel |t| limit %.2f (family-wise alpha %.3g): "
           "%d failed, worst |t| %.2f; pooled z %.2f, relative bias of the image mean %+.4f%%\n",
           r.pixels_tested, r.pixels_rare, t_crit, alpha, r.pixels_failed, r.worst_t, r.pooled_z,
           100.0 * r.mean_rel_bias);
    return r;
}

#endif
