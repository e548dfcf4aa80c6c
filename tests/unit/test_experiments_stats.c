/* test_experiments_stats.c: the harness's statistics in-process (experiments/stats.h):
 *  - running_mean (Welford) equals the two-pass mean and standard error, also for values with a
 *    large common offset where the naive sum of squares cancels; one value has no standard error;
 *  - jackknife_se of the mean's leave-one-out values equals the classical s / sqrt(n) exactly (an
 *    identity of the jackknife for linear estimators);
 *  - Student t's CDF and quantiles against tabulated values;
 *  - paired changes (Student t over seeds' log ratios, the bootstrap for heavy tails, the paired
 *    jackknife for ensemble statistics) on constructed data with known answers, and what pairing
 *    gains over independent means;
 *  - claim_verdict's five classes (reproduced, partly, not reproduced, opposite, undecided) and the
 *    seeds that would decide an undecided claim;
 *  - the reference's own noise from its two halves, subtracted from a relMSE;
 *  - equal_time_spp removes the fixed per-frame cost and falls back to the whole 1-spp time when
 *    timing noise hides the per-path cost. */
#include <math.h>
#include <string.h>

#include "experiments/stats.h"
#include "test_util.h"

static void test_running_mean(void)
{
    const double offset = 1e9;
    const double x[6] = {1.0, 2.0, 4.0, 8.0, 16.0, 32.0};
    struct running_mean r = {0};
    EXPECT(isnan(running_mean_sem(&r)), "an empty stream has no standard error");
    running_mean_add(&r, offset + x[0]);
    EXPECT(r.n == 1 && r.mean == offset + x[0] && isnan(running_mean_sem(&r)), "one value: its mean, no error");
    for (int k = 1; k < 6; k++)
        running_mean_add(&r, offset + x[k]);
    double mean = 0.0, ss = 0.0;
    for (int k = 0; k < 6; k++)
        mean += x[k] / 6.0;
    for (int k = 0; k < 6; k++)
        ss += (x[k] - mean) * (x[k] - mean);
    const double sem = sqrt(ss / 5.0 / 6.0);
    EXPECT(fabs(r.mean - (offset + mean)) < 1e-6, "Welford mean %.9g, two-pass %.9g", r.mean, offset + mean);
    EXPECT(fabs(running_mean_sem(&r) - sem) < 1e-6 * sem, "Welford sem %.9g, two-pass %.9g", running_mean_sem(&r),
           sem);
}

static void test_jackknife(void)
{
    const double x[5] = {3.0, 1.0, 4.0, 1.0, 5.0};
    double theta[5], mean = 0.0, ss = 0.0;
    for (int i = 0; i < 5; i++) {
        double s = 0.0;
        for (int j = 0; j < 5; j++)
            s += j == i ? 0.0 : x[j];
        theta[i] = s / 4.0; /* the mean without x_i */
        mean += x[i] / 5.0;
    }
    for (int i = 0; i < 5; i++)
        ss += (x[i] - mean) * (x[i] - mean);
    const double classical = sqrt(ss / 4.0 / 5.0);
    EXPECT(fabs(jackknife_se(theta, 5) - classical) < 1e-12, "jackknife %.12g, s / sqrt(n) %.12g",
           jackknife_se(theta, 5), classical);
    EXPECT(isnan(jackknife_se(theta, 1)), "one leave-one-out value has no jackknife error");
}

/* A change with the interval [lo, hi] in percent, as the verdict sees it. */
static struct rel_change interval(double pct, double lo, double hi)
{
    return (struct rel_change){pct, lo, hi, log1p(pct / 100.0), (log1p(hi / 100.0) - log1p(lo / 100.0)) / 4.0, 4,
                               INTERVAL_T, 0, 0.0, 0};
}

static void expect_verdict(struct rel_change c, struct claim k, const char *want, const char *what)
{
    char why[160];
    const char *got = claim_verdict(c, k, why, sizeof why);
    EXPECT(!strcmp(got, want), "%s: [%g, %g] against %g%%: %s, expected %s (%s)", what, c.lo, c.hi, k.limit, got, want,
           why);
}

