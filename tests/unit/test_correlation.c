/* test_correlation.c: unit tests of the correlation metrics (000 Appendix A, Eq. 16-17) and the
 * hard-pixel classification (000 Sec. 7) in restir/metrics.h: hand-computed tiny cases, a direct
 * evaluation of Eq. 16 on random data, noise with known (zero or perfect) correlation, and a
 * synthetic G-buffer. Must never depend on Embree or files. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "restir/metrics.h"
#include "test_util.h"

#define EPS 1e-4f

/* I = 0.5 + u, u uniform in [0,1): mean 1, variance 1/12, so relative variance 1/12. */
static void fill_noise(float *dst, size_t count, uint64_t seed)
{
    pcg32 rng = pcg32_make(seed, 11u);
    for (size_t k = 0; k < count; k++)
        dst[k] = 0.5f + pcg32_float(&rng);
}

/* Eq. 16 evaluated literally: every pair (i, j) in the disk, two passes per pixel for the mean. */
static double brute_spatial(const float *runs, int n_runs, int w, int h, int radius, float eps,
                            const unsigned char *mask)
{
    size_t np = (size_t)w * (size_t)h;
    double total = 0.0;
    int counted = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            if (mask && !mask[i])
                continue;
            double mi = 0.0;
            for (int n = 0; n < n_runs; n++)
                mi += runs[(size_t)n * np + i];
            mi /= n_runs;
            double sum = 0.0;
            int neighbors = 0;
            for (int yy = 0; yy < h; yy++)
                for (int xx = 0; xx < w; xx++) {
                    size_t j = (size_t)yy * (size_t)w + (size_t)xx;
                    if (j == i || (xx - x) * (xx - x) + (yy - y) * (yy - y) > radius * radius)
                        continue;
                    double mj = 0.0;
                    for (int n = 0; n < n_runs; n++)
                        mj += runs[(size_t)n * np + j];
                    mj /= n_runs;
                    double r = 0.0;
                    for (int n = 0; n < n_runs; n++)
                        r += (runs[(size_t)n * np + i] - mi) / (mi + eps) * ((runs[(size_t)n * np + j] - mj) / (mj + eps));
                    sum += r / (n_runs - 1);
                    neighbors++;
                }
            if (neighbors > 0) {
                total += sum / neighbors;
                counted++;
            }
        }
    return total / counted;
}

/* Mean over the masked pixels and frames t0 .. t1 - 1 of the per-pixel relative sample variance
 * 1/(N-1) sum_n ((I - mean) / (mean + eps))^2. */
static double mean_relvar(const float *seq, int n_runs, int frames, size_t np, int t0, int t1,
                          const unsigned char *mask)
{
    double total = 0.0;
    long count = 0;
    for (int t = t0; t < t1; t++)
        for (size_t i = 0; i < np; i++) {
            if (mask && !mask[i])
                continue;
            double m = 0.0, s = 0.0;
            for (int n = 0; n < n_runs; n++)
                m += seq[((size_t)n * (size_t)frames + (size_t)t) * np + i];
            m /= n_runs;
            for (int n = 0; n < n_runs; n++) {
                double z = (seq[((size_t)n * (size_t)frames + (size_t)t) * np + i] - m) / (m + EPS);
                s += z * z;
            }
            total += s / (n_runs - 1);
            count++;
        }
    return total / (double)count;
}

/* 3x1 image, 3 runs, eps = 0:
 *   pixel 0: (1, 2, 3)  mean 2  z = (-1/2, 0, 1/2)
 *   pixel 1: (2, 2, 5)  mean 3  z = (-1/3, -1/3, 2/3)
 *   pixel 2: (4, 0, 2)  mean 2  z = (1, -1, 0)
 * r_01 = (1/6 + 0 + 1/3) / 2 = 1/4, r_12 = (-1/3 + 1/3 + 0) / 2 = 0, r_02 = (-1/2 + 0 + 0) / 2 = -1/4.
 * Radius 1: radial covariances 1/4, (1/4 + 0) / 2 = 1/8, 0; mean 1/8; mask {1,1,0}: 3/16.
 * Radius 2: (1/4 - 1/4) / 2 = 0, 1/8, (-1/4 + 0) / 2 = -1/8; mean 0. */
