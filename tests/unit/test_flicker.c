/* test_flicker.c: unit tests of the flicker metric and the boiling index (restir/metrics.h, issue
 * 58): a hand-computed case, a still sequence, runs with different levels, independent per-pixel
 * noise (index about 1) and noise shared by 16 x 16 blotches (index 256), and refused arguments.
 * Must never depend on Embree or files. */
#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "restir/metrics.h"
#include "test_util.h"

/* 2 x 2 pixels, 1 run, 3 frames; reference 1 everywhere. Pixel 0 takes 1, 2, 3 (variance 1), the
 * others stay 1. Block 1: mean over pixels of var / (1 + 1e-3) = 0.25 / 1.001. Block 2: the block mean
 * takes 1.0, 1.25, 1.5 (variance 1/16), so 0.0625 / 1.001. */
static void test_hand(void)
{
    float seq[12] = {1, 1, 1, 1, 2, 1, 1, 1, 3, 1, 1, 1};
    const float ref[4] = {1, 1, 1, 1};
    EXPECT_NEAR(restir_metrics_flicker(seq, 1, 3, 2, 2, ref, 1, 2), 0.25 / 1.001, 1e-12, "block 1");
    EXPECT_NEAR(restir_metrics_flicker(seq, 1, 3, 2, 2, ref, 2, 2), 0.0625 / 1.001, 1e-12, "block 2");
    /* a reference twice as bright quarters it (R_b^2 + 1e-3) */
    const float ref2[4] = {2, 2, 2, 2};
    EXPECT_NEAR(restir_metrics_flicker(seq, 1, 3, 2, 2, ref2, 1, 2), 0.25 / 4.001, 1e-12, "reference 2");
    /* a 3 x 3 image at block 2 keeps one block (the last column and row are left out) */
    float s9[18] = {0};
    const float r9[9] = {1, 1, 1, 1, 1, 1, 1, 1, 1};
    s9[9 + 8] = 5.0f; /* the bottom-right pixel, outside the block, flickers */
    EXPECT_NEAR(restir_metrics_flicker(s9, 1, 2, 3, 3, r9, 2, 2), 0.0, 0.0, "the edge outside every block");
}

/* A still sequence does not flicker; two runs at different constant levels neither: each run is
 * measured about its own temporal mean. */
static void test_still(void)
{
    float seq[2 * 4 * 4];
    for (int k = 0; k < 32; k++)
        seq[k] = k < 16 ? 1.0f : 2.0f; /* run 0: 1, run 1: 2, 4 frames of 2 x 2 */
    const float ref[4] = {1.5f, 1.5f, 1.5f, 1.5f};
    EXPECT_NEAR(restir_metrics_flicker(seq, 2, 4, 2, 2, ref, 1, 2), 0.0, 0.0, "still runs");
}

/* I = 0.5 + u, u uniform: variance 1/12 per pixel and frame against a reference of 1. Independent
 * pixels: flicker(1) ~ 1/12.012, flicker(16) ~ flicker(1) / 256, boiling index ~ 1. Blotches: one
 * value per 16 x 16 block and frame: flicker(16) = flicker(1) exactly, index 256. */
