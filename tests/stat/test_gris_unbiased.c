/* test_gris_unbiased.c: RIS and GRIS unbiasedness on 1-D integrands with known integrals, and the
 * measurable bias of 1/M weights (004 Eq. 5-12). Must never depend on Embree, files or renderer. */
#include <math.h>

#include "accum.h"
#include "core/rng.h"
#include "restir/mis.h"
#include "restir/gris.h"
#include "test_util.h"

#define TRIALS 400000
#define Z_MAX 4.5

/* Integrand family g(t) = t^2 + 0.1 sin(20 t) + 0.2 (>= 0.1), its antiderivative, and the target
 * approximation g_hat(t) = t^2 + 0.2 that ignores the oscillation. */
static double g(double t) { return t * t + 0.1 * sin(20.0 * t) + 0.2; }
static double g_int(double t) { return t * t * t / 3.0 - 0.005 * cos(20.0 * t) + 0.2 * t; }
static double g_hat(double t) { return t * t + 0.2; }

/* Unbiased check: within Z_MAX sigma of the mean AND within 1% relative. */
static void expect_unbiased(const struct accum *a, double exact, const char *what)
{
    double m = acc_mean(a), s = acc_sigma(a);
    double z = (m - exact) / s;
    printf("  %-44s mean %.6f exact %.6f sigma %.6f z %+.2f rel %+.4f%%\n", what, m, exact, s, z,
           100.0 * (m - exact) / exact);
    EXPECT(fabs(z) < Z_MAX, "%s: z = %.2f", what, z);
    EXPECT(fabs(m - exact) < 0.01 * fabs(exact), "%s: relative error %.4f", what,
           (m - exact) / exact);
}

/* ---------------- (a) RIS on [0,1] (004 Sec. 2.2, Eq. 2 and Eq. 7 with m_i = 1/M) ------------ */

enum source { SRC_UNIFORM, SRC_LINEAR, SRC_MIXED };

/* Linear source pdf p(x) = 0.5 + x on [0,1], sampled by inverting its CDF 0.5 x + x^2 / 2. */
static double linear_pdf(double x) { return 0.5 + x; }
static double linear_sample(float u) { return -0.5 + sqrt(0.25 + 2.0 * (double)u); }

static double ris_estimate(pcg32 *rng, int M, enum source src)
{
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double y = 0.0;
    for (int i = 0; i < M; i++) {
        int linear = src == SRC_LINEAR || (src == SRC_MIXED && (i & 1));
        double x, pdf;
        if (linear) {
            x = linear_sample(pcg32_float(rng));
            pdf = linear_pdf(x);
        } else {
            x = (double)pcg32_float(rng);
            pdf = 1.0;
        }
        /* Eq. 2 with the 1/M resampling MIS weight: every source covers all of [0,1] */
        float w = (float)(g_hat(x) / (pdf * (double)M));
        if (restir_reservoir_offer(&r, w, pcg32_float(rng)))
            y = x;
    }
    float W = restir_gris_contribution_weight(&r, (float)g_hat(y)); /* Eq. 7 */
    return g(y) * (double)W;
}

static void test_ris(void)
{
    static const struct {
        int M;
        enum source src;
        const char *name;
    } cases[] = {{1, SRC_UNIFORM, "RIS M=1 uniform"},    {4, SRC_UNIFORM, "RIS M=4 uniform"},
                 {16, SRC_UNIFORM, "RIS M=16 uniform"},  {1, SRC_LINEAR, "RIS M=1 linear pdf"},
                 {8, SRC_LINEAR, "RIS M=8 linear pdf"}, {8, SRC_MIXED, "RIS M=8 uniform+linear"}};
    const double exact = g_int(1.0) - g_int(0.0);
    for (unsigned c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        pcg32 rng = rng_for(11u, c, 0u, 0u);
        struct accum a = {0.0, 0.0, 0};
        for (long t = 0; t < TRIALS; t++)
            acc_add(&a, ris_estimate(&rng, cases[c].M, cases[c].src));
        expect_unbiased(&a, exact, cases[c].name);
    }
}

