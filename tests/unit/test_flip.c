/* test_flip.c: FLIP and HDR-FLIP (restir/metrics.h: restir_metrics_flip_ldr, restir_metrics_flip) checked from their
 * definition (Andersson et al. 2020, 2021), every step against values computed by hand (with a double-precision
 * python3 one-off written from the papers, not from our C), and the whole against properties:
 *  - the colour steps: linear RGB -> XYZ -> YCxCz of white and of pure red, the inverse, CIELAB with the Hunt
 *    adjustment, HyAB of green and blue giving c_max = 41.276, the remap's knee at p_c c_max giving p_t;
 *  - the filters: CSF kernels of unit sum and radius 10 at 67.02 PPD, feature kernels of radius 9 whose lobes sum to
 *    +1 and -1, with hand-computed taps;
 *  - a constant-colour pair (no edges: the feature term is exactly 0) gives the remapped colour error in every
 *    pixel, in LDR and (through ACES at the one exposure) in HDR;
 *  - HDR exposures of constructed references: start, stop, count, the median element, our rules for a median of 0
 *    and a black reference;
 *  - 0 for identical images; LDR symmetric in its inputs bit for bit; HDR not (exposures follow the reference),
 *    but symmetric when both images have the same luminances in another order;
 *  - the mean grows with blur width and with noise amplitude;
 *  - NaN and infinite pixels make the mean NaN; bad arguments return -1 and write nothing; 1 or 2 threads give
 *    the same bits. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "metrics/flip_internal.h"
#include "restir/metrics.h"
#include "restir/threads.h"
#include "test_util.h"

static const double ppd67 = RESTIR_METRICS_FLIP_PPD;

static void test_ppd(void)
{
    /* PPD = d (resX / W) pi / 180 = 0.7 (3840 / 0.7) pi / 180 = 3840 pi / 180 = 67.020643 */
    EXPECT_NEAR(restir_metrics_flip_ppd(0.7, 0.7, 3840), 67.020643276582, 1e-9, "default ppd");
    EXPECT_NEAR(RESTIR_METRICS_FLIP_PPD, restir_metrics_flip_ppd(0.7, 0.7, 3840), 1e-12, "the constant");
    EXPECT_NEAR(restir_metrics_flip_ppd(1.0, 0.5, 1920), 1920.0 * 2.0 * 3.14159265358979323846 / 180.0, 1e-9,
                "another monitor");
    EXPECT(isnan(restir_metrics_flip_ppd(0.0, 0.7, 3840)) && isnan(restir_metrics_flip_ppd(0.7, -1.0, 3840)) &&
               isnan(restir_metrics_flip_ppd(NAN, 0.7, 3840)) && isnan(restir_metrics_flip_ppd(0.7, INFINITY, 3840)) &&
               isnan(restir_metrics_flip_ppd(0.7, 0.7, 0)),
           "bad viewing conditions are NaN");
}