static void test_spatial_hand(void)
{
    const float runs[9] = {1, 2, 4, /* run 0 */ 2, 2, 0, /* run 1 */ 3, 5, 2 /* run 2 */};
    EXPECT_NEAR(restir_metrics_spatial_covariance(runs, 3, 3, 1, 1, 0.0f, NULL), 0.125, 1e-14, "3x1 radius 1");
    const unsigned char first_two[3] = {1, 1, 0};
    EXPECT_NEAR(restir_metrics_spatial_covariance(runs, 3, 3, 1, 1, 0.0f, first_two), 0.1875, 1e-14, "3x1 masked");
    EXPECT_NEAR(restir_metrics_spatial_covariance(runs, 3, 3, 1, 2, 0.0f, NULL), 0.0, 1e-14, "3x1 radius 2");
    /* With eps, every z_i scales by mean_i / (mean_i + eps): r_01 = 1/4 * 2/(2+eps) * 3/(3+eps),
     * r_12 stays 0, and the mean is (r_01 + r_01 / 2 + 0) / 3 = r_01 / 2. */
    double e = (double)EPS;
    EXPECT_NEAR(restir_metrics_spatial_covariance(runs, 3, 3, 1, 1, EPS, NULL), 0.125 * (2.0 / (2.0 + e)) * (3.0 / (3.0 + e)),
                1e-14, "3x1 radius 1 eps");
    /* A large radius covers the whole row: same as radius 2. */
    EXPECT_NEAR(restir_metrics_spatial_covariance(runs, 3, 3, 1, 1000000, 0.0f, NULL), 0.0, 1e-14, "3x1 huge radius");

    /* 2x2 image, 2 runs (N - 1 = 1), eps = 0; pixels p0 (0,0) p1 (1,0) p2 (0,1) p3 (1,1):
     *   p0 (1, 3) z = (-1/2, 1/2); p1 (3, 1) z = (1/2, -1/2); p2 (2, 2) z = 0; p3 (1, 3) like p0.
     * r_01 = -1/2, r_13 = -1/2, r_03 = 1/2 (diagonal), every r with p2 = 0, r_12 = 0 (diagonal).
     * Radius 1 (no diagonals): p0 (r_01 + r_02) / 2 = -1/4, p1 (r_10 + r_13) / 2 = -1/2, p2 0,
     * p3 (r_31 + r_32) / 2 = -1/4: mean -1/4. Radius 2 (diagonals too): p0 (-1/2 + 0 + 1/2) / 3 = 0,
     * p1 (-1/2 + 0 - 1/2) / 3 = -1/3, p2 0, p3 (1/2 - 1/2 + 0) / 3 = 0: mean -1/12. */
    const float quad[8] = {1, 3, 2, 1, /* run 0 */ 3, 1, 2, 3 /* run 1 */};
    EXPECT_NEAR(restir_metrics_spatial_covariance(quad, 2, 2, 2, 1, 0.0f, NULL), -0.25, 1e-14, "2x2 radius 1");
    EXPECT_NEAR(restir_metrics_spatial_covariance(quad, 2, 2, 2, 2, 0.0f, NULL), -1.0 / 12.0, 1e-14, "2x2 radius 2");
    const unsigned char only_p1[4] = {0, 9, 0, 0};
    EXPECT_NEAR(restir_metrics_spatial_covariance(quad, 2, 2, 2, 1, 0.0f, only_p1), -0.5, 1e-14, "2x2 mask p1");

    /* Undefined cases. */
    const unsigned char none[3] = {0, 0, 0};
    EXPECT(isnan(restir_metrics_spatial_covariance(runs, 3, 3, 1, 1, 0.0f, none)), "empty mask");
    EXPECT(isnan(restir_metrics_spatial_covariance(runs, 3, 3, 1, 0, 0.0f, NULL)), "radius 0: no neighbors");
    EXPECT(isnan(restir_metrics_spatial_covariance(runs, 1, 3, 1, 1, 0.0f, NULL)), "one run");
    EXPECT(isnan(restir_metrics_spatial_covariance(runs, 3, 3, 1, -1, 0.0f, NULL)), "negative radius");
    EXPECT(isnan(restir_metrics_spatial_covariance(NULL, 3, 3, 1, 1, 0.0f, NULL)), "NULL runs");
}