/* Each class of the verdict rule (DESIGN.md, docs/EVALUATION.md) on constructed intervals. */
static void test_verdicts(void)
{
    const struct claim r29 = {CLAIM_REDUCTION, 29.0}, lower = {CLAIM_REDUCTION, 0.0};
    expect_verdict(interval(-30.0, -35.0, -25.0), r29, "reproduced", "reaches -29% on the paper's side");
    expect_verdict(interval(-50.0, -60.0, -40.0), r29, "reproduced", "beyond the paper's effect");
    expect_verdict(interval(-10.0, -15.0, -5.0), r29, "partly", "a smaller gain");
    expect_verdict(interval(-2.0, -8.0, 4.0), r29, "not reproduced", "holds zero, excludes -29%");
    expect_verdict(interval(8.0, 3.0, 13.0), r29, "opposite", "higher");
    expect_verdict(interval(-13.8, -57.9, 30.3), r29, "undecided", "holds both zero and -29% (002's ajar row)");
    expect_verdict(interval(-5.0, -8.0, -2.0), lower, "reproduced", "any reduction, significant");
    expect_verdict(interval(-1.0, -4.0, 2.0), lower, "undecided", "any reduction, within the noise");
    expect_verdict(interval(3.0, 1.0, 5.0), lower, "opposite", "any reduction, higher");
    char why[160];
    claim_verdict(interval(-13.8, -57.9, 30.3), r29, why, sizeof why);
    EXPECT(strstr(why, "seeds would decide") != NULL, "an undecided row says how many seeds decide it: %s", why);
    const struct claim small = {CLAIM_SMALL, 5.0};
    expect_verdict(interval(1.0, -2.0, 4.0), small, "reproduced", "within +-5%");
    expect_verdict(interval(9.0, 7.0, 11.0), small, "not reproduced", "wholly above +5%");
    expect_verdict(interval(4.0, 2.0, 6.0), small, "undecided", "straddles +5%");
    const struct claim cost = {CLAIM_COST, 4.4};
    expect_verdict(interval(2.4, 1.0, 3.8), cost, "reproduced", "at most 4.4% more");
    expect_verdict(interval(6.0, 5.0, 7.0), cost, "not reproduced", "more than 4.4%");
    expect_verdict(interval(4.8, 3.0, 6.6), cost, "undecided", "the interval holds 4.4%");
    const struct claim none = {CLAIM_NONE, 0.0};
    expect_verdict(interval(-5.0, -8.0, -2.0), none, "lower", "no claim, lower");
    expect_verdict(interval(5.0, 2.0, 8.0), none, "higher", "no claim, higher");
    expect_verdict(interval(1.0, -2.0, 4.0), none, "no difference", "no claim, within the noise");
    /* a reference whose own error is as large as the difference judged cannot judge it */
    struct rel_change noisy_ref = interval(-30.0, -35.0, -25.0);
    noisy_ref.ref_ratio = 1.5;
    expect_verdict(noisy_ref, r29, "refused", "the reference's noise exceeds the difference");
    noisy_ref.ref_ratio = 0.1;
    expect_verdict(noisy_ref, r29, "reproduced", "a reference a tenth of the difference judges it");
    /* a metric whose reference error the step did not record: judged, and the row says it went unchecked */
    struct rel_change unchecked = interval(8.0, 3.0, 13.0);
    unchecked.ref_unchecked = 1;
    expect_verdict(unchecked, r29, "opposite", "unchecked against the reference");
    claim_verdict(unchecked, r29, why, sizeof why);
    EXPECT(strstr(why, "not checked against the reference's own error") != NULL, "an unchecked row says so: %s", why);
    unchecked = interval(-13.8, -57.9, 30.3);
    unchecked.ref_unchecked = 1;
    claim_verdict(unchecked, r29, why, sizeof why);
    EXPECT(strstr(why, "seeds would decide it at the measured spread; not checked") != NULL, "both reasons: %s", why);
    /* without an interval the estimate alone decides, and says so */
    struct rel_change point = interval(-30.0, NAN, NAN);
    point.interval = INTERVAL_NONE;
    EXPECT(!strcmp(claim_verdict(point, r29, why, sizeof why), "reproduced") && !strcmp(why, "no spread"),
           "a point estimate: %s", why);
    const double pos[2] = {1.0, 2.0}, neg[2] = {-0.5, 1.0}, nan2[2] = {NAN, 1.0};
    EXPECT(!strcmp(claim_verdict(paired_change(pos, neg, 2, 0), r29, why, sizeof why), "undefined"),
           "a baseline <= 0 has no relative change");
    EXPECT(!strcmp(claim_verdict(paired_change(nan2, pos, 2, 0), r29, why, sizeof why), "not measured"),
           "a missing value is not measured");
}