static void test_color_steps(void)
{
    float ycc[3], rgb[3], lab[3];
    /* White: the matrix rows sum to the white point, so XYZ / white = (1, 1, 1): Y' = 116 - 16 = 100, Cx = Cz = 0. */
    const float white[3] = {1.0f, 1.0f, 1.0f};
    restir_flip_rgb_to_ycxcz(white, ycc);
    EXPECT_NEAR(ycc[0], 100.0, 2e-5, "white Y'");
    EXPECT_NEAR(ycc[1], 0.0, 2e-4, "white Cx");
    EXPECT_NEAR(ycc[2], 0.0, 2e-4, "white Cz");
    /* Red (1, 0, 0): X = 10135552 / 24577794 = 0.412386563, Y = 2613072 / 12288897 = 0.212636822,
     * Z = 1425312 / 73733382 = 0.019330620; X / 0.950428545 = 0.433895389, Z / 1.088900371 = 0.017752423.
     * Y' = 116 * 0.212636822 - 16 = 8.665871; Cx = 500 (0.433895389 - 0.212636822) = 110.629284;
     * Cz = 200 (0.212636822 - 0.017752423) = 38.976880. */
    const float red[3] = {1.0f, 0.0f, 0.0f};
    restir_flip_rgb_to_ycxcz(red, ycc);
    EXPECT_NEAR(ycc[0], 8.665871315, 1e-5, "red Y'");
    EXPECT_NEAR(ycc[1], 110.629283663, 1e-4, "red Cx");
    EXPECT_NEAR(ycc[2], 38.976879706, 1e-4, "red Cz");
    /* and back, with the paper's 9-decimal inverse rows */
    restir_flip_ycxcz_to_rgb(ycc, rgb);
    EXPECT_NEAR(rgb[0], 1.0, 1e-5, "red back r");
    EXPECT_NEAR(rgb[1], 0.0, 1e-5, "red back g");
    EXPECT_NEAR(rgb[2], 0.0, 1e-5, "red back b");
    /* CIELAB of red: f(t) = t^(1/3) for all three (each > (6/29)^3 = 0.008856): f(0.433895389) = 0.757056591,
     * f(0.212636822) = 0.596869643, f(0.017752423) = 0.260867042; L = 116 * 0.596869643 - 16 = 53.236879,
     * a = 500 (0.757056591 - 0.596869643) = 80.093474, b = 200 (0.596869643 - 0.260867042) = 67.200520;
     * Hunt: a, b times 0.01 L = 0.53236879: 42.639266, 35.775459. */
    restir_flip_rgb_to_lab_hunt(red, lab);
    EXPECT_NEAR(lab[0], 53.236878530, 2e-5, "red L");
    EXPECT_NEAR(lab[1], 42.639265671, 2e-5, "red Hunt a");
    EXPECT_NEAR(lab[2], 35.775459255, 2e-5, "red Hunt b");
    restir_flip_rgb_to_lab_hunt(white, lab);
    EXPECT_NEAR(lab[0], 100.0, 2e-5, "white L");
    EXPECT(fabsf(lab[1]) < 1e-4f && fabsf(lab[2]) < 1e-4f, "white is achromatic: %g %g", lab[1], lab[2]);
    /* below (6/29)^3 CIELAB's linear segment: grey 0.001 has Y = 0.001, f = 0.001 * 841 / 108 + 4 / 29 */
    const float dark[3] = {0.001f, 0.001f, 0.001f};
    restir_flip_rgb_to_lab_hunt(dark, lab);
    EXPECT_NEAR(lab[0], 116.0 * (0.001 * 841.0 / 108.0 + 4.0 / 29.0) - 16.0, 1e-5, "dark grey L (linear segment)");
    /* clamping before Lab (NaN kept) */
    const float over[3] = {2.0f, -1.0f, 0.0f}, nan3[3] = {NAN, 0.0f, 0.0f};
    float lab_red[3];
    restir_flip_rgb_to_lab_hunt(red, lab_red);
    restir_flip_rgb_to_lab_hunt(over, lab);
    EXPECT(lab[0] == lab_red[0] && lab[1] == lab_red[1] && lab[2] == lab_red[2], "(2, -1, 0) clamps to red");
    restir_flip_rgb_to_lab_hunt(nan3, lab);
    EXPECT(isnan(lab[0]) && isnan(lab[1]), "NaN stays NaN through Lab");
    /* the cube root against libm's over CIELAB's range */
    double worst = 0.0;
    for (int i = 0; i <= 100000; i++) {
        const float t = (float)(0.008856 + (1.1 - 0.008856) * i / 100000.0);
        const double err = fabs((double)restir_flip_cbrt(t) / cbrt((double)t) - 1.0);
        worst = err > worst ? err : worst;
    }
    EXPECT(worst < 5e-7, "cube root relative error %g", worst);
}