/* One pixel, 3 runs, 2 frames, eps = 0 (seq[n * frames + t]):
 *   frame 0: (1, 2, 3) z = (-1/2, 0, 1/2); frame 1: (2, 2, 5) z = (-1/3, -1/3, 2/3).
 * Lag 1: a = (1/6 + 0 + 1/3) / 2 = 1/4. Lag 0: mean of (1/4 + 0 + 1/4) / 2 = 1/4 and
 * (1/9 + 1/9 + 4/9) / 2 = 1/3, i.e. 7/24. */
static void test_temporal_hand(void)
{
    const float seq[6] = {1, 2, /* run 0 */ 2, 2, /* run 1 */ 3, 5 /* run 2 */};
    EXPECT_NEAR(restir_metrics_temporal_autocovariance(seq, 3, 2, 1, 1, 1, 0.0f, NULL), 0.25, 1e-14, "lag 1");
    EXPECT_NEAR(restir_metrics_temporal_autocovariance(seq, 3, 2, 1, 1, 0, 0.0f, NULL), 7.0 / 24.0, 1e-14, "lag 0");
    EXPECT(isnan(restir_metrics_temporal_autocovariance(seq, 3, 2, 1, 1, 2, 0.0f, NULL)), "lag >= frames");
    EXPECT(isnan(restir_metrics_temporal_autocovariance(seq, 3, 2, 1, 1, -1, 0.0f, NULL)), "negative lag");
    EXPECT(isnan(restir_metrics_temporal_autocovariance(seq, 1, 2, 1, 1, 1, 0.0f, NULL)), "one run");
    const unsigned char none[1] = {0};
    EXPECT(isnan(restir_metrics_temporal_autocovariance(seq, 3, 2, 1, 1, 1, 0.0f, none)), "empty mask");
}

/* The prefix-sum evaluation against the literal Eq. 16 on random data with uneven means, with and
 * without a mask, and with radii larger than the image. */
static void test_spatial_brute(void)
{
    enum { W = 21, H = 13, N = 5 };
    static float runs[N * W * H];
    unsigned char mask[W * H];
    pcg32 rng = pcg32_make(77u, 3u);
    for (int i = 0; i < W * H; i++) {
        float scale = 0.01f + 3.0f * pcg32_float(&rng);
        for (int n = 0; n < N; n++)
            runs[n * W * H + i] = scale * pcg32_float(&rng) * pcg32_float(&rng);
        mask[i] = pcg32_float(&rng) < 0.4f;
    }
    runs[5] = runs[W * H + 5] = runs[2 * W * H + 5] = runs[3 * W * H + 5] = runs[4 * W * H + 5] = 0.0f; /* black */
    const int radii[5] = {1, 2, 3, 8, 30};
    for (int k = 0; k < 5; k++) {
        double got = restir_metrics_spatial_covariance(runs, N, W, H, radii[k], EPS, NULL);
        double want = brute_spatial(runs, N, W, H, radii[k], EPS, NULL);
        EXPECT(fabs(got - want) <= 1e-12 * (1.0 + fabs(want)), "radius %d: %.15g vs %.15g", radii[k], got, want);
        got = restir_metrics_spatial_covariance(runs, N, W, H, radii[k], EPS, mask);
        want = brute_spatial(runs, N, W, H, radii[k], EPS, mask);
        EXPECT(fabs(got - want) <= 1e-12 * (1.0 + fabs(want)), "masked radius %d: %.15g vs %.15g", radii[k], got, want);
    }
}

