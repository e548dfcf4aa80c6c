/* restir/metrics.h: image error metrics against a reference, as the papers define them, and the
 * correlation metrics of 000. Images are interleaved RGB floats, row-major.
 * Pixel values are taken as they are: negative ones count like any other, and a NaN or infinite one
 * makes the metrics it enters NaN or infinite (a broken image must not look converged). A count
 * of pixels whose 3 doubles per pixel overflow the address range is refused like a NULL pointer.
 * Nothing here aborts or writes to stdout or stderr. Every function is thread-safe, runs on the
 * calling thread and keeps no pointer past the call.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_METRICS_H
#define RESTIR_METRICS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct restir_metrics_error {
    double relmse; /* mean over pixels and channels of (I - R)^2 / (R^2 + 1e-3) */
    double mape;   /* 004: mean over pixels and channels of |I - R| / (R + 0.01 mean(R)) */
    double smape;  /* 000 footnote 3: 100 mean over pixels of |I - R| / (|I| + |R| + 1e-4), luminance */
    double luma_rmse; /* sqrt(mean over pixels of (lum(I) - lum(R))^2) */
};

/* Computes all metrics over n_pixels RGB pixels; mask (may be NULL) selects pixels with nonzero
 * entries. Returns 0, or -1 without writing if no pixel is selected (n_pixels = 0 included) or
 * image, reference or out is NULL. */
int restir_metrics_compute(const float *image, const float *reference, size_t n_pixels,
                         const unsigned char *mask, struct restir_metrics_error *out);

/* out[i] = L(image pixel i) in double, the luminance SMAPE and luma RMSE use. Returns 0 (n_pixels
 * = 0: nothing written), or -1 without writing for a NULL image or out. */
int restir_metrics_luminance(const float *image, size_t n_pixels, double *out);
/* SMAPE of an image given as its luminance (restir_metrics_luminance) against an RGB reference:
 * exactly (bit for bit) restir_metrics_compute's smape of that image. Returns 0, or -1 without
 * writing if no pixel is selected or luminance, reference or smape is NULL. */
int restir_metrics_smape_luminance(const double *luminance, const float *reference, size_t n_pixels,
                           const unsigned char *mask, double *smape);

/* The per-pixel terms of relMSE: out[i] = mean over channels of (I - R)^2 / (R^2 + 1e-3), so the mean
 * of out over the image is restir_metrics_error's relmse (per-block errors, the lag of
 * `restir compare`). Returns 0 (n_pixels = 0: nothing written), or -1 without writing for a NULL
 * image, reference or out or a count whose RGB arrays cannot be addressed. Any thread; reads and
 * writes only its arguments. */
int restir_metrics_relmse_map(const float *image, const float *reference, size_t n_pixels, float *out);

/* The per-pixel terms of MAPE: out[i] = mean over channels of |I - R| / (R + 0.01 mean(R)), so
 * the mean of out over the image is restir_metrics_error's mape (heat maps of reports). Returns 0
 * (n_pixels = 0: nothing written), or -1 without writing for a NULL image, reference or out. */
int restir_metrics_mape_map(const float *image, const float *reference, size_t n_pixels, float *out);

/* 002 Figure 7's gradient images as a number: the relMSE of estimated forward differences
 * dx[a] = F(a + x) - F(a), dy[a] = F(a + y) - F(a) (RGB per pixel, as the gradient methods store
 * them) against the reference's own, mean over the pairs inside the image and channels of
 * (G - (R_b - R_a))^2 / (((R_a + R_b) / 2)^2 + 1e-3): relMSE's form, with the pair's mean as R.
 * The paper shows the images only; this is our measure of them. NaN for NULL inputs, width or
 * height < 1, an image with no pair (1 x 1) or one too large to address. */