/* ---------------- (b) GRIS across 4 pixel domains with failing shifts (004 Eq. 5-12) ---------
 * Every pixel domain is [0,1]. Pixel k's sample x sits at "scene point" s = a_k x + o_k, its
 * integrand is f_k(x) = g(a_k x + o_k) and its target p_hat_k(x) = g_hat(a_k x + o_k), except
 * pixel 2 whose target is zero for x in [0.4, 0.6) (f_2 is not). The shift into pixel 0 keeps the
 * scene point: T_k(x) = (a_k x + o_k - o_0) / a_0, a partial bijection that fails when the result
 * leaves [0,1]. Pixel 0 (a = 1, o = 0.3) is canonical.
 *   pixel 1: T_1(x) = x + 0.2   (fails for x > 0.8; image [0.2, 1])
 *   pixel 2: T_2(x) = x - 0.15  (fails for x < 0.15; image [0, 0.85] minus [0.25, 0.45))
 *   pixel 3: T_3(x) = 1.25 x    (fails for x > 0.8; |dT_3/dx| = 1.25, image [0, 1]) */
#define NPIX 4
#define INIT_M 4
static const double pix_a[NPIX] = {1.0, 1.0, 1.0, 1.25};
static const double pix_o[NPIX] = {0.3, 0.5, 0.15, 0.3};

static double target(int k, double x)
{
    if (x < 0.0 || x > 1.0)
        return 0.0;
    if (k == 2 && x >= 0.4 && x < 0.6)
        return 0.0;
    return g_hat(pix_a[k] * x + pix_o[k]);
}
static double f_pixel0(double y) { return g(y + pix_o[0]); }

/* Shift T_k into pixel 0; returns 0 when it fails, else 1 with y and |dT_k/dx|. */
static int shift_to0(int k, double x, double *y, double *jac)
{
    double v = (pix_a[k] * x + pix_o[k] - pix_o[0]) / pix_a[0];
    if (v < 0.0 || v > 1.0)
        return 0;
    *y = v;
    *jac = pix_a[k] / pix_a[0];
    return 1;
}

/* 004 Eq. 10: p_hat_{<-k}(y) = [y in T_k(supp)] p_hat_k(T_k^{-1}(y)) |dT_k^{-1}/dy|. */
static double target_from(int k, double y)
{
    double x = (pix_a[0] * y + pix_o[0] - pix_o[k]) / pix_a[k];
    if (x < 0.0 || x > 1.0)
        return 0.0;
    return target(k, x) * (pix_a[0] / pix_a[k]);
}

/* Initial sample of pixel k: RIS from INIT_M uniform candidates; W = 0 when none is valid. */
static void initial_sample(pcg32 *rng, int k, double *x_out, double *W_out)
{
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double x = 0.0;
    for (int i = 0; i < INIT_M; i++) {
        double cand = (double)pcg32_float(rng);
        if (restir_reservoir_offer(&r, (float)(target(k, cand) / INIT_M), pcg32_float(rng)))
            x = cand;
    }
    *x_out = x;
    *W_out = (double)restir_gris_contribution_weight(&r, (float)target(k, x));
}

/* One GRIS merge into pixel 0 from pixels 0..3; returns f_0(Y) W_Y. */
static double gris_estimate(pcg32 *rng, enum restir_mis mode, const float *conf, int use_jacobian)
{
    double y[NPIX], W[NPIX], jac[NPIX];
    int ok[NPIX];
    for (int k = 0; k < NPIX; k++) {
        double x;
        initial_sample(rng, k, &x, &W[k]);
        ok[k] = W[k] > 0.0 && shift_to0(k, x, &y[k], &jac[k]); /* Eq. 5 */
    }
    /* p[k*n+j] = p_hat_{<-k}(Y_j); columns of failed shifts are never used */
    float p[NPIX * NPIX], m[NPIX];
    for (int k = 0; k < NPIX; k++)
        for (int j = 0; j < NPIX; j++)
            p[k * NPIX + j] =
                ok[j] && restir_mis_needs(mode, k, j) ? (float)target_from(k, y[j]) : 0.0f;
    restir_mis_weights(mode, NPIX, conf, p, m);
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double ysel = 0.0;
    for (int j = 0; j < NPIX; j++) {
        /* Eq. 6: w_j = [X_j in D(T_j)] m_j(Y_j) p_hat(Y_j) W_{X_j} |dT_j/dX_j| */
        double w = ok[j] ? (double)m[j] * target(0, y[j]) * W[j] * (use_jacobian ? jac[j] : 1.0)
                         : 0.0;
        if (restir_reservoir_offer(&r, (float)w, pcg32_float(rng)))
            ysel = y[j];
    }
    double Wy = (double)restir_gris_contribution_weight(&r, (float)target(0, ysel)); /* Eq. 7 */
    return f_pixel0(ysel) * Wy;
}

