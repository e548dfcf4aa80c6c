/* test_metrics.c: unit tests for restir_metrics_compute and the gradient metrics (relMSE, trimmed, MAPE) on small
 * images with hand-computed values.
 * Must never depend on src/ headers, files or the renderer; only on include/restir/metrics.h. */
#include <math.h>
#include <string.h>

#include "restir/metrics.h"
#include "test_util.h"

/* Two pixels. Reference R and image I (all values exact in float):
 *   R0 = (1, 0, 2)      I0 = (1, 0.5, 1)     I0 - R0 = (0, 0.5, -1)
 *   R1 = (0.5, 1, 0.5)  I1 = (0.5, 1, 1.5)   I1 - R1 = (0, 0, 1)        */
static const float ref2[6] = {1.0f, 0.0f, 2.0f, 0.5f, 1.0f, 0.5f};
static const float img2[6] = {1.0f, 0.5f, 1.0f, 0.5f, 1.0f, 1.5f};

static void test_two_pixels(void)
{
    struct restir_metrics_error e;
    EXPECT(restir_metrics_compute(img2, ref2, 2, NULL, &e) == 0, "compute failed");

    /* relMSE: terms 0/(1+1e-3), 0.25/(0+1e-3) = 250, 1/(4+1e-3), 0, 0, 1/(0.25+1e-3);
     * sum = 250 + 0.2499375156 + 3.9840637450 = 254.2340012607, mean over 6 = 42.37233354. */
    double relmse = (0.25 / 1e-3 + 1.0 / 4.001 + 1.0 / 0.251) / 6.0;
    EXPECT_NEAR(e.relmse, relmse, 1e-12, "relmse");
    EXPECT_NEAR(e.relmse, 42.37233354, 1e-7, "relmse decimal");
    /* the per-pixel terms: (0 + 250 + 1 / 4.001) / 3 and (0 + 0 + 1 / 0.251) / 3, whose mean is relMSE */
    float map[2];
    EXPECT(restir_metrics_relmse_map(img2, ref2, 2, map) == 0, "relmse_map failed");
    EXPECT_NEAR(map[0], (250.0 + 1.0 / 4.001) / 3.0, 1e-4, "relmse_map pixel 0");
    EXPECT_NEAR(map[1], (1.0 / 0.251) / 3.0, 1e-6, "relmse_map pixel 1");
    EXPECT_NEAR(0.5 * ((double)map[0] + map[1]), e.relmse, 1e-4, "relmse_map's mean is relmse");

    /* MAPE: mean(R) = (1 + 0 + 2 + 0.5 + 1 + 0.5) / 6 = 5/6, so the offset is 1/120.
     * Nonzero terms: 0.5 / (0 + 1/120) = 60, 1 / (2 + 1/120) = 120/241, 1 / (0.5 + 1/120) = 120/61;
     * sum = 60 + 0.4979253112 + 1.9672131148 = 62.4651384260, mean over 6 = 10.41085640. */
    double mape = (60.0 + 120.0 / 241.0 + 120.0 / 61.0) / 6.0;
    EXPECT_NEAR(e.mape, mape, 1e-12, "mape");
    EXPECT_NEAR(e.mape, 10.41085640, 1e-7, "mape decimal");

    /* Luminance L = 0.2126 r + 0.7152 g + 0.0722 b:
     *   L(R0) = 0.2126 + 0.1444 = 0.357       L(I0) = 0.2126 + 0.3576 + 0.0722 = 0.6424
     *   L(R1) = 0.1063 + 0.7152 + 0.0361 = 0.8576   L(I1) = 0.1063 + 0.7152 + 0.1083 = 0.9298
     * differences 0.2854 and 0.0722.
     * SMAPE = 100 * (0.2854 / (0.6424 + 0.357 + 1e-4) + 0.0722 / (0.9298 + 0.8576 + 1e-4)) / 2
     *       = 100 * (0.2855427714 + 0.0403916084) / 2 = 16.29671899. */
    double smape = 100.0 * (0.2854 / 0.9995 + 0.0722 / 1.7875) / 2.0;
    EXPECT_NEAR(e.smape, smape, 1e-9, "smape");
    EXPECT_NEAR(e.smape, 16.29671899, 1e-6, "smape decimal");

    /* luma RMSE = sqrt((0.2854^2 + 0.0722^2) / 2) = sqrt((0.08145316 + 0.00521284) / 2)
     *           = sqrt(0.043333) = 0.2081658. */
    EXPECT_NEAR(e.luma_rmse, 0.20816580, 1e-7, "luma_rmse");
}

