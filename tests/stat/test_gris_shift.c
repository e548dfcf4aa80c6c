/* test_gris_shift.c: GRIS with generalized balance (004 Eq. 9) and defensive pairwise (004 Eq.
 * 11-12) resampling MIS weights is unbiased on synthetic 1-D domains whose shift maps are
 * non-trivial partial bijections (Jacobian != 1, undefined on part of the source domain), checked
 * against a closed-form integral; "1/M" weights on the same setup must be detected as biased and
 * must land on their own predicted (wrong) value. Must never depend on Embree, files or renderer.
 *
 * Setup. Target domain Omega_0 = [0,1), integrand f_0(y) = 0.25 + sin^2(pi y) + a tent spike of
 * height 6 and half-width 0.03 at y = 0.8; int f_0 = 0.25 + 0.5 + 0.18 = 0.93.
 * Domain 0 is canonical (identity shift, 004 Sec. 2.3.3): it samples p_0(y) = 1.5 - y > 0 on all
 * of [0,1), so it alone covers supp f_0. Three source domains Omega_i = [0,1), each with its own
 * integrand f_i (its RIS target p_hat_i = f_i), its own linear density p_i (not proportional to
 * f_i, sampled by inverse CDF) and its own shift T_i: Omega_i -> Omega_0, undefined where x lies
 * in a failure interval or where T_i(x) leaves [0,1):
 *   i  f_i = p_hat_i               p_i           T_i(x)         T_i also fails for x in
 *   1  0.2 + 3 x^2                 0.5 + x       0.6 x + 0.4    [0.6, 0.75)
 *   2  1.3 - x, 0 on [0.55,0.65)   1.2 - 0.4 x   1.5 x^2 - 0.2  [0.8, 0.84)
 *   3  0.05 + exp(-(x-.35)^2/.0225) 0.75 + 0.5 x 1.6 x - 0.3    [0.64, 0.72)
 * (T_2 leaves [0,1) outside x in [0.365, 0.894), T_3 outside [0.1875, 0.8125)),
 * so |dT/dx| is 0.6, 3 x and 1.6 (never 1) and every T_i covers only part of Omega_0.
 * No neighbour reaches the spike, neighbour 1 never reaches [0, 0.4) and, with RIS inputs,
 * neighbour 2 never reaches T_2([0.55, 0.65)): 1/M loses mass there (violates 004 Eq. 8). */
#include <math.h>
#include <stdint.h>

#include "accum.h"
#include "core/rng.h"
#include "restir/mis.h"
#include "restir/gris.h"
#include "synthetic_domains.h"
#include "synthetic_integrand.h"
#include "test_util.h"

#define NDOM 4
#define TRIALS 1000000L       /* per balance / pairwise row */
#define TRIALS_BIASED 250000L /* per 1/M row: its bias is hundreds of sigma even at this count */
#define CHUNKS 16             /* fixed streams per row: results do not depend on the thread count */
#define Z_MAX 4.5             /* unbiased runs: |z| below this */
#define Z_BIASED 6.0          /* 1/M runs: |z| against the true integral above this */
#define REL_MAX 0.01          /* unbiased runs: relative error below 1% as a sanity bound */
#define RIS_K 3               /* candidates of the inner RIS that makes W a genuine RIS UCW */

/* ---------------- target domain: integrand (synthetic_integrand.h), the two targets ---------- */


/* Target of the target domain: TARGET_F uses p_hat_0 = f_0 (then f_0(Y) W_Y = sum w and the WRS
 * pick is irrelevant); TARGET_SMOOTH uses p_hat_0 = 0.35 + sin^2(pi y), which ignores the spike,
 * so unbiasedness cannot come from p_hat == f and the selection matters. Both are > 0 on [0,1),
 * so supp f_0 is inside supp p_hat_0 as 004 Eq. 3/7 require. */
enum target { TARGET_F, TARGET_SMOOTH };
static double phat0(enum target t, double y)
{
    if (y < 0.0 || y >= 1.0)
        return 0.0;
    return t == TARGET_F ? synthetic_f0(y) : 0.35 + synthetic_sin2(y);
}

