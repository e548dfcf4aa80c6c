/* test_experiments_stats.c: the harness's statistics in-process (experiments/stats.h):
 *  - running_mean (Welford) equals the two-pass mean and standard error, also for values with a
 *    large common offset where the naive sum of squares cancels; one value has no standard error;
 *  - jackknife_se of the mean's leave-one-out values equals the classical s / sqrt(n) exactly (an
 *    identity of the jackknife for linear estimators);
 *  - rel_change_of propagates two standard errors to first order, and claim_verdict decides each
 *    kind of claim at two standard deviations, including the undefined and unmeasured cases;
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

static void test_verdicts(void)
{
    char why[128];
    struct rel_change c = rel_change_of(90.0, 1.0, 100.0, 1.0);
    EXPECT(fabs(c.pct + 10.0) < 1e-12, "90 against 100 is -10%%, got %g", c.pct);
    const double sd = 100.0 * sqrt(1.0 / 1e4 + 8100.0 * 1.0 / 1e8);
    EXPECT(fabs(c.sd - sd) < 1e-12, "propagated sd %g, expected %g", c.sd, sd);
    EXPECT(!strcmp(claim_verdict(c, (struct claim){CLAIM_REDUCTION, 8.0}, why, sizeof why), "reproduced"),
           "-10%% +- 1.3 reproduces a claimed 8%% reduction (%s)", why);
    EXPECT(!strcmp(claim_verdict(c, (struct claim){CLAIM_REDUCTION, 30.0}, why, sizeof why), "partly"),
           "-10%% +- 1.3 is partly a claimed 30%% reduction");
    struct rel_change noisy = rel_change_of(99.0, 5.0, 100.0, 5.0);
    EXPECT(!strcmp(claim_verdict(noisy, (struct claim){CLAIM_REDUCTION, 0.0}, why, sizeof why), "not reproduced") &&
               !strcmp(why, "within the noise"),
           "-1%% +- 7 is within the noise, not a reduction (%s)", why);
    struct rel_change worse = rel_change_of(120.0, 1.0, 100.0, 1.0);
    EXPECT(!strcmp(claim_verdict(worse, (struct claim){CLAIM_REDUCTION, 0.0}, why, sizeof why), "not reproduced") &&
               !strcmp(why, "worse"),
           "+20%% is worse (%s)", why);
    EXPECT(!strcmp(claim_verdict(worse, (struct claim){CLAIM_NONE, 0.0}, why, sizeof why), "higher"), "+20%% is higher");
    struct rel_change small = rel_change_of(101.0, 0.5, 100.0, 0.5);
    EXPECT(!strcmp(claim_verdict(small, (struct claim){CLAIM_SMALL, 3.0}, why, sizeof why), "reproduced"),
           "+1%% +- 0.7 is a change within 3%%");
    EXPECT(!strcmp(claim_verdict(small, (struct claim){CLAIM_SMALL, 1.0}, why, sizeof why), "not reproduced"),
           "+1%% +- 0.7 may exceed 1%%");
    struct rel_change cost = rel_change_of(104.0, NAN, 100.0, NAN);
    EXPECT(isnan(cost.sd), "times have no spread");
    EXPECT(!strcmp(claim_verdict(cost, (struct claim){CLAIM_COST, 4.4}, why, sizeof why), "reproduced"),
           "+4%% costs at most 4.4%%");
    EXPECT(!strcmp(claim_verdict(cost, (struct claim){CLAIM_COST, 3.0}, why, sizeof why), "not reproduced"),
           "+4%% costs more than 3%%");
    struct rel_change nobase = rel_change_of(1.0, 0.1, -0.5, 0.1);
    EXPECT(nobase.no_base && !strcmp(claim_verdict(nobase, (struct claim){CLAIM_REDUCTION, 0.0}, why, sizeof why),
                                     "undefined"),
           "a negative baseline has no relative change");
    struct rel_change missing = rel_change_of(NAN, NAN, 1.0, 0.1);
    EXPECT(!strcmp(claim_verdict(missing, (struct claim){CLAIM_REDUCTION, 0.0}, why, sizeof why), "not measured"),
           "a missing value is not measured");
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
    test_equal_time();
    return test_finish();
}