static void test_hyab_cmax_remap(void)
{
    /* Hunt-adjusted Lab of green (87.736211, -75.609930, 72.981231) and blue (32.298170, 25.578083, -34.836366):
     * HyAB = |87.736211 - 32.298170| + hypot(-101.188013, 107.817597) = 55.438041 + 147.863614 = 203.301655;
     * c_max = 203.301655^0.7 = 41.276098. */
    const float green[3] = {0.0f, 1.0f, 0.0f}, blue[3] = {0.0f, 0.0f, 1.0f};
    float lg[3], lb[3];
    restir_flip_rgb_to_lab_hunt(green, lg);
    restir_flip_rgb_to_lab_hunt(blue, lb);
    EXPECT_NEAR(lg[0], 87.736210661, 3e-5, "green L");
    EXPECT_NEAR(lb[2], -34.836366021, 3e-5, "blue Hunt b");
    EXPECT_NEAR(restir_flip_hyab(lg, lb), 203.301654592, 2e-4, "HyAB(green, blue)");
    EXPECT(restir_flip_hyab(lg, lb) == restir_flip_hyab(lb, lg), "HyAB is symmetric");
    EXPECT(restir_flip_hyab(lg, lg) == 0.0f, "HyAB of a colour with itself");
    const double cmax = restir_flip_cmax();
    EXPECT_NEAR(cmax, 41.276098412, 2e-5, "c_max (the notes: about 41.28)");
    /* remap: the knee p_c c_max -> p_t from both sides; 0 -> 0; c_max -> 1; half the knee -> p_t / 2 */
    const float c = (float)cmax, knee = 0.4f * c;
    EXPECT_NEAR(restir_flip_remap_color(knee, c), 0.95, 1e-6, "remap at p_c c_max");
    EXPECT_NEAR(restir_flip_remap_color(nextafterf(knee, 0.0f), c), 0.95, 1e-6, "remap just below the knee");
    EXPECT(restir_flip_remap_color(0.0f, c) == 0.0f, "remap(0)");
    EXPECT_NEAR(restir_flip_remap_color(c, c), 1.0, 1e-6, "remap(c_max)");
    EXPECT_NEAR(restir_flip_remap_color(0.5f * knee, c), 0.475, 1e-6, "remap halfway to the knee");
    /* above the knee: linear from 0.95 to 1: at knee + 0.3 (c_max - knee), 0.95 + 0.3 * 0.05 = 0.965 */
    EXPECT_NEAR(restir_flip_remap_color(knee + 0.3f * (c - knee), c), 0.965, 1e-6, "remap above the knee");
}

static double sum_f(const float *v, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += v[i];
    return s;
}

static void test_kernels(void)
{
    struct restir_flip_kernels k;
    EXPECT(restir_flip_kernels_init(&k, ppd67) == 0, "kernels at 67 PPD");
    /* radius ceil(3 sqrt(0.04 / (2 pi^2)) 67.02) = ceil(9.05) = 10; sigma = 0.5 * 0.082 * 67.02 = 2.748,
     * ceil(3 sigma) = ceil(8.24) = 9 */
    EXPECT(k.csf_radius == 10, "CSF radius %d", k.csf_radius);
    EXPECT(k.feature_radius == 9, "feature radius %d", k.feature_radius);
    const int nc = 2 * k.csf_radius + 1, nf = 2 * k.feature_radius + 1;
    for (int j = 0; j < 4; j++) {
        EXPECT_NEAR(sum_f(k.csf[j], nc), 1.0, 1e-6, "CSF kernel sum");
        for (int i = 0; i < nc; i++)
            EXPECT(k.csf[j][i] == k.csf[j][nc - 1 - i] && k.csf[j][i] >= 0.0f, "CSF %d tap %d symmetric", j, i);
    }
    /* Y's centre tap: exp(0) / sum_x exp(-pi^2 (x / 67.02)^2 / 0.0047) = 0.385760; its edge taps exp(-pi^2
     * (10 / 67.02)^2 / 0.0047) / sum = 1.9e-21 */
    EXPECT_NEAR(k.csf[0][10], 0.385760197, 1e-7, "CSF Y centre");
    EXPECT_NEAR(k.csf[0][0], 1.91825353e-21, 1e-26, "CSF Y edge");
    /* Cz: A_j (sum g_j)^2 shares 0.761457 (34.1, b 0.04) and 0.238543 (13.5, b 0.025) */
    EXPECT_NEAR(k.cz_weight[0], 0.761456961, 1e-6, "Cz weight 1");
    EXPECT_NEAR(k.cz_weight[0] + k.cz_weight[1], 1.0, 1e-7, "Cz weights sum");
    EXPECT_NEAR(sum_f(k.g, nf), 1.0, 1e-6, "feature Gaussian sum");
    EXPECT_NEAR(k.g[9], 0.145257466, 1e-7, "feature Gaussian centre");
    double pos1 = 0.0, neg1 = 0.0, pos2 = 0.0, neg2 = 0.0;
    for (int i = 0; i < nf; i++) {
        pos1 += k.d1[i] > 0.0f ? k.d1[i] : 0.0f;
        neg1 += k.d1[i] < 0.0f ? k.d1[i] : 0.0f;
        pos2 += k.d2[i] > 0.0f ? k.d2[i] : 0.0f;
        neg2 += k.d2[i] < 0.0f ? k.d2[i] : 0.0f;
        EXPECT(k.d1[i] == -k.d1[nf - 1 - i] && k.d2[i] == k.d2[nf - 1 - i], "derivative taps %d (anti)symmetric", i);
    }
    EXPECT_NEAR(pos1, 1.0, 1e-6, "edge kernel positive lobe");
    EXPECT_NEAR(neg1, -1.0, 1e-6, "edge kernel negative lobe");
    EXPECT_NEAR(pos2, 1.0, 1e-6, "point kernel positive lobe");
    EXPECT_NEAR(neg2, -1.0, 1e-6, "point kernel negative lobe");
    /* -x g at x = +1 over the positive lobe's sum: -0.125649; (x^2 / sigma^2 - 1) g: centre -0.298902 (over the
     * negative lobe), x = 9: +0.0138062 (over the positive lobe) */
    EXPECT_NEAR(k.d1[10], -0.125649028, 1e-7, "edge tap at +1");
    EXPECT_NEAR(k.d2[9], -0.298901543, 1e-7, "point centre tap");
    EXPECT_NEAR(k.d2[18], 0.0138061614, 1e-8, "point tap at +9");
    restir_flip_kernels_fini(&k);
    /* the radii follow the PPD: 30 PPD -> ceil(4.05) = 5 and ceil(3.69) = 4; 1 PPD -> 1 and 1 */
    EXPECT(restir_flip_kernels_init(&k, 30.0) == 0 && k.csf_radius == 5 && k.feature_radius == 4, "radii at 30 PPD");
    restir_flip_kernels_fini(&k);
    EXPECT(restir_flip_kernels_init(&k, 1.0) == 0 && k.csf_radius == 1 && k.feature_radius == 1, "radii at 1 PPD");
    restir_flip_kernels_fini(&k);
    EXPECT(restir_flip_kernels_init(&k, NAN) == -1 && restir_flip_kernels_init(&k, 0.0) == -1 &&
               restir_flip_kernels_init(&k, 1e9) == -1 && k.storage == NULL,
           "refused PPDs");
}