/* ---------------- domains: densities, source targets, shift maps ------------------------------ */

static const struct synthetic_domain dom[NDOM] = {
    {SHIFT_IDENTITY, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.5, -1.0},
    {SHIFT_AFFINE, 0.6, 0.4, 0.6, 0.75, 0.0, 0.0, 0.5, 1.0},
    {SHIFT_QUADRATIC, 1.5, -0.2, 0.8, 0.84, 0.55, 0.65, 1.2, -0.4},
    {SHIFT_AFFINE, 1.6, -0.3, 0.64, 0.72, 0.0, 0.0, 0.75, 0.5},
};

/* Source integrands f_i = source targets p_hat_i, i >= 1 (different shapes per domain). */
static double f_src(int k, double x)
{
    if (synthetic_target_vanishes(&dom[k], x))
        return 0.0;
    switch (k) {
    case 1:
        return 0.2 + 3.0 * x * x;
    case 2:
        return 1.3 - x;
    default: {
        double d = (x - 0.35) / 0.15;
        return 0.05 + exp(-d * d);
    }
    }
}

/* Target of domain k in its own coordinates: p_hat_0 for the canonical, f_k for the others. */
static double target_of(int k, enum target t, double x)
{
    return k == 0 ? phat0(t, x) : f_src(k, x);
}

/* 004 Eq. 10: p_hat_{<-k}(y) = [y in T_k(supp X_k)] p_hat_k(T_k^{-1}(y)) |dT_k^{-1}/dy|.
 * Here supp p_hat_k is inside supp X_k for both input kinds, so the bracket reduces to "y is in
 * the image of T_k"; outside it, or where p_hat_k vanishes, the value is 0. */
static double phat_from(int k, enum target t, double y)
{
    double x, jac;
    if (!synthetic_shift_inv(&dom[k], y, &x, &jac))
        return 0.0;
    return target_of(k, t, x) / jac;
}

/* ---------------- one GRIS merge -------------------------------------------------------------- */

enum inputs { INPUT_PDF, INPUT_RIS };

/* Input (X_k, W_k) of domain k: INPUT_PDF draws X ~ p_k with W = 1/p_k(X) (supp X_k = [0,1));
 * INPUT_RIS resamples RIS_K candidates from p_k towards target p_hat_k, W = sum w / p_hat_k(X)
 * (004 Eq. 2 and 7 with m = 1/K; supp X_k = supp p_hat_k). W = 0 when no candidate was valid. */
static void domain_input(pcg32 *rng, int k, enum target t, enum inputs in, double *x, double *W)
{
    if (in == INPUT_PDF) {
        *x = synthetic_pdf_sample(&dom[k], pcg32_float(rng));
        *W = 1.0 / synthetic_pdf(&dom[k], *x);
        return;
    }
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double sel = 0.0;
    for (int i = 0; i < RIS_K; i++) {
        double cand = synthetic_pdf_sample(&dom[k], pcg32_float(rng));
        float w = (float)(target_of(k, t, cand) / ((double)RIS_K * synthetic_pdf(&dom[k], cand)));
        if (restir_reservoir_offer(&r, w, pcg32_float(rng)))
            sel = cand;
    }
    *x = sel;
    *W = (double)restir_gris_contribution_weight(&r, (float)target_of(k, t, sel));
}

static const float conf[NDOM] = {1.0f, 2.0f, 0.5f, 3.0f};

