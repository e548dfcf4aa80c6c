/* flip_color.c: FLIP's c_max, the ACES tone mapper's x_max and HDR-FLIP's exposure range (metrics/flip_internal.h,
 * which holds the per-pixel colour steps), written from Andersson et al. 2020 and 2021.
 * Must never depend on anything outside librestir (libm only). */
#include <math.h>
#include <stdlib.h>

#include "metrics/flip_internal.h"

double restir_flip_cmax(void)
{
    const float green[3] = {0.0f, 1.0f, 0.0f}, blue[3] = {0.0f, 0.0f, 1.0f};
    float lg[3], lb[3];
    restir_flip_rgb_to_lab_hunt(green, lg);
    restir_flip_rgb_to_lab_hunt(blue, lb);
    return pow((double)restir_flip_hyab(lg, lb), RESTIR_FLIP_QC);
}

double restir_flip_aces_xmax(void)
{
    /* (a - t d) x^2 + (b - t e) x - t f = 0, t = 0.85: a > t d, so the positive root takes the + sign */
    const double t = RESTIR_FLIP_Y_TARGET, qa = RESTIR_FLIP_ACES_A - t * RESTIR_FLIP_ACES_D,
                 qb = RESTIR_FLIP_ACES_B - t * RESTIR_FLIP_ACES_E, qc = -t * RESTIR_FLIP_ACES_F;
    return (-qb + sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);
}

static void swap_d(double *a, double *b)
{
    const double t = *a;
    *a = *b;
    *b = t;
}

static int cmp_double(const void *pa, const void *pb)
{
    const double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Element k (0-based) of v[0..n) sorted ascending, v reordered (no NaN in v). Hoare quickselect with a
 * median-of-three pivot; after 64 + 4 log2(n) rounds (an adversarial order) the rest is sorted by qsort. */
static double select_kth(double *v, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1, rounds = 64;
    for (size_t m = n; m > 1; m /= 2)
        rounds += 4;
    while (hi > lo) {
        if (rounds-- == 0) {
            qsort(v + lo, hi - lo + 1, sizeof(double), cmp_double);
            return v[k];
        }
        const size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < v[lo])
            swap_d(&v[mid], &v[lo]);
        if (v[hi] < v[lo])
            swap_d(&v[hi], &v[lo]);
        if (v[hi] < v[mid])
            swap_d(&v[hi], &v[mid]);
        const double pivot = v[mid];
        size_t i = lo, j = hi;
        for (;;) { /* v[lo] <= pivot <= v[hi] stop both scans inside [lo, hi] */
            while (v[i] < pivot)
                i++;
            while (v[j] > pivot)
                j--;
            if (i >= j)
                break;
            swap_d(&v[i], &v[j]);
            i++;
            j--;
        }
        /* now v[lo..j] <= pivot <= v[j+1..hi] */
        if (k <= j)
            hi = j;
        else
            lo = j + 1;
    }
    return v[k];
}

int restir_flip_exposures(const float *reference, size_t n_pixels, double *start, double *stop, int *count)
{
    double *y = malloc(sizeof(double) * (n_pixels ? n_pixels : 1));
    if (!y)
        return -1;
    size_t n = 0, positive = 0;
    double y_max = -INFINITY;
    for (size_t i = 0; i < n_pixels; i++) {
        const float *p = reference + 3 * i;
        const double l = 0.2126 * (double)p[0] + 0.7152 * (double)p[1] + 0.0722 * (double)p[2];
        if (!isfinite(l))
            continue;
        y[n++] = l;
        positive += l > 0.0;
        y_max = l > y_max ? l : y_max;
    }
    double y_median = n ? select_kth(y, n, n / 2) : 0.0;
    if (y_median <= 0.0 && positive > 0) { /* the median of the positive luminances instead */
        size_t m = 0;
        for (size_t i = 0; i < n; i++)
            if (y[i] > 0.0)
                y[m++] = y[i];
        y_median = select_kth(y, m, m / 2);
    }
    free(y);
    if (positive == 0) {
        *start = *stop = 0.0;
        *count = 2;
        return 0;
    }
    const double x_max = restir_flip_aces_xmax();
    *start = log2(x_max / y_max);
    *stop = log2(x_max / y_median);
    const double span = ceil(*stop - *start); /* at most ~300: finite float luminances span < 2^300 */
    *count = span > 2.0 ? (int)span : 2;
    return 0;
}