/* A w x h image filled with one colour. */
static float *constant_image(int w, int h, const float c[3])
{
    float *img = malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    for (int i = 0; i < w * h; i++)
        memcpy(img + 3 * i, c, sizeof(float) * 3);
    return img;
}

static void test_constant_pair(void)
{
    /* No edges: every pixel's feature responses are exactly 0 (the derivative filters of a constant image), so
     * FLIP = dE_c^1. A = (0.2, 0.4, 0.6), B = (0.25, 0.35, 0.5): Hunt Lab (67.419982, -4.587207, -14.897673) and
     * (64.927898, -0.999008, -11.018584); HyAB = 2.492085 + hypot(3.588199, 3.879089) = 7.776259;
     * 7.776259^0.7 = 4.205338 < knee 0.4 * 41.276098 = 16.510439, so FLIP = 4.205338 * 0.95 / 16.510439
     * = 0.241827. */
    enum { W = 24, H = 17 };
    const float a[3] = {0.2f, 0.4f, 0.6f}, b[3] = {0.25f, 0.35f, 0.5f};
    float *ia = constant_image(W, H, a), *ib = constant_image(W, H, b), map[W * H];
    double mean = -1.0;
    EXPECT(restir_metrics_flip_ldr(ia, ib, W, H, ppd67, map, &mean) == 0, "LDR constant pair");
    int off = 0;
    for (int i = 0; i < W * H; i++)
        off += fabs(map[i] - 0.241826832) > 2e-6;
    EXPECT(off == 0, "%d pixels of the constant pair are not the remapped colour error 0.241827 (first %.9f)", off,
           map[0]);
    EXPECT_NEAR(mean, 0.241826832, 2e-6, "LDR constant pair mean");
    /* HDR with B as the reference: Y_max = Y_median = L(B) = 0.2126 * 0.25 + 0.7152 * 0.35 + 0.0722 * 0.5
     * = 0.339570, so start = stop = log2(2.118872 / 0.339570) = 2.641516 and count = max(2, 0) = 2 (that exposure
     * twice). Times 2^2.641516 = 6.2399, ACES per channel, then as above: 0.133578. */
    EXPECT(restir_metrics_flip(ia, ib, W, H, ppd67, map, &mean) == 0, "HDR constant pair");
    off = 0;
    for (int i = 0; i < W * H; i++)
        off += fabs(map[i] - 0.133577839) > 2e-6;
    EXPECT(off == 0, "%d pixels of the HDR constant pair are not 0.133578 (first %.9f)", off, map[0]);
    EXPECT_NEAR(mean, 0.133577839, 2e-6, "HDR constant pair mean");
    free(ia);
    free(ib);
}