double restir_metrics_gradient_relmse(const float *dx, const float *dy, const float *reference, int width, int height);
/* Issue 42: restir_metrics_gradient_relmse as a trimmed mean, because ~1% of the pairs (single-pixel spikes on
 * dark surfaces, light edges: a small pair mean in the denominator) carry most of it. Each pair inside the image
 * is ranked by its three channels' terms summed (its whole share of the relMSE); a NaN or infinite sum ranks
 * above every finite one and equal sums rank the earlier pair first (row-major by a, the x pair (a, a + x)
 * before the y pair (a, a + y)). The first round(fraction * P) of the P pairs (halves rounded up) are left out
 * and the mean is over the other pairs' channels; fraction = 0 gives restir_metrics_gradient_relmse's exact
 * bits. We use fraction = 0.01. Dimensionless (G and R in the same radiance units); the inputs are only read,
 * on the calling thread, and a scratch buffer is freed before returning. NaN as restir_metrics_gradient_relmse,
 * and for a NaN, negative or >= 1 fraction, one that leaves no pair, a pair whose sum is NaN or infinite (a
 * broken image must not be trimmed into looking converged) and when a scratch allocation of 34 bytes per pixel
 * fails. */
double restir_metrics_gradient_relmse_trimmed(const float *dx, const float *dy, const float *reference, int width,
                                              int height, double fraction);
/* Where the pairs that restir_metrics_gradient_relmse_trimmed leaves out are: mask_out (width * height bytes,
 * caller-owned) gets, per pixel a, bit 0 set when the pair (a, a + x) is one of them and bit 1 when (a, a + y)
 * is; here a pair with a NaN or infinite sum is simply among the worst. Returns the number of pairs marked
 * (round(fraction * P)), or -1 without writing for NULL arguments, sizes or a fraction that
 * restir_metrics_gradient_relmse_trimmed refuses (a fraction leaving no pair is allowed here), or a failed
 * scratch allocation. */
long restir_metrics_gradient_worst_pairs(const float *dx, const float *dy, const float *reference, int width,
                                         int height, double fraction, unsigned char *mask_out);
/* Issue 42: gradient MAPE, robust to the pairs that dominate the relMSE: the mean over the pairs inside the
 * image and channels of |G - D| / (|D| + 0.01 mean|D|), D = R_b - R_a the reference's forward difference and
 * mean|D| the mean of |D| over those pairs and channels: the offset is 1% of the mean of the denominator's
 * quantity, as restir_metrics_error's mape (0.01 mean(R)), and a term with G == D counts 0 even where its
 * denominator is 0. A flat reference (every D = 0) therefore makes any error infinite, as a black reference
 * does for the image MAPE. NaN as restir_metrics_gradient_relmse. */
double restir_metrics_gradient_mape(const float *dx, const float *dy, const float *reference, int width, int height);

/* FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", 2020) and HDR-FLIP (Andersson et
 * al., "Visualizing Errors in Rendered High Dynamic Range Images", 2021): a per-pixel perceptual error in [0, 1]
 * (0: no visible difference) of a test image against a reference seen at ppd pixels per degree of visual angle,
 * and its mean. Written from the papers' definitions, in float32 as NVIDIA's FLIP is (with separable filters
 * and sums in its own order): per pixel within 1e-5 of a direct double-precision evaluation, not bit for bit
 * any other implementation.
 *
 * Images: interleaved linear RGB floats (sRGB / Rec. 709 primaries, D65), row-major, width x height; only read.
 * map_out (may be NULL; caller-owned, width x height floats) receives the per-pixel error; *mean_out (required)
 * its arithmetic mean, summed in double in pixel order. Scratch of about 60 bytes per pixel is allocated and freed
 * before returning. The image is split over rows between restir_threads_get() threads (restir/threads.h; one
 * below 16384 pixels); the result does not depend on the thread count. Both functions return 0, or -1 without
 * writing map_out or *mean_out for a NULL test, reference or mean_out, width or height < 1, a size whose scratch
 * overflows the address range, a ppd that is NaN, infinite, <= 0 or above RESTIR_METRICS_FLIP_PPD_MAX, or no
 * memory.
 *
 * Bad pixels: a NaN or infinite input value is read as NaN (never clamped into range), which the filters spread
 * over their support (up to ceil(0.135 ppd) pixels around it), so the map is NaN there and the mean is NaN: a
 * broken image does not look perfect. */

/* The default viewing condition of FLIP's tool: a 0.7 m wide 3840-pixel monitor seen from 0.7 m,
 * 3840 pi / 180 = 67.02 pixels per degree (restir_metrics_flip_ppd(0.7, 0.7, 3840)). */
#define RESTIR_METRICS_FLIP_PPD 67.02064327658226
/* The largest ppd the FLIP functions take (a 4K monitor seen from about 10 m): the filters grow with it. */
#define RESTIR_METRICS_FLIP_PPD_MAX 1000.0