static void test_mask(void)
{
    struct restir_metrics_error e;
    const unsigned char only_second[2] = {0, 7};
    EXPECT(restir_metrics_compute(img2, ref2, 2, only_second, &e) == 0, "masked compute failed");
    /* Pixel 1 only: relMSE = (1 / 0.251) / 3 = 1.3280212483. */
    EXPECT_NEAR(e.relmse, 1.0 / 0.251 / 3.0, 1e-12, "masked relmse");
    /* mean(R) over the selected pixel = 2/3, offset 1/150: MAPE = (1 / (0.5 + 1/150)) / 3
     * = (150/76) / 3 = 0.6578947368. */
    EXPECT_NEAR(e.mape, 150.0 / 76.0 / 3.0, 1e-12, "masked mape");
    /* SMAPE = 100 * 0.0722 / 1.7875 = 4.039160839; luma RMSE = 0.0722. */
    EXPECT_NEAR(e.smape, 100.0 * 0.0722 / 1.7875, 1e-9, "masked smape");
    EXPECT_NEAR(e.luma_rmse, 0.0722, 1e-7, "masked luma_rmse");

    const unsigned char none[2] = {0, 0};
    memset(&e, 0, sizeof e);
    EXPECT(restir_metrics_compute(img2, ref2, 2, none, &e) == -1, "empty mask accepted");
    EXPECT(restir_metrics_compute(img2, ref2, 0, NULL, &e) == -1, "zero pixels accepted");
}

static void test_identical(void)
{
    struct restir_metrics_error e;
    EXPECT(restir_metrics_compute(ref2, ref2, 2, NULL, &e) == 0, "compute failed");
    EXPECT(e.relmse == 0.0 && e.mape == 0.0 && e.smape == 0.0 && e.luma_rmse == 0.0,
           "identical: %g %g %g %g", e.relmse, e.mape, e.smape, e.luma_rmse);

    /* An all-black reference matched exactly: 0, not NaN, although MAPE's denominator is 0. */
    const float black[9] = {0};
    EXPECT(restir_metrics_compute(black, black, 3, NULL, &e) == 0, "compute failed");
    EXPECT(e.relmse == 0.0 && e.mape == 0.0 && e.smape == 0.0 && e.luma_rmse == 0.0,
           "black identical: %g %g %g %g", e.relmse, e.mape, e.smape, e.luma_rmse);
}

static void test_help(void)
{
    const char *h = restir_metrics_definitions();
    EXPECT(h && strstr(h, "relMSE") && strstr(h, "MAPE") && strstr(h, "SMAPE") &&
               strstr(h, "RMSE") && strstr(h, "0.7152") && strstr(h, "gradient relMSE") &&
               strstr(h, "trim 1%") && strstr(h, "gradient MAPE"),
           "help text incomplete");
}

/* SMAPE from the luminance alone (what study jobs keep) has restir_metrics_compute's exact bits. */
static void test_smape_from_luminance(void)
{
    enum { N = 999 };
    static float img[3 * N], ref[3 * N];
    static double lum[N];
    static unsigned char mask[N];
    unsigned s = 12345u;
    for (int i = 0; i < 3 * N; i++) {
        s = s * 1664525u + 1013904223u;
        img[i] = (float)(s >> 8) / 16777216.0f * (i % 7 == 0 ? 100.0f : 1.0f);
        s = s * 1664525u + 1013904223u;
        ref[i] = (float)(s >> 8) / 16777216.0f;
    }
    for (int i = 0; i < N; i++)
        mask[i] = (unsigned char)(i % 3 == 0);
    restir_metrics_luminance(img, N, lum);
    struct restir_metrics_error e;
    double smape = -1.0;
    EXPECT(restir_metrics_compute(img, ref, N, NULL, &e) == 0 && restir_metrics_smape_luminance(lum, ref, N, NULL, &smape) == 0,
           "smape from luminance");
    EXPECT(memcmp(&smape, &e.smape, sizeof smape) == 0, "smape from luminance %.17g != %.17g", smape, e.smape);
    EXPECT(restir_metrics_compute(img, ref, N, mask, &e) == 0 && restir_metrics_smape_luminance(lum, ref, N, mask, &smape) == 0,
           "masked smape from luminance");
    EXPECT(memcmp(&smape, &e.smape, sizeof smape) == 0, "masked smape %.17g != %.17g", smape, e.smape);
    memset(mask, 0, sizeof mask);
    EXPECT(restir_metrics_smape_luminance(lum, ref, N, mask, &smape) == -1, "empty mask accepted");
}

/* The 2 x 2 grey reference [1 3; 0 1] of the gradient tests and its forward differences, exact but dx at
 * (0, 0) = 2.5; the entries whose pair leaves the image hold junk. */
static void grey_2x2(float ref[12], float dx[12], float dy[12], float junk)
{
    const float r[4] = {1, 3, 0, 1}, gx[4] = {2.5f, junk, 1, junk}, gy[4] = {-1, -2, junk, junk};
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++) {
            ref[3 * i + c] = r[i];
            dx[3 * i + c] = gx[i];
            dy[3 * i + c] = gy[i];
        }
}