static void test_exposures(void)
{
    double start, stop, xmax = restir_flip_aces_xmax();
    int count;
    /* x_max solves aces(x) = 0.85: 2.118872 (the notes: about 2.119) */
    EXPECT_NEAR(xmax, 2.118872324, 1e-8, "x_max");
    EXPECT_NEAR(restir_flip_aces((float)xmax), 0.85, 1e-6, "aces(x_max)");
    EXPECT(restir_flip_aces(0.0f) == 0.0f, "aces(0)");
    /* greys have luminance = their value (0.2126 + 0.7152 + 0.0722 = 1): values 0.25, 0, 1, 4, 0.5 sort to
     * 0, 0.25, 0.5, 1, 4; element 5 / 2 = 2 is 0.5. start = log2(2.118872 / 4) = -0.916717,
     * stop = log2(2.118872 / 0.5) = 2.083283, stop - start = log2(8) = 3: 3 exposures */
    const float grey5[15] = {0.25f, 0.25f, 0.25f, 0, 0, 0, 1, 1, 1, 4, 4, 4, 0.5f, 0.5f, 0.5f};
    EXPECT(restir_flip_exposures(grey5, 5, &start, &stop, &count) == 0, "exposures");
    EXPECT_NEAR(start, log2(xmax / 4.0), 1e-12, "start");
    EXPECT_NEAR(stop, log2(xmax / 0.5), 1e-12, "stop");
    EXPECT(count == 3, "count %d, want ceil(3) = 3", count);
    /* even N: 0, 1, 2, 8 -> element 4 / 2 = 2 is 2 (the upper median, as FLIP's partial sort takes it); span
     * log2(8 / 2) = 2: max(2, 2) = 2 */
    const float grey4[12] = {8, 8, 8, 1, 1, 1, 0, 0, 0, 2, 2, 2};
    EXPECT(restir_flip_exposures(grey4, 4, &start, &stop, &count) == 0 && count == 2, "even count %d", count);
    EXPECT_NEAR(stop, log2(xmax / 2.0), 1e-12, "even N median is element N / 2");
    /* a span of 2.5 stops: ceil -> 3; a uniform image: span 0 -> 2 exposures at the same value */
    const float grey2[6] = {1, 1, 1, 0.1767767f, 0.1767767f, 0.1767767f}; /* 2^-2.5 = 0.1767767 */
    EXPECT(restir_flip_exposures(grey2, 2, &start, &stop, &count) == 0 && count == 2, "N = 2: median is the max");
    const float grey3[9] = {1, 1, 1, 0.1767767f, 0.1767767f, 0.1767767f, 0.1767767f, 0.1767767f, 0.1767767f};
    EXPECT(restir_flip_exposures(grey3, 3, &start, &stop, &count) == 0 && count == 3, "span 2.5 -> %d", count);
    EXPECT_NEAR(stop - start, 2.5, 1e-6, "span 2.5");
    /* colours: luminance 0.2126 R + 0.7152 G + 0.0722 B; red 1 (0.2126) and green 1 (0.7152): median element 1 of
     * (0.2126, 0.7152) is 0.7152, max 0.7152 */
    const float rg[6] = {1, 0, 0, 0, 1, 0};
    EXPECT(restir_flip_exposures(rg, 2, &start, &stop, &count) == 0, "colours");
    EXPECT_NEAR(start, log2(xmax / 0.7152), 1e-6, "colour start");
    EXPECT_NEAR(stop, start, 1e-12, "colour stop");
    /* our rules: a median of 0 (3 of 5 black) takes the positive median (0.5, 2: element 1 = 2); no positive
     * luminance gives exposure 0 twice; NaN / infinite pixels are left out */
    const float dark5[15] = {0, 0, 0, 0.5f, 0.5f, 0.5f, 0, 0, 0, 2, 2, 2, 0, 0, 0};
    EXPECT(restir_flip_exposures(dark5, 5, &start, &stop, &count) == 0, "mostly black");
    EXPECT_NEAR(stop, log2(xmax / 2.0), 1e-12, "median of the positive luminances");
    const float black[6] = {0, 0, 0, -1, -1, -1};
    EXPECT(restir_flip_exposures(black, 2, &start, &stop, &count) == 0 && start == 0.0 && stop == 0.0 && count == 2,
           "no positive luminance");
    const float with_nan[9] = {NAN, 0, 0, 4, 4, 4, INFINITY, 1, 1};
    EXPECT(restir_flip_exposures(with_nan, 3, &start, &stop, &count) == 0, "NaN pixel");
    EXPECT_NEAR(start, log2(xmax / 4.0), 1e-12, "finite pixels only");
    /* the median by selection against a sort, on 1001 pseudo-random values with many ties */
    enum { N = 1001 };
    static float many[3 * N];
    static double sorted[N];
    uint32_t s = 12345;
    for (int i = 0; i < N; i++) {
        s = s * 1664525u + 1013904223u;
        const float v = (float)(s >> 24) / 16.0f; /* 256 distinct values: many ties */
        many[3 * i] = many[3 * i + 1] = many[3 * i + 2] = v;
        sorted[i] = 0.2126 * v + 0.7152 * v + 0.0722 * v;
    }
    for (int i = 1; i < N; i++) /* insertion sort */
        for (int j = i; j > 0 && sorted[j - 1] > sorted[j]; j--) {
            const double t = sorted[j];
            sorted[j] = sorted[j - 1];
            sorted[j - 1] = t;
        }
    EXPECT(restir_flip_exposures(many, N, &start, &stop, &count) == 0, "many");
    EXPECT_NEAR(stop, log2(xmax / sorted[N / 2]), 1e-12, "selected median");
    EXPECT_NEAR(start, log2(xmax / sorted[N - 1]), 1e-12, "max");
}