/* Independent noise: E[r_ij] = 0 for i != j. Each r_ij has variance about N s^4 / (N-1)^2 with
 * s^2 = 1/12 the relative variance; distinct pairs are uncorrelated and the image mean counts each
 * pair twice, so the standard error is about sqrt(2 N / (P K)) s^2 / (N - 1) for P pixels with K
 * neighbors on average (K = 172.6 here: 196 inside, fewer at the borders; 150 is used). We allow 5
 * of them. */
static void test_independent_noise(void)
{
    enum { W = 64, H = 48, N = 8, F = 7, LAG = 3 };
    const double relvar = 1.0 / 12.0;
    float *runs = malloc(sizeof(float) * N * W * H);
    fill_noise(runs, (size_t)N * W * H, 1001u);
    double cov = restir_metrics_spatial_covariance(runs, N, W, H, 8, EPS, NULL);
    double se = sqrt(2.0 * N / ((double)W * H * 150.0)) * relvar / (N - 1);
    EXPECT(fabs(cov) < 5.0 * se, "independent spatial covariance %.3g (5 SE = %.3g, relvar %.3g)", cov, 5.0 * se,
           relvar);
    free(runs);

    /* Independent frames: a_i^(t) has variance about N s^4 / (N-1)^2, uncorrelated over pixels
     * and the F - LAG frame pairs. */
    float *seq = malloc(sizeof(float) * N * F * W * H);
    fill_noise(seq, (size_t)N * F * W * H, 2002u);
    double auto_cov = restir_metrics_temporal_autocovariance(seq, N, F, W, H, LAG, EPS, NULL);
    double se_t = sqrt((double)N / ((double)W * H * (F - LAG))) * relvar / (N - 1);
    EXPECT(fabs(auto_cov) < 5.0 * se_t, "independent autocovariance %.3g (5 SE = %.3g)", auto_cov, 5.0 * se_t);
    /* Lag 0 is the mean relative variance: exactly the direct computation, and near 1/12 times
     * 1 + 3 s^2 / N = 1 + 1/32, the bias of dividing by the squared sample mean (E[1/m^2] ~
     * (1 + 3 Var(m)) for mean 1); the estimate's own spread is about 0.3%. */
    double lag0 = restir_metrics_temporal_autocovariance(seq, N, F, W, H, 0, EPS, NULL);
    EXPECT_NEAR(lag0, mean_relvar(seq, N, F, (size_t)W * H, 0, F, NULL), 1e-12, "lag 0 = relative variance");
    EXPECT_NEAR(lag0, relvar * (1.0 + 1.0 / 32.0), 0.02 * relvar, "lag 0 near 1/12 (1 + 1/32)");
    free(seq);
}

/* Every pixel of run n is 1 + c_n: z_ni = (c_n - mean c) / (1 + mean c + eps) is the same for all
 * pixels, so every r_ij is the relative variance S / (1 + mean c + eps)^2, S = sample variance of c. */
static void test_perfect_spatial(void)
{
    enum { W = 40, H = 30, N = 8 };
    static float runs[N * W * H];
    pcg32 rng = pcg32_make(4242u, 5u);
    double c[N], cm = 0.0;
    for (int n = 0; n < N; n++) {
        float v = 1.0f + pcg32_float(&rng);
        for (int i = 0; i < W * H; i++)
            runs[n * W * H + i] = v;
        c[n] = (double)v; /* 1 + c_n exactly as stored */
        cm += c[n] / N;
    }
    double s = 0.0;
    for (int n = 0; n < N; n++)
        s += (c[n] - cm) * (c[n] - cm) / (N - 1);
    double want = s / ((cm + (double)EPS) * (cm + (double)EPS));
    double got = restir_metrics_spatial_covariance(runs, N, W, H, 8, EPS, NULL);
    EXPECT(fabs(got - want) <= 1e-12 * want, "perfect spatial %.15g vs relvar %.15g", got, want);
    unsigned char mask[W * H];
    for (int i = 0; i < W * H; i++)
        mask[i] = (unsigned char)(i % 7 == 0);
    got = restir_metrics_spatial_covariance(runs, N, W, H, 3, EPS, mask);
    EXPECT(fabs(got - want) <= 1e-12 * want, "perfect spatial masked %.15g vs relvar %.15g", got, want);
}