/* Pixels per degree of a monitor monitor_width wide with resolution_x pixels across, seen from distance (any
 * length unit, the same for both): distance (resolution_x / monitor_width) pi / 180. NaN for a distance or width
 * that is not finite and > 0, or resolution_x < 1. */
double restir_metrics_flip_ppd(double distance, double monitor_width, int resolution_x);

/* LDR-FLIP (2020) of images whose values are taken as linear RGB in [0, 1] (each value clamped to it): colour
 * pipeline (YCxCz, contrast sensitivity filters, CIELAB with the Hunt adjustment, HyAB^0.7 remapped by c_max) and
 * feature pipeline (edges and points of the luminance), combined per pixel as dE_c^(1 - dE_f); see
 * restir_metrics_definitions(). Symmetric: swapping test and reference gives the same map. */
int restir_metrics_flip_ldr(const float *test, const float *reference, int width, int height, double ppd,
                            float *map_out, double *mean_out);

/* HDR-FLIP (2021) of linear radiance images: exposures e from start = log2(x_max / Y_max) to
 * stop = log2(x_max / Y_median), max(2, ceil(stop - start)) of them evenly spaced with both ends, taken from the
 * REFERENCE's luminance (x_max = 2.119..., where ACES reaches 0.85; Y_median element N / 2 of the sorted
 * luminances, zeros included); for each, both images are scaled by 2^e, tone-mapped by ACES and clamped to
 * [0, 1], and LDR-FLIP runs on the result; the map is the per-pixel maximum over the exposures. Not symmetric:
 * the exposures follow the reference. Our rules where the papers leave it undefined: negative values count as 0
 * (ACES would show large negative ones bright); exposures use the finite luminances only; a median <= 0 is
 * replaced by the median of the positive luminances; a reference with no positive luminance gets exposure 0
 * twice. Cost: one LDR-FLIP per exposure (often 5 to 15). */
int restir_metrics_flip(const float *test, const float *reference, int width, int height, double ppd, float *map_out,
                        double *mean_out);

/* The definitions above as plain text (a static string, one metric per line), for a program's
 * documentation or output. */
const char *restir_metrics_definitions(void);

/* Correlation metrics (000 Appendix A) and hard pixels (000 Sec. 7). Images here are scalar
 * luminance, one float per pixel, row-major; sums in double precision. The undefined cases
 * (a NULL image, fewer than 2 runs, bad sizes: <= 0 or too large to address, no pixel to average)
 * return NaN. A NaN or infinite luminance or eps that enters the averages (or a mean + eps of 0
 * there) makes the result NaN or infinite. */

/* 000 Eq. 16 and Appendix A: average relative covariance. runs holds n_runs >= 2 independent
 * luminance images, run-major (runs[n * w * h + i]). With z_ni = (I_ni - mean_i) / (mean_i + eps)
 * and mean_i the sample mean over the runs, r_ij = 1/(N-1) sum_n z_ni z_nj is averaged over the
 * in-image pixels j != i with |j - i|^2 <= radius^2 (the "radial relative covariance"; j is not
 * masked), then over the pixels i with mask[i] != 0 (mask may be NULL: all pixels) that have at
 * least one such j. Returns that mean; the paper uses radius 8 and eps = 1e-4. */
double restir_metrics_spatial_covariance(const float *runs, int n_runs, int width, int height, int radius, float eps,
                                 const unsigned char *mask);

/* 000 Eq. 17: relative autocovariance at lag T. seq holds n_runs >= 2 independent sequences of
 * `frames` luminance images: seq[((size_t)n * frames + t) * w * h + i]. a_i^(t) = 1/(N-1)
 * sum_n z_ni^(t) z_ni^(t+lag), z as above per frame, averaged over the masked pixels (mask may be
 * NULL) and over t = 0 .. frames - 1 - lag (0 <= lag < frames; lag 0 gives the mean relative
 * variance). The paper uses lag 3. */
double restir_metrics_temporal_autocovariance(const float *seq, int n_runs, int frames, int width, int height, int lag,
                                      float eps, const unsigned char *mask);