/* One GRIS merge into domain 0 (004 Eq. 5-7); returns f_0(Y) W_Y. */
static double gris_once(pcg32 *rng, enum restir_mis mode, enum target t, enum inputs in)
{
    double y[NDOM], W[NDOM], jac[NDOM];
    int ok[NDOM];
    for (int k = 0; k < NDOM; k++) {
        double x;
        domain_input(rng, k, t, in, &x, &W[k]);
        ok[k] = W[k] > 0.0 && synthetic_shift_fwd(&dom[k], x, &y[k], &jac[k]); /* Eq. 5 */
    }
    /* p[k*n+j] = p_hat_{<-k}(Y_j) (Eq. 10); entries of failed columns stay unused */
    float p[NDOM * NDOM], m[NDOM];
    for (int k = 0; k < NDOM; k++)
        for (int j = 0; j < NDOM; j++)
            p[k * NDOM + j] =
                ok[j] && restir_mis_needs(mode, k, j) ? (float)phat_from(k, t, y[j]) : 0.0f;
    restir_mis_weights(mode, NDOM, conf, p, m); /* Eq. 9, Eq. 11-12, or 1/M */
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double ysel = 0.0;
    for (int j = 0; j < NDOM; j++) {
        /* Eq. 6: w_j = [X_j in D(T_j)] m_j(Y_j) p_hat(Y_j) W_{X_j} |dT_j/dX_j| */
        double w = ok[j] ? (double)m[j] * phat0(t, y[j]) * W[j] * jac[j] : 0.0;
        if (restir_reservoir_offer(&r, (float)w, pcg32_float(rng)))
            ysel = y[j];
    }
    double Wy = (double)restir_gris_contribution_weight(&r, (float)phat0(t, ysel)); /* Eq. 7 */
    return synthetic_f0(ysel) * Wy;
}

/* ---------------- what 1/M converges to -------------------------------------------------------
 * With constant m_i = c_i / sum c, E[f_0(Y) W_Y] = sum_i m_i int_{T_i(supp X_i)} f_0(y) dy (004
 * Eq. 3, 6, 7 with the change of variables through T_i): each domain's share is only paid over
 * the part of Omega_0 it can reach. supp X_i is [0,1) minus, for RIS inputs, the zero set of f_i;
 * the shifts are increasing, so interval images are intervals. */
static double reach_integral(int k, double lo, double hi)
{
    /* integral of f_0 over T_k([lo,hi) minus the failure interval) */
    const struct synthetic_domain *d = &dom[k];
    double cuts[2][2] = {{lo, hi}, {0.0, 0.0}};
    int n = 1;
    if (d->kind != SHIFT_IDENTITY && d->fail_hi > d->fail_lo) {
        double fl = fmax(lo, d->fail_lo), fh = fmin(hi, d->fail_hi);
        if (fh > fl) {
            cuts[0][1] = fl;
            cuts[1][0] = fh;
            cuts[1][1] = hi;
            n = 2;
        }
    }
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double a = cuts[i][0], b = cuts[i][1];
        if (!(b > a))
            continue;
        double ya = synthetic_shift_map(d, a), yb = synthetic_shift_map(d, b);
        ya = fmin(fmax(ya, 0.0), 1.0);
        yb = fmin(fmax(yb, 0.0), 1.0);
        if (yb > ya)
            sum += synthetic_f0_int(ya, yb);
    }
    return sum;
}

static double uniform_expectation(enum inputs in)
{
    double csum = 0.0, e = 0.0;
    for (int k = 0; k < NDOM; k++)
        csum += conf[k];
    for (int k = 0; k < NDOM; k++) {
        double reach;
        if (in == INPUT_RIS && dom[k].zero_hi > dom[k].zero_lo)
            reach = reach_integral(k, 0.0, dom[k].zero_lo) + reach_integral(k, dom[k].zero_hi, 1.0);
        else
            reach = reach_integral(k, 0.0, 1.0);
        e += (double)conf[k] / csum * reach;
    }
    return e;
}

/* ---------------- statistics and driver ------------------------------------------------------- */

/* trials independent merges split over CHUNKS fixed RNG streams, summed in chunk order. */
static struct accum run(unsigned seed, enum restir_mis mode, enum target t, enum inputs in,
                        long trials)
{
    struct accum part[CHUNKS];
#if defined(_OPENMP)
#pragma omp parallel for schedule(static)
#endif
    for (int c = 0; c < CHUNKS; c++) {
        pcg32 rng = rng_for(seed, (uint64_t)c, (uint64_t)mode, 2u * (uint64_t)t + (uint64_t)in);
        struct accum a = {0.0, 0.0, 0};
        for (long i = 0; i < trials / CHUNKS; i++)
            acc_add(&a, gris_once(&rng, mode, t, in));
        part[c] = a;
    }
    struct accum total = {0.0, 0.0, 0};
    for (int c = 0; c < CHUNKS; c++)
        acc_merge(&total, &part[c]);
    return total;
}

