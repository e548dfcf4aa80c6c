/* metrics.c: the project's image error metrics (relMSE, MAPE, SMAPE, luminance RMSE, gradient relMSE, trimmed and
 * MAPE) as declared in restir/metrics.h. Must never depend on src/ headers, a ray tracer, files or the renderer. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/metrics.h"

static double metrics_luminance(const float *p)
{
    return 0.2126 * (double)p[0] + 0.7152 * (double)p[1] + 0.0722 * (double)p[2];
}

static int metrics_selected(const unsigned char *mask, size_t i)
{
    return mask == NULL || mask[i] != 0;
}

/* 1 when n RGB pixels cannot be an array (3 n floats overflow the address range). */
static int metrics_too_many(size_t n_pixels)
{
    return n_pixels > SIZE_MAX / (3 * sizeof(double));
}

int restir_metrics_luminance(const float *image, size_t n_pixels, double *out)
{
    if (!image || !out || metrics_too_many(n_pixels))
        return -1;
    for (size_t i = 0; i < n_pixels; i++)
        out[i] = metrics_luminance(image + 3 * i);
    return 0;
}

/* SMAPE's per-pixel term, shared by restir_metrics_compute and restir_metrics_smape_luminance so that both
 * give the same bits. */
static double smape_term(double li, double lr)
{
    return fabs(li - lr) / (fabs(li) + fabs(lr) + 1e-4);
}

int restir_metrics_smape_luminance(const double *luminance, const float *reference, size_t n_pixels,
                           const unsigned char *mask, double *smape)
{
    if (!luminance || !reference || !smape || metrics_too_many(n_pixels))
        return -1;
    size_t count = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n_pixels; i++) {
        if (!metrics_selected(mask, i))
            continue;
        count++;
        sum += smape_term(luminance[i], metrics_luminance(reference + 3 * i));
    }
    if (count == 0)
        return -1;
    *smape = 100.0 * sum / (double)count;
    return 0;
}

/* One channel's relMSE term: (I - R)^2 / (R^2 + 1e-3). */
static inline double relmse_term(double image, double reference)
{
    const double d = image - reference;
    return d * d / (reference * reference + 1e-3);
}

int restir_metrics_compute(const float *image, const float *reference, size_t n_pixels,
                         const unsigned char *mask, struct restir_metrics_error *out)
{
    if (!image || !reference || !out || metrics_too_many(n_pixels))
        return -1;
    /* First pass: count selected pixels and the reference mean that MAPE's denominator uses. */
    size_t count = 0;
    double ref_sum = 0.0;
    for (size_t i = 0; i < n_pixels; i++) {
        if (!metrics_selected(mask, i))
            continue;
        count++;
        for (int c = 0; c < 3; c++)
            ref_sum += (double)reference[3 * i + (size_t)c];
    }
    if (count == 0)
        return -1;
    double ref_mean = ref_sum / (3.0 * (double)count);
    double mape_offset = 0.01 * ref_mean;

    double relmse = 0.0, mape = 0.0, smape = 0.0, luma_se = 0.0;
    for (size_t i = 0; i < n_pixels; i++) {
        if (!metrics_selected(mask, i))
            continue;
        const float *p = image + 3 * i;
        const float *r = reference + 3 * i;
        for (int c = 0; c < 3; c++) {
            double iv = (double)p[c], rv = (double)r[c];
            double d = iv - rv;
            relmse += relmse_term(iv, rv);
            /* An exact match contributes 0 even where the denominator vanishes. */
            if (d != 0.0)
                mape += fabs(d) / (rv + mape_offset);
        }
        double li = metrics_luminance(p), lr = metrics_luminance(r);
        double dl = li - lr;
        smape += smape_term(li, lr);
        luma_se += dl * dl;
    }
    double n = (double)count;
    out->relmse = relmse / (3.0 * n);
    out->mape = mape / (3.0 * n);
    out->smape = 100.0 * smape / n;
    out->luma_rmse = sqrt(luma_se / n);
    return 0;
}

/* The gradient metrics' shared argument check: 1 when the arguments describe an image with at least one pair. */
static int grad_args_ok(const float *dx, const float *dy, const float *reference, int width, int height)
{
    return dx && dy && reference && width >= 1 && height >= 1 && (width >= 2 || height >= 2) &&
           (size_t)width <= SIZE_MAX / (3 * sizeof(double)) / (size_t)height;
}

/* Pair slot p = 2 a + dir of pixel a = y w + x: dir 0 is (a, a + x), dir 1 is (a, a + y). 1 when that pair lies
 * inside the image (002's public code skips the last column's dx and the last row's dy the same way). */
