/* test_metrics.c: unit tests for restir_metrics_compute and restir_metrics_gradient_relmse on small images with hand-computed values.
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
               strstr(h, "RMSE") && strstr(h, "0.7152") && strstr(h, "gradient relMSE"),
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

/* A 2x2 grey reference R = [1 3; 0 1]: its forward differences are dx = (2, 1) on the rows, dy = (-1, -2)
 * on the columns, pair means 2, 0.5, 0.5, 2. Estimated gradients exact but dx at (0,0) = 2.5: one
 * pair of 4 is off by 0.5 in each channel, so the mean over 12 terms is 3 * 0.25 / (2^2 + 1e-3) / 12. The
 * entries whose pair leaves the image hold junk that must not count. */
static void test_gradient_relmse(void)
{
    const float junk = 1e30f;
    float ref[12], dx[12], dy[12];
    const float r[4] = {1, 3, 0, 1}, gx[4] = {2.5f, junk, 1, junk}, gy[4] = {-1, -2, junk, junk};
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 3; c++) {
            ref[3 * i + c] = r[i];
            dx[3 * i + c] = gx[i];
            dy[3 * i + c] = gy[i];
        }
    EXPECT_NEAR(restir_metrics_gradient_relmse(dx, dy, ref, 2, 2), 0.75 / 4.001 / 12.0, 1e-12, "gradient relmse");
    dx[0] = dx[1] = dx[2] = 2.0f;
    EXPECT(restir_metrics_gradient_relmse(dx, dy, ref, 2, 2) == 0.0, "exact gradients");
    /* one row: only x pairs exist, dy must not be read */
    dy[0] = dy[1] = dy[2] = dy[3] = dy[4] = dy[5] = junk;
    EXPECT_NEAR(restir_metrics_gradient_relmse(dx, dy, ref, 2, 1), 0.0, 0.0, "one row");
    EXPECT(isnan(restir_metrics_gradient_relmse(dx, dy, ref, 1, 1)), "a single pixel has no pair");
    EXPECT(isnan(restir_metrics_gradient_relmse(NULL, dy, ref, 2, 2)), "NULL gradients");
}

int main(void)
{
    test_gradient_relmse();
    test_smape_from_luminance();
    test_two_pixels();
    test_mask();
    test_identical();
    test_help();
    return test_finish();
}