/* Integral of f_0 over [a,b] in pixel 0's coordinates. */
static double f0_int(double a, double b) { return g_int(b + pix_o[0]) - g_int(a + pix_o[0]); }

/* What 1/M converges to: each domain i hands its constant share c_i / sum c only over the part of
 * pixel 0 it can produce, E = sum_i (c_i / sum c) int_{T_i(supp X_i)} f_0, so the mass of the
 * regions a domain cannot reach is lost (the violation of 004 Eq. 8). */
static double uniform_expectation(const float *c)
{
    double cover[NPIX] = {f0_int(0.0, 1.0), f0_int(0.2, 1.0),
                          f0_int(0.0, 0.25) + f0_int(0.45, 0.85), f0_int(0.0, 1.0)};
    double csum = 0.0, e = 0.0;
    for (int k = 0; k < NPIX; k++)
        csum += c[k];
    for (int k = 0; k < NPIX; k++)
        e += c[k] / csum * cover[k];
    return e;
}

static struct accum run_gris(unsigned seed, enum restir_mis mode, const float *c, int use_jacobian)
{
    pcg32 rng = rng_for(seed, (uint64_t)mode, 0u, (uint64_t)use_jacobian);
    struct accum a = {0.0, 0.0, 0};
    for (long t = 0; t < TRIALS; t++)
        acc_add(&a, gris_estimate(&rng, mode, c, use_jacobian));
    return a;
}

static void test_gris(void)
{
    const double exact = f0_int(0.0, 1.0);
    static const float conf[3][NPIX] = {{1.0f, 1.0f, 1.0f, 1.0f},
                                        {1.0f, 5.0f, 20.0f, 5.0f},
                                        {20.0f, 1.0f, 5.0f, 20.0f}};
    char name[96];
    for (int ci = 0; ci < 3; ci++) {
        const float *c = conf[ci];
        for (int mode = RESTIR_MIS_BALANCE; mode <= RESTIR_MIS_PAIRWISE; mode++) {
            struct accum a = run_gris(100u + (unsigned)ci, (enum restir_mis)mode, c, 1);
            snprintf(name, sizeof name, "GRIS %s c=(%g,%g,%g,%g)",
                     restir_mis_name((enum restir_mis)mode), (double)c[0], (double)c[1],
                     (double)c[2], (double)c[3]);
            expect_unbiased(&a, exact, name);
        }
    }

    /* 1/M: biased by the regions some domains cannot reach; the test must see it */
    for (int ci = 0; ci < 2; ci++) {
        const float *c = conf[ci];
        struct accum a = run_gris(200u + (unsigned)ci, RESTIR_MIS_UNIFORM, c, 1);
        double m = acc_mean(&a), s = acc_sigma(&a);
        double bias_sigmas = (m - exact) / s;
        printf("  1/M c=(%g,%g,%g,%g): mean %.6f exact %.6f sigma %.6f bias %+.6f (%+.1f sigma, "
               "%+.2f%%)\n",
               (double)c[0], (double)c[1], (double)c[2], (double)c[3], m, exact, s, m - exact,
               bias_sigmas, 100.0 * (m - exact) / exact);
        EXPECT(fabs(bias_sigmas) > 6.0, "1/M bias only %.2f sigma: the test has no power",
               bias_sigmas);
        snprintf(name, sizeof name, "1/M matches predicted biased value c%d", ci);
        expect_unbiased(&a, uniform_expectation(c), name);
    }

    /* Dropping |dT/dx| from Eq. 6 must also be visible (pixel 3's shift scales by 1.25). */
    struct accum a = run_gris(300u, RESTIR_MIS_BALANCE, conf[0], 0);
    double bias_sigmas = (acc_mean(&a) - exact) / acc_sigma(&a);
    printf("  balance without Jacobian: mean %.6f exact %.6f (%+.1f sigma)\n", acc_mean(&a), exact,
           bias_sigmas);
    EXPECT(fabs(bias_sigmas) > 6.0, "missing Jacobian bias only %.2f sigma", bias_sigmas);
}

int main(void)
{
    test_ris();
    test_gris();
    return test_finish();
}