static int grad_pair_inside(int x, int y, int dir, int width, int height)
{
    return dir == 0 ? x + 1 < width : y + 1 < height;
}

/* The pairs inside a width x height image in slot order p = 2 a + dir (row-major a, x pair first):
 *   for (struct grad_pairs it = {w, h, 0}; grad_pairs_next(&it, &a, &dir);) ... */
struct grad_pairs {
    int width, height;
    size_t next; /* the next slot to look at */
};

/* The next pair inside the image: 1 with its pixel *a and direction *dir, 0 when there is none left. */
static int grad_pairs_next(struct grad_pairs *it, size_t *a, int *dir)
{
    const size_t slots = 2 * (size_t)it->width * (size_t)it->height;
    while (it->next < slots) {
        const size_t p = it->next++, px = p / 2;
        const int d = (int)(p % 2);
        if (grad_pair_inside((int)(px % (size_t)it->width), (int)(px / (size_t)it->width), d, it->width, it->height)) {
            *a = px;
            *dir = d;
            return 1;
        }
    }
    return 0;
}

/* Channel c of pair (a, dir): the estimated difference G_c and the reference's R_bc - R_ac, and the pair's mean
 * (R_ac + R_bc) / 2. */
static void grad_channel(const float *dx, const float *dy, const float *reference, int width, size_t a, int dir, int c,
                         double *g, double *g_ref, double *mean)
{
    const size_t b = dir == 0 ? a + 1 : a + (size_t)width;
    const double ra = (double)reference[3 * a + (size_t)c], rb = (double)reference[3 * b + (size_t)c];
    *g = (double)(dir == 0 ? dx : dy)[3 * a + (size_t)c];
    *g_ref = rb - ra;
    *mean = 0.5 * (ra + rb);
}

/* One channel's gradient relMSE term (restir_metrics_gradient_relmse). */
static double grad_relmse_term(const float *dx, const float *dy, const float *reference, int width, size_t a, int dir,
                               int c)
{
    double g, g_ref, m;
    grad_channel(dx, dy, reference, width, a, dir, c, &g, &g_ref, &m);
    const double d = g - g_ref;
    return d * d / (m * m + 1e-3);
}

double restir_metrics_gradient_relmse(const float *dx, const float *dy, const float *reference, int width, int height)
{
    if (!grad_args_ok(dx, dy, reference, width, height))
        return NAN;
    double sum = 0.0;
    size_t terms = 0, a;
    int dir;
    for (struct grad_pairs it = {width, height, 0}; grad_pairs_next(&it, &a, &dir); terms += 3)
        for (int c = 0; c < 3; c++)
            sum += grad_relmse_term(dx, dy, reference, width, a, dir, c);
    return sum / (double)terms;
}

/* A pair's rank key: its relMSE terms summed over the channels, a NaN or infinite sum as +inf (the worst). */
static double grad_rank_key(double e)
{
    return isfinite(e) ? e : INFINITY;
}

static int grad_key_descending(const void *pa, const void *pb)
{
    const double a = *(const double *)pa, b = *(const double *)pb;
    return (a < b) - (a > b);
}

/* The worst pairs of restir_metrics_gradient_relmse_trimmed and restir_metrics_gradient_worst_pairs. Fills
 * worst[p] (2 w h slots, p = 2 a + dir) with 1 for the round(fraction * P) pairs (halves up) of the P inside the
 * image with the largest rank key, ties between equal keys going to the earlier slot, 0 for the others and the
 * slots of pairs outside the image; *pairs = P, *finite = 0 when some pair's sum is NaN or infinite. Returns the
 * number marked, or -1 (memory). The arguments are checked by the caller, fraction in [0, 1). */