/* A test scene with edges, gradients and colour: w x h linear RGB scaled by `peak` (HDR when peak > 1). */
static float *pattern(int w, int h, float peak)
{
    float *img = malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = img + 3 * ((size_t)y * w + x);
            const int check = ((x / 6) + (y / 6)) % 2;
            const float ramp = (float)x / (float)(w - 1);
            p[0] = peak * (check ? 0.8f * ramp + 0.1f : 0.15f);
            p[1] = peak * (check ? 0.5f : 0.2f + 0.6f * (float)y / (float)(h - 1));
            p[2] = peak * ((x - w / 2) * (x - w / 2) + (y - h / 2) * (y - h / 2) < 64 ? 0.9f : 0.3f * ramp);
        }
    return img;
}

/* img blurred by a Gaussian of std sigma pixels (separable, clamped edges). */
static float *blurred(const float *img, int w, int h, double sigma)
{
    const int r = (int)ceil(3.0 * sigma);
    double kern[64], sum = 0.0;
    for (int i = -r; i <= r; i++)
        sum += kern[i + r] = exp(-0.5 * i * i / (sigma * sigma));
    float *tmp = malloc(sizeof(float) * 3 * (size_t)w * h), *out = malloc(sizeof(float) * 3 * (size_t)w * h);
    for (int pass = 0; pass < 2; pass++) {
        const float *src = pass ? tmp : img;
        float *dst = pass ? out : tmp;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                for (int c = 0; c < 3; c++) {
                    double acc = 0.0;
                    for (int i = -r; i <= r; i++) {
                        int xx = pass ? x : x + i, yy = pass ? y + i : y;
                        xx = xx < 0 ? 0 : xx >= w ? w - 1 : xx;
                        yy = yy < 0 ? 0 : yy >= h ? h - 1 : yy;
                        acc += kern[i + r] * src[3 * ((size_t)yy * w + xx) + c];
                    }
                    dst[3 * ((size_t)y * w + x) + c] = (float)(acc / sum);
                }
    }
    free(tmp);
    return out;
}

/* img plus uniform noise of half-width amp * value (relative: HDR images keep their range), seed fixed. */
static float *noisy(const float *img, int n, float amp, uint32_t seed)
{
    float *out = malloc(sizeof(float) * 3 * (size_t)n);
    for (int i = 0; i < 3 * n; i++) {
        seed = seed * 1664525u + 1013904223u;
        const float u = (float)(seed >> 8) / 16777216.0f * 2.0f - 1.0f;
        out[i] = img[i] * (1.0f + amp * u);
    }
    return out;
}

typedef int (*flip_fn)(const float *, const float *, int, int, double, float *, double *);

