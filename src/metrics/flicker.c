/* flicker.c: flicker of a static camera's frames at a block scale and the boiling index built from
 * it (restir/metrics.h). Serial code (librestir does not link OpenMP). Must never depend on src/
 * headers, a ray tracer, files or the renderer. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "restir/metrics.h"

#define FLICKER_EPS 1e-3 /* relMSE's: the squared reference block mean is never divided by 0 */

/* Block means of one luminance image into out[by * bw + bx] (blocks of block x block pixels, bw x bh
 * of them from the top-left corner). */
static void block_means(const float *img, int width, int block, int bw, int bh, double *out)
{
    const double inv = 1.0 / ((double)block * (double)block);
    for (int by = 0; by < bh; by++)
        for (int bx = 0; bx < bw; bx++) {
            double sum = 0.0;
            for (int y = by * block; y < (by + 1) * block; y++) {
                const float *row = img + (size_t)y * (size_t)width + (size_t)bx * (size_t)block;
                for (int x = 0; x < block; x++)
                    sum += (double)row[x];
            }
            out[(size_t)by * (size_t)bw + (size_t)bx] = sum * inv;
        }
}

double restir_metrics_flicker(const float *seq, int n_runs, int frames, int width, int height,
                              const float *reference, int block, int norm_block)
{
    if (!seq || !reference || n_runs < 1 || frames < 2 || width <= 0 || height <= 0 || block < 1 ||
        norm_block < block || norm_block % block != 0 || norm_block > width || norm_block > height)
        return NAN;
    const size_t npix = (size_t)width * (size_t)height;
    if (npix > SIZE_MAX / sizeof(float) / (size_t)frames / (size_t)n_runs)
        return NAN;
    /* only whole normalisation blocks count, so every block size sees the same pixels */
    const int nw = width / norm_block, nh = height / norm_block, per = norm_block / block;
    const int bw = nw * per, bh = nh * per;
    const size_t nb = (size_t)bw * (size_t)bh;
    double *ref = malloc((size_t)nw * (size_t)nh * sizeof *ref), *cur = malloc(nb * sizeof *cur);
    double *mean = malloc(nb * sizeof *mean), *m2 = malloc(nb * sizeof *m2);
    if (!ref || !cur || !mean || !m2) {
        free(ref);
        free(cur);
        free(mean);
        free(m2);
        return NAN;
    }
    block_means(reference, width, norm_block, nw, nh, ref);
    double total = 0.0;
    for (int n = 0; n < n_runs; n++) {
        /* Welford over the frames, per block: each run about its own temporal mean */
        for (size_t b = 0; b < nb; b++)
            mean[b] = m2[b] = 0.0;
        for (int t = 0; t < frames; t++) {
            block_means(seq + ((size_t)n * (size_t)frames + (size_t)t) * npix, width, block, bw, bh, cur);
            for (size_t b = 0; b < nb; b++) {
                const double d = cur[b] - mean[b];
                mean[b] += d / (double)(t + 1);
                m2[b] += d * (cur[b] - mean[b]);
            }
        }
        for (int by = 0; by < bh; by++)
            for (int bx = 0; bx < bw; bx++) {
                const double r = ref[(size_t)(by / per) * (size_t)nw + (size_t)(bx / per)];
                total += m2[(size_t)by * (size_t)bw + (size_t)bx] / (double)(frames - 1) / (r * r + FLICKER_EPS);
            }
    }
    free(ref);
    free(cur);
    free(mean);
    free(m2);
    return total / ((double)nb * (double)n_runs);
}

double restir_metrics_boiling_index(double flicker_1, double flicker_16)
{
    return 256.0 * flicker_16 / flicker_1;
}