static void test_noise_and_blotches(void)
{
    const int w = 64, h = 64, frames = 24, runs = 2;
    const size_t npix = (size_t)w * h, n = (size_t)runs * frames * npix;
    float *white = malloc(n * sizeof *white), *blot = malloc(n * sizeof *blot), *ref = malloc(npix * sizeof *ref);
    pcg32 rng = pcg32_make(58u, 3u);
    for (size_t k = 0; k < n; k++)
        white[k] = 0.5f + pcg32_float(&rng);
    for (size_t img = 0; img < (size_t)runs * frames; img++) {
        float v[16];
        for (int b = 0; b < 16; b++)
            v[b] = 0.5f + pcg32_float(&rng);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                blot[img * npix + (size_t)y * w + x] = v[(y / 16) * 4 + x / 16];
    }
    for (size_t i = 0; i < npix; i++)
        ref[i] = 1.0f;
    const double f1 = restir_metrics_flicker(white, runs, frames, w, h, ref, 1, 16);
    const double f4 = restir_metrics_flicker(white, runs, frames, w, h, ref, 4, 16);
    const double f16 = restir_metrics_flicker(white, runs, frames, w, h, ref, 16, 16);
    const double expect = (1.0 / 12.0) / 1.001;
    EXPECT(fabs(f1 - expect) < 0.03 * expect, "independent noise, block 1: %g", f1);
    EXPECT(fabs(16.0 * f4 - expect) < 0.1 * expect, "independent noise, block 4: %g", f4);
    /* 16 blocks x 2 runs x 23 degrees of freedom: the index's relative spread is about 0.05 */
    const double bi = restir_metrics_boiling_index(f1, f16);
    EXPECT(bi > 0.75 && bi < 1.3, "independent noise: boiling index %g, want about 1", bi);
    const double b1 = restir_metrics_flicker(blot, runs, frames, w, h, ref, 1, 16);
    const double b16 = restir_metrics_flicker(blot, runs, frames, w, h, ref, 16, 16);
    EXPECT(fabs(b16 - b1) < 1e-12 * b1, "blotches: block 16 %g, block 1 %g", b16, b1);
    EXPECT_NEAR(restir_metrics_boiling_index(b1, b16), 256.0, 1e-9, "blotches: index 256");
    /* an uneven image: pixel i's value R_i (0.5 + u), R_i from 0.05 to 20 over the image, and the same
     * as reference: each pixel's relative variance differs, yet the index stays about 1 because every
     * scale normalises by the 16 x 16 block's reference */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            ref[(size_t)y * w + x] = 0.05f * powf(400.0f, (float)((x * 7 + y * 13) % 64) / 63.0f);
    for (size_t k = 0; k < n; k++)
        white[k] = ref[k % npix] * (0.5f + pcg32_float(&rng));
    const double u1 = restir_metrics_flicker(white, runs, frames, w, h, ref, 1, 16);
    const double u16 = restir_metrics_flicker(white, runs, frames, w, h, ref, 16, 16);
    const double ub = restir_metrics_boiling_index(u1, u16);
    EXPECT(ub > 0.7 && ub < 1.4, "independent noise on an uneven image: boiling index %g, want about 1", ub);
    free(white);
    free(blot);
    free(ref);
}

static void test_refused(void)
{
    float seq[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    const float ref[4] = {1, 1, 1, 1};
    EXPECT(isnan(restir_metrics_flicker(NULL, 1, 2, 2, 2, ref, 1, 1)), "NULL seq");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 2, 2, NULL, 1, 1)), "NULL reference");
    EXPECT(isnan(restir_metrics_flicker(seq, 0, 2, 2, 2, ref, 1, 1)), "no run");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 1, 2, 2, ref, 1, 1)), "one frame");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 2, 2, ref, 0, 1)), "block 0");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 2, 2, ref, 2, 1)), "norm_block below block");
    float s36[2 * 36] = {0}, r36[36] = {0};
    EXPECT(isnan(restir_metrics_flicker(s36, 1, 2, 6, 6, r36, 2, 3)), "norm_block not a multiple of block");
    EXPECT_NEAR(restir_metrics_flicker(s36, 1, 2, 6, 6, r36, 2, 6), 0.0, 0.0, "6 x 6 at blocks 2 of 6");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 2, 2, ref, 3, 3)), "blocks larger than the image");
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 0, 2, ref, 1, 1)), "width 0");
    EXPECT_NEAR(restir_metrics_flicker(seq, 1, 2, 2, 2, ref, 1, 1), 0.0, 0.0, "valid call");
    seq[5] = NAN;
    EXPECT(isnan(restir_metrics_flicker(seq, 1, 2, 2, 2, ref, 1, 1)), "a NaN value");
}

int main(void)
{
    test_hand();
    test_still();
    test_noise_and_blotches();
    test_refused();
    return test_finish();
}