static long grad_rank_worst(const float *dx, const float *dy, const float *reference, int width, int height,
                            double fraction, unsigned char *worst, size_t *pairs, int *finite)
{
    const size_t slots = 2 * (size_t)width * (size_t)height;
    double *key = malloc(sizeof(double) * slots), *sorted = malloc(sizeof(double) * slots);
    if (!key || !sorted) {
        free(key);
        free(sorted);
        return -1;
    }
    size_t n = 0, a;
    int dir;
    *finite = 1;
    memset(worst, 0, slots);
    for (size_t p = 0; p < slots; p++)
        key[p] = -INFINITY; /* below every pair's key: slots outside the image are never marked */
    for (struct grad_pairs it = {width, height, 0}; grad_pairs_next(&it, &a, &dir);) {
        const size_t p = 2 * a + (size_t)dir;
        double e = 0.0;
        for (int c = 0; c < 3; c++)
            e += grad_relmse_term(dx, dy, reference, width, a, dir, c);
        *finite &= isfinite(e) != 0;
        key[p] = grad_rank_key(e);
        sorted[n++] = key[p];
    }
    *pairs = n;
    const size_t k = (size_t)floor(fraction * (double)n + 0.5);
    if (k > 0) {
        qsort(sorted, n, sizeof(double), grad_key_descending);
        const double t = sorted[k - 1]; /* the k-th largest key: every key above it is marked */
        size_t above = 0;
        while (sorted[above] > t)
            above++;
        size_t ties = k - above; /* the keys equal to t to mark, the earliest slots first */
        for (size_t p = 0; p < slots; p++) {
            if (key[p] > t)
                worst[p] = 1;
            else if (key[p] == t && ties > 0) {
                worst[p] = 1;
                ties--;
            }
        }
    }
    free(key);
    free(sorted);
    return (long)k;
}

/* 1 when fraction is a share of pairs to leave out: in [0, 1). */
static int grad_fraction_ok(double fraction)
{
    return fraction >= 0.0 && fraction < 1.0;
}

double restir_metrics_gradient_relmse_trimmed(const float *dx, const float *dy, const float *reference, int width,
                                              int height, double fraction)
{
    if (!grad_args_ok(dx, dy, reference, width, height) || !grad_fraction_ok(fraction))
        return NAN;
    unsigned char *worst = malloc(2 * (size_t)width * (size_t)height);
    size_t pairs = 0;
    int finite = 1;
    const long k = worst ? grad_rank_worst(dx, dy, reference, width, height, fraction, worst, &pairs, &finite) : -1;
    if (k < 0 || !finite || (size_t)k >= pairs) { /* memory, a broken image (never trimmed away), no pair left */
        free(worst);
        return NAN;
    }
    /* the sum in restir_metrics_gradient_relmse's order and bits, the marked pairs left out */
    double sum = 0.0;
    size_t a;
    int dir;
    for (struct grad_pairs it = {width, height, 0}; grad_pairs_next(&it, &a, &dir);)
        if (!worst[2 * a + (size_t)dir])
            for (int c = 0; c < 3; c++)
                sum += grad_relmse_term(dx, dy, reference, width, a, dir, c);
    free(worst);
    return sum / (3.0 * (double)(pairs - (size_t)k));
}

long restir_metrics_gradient_worst_pairs(const float *dx, const float *dy, const float *reference, int width,
                                         int height, double fraction, unsigned char *mask_out)
{
    if (!grad_args_ok(dx, dy, reference, width, height) || !grad_fraction_ok(fraction) || !mask_out)
        return -1;
    const size_t npix = (size_t)width * (size_t)height;
    unsigned char *worst = malloc(2 * npix);
    size_t pairs = 0;
    int finite = 1;
    const long k = worst ? grad_rank_worst(dx, dy, reference, width, height, fraction, worst, &pairs, &finite) : -1;
    for (size_t a = 0; k >= 0 && a < npix; a++)
        mask_out[a] = (unsigned char)(worst[2 * a] | worst[2 * a + 1] << 1);
    free(worst);
    return k;
}

double restir_metrics_gradient_mape(const float *dx, const float *dy, const float *reference, int width, int height)
{
    if (!grad_args_ok(dx, dy, reference, width, height))
        return NAN;
    /* First pass: the mean |R_b - R_a| over the pairs and channels, whose 1% is the offset (as the image MAPE's
     * 0.01 mean(R): the mean of what the denominator holds). */
    double ref_sum = 0.0;
    size_t terms = 0;
    for (int pass = 0; pass < 2; pass++) {
        const double offset = pass ? 0.01 * ref_sum / (double)terms : 0.0;
        double sum = 0.0;
        size_t a;
        int dir;
        for (struct grad_pairs it = {width, height, 0}; grad_pairs_next(&it, &a, &dir);)
            for (int c = 0; c < 3; c++) {
                double g, g_ref, m;
                grad_channel(dx, dy, reference, width, a, dir, c, &g, &g_ref, &m);
                if (pass == 0) {
                    ref_sum += fabs(g_ref);
                    terms++;
                } else if (g != g_ref) /* as the image MAPE: an exact match is 0 where the offset is 0 */
                    sum += fabs(g - g_ref) / (fabs(g_ref) + offset);
            }
        if (pass)
            return sum / (double)terms;
    }
    return NAN; /* not reached */
}