/* Frames 0 .. LAG-1 are independent noise and frame t copies frame t - LAG: each a_i^(t) is pixel
 * i's relative sample variance at frame t. */
static void test_perfect_temporal(void)
{
    enum { W = 32, H = 24, N = 8, F = 7, LAG = 3, NP = W * H };
    float *seq = malloc(sizeof(float) * N * F * NP);
    for (int n = 0; n < N; n++) {
        fill_noise(seq + (size_t)n * F * NP, (size_t)LAG * NP, 3003u + (uint64_t)n);
        for (int t = LAG; t < F; t++)
            memcpy(seq + ((size_t)n * F + t) * NP, seq + ((size_t)n * F + t - LAG) * NP, sizeof(float) * NP);
    }
    double want = mean_relvar(seq, N, F, NP, 0, F - LAG, NULL);
    double got = restir_metrics_temporal_autocovariance(seq, N, F, W, H, LAG, EPS, NULL);
    EXPECT(fabs(got - want) <= 1e-12 * want, "perfect temporal %.15g vs relvar %.15g", got, want);
    /* Near 1/12 (1 + 1/32) as for lag 0 in test_independent_noise; 3 distinct frames of 768
     * pixels: spread about 1%. */
    EXPECT_NEAR(got, (1.0 + 1.0 / 32.0) / 12.0, 0.04 / 12.0, "perfect temporal near 1/12 (1 + 1/32)");

    unsigned char mask[NP];
    for (int i = 0; i < NP; i++)
        mask[i] = (unsigned char)(i % 5 == 1 ? 3 : 0);
    want = mean_relvar(seq, N, F, NP, 0, F - LAG, mask);
    got = restir_metrics_temporal_autocovariance(seq, N, F, W, H, LAG, EPS, mask);
    EXPECT(fabs(got - want) <= 1e-12 * want, "perfect temporal masked %.15g vs %.15g", got, want);

    /* Lag 2 pairs independent frames of this sequence: about 0 again. */
    got = restir_metrics_temporal_autocovariance(seq, N, F, W, H, 2, EPS, NULL);
    double se = sqrt((double)N / ((double)NP * (F - 2))) / 12.0 / (N - 1);
    EXPECT(fabs(got) < 5.0 * se, "lag 2 of the copy sequence %.3g (5 SE = %.3g)", got, 5.0 * se);
    free(seq);
}

/* 24x16 G-buffer: a plane (normal +z, depth 1) crossed by a one-pixel strip at x = 10 with
 * perpendicular normals (+x: dot 0 < 0.5), and an invalid 4x4 block at x >= 20, y >= 12.
 * Radius 2 disk: 12 neighbors inside (dx^2 + dy^2 <= 4), 11 one row from the border, 8 on it.
 *   strip pixel: compatible only with the strip (dy = +-1, +-2): 4/12 = 1/3; 3/11 at y = 1, 14;
 *     2/8 = 1/4 at y = 0, 15.
 *   x = 9, 11: 3 strip neighbors (dx = +-1, |dy| <= 1): 9/12 = 0.75; 8/11 at y = 1, 14; at
 *     y = 0, 15 two of 8: 0.75.
 *   x = 8, 12: one strip neighbor (dx = +-2, dy = 0): 11/12 (10/11, 7/8 near the borders).
 *   all other valid pixels: 1 (invalid neighbors are not counted).
 * Valid pixels: 384 - 16 = 368; 0.1 * 368 = 36.8 rounds to 37 (floor would give 36): the 16 strip
 * pixels, the four 8/11 pixels, then 17 of the 28 pixels at 0.75 in index order: (9,0), (11,0),
 * (9|11, 2..8) and (9,9). */
static int strip_expected_hard(int x, int y)
{
    if (x == 10)
        return 1;
    if (x != 9 && x != 11)
        return 0;
    if (y == 1 || y == 14 || y == 0)
        return 1;
    return (y >= 2 && y <= 8) || (y == 9 && x == 9);
}