static void test_identical_and_symmetry(void)
{
    enum { W = 48, H = 40 };
    const flip_fn fns[2] = {restir_metrics_flip_ldr, restir_metrics_flip};
    const char *names[2] = {"LDR", "HDR"};
    for (int f = 0; f < 2; f++) {
        float *ref = pattern(W, H, f ? 6.0f : 1.0f), *test = noisy(ref, W * H, 0.3f, 7u);
        static float map[W * H], swapped[W * H];
        double mean = -1.0, mean_swapped = -1.0;
        EXPECT(fns[f](ref, ref, W, H, ppd67, map, &mean) == 0 && mean == 0.0, "%s identical: mean %g", names[f], mean);
        int nonzero = 0;
        for (int i = 0; i < W * H; i++)
            nonzero += map[i] != 0.0f;
        EXPECT(nonzero == 0, "%s identical: %d pixels not 0", names[f], nonzero);
        EXPECT(fns[f](test, ref, W, H, ppd67, map, &mean) == 0 && mean > 0.01, "%s noisy: mean %g", names[f], mean);
        EXPECT(fns[f](ref, test, W, H, ppd67, swapped, &mean_swapped) == 0, "%s swapped", names[f]);
        if (f == 0) /* every step treats the two images alike: HyAB and |difference| of features are symmetric */
            EXPECT(memcmp(map, swapped, sizeof map) == 0 && mean == mean_swapped,
                   "LDR-FLIP is symmetric (%.9g vs %.9g)", mean, mean_swapped);
        else /* the exposures come from the reference, whose luminances differ from the test's */
            EXPECT(mean != mean_swapped, "HDR-FLIP should depend on which image is the reference (%.9g both)", mean);
        free(test);
        free(ref);
    }
    /* HDR with the same luminances in both (the test is the reference mirrored left-right): the same exposures,
     * so symmetric again */
    float *ref = pattern(W, H, 6.0f), *mirror = malloc(sizeof(float) * 3 * W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            memcpy(mirror + 3 * (y * W + x), ref + 3 * (y * W + (W - 1 - x)), sizeof(float) * 3);
    static float m1[W * H], m2[W * H];
    double a = -1.0, b = -2.0;
    EXPECT(restir_metrics_flip(mirror, ref, W, H, ppd67, m1, &a) == 0 &&
               restir_metrics_flip(ref, mirror, W, H, ppd67, m2, &b) == 0,
           "HDR mirrored");
    EXPECT(a > 0.0 && a == b && memcmp(m1, m2, sizeof m1) == 0, "HDR with equal luminance sets is symmetric (%g %g)",
           a, b);
    free(mirror);
    free(ref);
}

static void test_monotone(void)
{
    enum { W = 64, H = 48 };
    const flip_fn fns[2] = {restir_metrics_flip_ldr, restir_metrics_flip};
    const char *names[2] = {"LDR", "HDR"};
    for (int f = 0; f < 2; f++) {
        float *ref = pattern(W, H, f ? 8.0f : 0.9f);
        const double sigmas[4] = {0.5, 1.0, 2.0, 4.0};
        double last = 0.0;
        for (int s = 0; s < 4; s++) {
            float *b = blurred(ref, W, H, sigmas[s]);
            double mean = -1.0;
            EXPECT(fns[f](b, ref, W, H, ppd67, NULL, &mean) == 0, "%s blur", names[f]);
            EXPECT(mean > last, "%s: blur sigma %g gives mean %.6f, not above %.6f", names[f], sigmas[s], mean, last);
            last = mean;
            free(b);
        }
        const float amps[4] = {0.02f, 0.05f, 0.1f, 0.2f};
        last = 0.0;
        for (int s = 0; s < 4; s++) {
            float *n = noisy(ref, W * H, amps[s], 99u); /* the same seed: the same noise, scaled */
            double mean = -1.0;
            EXPECT(fns[f](n, ref, W, H, ppd67, NULL, &mean) == 0, "%s noise", names[f]);
            EXPECT(mean > last, "%s: noise %g gives mean %.6f, not above %.6f", names[f], amps[s], mean, last);
            last = mean;
            free(n);
        }
        free(ref);
    }
}

static void test_bad_pixels(void)
{
    enum { W = 40, H = 30 };
    const flip_fn fns[2] = {restir_metrics_flip_ldr, restir_metrics_flip};
    for (int f = 0; f < 2; f++) {
        float *ref = pattern(W, H, f ? 4.0f : 1.0f), *test = pattern(W, H, f ? 4.0f : 1.0f);
        static float map[W * H];
        double mean = 0.0;
        const float bad[2] = {NAN, INFINITY};
        for (int k = 0; k < 2; k++) {
            test[3 * (5 * W + 5) + 1] = bad[k];
            EXPECT(fns[f](test, ref, W, H, ppd67, map, &mean) == 0 && isnan(mean), "%s: a %g pixel: mean %g",
                   f ? "HDR" : "LDR", bad[k], mean);
            EXPECT(isnan(map[5 * W + 5]) && map[(H - 1) * W + W - 1] == 0.0f, "%s: the map is NaN there only",
                   f ? "HDR" : "LDR");
            test[3 * (5 * W + 5) + 1] = ref[3 * (5 * W + 5) + 1];
        }
        /* out-of-range LDR values are clamped (that is LDR-FLIP's input); HDR's negative values count as 0 */
        for (int i = 0; i < 3 * W * H; i++)
            test[i] = f ? -ref[i] : ref[i] + 2.0f;
        const float white[3] = {1.0f, 1.0f, 1.0f}, black[3] = {0.0f, 0.0f, 0.0f};
        float *same = constant_image(W, H, f ? black : white);
        double clamped = -1.0;
        EXPECT(fns[f](test, ref, W, H, ppd67, NULL, &mean) == 0 &&
                   fns[f](same, ref, W, H, ppd67, NULL, &clamped) == 0 && mean == clamped && mean > 0.0,
               "%s: out-of-range values read as %s (%g vs %g)", f ? "HDR" : "LDR", f ? "0" : "1", mean, clamped);
        free(same);
        free(test);
        free(ref);
    }
}

static void test_bad_arguments(void)
{
    const float img[12] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f, 0.0f, 0.5f};
    float map[4];
    double mean;
    const flip_fn fns[2] = {restir_metrics_flip_ldr, restir_metrics_flip};
    for (int f = 0; f < 2; f++) {
        map[0] = map[1] = map[2] = map[3] = 7.0f;
        mean = 7.0;
        EXPECT(fns[f](NULL, img, 2, 2, ppd67, map, &mean) == -1, "NULL test");
        EXPECT(fns[f](img, NULL, 2, 2, ppd67, map, &mean) == -1, "NULL reference");
        EXPECT(fns[f](img, img, 2, 2, ppd67, map, NULL) == -1, "NULL mean");
        EXPECT(fns[f](img, img, 0, 2, ppd67, map, &mean) == -1 && fns[f](img, img, 2, -1, ppd67, map, &mean) == -1,
               "sizes < 1");
        EXPECT(fns[f](img, img, INT32_MAX, INT32_MAX, ppd67, map, &mean) == -1, "a size too large");
        const double bad_ppd[5] = {NAN, INFINITY, 0.0, -67.0, RESTIR_METRICS_FLIP_PPD_MAX * 1.01};
        for (int k = 0; k < 5; k++)
            EXPECT(fns[f](img, img, 2, 2, bad_ppd[k], map, &mean) == -1, "ppd %g", bad_ppd[k]);
        EXPECT(map[0] == 7.0f && map[1] == 7.0f && map[2] == 7.0f && map[3] == 7.0f && mean == 7.0,
               "nothing written on refusal");
        /* the smallest image, and the largest and a tiny ppd, work */
        EXPECT(fns[f](img, img + 3, 1, 1, ppd67, map, &mean) == 0 && isfinite(mean) && mean == map[0], "1 x 1");
        EXPECT(fns[f](img, img, 2, 2, RESTIR_METRICS_FLIP_PPD_MAX, map, &mean) == 0 && mean == 0.0, "largest ppd");
        EXPECT(fns[f](img, img, 2, 2, 1e-3, NULL, &mean) == 0 && mean == 0.0, "tiny ppd");
    }
}

static void test_threads(void)
{
    enum { W = 160, H = 120 }; /* above the 16384 pixels where the work is split */
    float *ref = pattern(W, H, 5.0f), *test = noisy(ref, W * H, 0.2f, 3u);
    static float m1[W * H], m2[W * H];
    double a = -1.0, b = -2.0;
    restir_threads_set(1);
    EXPECT(restir_metrics_flip(test, ref, W, H, ppd67, m1, &a) == 0, "1 thread");
    restir_threads_set(2);
    EXPECT(restir_metrics_flip(test, ref, W, H, ppd67, m2, &b) == 0, "2 threads");
    restir_threads_set(0);
    EXPECT(a == b && memcmp(m1, m2, sizeof m1) == 0, "1 and 2 threads differ: %.9g vs %.9g", a, b);
    free(test);
    free(ref);
}

int main(void)
{
    test_ppd();
    test_color_steps();
    test_hyab_cmax_remap();
    test_kernels();
    test_constant_pair();
    test_exposures();
    test_identical_and_symmetry();
    test_monotone();
    test_bad_pixels();
    test_bad_arguments();
    test_threads();
    return test_finish();
}