const char *restir_metrics_definitions(void)
{
    return "Error metrics (image I against reference R; interleaved RGB; only pixels selected by\n"
           "the mask, if any; sums in double precision):\n"
           "  relMSE    = mean over pixels and channels c of (I_c - R_c)^2 / (R_c^2 + 1e-3)\n"
           "  MAPE      = mean over pixels and channels c of |I_c - R_c| / (R_c + 0.01 * mean(R)),\n"
           "              mean(R) = mean of R over all selected pixels and all three channels;\n"
           "              a channel with I_c == R_c contributes 0\n"
           "  SMAPE     = 100 * mean over pixels of |L(I) - L(R)| / (|L(I)| + |L(R)| + 1e-4)\n"
           "  luma RMSE = sqrt(mean over pixels of (L(I) - L(R))^2)\n"
           "  gradient relMSE (gradient methods, 002 Fig. 7) = mean over the pixel pairs (a, b = a + x)\n"
           "              and (a, b = a + y) inside the image and channels c of (G_c - (R_bc - R_ac))^2 /\n"
           "              (((R_ac + R_bc) / 2)^2 + 1e-3), G the estimated forward difference F(b) - F(a)\n"
           "  gradient relMSE trim 1% = the same mean without the worst 1% of the P pairs: the pairs are ranked\n"
           "              by their three channels' terms summed (NaN or infinite sums first, ties to the earlier\n"
           "              pair: row-major a, the x pair before the y pair) and the first round(0.01 P) (halves up)\n"
           "              are left out; the mean is over the other pairs' 3 (P - round(0.01 P)) terms; NaN when\n"
           "              some pair's sum is NaN or infinite (a broken image is not trimmed away)\n"
           "  gradient MAPE = mean over the same pairs and channels of |G_c - D_c| / (|D_c| + 0.01 * mean|D|),\n"
           "              D_c = R_bc - R_ac, mean|D| = mean of |D_c| over all pairs and channels (the image\n"
           "              MAPE's 1% of the mean of the denominator's quantity); a term with G_c == D_c is 0\n"
           "  FLIP      = mean over pixels of HDR-FLIP (Andersson et al. 2020, 2021) at 67.02 pixels per degree\n"
           "              (a 0.7 m wide 3840-pixel monitor seen from 0.7 m): per exposure e, both images times 2^e,\n"
           "              ACES-tone-mapped (negative values as 0) and clamped to [0, 1], then LDR-FLIP per pixel:\n"
           "              dE_c^(1 - dE_f), dE_c the HyAB^0.7 distance (remapped to [0, 1] by c_max = 41.28) of the\n"
           "              Hunt-adjusted CIELAB of both images filtered by the contrast sensitivity functions in YCxCz,\n"
           "              dE_f = sqrt(max(|edges(I) - edges(R)|, |points(I) - points(R)|) / sqrt 2) from Gaussian\n"
           "              derivative filters (sigma 0.041 degrees) of the luminance; the maximum over exposures\n"
           "              log2(2.119 / Y_max) to log2(2.119 / Y_median) of R, max(2, ceil(span)) of them; in [0, 1]\n"
           "  L(x)      = 0.2126 x_r + 0.7152 x_g + 0.0722 x_b (Rec. 709 luminance)\n";
}

int restir_metrics_relmse_map(const float *image, const float *reference, size_t n_pixels, float *out)
{
    if (!image || !reference || !out || metrics_too_many(n_pixels))
        return -1;
    for (size_t i = 0; i < n_pixels; i++) {
        double e = 0.0;
        for (int c = 0; c < 3; c++)
            e += relmse_term((double)image[3 * i + (size_t)c], (double)reference[3 * i + (size_t)c]);
        out[i] = (float)(e / 3.0);
    }
    return 0;
}

int restir_metrics_mape_map(const float *image, const float *reference, size_t n_pixels, float *out)
{
    if (!image || !reference || !out || metrics_too_many(n_pixels))
        return -1;
    double ref_sum = 0.0;
    for (size_t i = 0; i < 3 * n_pixels; i++)
        ref_sum += (double)reference[i];
    const double offset = n_pixels ? 0.01 * ref_sum / (3.0 * (double)n_pixels) : 0.0;
    for (size_t i = 0; i < n_pixels; i++) {
        double e = 0.0;
        for (int c = 0; c < 3; c++) {
            double d = (double)image[3 * i + (size_t)c] - (double)reference[3 * i + (size_t)c];
            if (d != 0.0) /* as restir_metrics_compute: an exact match is 0 where R + offset is 0 */
                e += fabs(d) / ((double)reference[3 * i + (size_t)c] + offset);
        }
        out[i] = (float)(e / 3.0);
    }
    return 0;
}