/* Student t against tabulated values (two-sided 95%: 12.706, 3.182, 2.365, 2.042; the median 0). */
static void test_student_t(void)
{
    EXPECT_NEAR(student_t_quantile(0.95, 1), 12.7062047, 1e-6, "t(0.975, 1)");
    EXPECT_NEAR(student_t_quantile(0.95, 3), 3.18244631, 1e-7, "t(0.975, 3)");
    EXPECT_NEAR(student_t_quantile(0.95, 7), 2.36462425, 1e-7, "t(0.975, 7)");
    EXPECT_NEAR(student_t_quantile(0.95, 30), 2.04227246, 1e-7, "t(0.975, 30)");
    EXPECT_NEAR(student_t_quantile(0.95, 100000), 1.95996398, 1e-4, "t tends to the normal");
    EXPECT_NEAR(student_t_cdf(0.0, 5), 0.5, 1e-15, "the median");
    EXPECT_NEAR(student_t_cdf(-2.0, 1), 0.5 - atan(2.0) / 3.14159265358979323846, 1e-12, "df 1 is Cauchy");
    EXPECT(isnan(student_t_quantile(0.95, 0)) && isnan(student_t_quantile(1.0, 3)), "bad arguments: NaN");
    /* the old rule's "two standard deviations" with 4 runs is an 85% interval, not 95% */
    const double cover = 2.0 * student_t_cdf(2.0, 3) - 1.0;
    EXPECT(cover > 0.85 && cover < 0.87, "2 sd with 3 degrees of freedom covers %.3f", cover);
}

/* Pairing: common random numbers make a constant ratio exact, which independent means cannot see;
 * the paired interval is Student t on the per-seed log ratios. */
static void test_pairing(void)
{
    const double base[8] = {10.0, 14.0, 7.0, 12.0, 9.0, 16.0, 11.0, 8.0};
    double ours[8], sem_b, mean_b = 0.0, ss = 0.0;
    for (int i = 0; i < 8; i++) {
        ours[i] = 0.9 * base[i];
        mean_b += base[i] / 8.0;
    }
    for (int i = 0; i < 8; i++)
        ss += (base[i] - mean_b) * (base[i] - mean_b);
    sem_b = sqrt(ss / 7.0 / 8.0);
    struct rel_change p = paired_change(ours, base, 8, 0);
    EXPECT(fabs(p.pct + 10.0) < 1e-9 && fabs(p.lo + 10.0) < 1e-9 && fabs(p.hi + 10.0) < 1e-9,
           "a constant -10%% per seed is exact when paired: %g [%g, %g]", p.pct, p.lo, p.hi);
    struct rel_change u = unpaired_change(0.9 * mean_b, 0.9 * sem_b, mean_b, sem_b, 8);
    EXPECT(u.lo < -20.0 && u.hi > 0.0, "unpaired, the seeds' spread hides it: [%g, %g]", u.lo, u.hi);
    /* per-seed log ratios with a known mean and spread: the interval is mean +- t(7) s / sqrt(8) */
    const double lr[8] = {-0.10, -0.05, -0.20, -0.12, 0.02, -0.08, -0.15, -0.04};
    double m = 0.0, s2 = 0.0;
    for (int i = 0; i < 8; i++) {
        ours[i] = base[i] * exp(lr[i]);
        m += lr[i] / 8.0;
    }
    for (int i = 0; i < 8; i++)
        s2 += (lr[i] - m) * (lr[i] - m) / 7.0;
    const double h = 2.36462425 * sqrt(s2 / 8.0);
    p = paired_change(ours, base, 8, 0);
    EXPECT(p.interval == INTERVAL_T && p.n == 8, "a t interval over 8 seeds");
    EXPECT_NEAR(p.pct, 100.0 * expm1(m), 1e-9, "the estimate is the geometric mean ratio");
    EXPECT_NEAR(p.lo, 100.0 * expm1(m - h), 1e-6, "lower end");
    EXPECT_NEAR(p.hi, 100.0 * expm1(m + h), 1e-6, "upper end");
    /* one seed: an estimate, no interval */
    p = paired_change(ours, base, 1, 0);
    EXPECT(p.interval == INTERVAL_NONE && isnan(p.lo), "one seed has no interval");
}