/* Flicker of a static camera's frames at block scale `block`: per run and block of
 * block x block pixels, the block's mean luminance in each frame and its variance over the frames
 * (1 / (frames - 1), about that run's own temporal mean), divided by (R^2 + 1e-3), R the reference's
 * mean over the norm_block x norm_block block that holds it (relMSE's normalisation, taken at one
 * scale for all block sizes); averaged over the blocks and the runs. Only whole norm_blocks from the
 * top-left corner count, so every block size sees the same pixels and independent per-pixel noise
 * gives flicker(s) = flicker(1) / s^2 in expectation, whatever the image; noise that moves s x s
 * pixels together (boiling) keeps flicker(s) near flicker(1). seq: n_runs >= 1 sequences of
 * `frames` >= 2 luminance images, seq[((size_t)n * frames + t) * w * h + i] (as
 * restir_metrics_temporal_autocovariance's); reference: one luminance image of w x h. A NaN value
 * makes it NaN. Returns NaN for NULL pointers, n_runs < 1, frames < 2, sizes <= 0, block < 1, a
 * norm_block that is not a multiple of block or is larger than the image, sizes whose images cannot
 * be addressed, or no memory. */
double restir_metrics_flicker(const float *seq, int n_runs, int frames, int width, int height,
                              const float *reference, int block, int norm_block);
/* The boiling index: 256 flicker(16) / flicker(1), both with norm_block 16: how many of a 16 x 16
 * block's pixels change together from frame to frame, about 1 for independent per-pixel noise, up
 * to 256 for blotches that cover whole blocks. NaN or infinite as the division gives it (flicker_1 =
 * 0: a still image). */
double restir_metrics_boiling_index(double flicker_1, double flicker_16);

/* 000 Sec. 7 hard pixels. A valid pixel's ratio is the fraction of the valid pixels j != i with
 * |j - i|^2 <= radius^2 that pass restir_neighbors_bitterli (000 Eq. 7) with the pixel as center
 * (0 if it has no valid neighbor). The round(fraction * valid) valid pixels (halves rounded up)
 * with the lowest ratios, ties broken by lower pixel index, are marked 1 in mask_out; all others
 * and invalid pixels 0. normals: 3 floats per pixel; depth: 1 per pixel; valid: 1 byte per pixel
 * (NULL = all valid). ratio_out (may be NULL) receives each pixel's ratio (-1 for invalid pixels).
 * The paper uses radius 30, normal_min 0.5, depth_max 0.1, fraction 0.1. A NaN or infinite
 * G-buffer value or threshold is read as restir_neighbors_bitterli reads it (a NaN fails the
 * test); radius may be +inf (the whole image); a NaN or negative fraction selects no pixel, one
 * >= 1 every valid one. Returns the number of hard pixels, or -1 without writing for NULL
 * normals/depth/mask_out, sizes <= 0, width * height > INT_MAX, a NaN or negative radius, or no
 * memory. */
int restir_metrics_hard_pixels(const float *normals, const float *depth, const unsigned char *valid, int width, int height,
                       float radius, float normal_min, float depth_max, float fraction, unsigned char *mask_out,
                       float *ratio_out);

/* Which neighbors a hard-pixel ratio counts. */
enum restir_hard_neighbors {
    RESTIR_HARD_NEIGHBORS_VALID = 0, /* the valid pixels only (restir_metrics_hard_pixels) */
    RESTIR_HARD_NEIGHBORS_ALL        /* every pixel of the disk inside the image, an invalid one (the sky)
                                        counting as failing Eq. 7: 000 Sec. 7's wording */
};
/* restir_metrics_hard_pixels with the ratio's neighbors counted as `counting` says: with
 * RESTIR_HARD_NEIGHBORS_ALL a valid pixel's ratio is the fraction of all pixels j != i of the disk
 * (clipped to the image) that are valid and pass Eq. 7, so a leaf against the sky is hard; ranking,
 * ties, arguments and returns as restir_metrics_hard_pixels (an unknown `counting` returns -1). */
int restir_metrics_hard_pixels_counting(const float *normals, const float *depth, const unsigned char *valid, int width,
                                        int height, float radius, float normal_min, float depth_max, float fraction,
                                        enum restir_hard_neighbors counting, unsigned char *mask_out, float *ratio_out);

#ifdef __cplusplus
}
#endif

#endif