static void test_hard_strip(void)
{
    enum { W = 24, H = 16, NP = W * H };
    float normals[3 * NP], depth[NP], ratio[NP];
    unsigned char valid[NP], mask[NP];
    int n_valid = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            normals[3 * i + 0] = x == 10 ? 1.0f : 0.0f;
            normals[3 * i + 1] = 0.0f;
            normals[3 * i + 2] = x == 10 ? 0.0f : 1.0f;
            depth[i] = 1.0f;
            valid[i] = !(x >= 20 && y >= 12);
            n_valid += valid[i];
        }
    EXPECT(n_valid == 368, "valid count %d", n_valid);
    int hard = restir_metrics_hard_pixels(normals, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 0.1f, mask, ratio);
    EXPECT(hard == 37, "hard count %d (round(36.8) = 37)", hard);
    int wrong = 0, marked = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            marked += mask[i];
            int want = valid[i] ? strip_expected_hard(x, y) : 0;
            if (mask[i] != want) {
                wrong++;
                printf("  strip: pixel (%d,%d) marked %d, want %d (ratio %g)\n", x, y, mask[i], want, ratio[i]);
            }
            if (!valid[i]) {
                EXPECT(ratio[i] == -1.0f, "invalid (%d,%d) ratio %g", x, y, ratio[i]);
            } else if (x < 8 || x > 12) {
                EXPECT(ratio[i] == 1.0f, "fully compatible (%d,%d) ratio %.9g", x, y, ratio[i]);
            }
        }
    EXPECT(wrong == 0 && marked == 37, "%d pixels misclassified, %d marked", wrong, marked);
    EXPECT_NEAR(ratio[5 * W + 10], 1.0 / 3.0, 1e-7, "strip interior");
    EXPECT_NEAR(ratio[0 * W + 10], 0.25, 1e-7, "strip top");
    EXPECT_NEAR(ratio[1 * W + 10], 3.0 / 11.0, 1e-7, "strip second row");
    EXPECT_NEAR(ratio[5 * W + 9], 0.75, 1e-7, "left of strip");
    EXPECT_NEAR(ratio[14 * W + 11], 8.0 / 11.0, 1e-7, "right of strip, second row from bottom");
    EXPECT_NEAR(ratio[5 * W + 12], 11.0 / 12.0, 1e-7, "two right of strip");
    EXPECT_NEAR(ratio[15 * W + 8], 7.0 / 8.0, 1e-7, "two left of strip, bottom row");
    EXPECT_NEAR(ratio[11 * W + 20], 1.0, 0.0, "above the invalid block");
    /* 000's wording: every pixel of the disk counts, an invalid one as failing Eq. 7. Above the
     * invalid block, 3 of the 12 neighbors within radius 2 are invalid: (20,12), (21,12), (20,13). */
    float ratio_all[NP];
    unsigned char mask_all[NP];
    int hard_all = restir_metrics_hard_pixels_counting(normals, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 0.1f,
                                                       RESTIR_HARD_NEIGHBORS_ALL, mask_all, ratio_all);
    EXPECT(hard_all == 37, "all neighbors: hard count %d", hard_all);
    EXPECT_NEAR(ratio_all[11 * W + 20], 0.75, 1e-7, "all neighbors: above the invalid block");
    EXPECT_NEAR(ratio_all[11 * W + 19], 11.0 / 12.0, 1e-7, "all neighbors: above-left of the block: (20,12) only");
    EXPECT_NEAR(ratio_all[5 * W + 10], 1.0 / 3.0, 1e-7, "all neighbors: strip interior unchanged");
    EXPECT(ratio_all[12 * W + 20] == -1.0f, "all neighbors: an invalid pixel has no ratio");
    EXPECT(restir_metrics_hard_pixels_counting(normals, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 0.1f,
                                               (enum restir_hard_neighbors)7, mask_all, NULL) == -1,
           "unknown counting mode");

    /* fraction 1 marks exactly the valid pixels; 0 marks none; no ratio_out is fine. */
    hard = restir_metrics_hard_pixels(normals, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 1.0f, mask, NULL);
    int same = 1;
    for (int i = 0; i < NP; i++)
        same &= mask[i] == valid[i];
    EXPECT(hard == 368 && same, "fraction 1: %d hard, mask == valid %d", hard, same);
    memset(mask, 7, sizeof mask);
    hard = restir_metrics_hard_pixels(normals, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 0.0f, mask, NULL);
    int any = 0;
    for (int i = 0; i < NP; i++)
        any |= mask[i];
    EXPECT(hard == 0 && any == 0, "fraction 0: %d hard, mask bits %d", hard, any);
    EXPECT(restir_metrics_hard_pixels(NULL, depth, valid, W, H, 2.0f, 0.5f, 0.1f, 0.1f, mask, NULL) == -1, "NULL normals");
    EXPECT(restir_metrics_hard_pixels(normals, depth, valid, W, H, -1.0f, 0.5f, 0.1f, 0.1f, mask, NULL) == -1,
           "negative radius");
}