/* The bootstrap for heavy-tailed metrics: with one outlying seed, the percentile interval is
 * reported only where it is wider than Student t's; the result is the same on every call. */
static void test_bootstrap(void)
{
    const double base[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    const double skew[8] = {0.80, 0.81, 0.79, 0.80, 0.82, 0.78, 0.80, 3.0}; /* one seed's outlier */
    struct rel_change t = paired_change(skew, base, 8, 0), b = paired_change(skew, base, 8, 1),
                      b2 = paired_change(skew, base, 8, 1);
    EXPECT(t.interval == INTERVAL_T, "without heavy tails: t");
    EXPECT(b.hi - b.lo >= t.hi - t.lo - 1e-12, "the reported interval is the wider: [%g, %g] vs t [%g, %g]", b.lo,
           b.hi, t.lo, t.hi);
    EXPECT(b.lo == b2.lo && b.hi == b2.hi, "the bootstrap is reproducible");
    /* symmetric log ratios: the bootstrap's percentile interval is narrower than t's with 8 seeds */
    const double sym[8] = {0.9, 1.1, 0.95, 1.05, 0.92, 1.08, 0.97, 1.03};
    struct rel_change s = paired_change(sym, base, 8, 1);
    EXPECT(s.interval == INTERVAL_T, "where t is wider, t is reported (%d)", (int)s.interval);
}

/* The paired jackknife of an ensemble statistic: with leave-one-out values of a mean, it is the
 * paired t interval on the per-seed log ratios' mean... to first order; exactly, its standard error
 * is the jackknife's of the leave-one-out log ratios. */
static void test_jackknife_change(void)
{
    const double a[4] = {2.0, 2.2, 1.8, 2.1}, b[4] = {2.5, 2.4, 2.6, 2.45};
    double theta[4];
    for (int i = 0; i < 4; i++)
        theta[i] = log(a[i] / b[i]);
    struct rel_change c = jackknife_change(2.0, 2.5, a, b, 4);
    const double se = jackknife_se(theta, 4), h = 3.18244631 * se;
    EXPECT(c.interval == INTERVAL_JACKKNIFE, "a jackknife interval");
    EXPECT_NEAR(c.pct, -20.0, 1e-9, "the estimate is the full statistics' ratio");
    EXPECT_NEAR(c.lo, 100.0 * expm1(log(0.8) - h), 1e-6, "lower end");
    EXPECT_NEAR(c.hi, 100.0 * expm1(log(0.8) + h), 1e-6, "upper end");
    c = jackknife_change(2.0, 2.5, a, b, 2);
    EXPECT(c.interval == INTERVAL_NONE && fabs(c.pct + 20.0) < 1e-9, "under 3 seeds: the estimate alone");
    EXPECT(jackknife_change(1.0, -0.1, a, b, 4).no_base, "a negative covariance has no ratio");
}

/* Seeds to decide: the least n whose interval half-width, at the measured per-seed spread, falls
 * below the estimate's distance to the farther of zero and the paper's effect. */
static void test_seeds_to_decide(void)
{
    const struct claim r29 = {CLAIM_REDUCTION, 29.0};
    struct rel_change c = {-13.8, -57.9, 30.3, log(0.862), 0.2, 4, INTERVAL_T, 0, 0.0, 0};
    const int n = stats_seeds_to_decide(c, r29);
    const double s = 0.2 * 2.0, d = fmax(fabs(log(0.862)), fabs(log(0.862) - log(0.71)));
    EXPECT(n > 4, "more seeds than measured: %d", n);
    EXPECT(student_t_quantile(0.95, n - 1) * s / sqrt(n) < d, "n = %d decides", n);
    EXPECT(student_t_quantile(0.95, n - 2) * s / sqrt(n - 1.0) >= d, "n - 1 = %d does not", n - 1);
    c.log_se = 0.0;
    EXPECT(stats_seeds_to_decide(c, r29) == -1, "no spread: nothing to say");
    struct rel_change zero = {0.0, -5.0, 5.0, 0.0, 0.02, 8, INTERVAL_T, 0, 0.0, 0};
    EXPECT(stats_seeds_to_decide(zero, (struct claim){CLAIM_REDUCTION, 0.0}) == -1,
           "an estimate of exactly zero never decides \"lower\"");
}

/* The reference's own noise from its halves: a = R + e1, b = R + e2 with e ~ N(0, sigma^2), r their
 * mean; x = R + e3. relMSE(x, r) - reference_halves_relmse(a, b) estimates relMSE(x, R) without the
 * reference's share sigma^2 / 2 / (R^2 + 1e-3). */
static void test_reference_halves(void)
{
    enum { N = 200000 };
    static float a[3 * N], b[3 * N], x[3 * N];
    const double R = 0.5, sa = 0.05, sx = 0.1;
    unsigned long long st = 42;
    for (int i = 0; i < 3 * N; i++) { /* Box-Muller from a 64-bit LCG */
        double g[3];
        for (int k = 0; k < 3; k++) {
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            const double u1 = ((st >> 11) + 0.5) / 9007199254740992.0;
            st = st * 6364136223846793005ull + 1442695040888963407ull;
            const double u2 = ((st >> 11) + 0.5) / 9007199254740992.0;
            g[k] = sqrt(-2.0 * log(u1)) * cos(6.28318530717958647692 * u2);
        }
        a[i] = (float)(R + sa * g[0]);
        b[i] = (float)(R + sa * g[1]);
        x[i] = (float)(R + sx * g[2]);
    }
    const double denom = R * R + 1e-3, ref_share = sa * sa / 2.0 / denom, truth = sx * sx / denom;
    const double v = reference_halves_relmse(a, b, N);
    EXPECT(fabs(v - ref_share) < 0.03 * ref_share, "reference variance share %g, expected %g", v, ref_share);
    double raw = 0.0;
    for (int i = 0; i < 3 * N; i++) {
        const double r = 0.5 * (a[i] + b[i]), d = x[i] - r;
        raw += d * d / (r * r + 1e-3) / (3.0 * N);
    }
    EXPECT(fabs(raw - (truth + ref_share)) < 0.03 * truth, "raw relMSE %g holds the reference's share", raw);
    EXPECT(fabs(raw - v - truth) < 0.03 * truth, "subtracted: %g, the truth %g", raw - v, truth);
    EXPECT(isnan(reference_halves_relmse(NULL, b, N)) && isnan(reference_halves_relmse(a, b, 0)), "bad arguments");
}

static void test_equal_time(void)
{
    /* 2 ms fixed + 3 ms per path: 1 spp 5 ms, 4 spp 14 ms; a 32 ms budget fits (32 - 2) / 3 = 10 paths */
    EXPECT(equal_time_spp(32.0, 5.0, 14.0) == 10, "fixed cost removed: %d spp", equal_time_spp(32.0, 5.0, 14.0));
    /* noise: 4 spp barely slower than 1 spp, so the 1-spp time is all per-path cost */
    EXPECT(equal_time_spp(32.0, 5.0, 5.5) == 6, "noisy timings: %d spp", equal_time_spp(32.0, 5.0, 5.5));
    EXPECT(equal_time_spp(1.0, 5.0, 14.0) == 1, "a budget below one path still renders one");
    EXPECT(equal_time_spp(NAN, 5.0, 14.0) == 1 && equal_time_spp(10.0, 0.0, 0.0) == 1, "degenerate timings: 1");
}

int main(void)
{
    test_running_mean();
    test_jackknife();
    test_verdicts();
    test_student_t();
    test_pairing();
    test_bootstrap();
    test_jackknife_change();
    test_seeds_to_decide();
    test_reference_halves();
    test_equal_time();
    return test_finish();
}