static const char *target_name(enum target t) { return t == TARGET_F ? "f0" : "smooth"; }
static const char *inputs_name(enum inputs in) { return in == INPUT_PDF ? "1/p" : "RIS3"; }

/* Prints one table row and returns z = (mean - reference) / sigma. */
static double row(const char *mode, enum target t, enum inputs in, const struct accum *a,
                  double ref, const char *ref_name)
{
    double m = acc_mean(a), s = acc_sigma(a), z = (m - ref) / s;
    printf("  %-9s %-7s %-5s %10.6f %10.6f %-6s %9.6f %+9.2f %+8.3f%%\n", mode, target_name(t),
           inputs_name(in), m, ref, ref_name, s, z, 100.0 * (m - ref) / ref);
    return z;
}

int main(void)
{
    const double exact = synthetic_f0_int(0.0, 1.0);
    EXPECT_NEAR(exact, 0.93, 1e-12, "closed-form integral of f_0");
    printf("GRIS with failing non-trivial shifts, %ld trials per row (1/M: %ld), c = (%g, %g, %g, "
           "%g)\n",
           TRIALS, TRIALS_BIASED, (double)conf[0], (double)conf[1], (double)conf[2],
           (double)conf[3]);
    printf("  %-9s %-7s %-5s %10s %10s %-6s %9s %9s %9s\n", "mode", "target", "input", "estimate",
           "reference", "", "sigma", "z", "rel");

    unsigned seed = 4000u;
    static const enum restir_mis good[2] = {RESTIR_MIS_BALANCE, RESTIR_MIS_PAIRWISE};
    for (int mi = 0; mi < 2; mi++)
        for (int t = TARGET_F; t <= TARGET_SMOOTH; t++)
            for (int in = INPUT_PDF; in <= INPUT_RIS; in++) {
                struct accum a = run(seed++, good[mi], (enum target)t, (enum inputs)in, TRIALS);
                double z = row(restir_mis_name(good[mi]), (enum target)t, (enum inputs)in, &a,
                               exact, "exact");
                double rel = (acc_mean(&a) - exact) / exact;
                EXPECT(fabs(z) < Z_MAX, "%s %s %s: z = %.2f", restir_mis_name(good[mi]),
                       target_name((enum target)t), inputs_name((enum inputs)in), z);
                EXPECT(fabs(rel) < REL_MAX, "%s %s %s: relative error %.4f",
                       restir_mis_name(good[mi]), target_name((enum target)t),
                       inputs_name((enum inputs)in), rel);
            }

    /* 1/M on the same setup: the test must be able to fail, and the failure must be the
     * predicted one (mass lost where some domain cannot reach, 004 Eq. 8 violated). */
    static const struct {
        enum target t;
        enum inputs in;
    } bad[2] = {{TARGET_F, INPUT_PDF}, {TARGET_SMOOTH, INPUT_RIS}};
    for (int bi = 0; bi < 2; bi++) {
        struct accum a = run(seed++, RESTIR_MIS_UNIFORM, bad[bi].t, bad[bi].in, TRIALS_BIASED);
        double z = row("1/M", bad[bi].t, bad[bi].in, &a, exact, "exact");
        EXPECT(fabs(z) > Z_BIASED, "1/M %s %s: bias only %.2f sigma, the test has no power",
               target_name(bad[bi].t), inputs_name(bad[bi].in), z);
        double pred = uniform_expectation(bad[bi].in);
        double zp = row("1/M", bad[bi].t, bad[bi].in, &a, pred, "pred");
        EXPECT(fabs(zp) < Z_MAX, "1/M %s %s: z = %.2f against its predicted value %.6f",
               target_name(bad[bi].t), inputs_name(bad[bi].in), zp, pred);
    }
    return test_finish();
}