/* 16x8 plane with a depth step: depth 1 at x < 8, 1.5 at x >= 8 (relative differences 0.5 and 1/3,
 * both >= 0.1), all valid (valid = NULL). Radius 2: columns 7 and 8 see 3-4 neighbors across the
 * step (ratios 2/3, 7/11, 5/8), columns 6 and 9 one (11/12, 10/11, 7/8), all others none (1).
 * fraction 0.125 of 128 = 16 = exactly columns 7 and 8. */
static void test_hard_depth_step(void)
{
    enum { W = 16, H = 8, NP = W * H };
    float normals[3 * NP], depth[NP], ratio[NP];
    unsigned char mask[NP];
    for (int i = 0; i < NP; i++) {
        normals[3 * i + 0] = 0.0f;
        normals[3 * i + 1] = 0.0f;
        normals[3 * i + 2] = 1.0f;
        depth[i] = i % W < 8 ? 1.0f : 1.5f;
    }
    int hard = restir_metrics_hard_pixels(normals, depth, NULL, W, H, 2.0f, 0.5f, 0.1f, 0.125f, mask, ratio);
    EXPECT(hard == 16, "depth step hard count %d", hard);
    int wrong = 0, ones = 1;
    for (int i = 0; i < NP; i++) {
        int x = i % W;
        wrong += mask[i] != (x == 7 || x == 8);
        if (x <= 5 || x >= 10)
            ones &= ratio[i] == 1.0f;
    }
    EXPECT(wrong == 0, "depth step: %d pixels misclassified", wrong);
    EXPECT(ones, "pixels whose disk stays on one side have ratio 1");
    EXPECT_NEAR(ratio[3 * W + 7], 2.0 / 3.0, 1e-7, "left of step");
    EXPECT_NEAR(ratio[0 * W + 8], 5.0 / 8.0, 1e-7, "right of step, top row");
    EXPECT_NEAR(ratio[1 * W + 7], 7.0 / 11.0, 1e-7, "left of step, second row");
    EXPECT_NEAR(ratio[4 * W + 9], 11.0 / 12.0, 1e-7, "two right of step");

    /* Every pixel tied (uniform plane, ratio 1): the lowest indices win. */
    for (int i = 0; i < NP; i++)
        depth[i] = 2.0f;
    hard = restir_metrics_hard_pixels(normals, depth, NULL, W, H, 3.5f, 0.5f, 0.1f, 0.1f, mask, NULL);
    int first = 1;
    for (int i = 0; i < NP; i++)
        first &= mask[i] == (i < 13);
    EXPECT(hard == 13 && first, "ties: %d hard (round(12.8) = 13), lowest indices %d", hard, first);
}

int main(void)
{
    test_spatial_hand();
    test_temporal_hand();
    test_spatial_brute();
    test_independent_noise();
    test_perfect_spatial();
    test_perfect_temporal();
    test_hard_strip();
    test_hard_depth_step();
    return test_finish();
}
