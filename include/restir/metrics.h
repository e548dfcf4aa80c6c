/* restir/metrics.h: image error metrics against a reference, defined once for the whole project
 * (DESIGN.md "Metrics"). Images are interleaved RGB floats, row-major.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_METRICS_H
#define RESTIR_METRICS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct restir_error {
    double relmse; /* mean over pixels and channels of (I - R)^2 / (R^2 + 1e-3) */
    double mape;   /* 004: mean over pixels and channels of |I - R| / (R + 0.01 mean(R)) */
    double smape;  /* 000 footnote 3: 100 mean over pixels of |I - R| / (|I| + |R| + 1e-4), luminance */
    double luma_rmse; /* sqrt(mean over pixels of (lum(I) - lum(R))^2) */
};

/* Computes all metrics over n_pixels RGB pixels; mask (may be NULL) selects pixels with nonzero
 * entries. Returns 0, or -1 if no pixel is selected. */
int restir_error_compute(const float *image, const float *reference, size_t n_pixels,
                         const unsigned char *mask, struct restir_error *out);

/* out[i] = L(image pixel i) in double, the luminance SMAPE and luma RMSE use. */
void restir_luminance_image(const float *image, size_t n_pixels, double *out);
/* SMAPE of an image given as its luminance (restir_luminance_image) against an RGB reference:
 * exactly (bit for bit) restir_error_compute's smape of that image. Returns 0, or -1 if no pixel
 * is selected. */
int restir_smape_luminance(const double *luminance, const float *reference, size_t n_pixels,
                           const unsigned char *mask, double *smape);

/* The per-pixel terms of MAPE: out[i] = mean over channels of |I - R| / (R + 0.01 mean(R)), so
 * the mean of out over the image is restir_error's mape (heat maps of reports). */
void restir_error_map_mape(const float *image, const float *reference, size_t n_pixels, float *out);

/* 002 Figure 7's gradient images as a number: the relMSE of estimated forward differences
 * dx[a] = F(a + x) - F(a), dy[a] = F(a + y) - F(a) (RGB per pixel, as the gradient methods store
 * them) against the reference's own, mean over the pairs inside the image and channels of
 * (G - (R_b - R_a))^2 / (((R_a + R_b) / 2)^2 + 1e-3): relMSE's form, with the pair's mean as R.
 * The paper shows the images only; this is our measure of them. NaN for NULL inputs or an image
 * with no pair. */
double restir_gradient_relmse(const float *dx, const float *dy, const float *reference, int width, int height);

/* Text with the definitions above, for --help. */
const char *restir_metrics_help(void);

/* Correlation metrics (000 Appendix A) and hard pixels (000 Sec. 7). Images here are scalar
 * luminance, one float per pixel, row-major; sums in double precision. The undefined cases
 * (fewer than 2 runs, bad sizes, no pixel to average) return NaN. */

/* 000 Eq. 16 and Appendix A: average relative covariance. runs holds n_runs >= 2 independent
 * luminance images, run-major (runs[n * w * h + i]). With z_ni = (I_ni - mean_i) / (mean_i + eps)
 * and mean_i the sample mean over the runs, r_ij = 1/(N-1) sum_n z_ni z_nj is averaged over the
 * in-image pixels j != i with |j - i|^2 <= radius^2 (the "radial relative covariance"; j is not
 * masked), then over the pixels i with mask[i] != 0 (mask may be NULL: all pixels) that have at
 * least one such j. Returns that mean; the paper uses radius 8 and eps = 1e-4. */
double restir_spatial_covariance(const float *runs, int n_runs, int width, int height, int radius, float eps,
                                 const unsigned char *mask);

/* 000 Eq. 17: relative autocovariance at lag T. seq holds n_runs >= 2 independent sequences of
 * `frames` luminance images: seq[((size_t)n * frames + t) * w * h + i]. a_i^(t) = 1/(N-1)
 * sum_n z_ni^(t) z_ni^(t+lag), z as above per frame, averaged over the masked pixels (mask may be
 * NULL) and over t = 0 .. frames - 1 - lag (0 <= lag < frames; lag 0 gives the mean relative
 * variance). The paper uses lag 3. */
double restir_temporal_autocovariance(const float *seq, int n_runs, int frames, int width, int height, int lag,
                                      float eps, const unsigned char *mask);

/* 000 Sec. 7 hard pixels. A valid pixel's ratio is the fraction of the valid pixels j != i with
 * |j - i|^2 <= radius^2 that pass restir_bitterli_compatible (000 Eq. 7) with the pixel as center
 * (0 if it has no valid neighbor). The round(fraction * valid) valid pixels (halves rounded up)
 * with the lowest ratios, ties broken by lower pixel index, are marked 1 in mask_out; all others
 * and invalid pixels 0. normals: 3 floats per pixel; depth: 1 per pixel; valid: 1 byte per pixel
 * (NULL = all valid). ratio_out (may be NULL) receives each pixel's ratio (-1 for invalid pixels).
 * The paper uses radius 30, normal_min 0.5, depth_max 0.1, fraction 0.1. Returns the number of
 * hard pixels, or -1 for NULL normals/depth/mask_out, sizes <= 0, radius < 0 or no memory. */
int restir_hard_pixels(const float *normals, const float *depth, const unsigned char *valid, int width, int height,
                       float radius, float normal_min, float depth_max, float fraction, unsigned char *mask_out,
                       float *ratio_out);

#ifdef __cplusplus
}
#endif

#endif