/* A 2x2 grey reference R = [1 3; 0 1]: its forward differences are dx = (2, 1) on the rows, dy = (-1, -2)
 * on the columns, pair means 2, 0.5, 0.5, 2. Estimated gradients exact but dx at (0,0) = 2.5: one
 * pair of 4 is off by 0.5 in each channel, so the mean over 12 terms is 3 * 0.25 / (2^2 + 1e-3) / 12. The
 * entries whose pair leaves the image hold junk that must not count. */
static void test_gradient_relmse(void)
{
    const float junk = 1e30f;
    float ref[12], dx[12], dy[12];
    grey_2x2(ref, dx, dy, junk);
    EXPECT_NEAR(restir_metrics_gradient_relmse(dx, dy, ref, 2, 2), 0.75 / 4.001 / 12.0, 1e-12, "gradient relmse");
    dx[0] = dx[1] = dx[2] = 2.0f;
    EXPECT(restir_metrics_gradient_relmse(dx, dy, ref, 2, 2) == 0.0, "exact gradients");
    /* one row: only x pairs exist, dy must not be read */
    dy[0] = dy[1] = dy[2] = dy[3] = dy[4] = dy[5] = junk;
    EXPECT_NEAR(restir_metrics_gradient_relmse(dx, dy, ref, 2, 1), 0.0, 0.0, "one row");
    EXPECT(isnan(restir_metrics_gradient_relmse(dx, dy, ref, 1, 1)), "a single pixel has no pair");
    EXPECT(isnan(restir_metrics_gradient_relmse(NULL, dy, ref, 2, 2)), "NULL gradients");
}

/* A grey reference (all 1) of w x h, so every reference difference D is 0 and every pair mean 1: a pair whose
 * three channels' estimate is e has relMSE terms e^2 / 1.001. */
static void grey_pairs(float *ref, float *dx, float *dy, int w, int h)
{
    for (int i = 0; i < 3 * w * h; i++) {
        ref[i] = 1.0f;
        dx[i] = dy[i] = 0.0f;
    }
}

static void set_pixel(float *g, int i, float v)
{
    g[3 * i] = g[3 * i + 1] = g[3 * i + 2] = v;
}

