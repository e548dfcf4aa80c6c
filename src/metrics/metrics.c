/* metrics.c: the project's image error metrics (relMSE, MAPE, SMAPE, luminance RMSE, gradient relMSE) as declared
 * in restir/metrics.h. Must never depend on src/ headers, a ray tracer, files or the renderer. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>

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
            relmse += d * d / (rv * rv + 1e-3);
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

double restir_metrics_gradient_relmse(const float *dx, const float *dy, const float *reference, int width, int height)
{
    if (!dx || !dy || !reference || width < 1 || height < 1 || (width < 2 && height < 2) ||
        (size_t)width > SIZE_MAX / (3 * sizeof(double)) / (size_t)height)
        return NAN;
    double sum = 0.0;
    size_t terms = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const size_t a = (size_t)y * (size_t)width + (size_t)x;
            for (int dir = 0; dir < 2; dir++) {
                if (dir == 0 ? x + 1 >= width : y + 1 >= height) /* the pair leaves the image */
                    continue;
                const size_t b = dir == 0 ? a + 1 : a + (size_t)width;
                const float *g = dir == 0 ? dx : dy;
                for (int c = 0; c < 3; c++) {
                    const double ra = (double)reference[3 * a + (size_t)c], rb = (double)reference[3 * b + (size_t)c];
                    const double d = (double)g[3 * a + (size_t)c] - (rb - ra), m = 0.5 * (ra + rb);
                    sum += d * d / (m * m + 1e-3);
                }
                terms += 3;
            }
        }
    return sum / (double)terms;
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
           "  L(x)      = 0.2126 x_r + 0.7152 x_g + 0.0722 x_b (Rec. 709 luminance)\n";
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