/* The trimmed gradient relMSE: how many pairs round(fraction * P) leaves out, that it ignores a spike, ties. */
static void test_gradient_relmse_trimmed(void)
{
    enum { W = 11, H = 3, N = W * H };
    float ref[3 * N], dx[3 * N], dy[3 * N];
    unsigned char mask[N];
    /* 11 x 3: P = 10 * 3 x pairs + 11 * 2 y pairs = 52, so 1% is 0.52 -> 1 pair left out. The y pair of pixel
     * (4, 1) is a spike of 3, the x pair of pixel (0, 0) is off by 0.5: untrimmed 3 (9 + 0.25) / 1.001 / (3 * 52),
     * trimmed (the spike out) 3 * 0.25 / 1.001 / (3 * 51). */
    grey_pairs(ref, dx, dy, W, H);
    set_pixel(dy, 1 * W + 4, 3.0f);
    set_pixel(dx, 0, 0.5f);
    EXPECT_NEAR(restir_metrics_gradient_relmse(dx, dy, ref, W, H), 9.25 / 1.001 / 52.0, 1e-12, "untrimmed");
    EXPECT_NEAR(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, W, H, 0.01), 0.25 / 1.001 / 51.0, 1e-12,
                "trimmed 1%% of 52 pairs");
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, W, H, 0.01, mask) == 1, "one pair is the worst 1%%");
    for (int i = 0; i < N; i++)
        EXPECT(mask[i] == (i == 1 * W + 4 ? 2 : 0), "mask[%d] = %d: only the y pair of (4, 1)", i, mask[i]);
    /* the spike ignored: 1000 times larger, the trimmed mean is the same bits; the untrimmed one is not */
    const double trimmed = restir_metrics_gradient_relmse_trimmed(dx, dy, ref, W, H, 0.01);
    set_pixel(dy, 1 * W + 4, 3000.0f);
    const double spiked = restir_metrics_gradient_relmse_trimmed(dx, dy, ref, W, H, 0.01);
    EXPECT(spiked == trimmed, "a 1000x spike moved the trimmed mean: %.17g vs %.17g", spiked, trimmed);
    EXPECT(restir_metrics_gradient_relmse(dx, dy, ref, W, H) > 1e5, "the spike dominates the untrimmed mean");
    /* fraction 0 is the untrimmed relMSE bit for bit */
    const double all = restir_metrics_gradient_relmse(dx, dy, ref, W, H);
    const double none = restir_metrics_gradient_relmse_trimmed(dx, dy, ref, W, H, 0.0);
    EXPECT(memcmp(&all, &none, sizeof all) == 0, "fraction 0: %.17g != %.17g", none, all);
    /* 10 x 3: P = 9 * 3 + 10 * 2 = 47, 1% is 0.47 -> nothing left out */
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 10, 3, 0.01, mask) == 0, "0.47 rounds to 0");

    /* 2 x 2 grey, P = 4: fraction 0.125 gives exactly 0.5, rounded up to 1; 0.124 gives 0. All four pairs off by
     * the same 1: a tie, so the earliest pair, the x pair of pixel 0, is the one left out. */
    grey_pairs(ref, dx, dy, 2, 2);
    for (int i = 0; i < 4; i++) {
        set_pixel(dx, i, 1.0f);
        set_pixel(dy, i, 1.0f);
    }
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 2, 2, 0.125, mask) == 1, "0.5 rounds up");
    EXPECT(mask[0] == 1 && mask[1] == 0 && mask[2] == 0 && mask[3] == 0, "tie: mask %d %d %d %d, want 1 0 0 0",
           mask[0], mask[1], mask[2], mask[3]);
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 2, 2, 0.124, mask) == 0, "0.496 rounds down");
    EXPECT_NEAR(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, 0.125), 1.0 / 1.001, 1e-12, "ties");
    /* three of four pairs out (0.75 * 4 = 3): the mean of the one left */
    set_pixel(dy, 1, 0.0f); /* the y pair of pixel 1 becomes exact, the best, and the only one kept */
    EXPECT(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, 0.75) == 0.0, "the best pair only");
    /* a NaN pair is never trimmed away in the mean, and it is among the worst in the mask */
    set_pixel(dy, 0, NAN);
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, 0.125)), "NaN trimmed away");
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 2, 2, 0.125, mask) == 1 && mask[0] == 2,
           "the NaN pair (y of pixel 0) is the worst: mask[0] = %d", mask[0]);
    /* bad arguments */
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, 1.0)), "fraction 1");
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, -0.1)), "negative fraction");
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, NAN)), "NaN fraction");
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 2, 2, 0.9)), "0.9 of 4 leaves no pair");
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 2, 2, 0.9, mask) == 4, "the mask may mark every pair");
    EXPECT(restir_metrics_gradient_worst_pairs(dx, dy, ref, 2, 2, 0.01, NULL) == -1, "NULL mask");
    EXPECT(isnan(restir_metrics_gradient_relmse_trimmed(dx, dy, ref, 1, 1, 0.01)), "no pair");
}

/* Gradient MAPE on test_gradient_relmse's 2 x 2 reference [1 3; 0 1]: |D| = 2, 1, 1, 2, mean 1.5, offset 0.015.
 * Exact gradients but dx at (0, 0) = 2.5: one pair of 4 off by 0.5 in each channel, 3 * 0.5 / 2.015 / 12. */
static void test_gradient_mape(void)
{
    const float junk = 1e30f;
    float ref[12], dx[12], dy[12];
    grey_2x2(ref, dx, dy, junk);
    EXPECT_NEAR(restir_metrics_gradient_mape(dx, dy, ref, 2, 2), 0.5 / 2.015 / 4.0, 1e-12, "gradient mape");
    /* dy at (1, 0) = -2 + 0.03 too: the offset still counts in a pair with a large |D| */
    set_pixel(dy, 1, -1.97f);
    EXPECT_NEAR(restir_metrics_gradient_mape(dx, dy, ref, 2, 2),
                (0.5 / 2.015 + (double)(2.0f - 1.97f) / 2.015) / 4.0, 1e-9, "two pairs");
    /* a flat reference: exact gradients are 0 (not 0 / 0), any error infinite (the offset is 0) */
    float grey[12], zero[12];
    for (int i = 0; i < 12; i++)
        grey[i] = 0.5f, zero[i] = 0.0f;
    EXPECT(restir_metrics_gradient_mape(zero, zero, grey, 2, 2) == 0.0, "exact on a flat reference");
    zero[0] = 0.1f;
    EXPECT(isinf(restir_metrics_gradient_mape(zero, zero, grey, 2, 2)), "an error on a flat reference");
    EXPECT(isnan(restir_metrics_gradient_mape(dx, dy, ref, 1, 1)), "a single pixel has no pair");
    EXPECT(isnan(restir_metrics_gradient_mape(dx, NULL, ref, 2, 2)), "NULL gradients");
}

int main(void)
{
    test_gradient_relmse();
    test_gradient_relmse_trimmed();
    test_gradient_mape();
    test_smape_from_luminance();
    test_two_pixels();
    test_mask();
    test_identical();
    test_help();
    return test_finish();
}
