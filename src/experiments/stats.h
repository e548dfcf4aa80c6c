/* experiments/stats.h: the statistics of the experiment harness, as functions of numbers only, so
 * they are tested in-process: running means with standard errors (Welford), jackknife standard
 * errors, relative changes with propagated spread and the verdict on a paper's claim, and the
 * equal-time budget of a method that fits it by paths per pixel.
 * Must never render, read files or print. */
#ifndef RESTIR_EXPERIMENTS_STATS_H
#define RESTIR_EXPERIMENTS_STATS_H

#include <stddef.h>

/* Welford's running mean and sum of squared deviations of a stream of numbers; zero-initialized
 * means empty. Numerically stable for any number of values. */
struct running_mean {
    long n;
    double mean, m2;
};
void running_mean_add(struct running_mean *r, double x);
/* The standard error of the mean, sqrt(m2 / (n - 1) / n); NaN with fewer than 2 values. */
double running_mean_sem(const struct running_mean *r);

/* The jackknife standard error of an estimator from its n >= 2 leave-one-out values theta[i]:
 * sqrt((n - 1) / n * sum (theta_i - mean)^2). NaN for n < 2. */
double jackknife_se(const double *theta, int n);

/* A relative change ours / base - 1 in percent, with its standard deviation from the two
 * standard errors (independent runs; first-order propagation). sd is NaN when either has no
 * spread; pct is NaN when either value is not finite. */
struct rel_change {
    double pct, sd;
    int no_base; /* the baseline is not positive (a covariance can be): a relative change means nothing */
};
struct rel_change rel_change_of(double ours, double ours_sem, double base, double base_sem);

/* What a paper claims about a change of ours against its baseline. */
enum claim_kind {
    CLAIM_REDUCTION, /* lower by at least limit percent (0: any reduction) */
    CLAIM_SMALL,     /* a change within +-limit percent */
    CLAIM_COST,      /* at most limit percent more time (times have no spread) */
    CLAIM_NONE,      /* no claim (our own variant): which way it went */
};
struct claim {
    enum claim_kind kind;
    double limit; /* percent */
};

/* The verdict on claim k at two standard deviations: for a reduction "reproduced" (significantly
 * lower, and the claimed limit within reach), "partly" (significantly lower, but less than the
 * limit) or "not reproduced" (within the noise, or higher); for a small change "reproduced" when
 * the whole interval lies within +-limit; for a cost when the change is at most limit; for no
 * claim "lower" / "higher" / "no difference"; "undefined" without a positive baseline and "not
 * measured" without a value. why (len bytes) gets the reason, "" when none. Returns a static
 * string. */
const char *claim_verdict(struct rel_change c, struct claim k, char *why, size_t len);

/* Equal time by paths per pixel: the spp that fits budget_ms from the frame times of the same
 * method at 1 and 4 spp. Their difference gives the cost per path and removes the fixed per-frame
 * cost (G-buffer, reconstruction); when timing noise makes the difference under a quarter of the
 * 1-spp time, the whole 1-spp time counts as per-path cost. At least 1. */
int equal_time_spp(double budget_ms, double ms_1spp, double ms_4spp);

#endif
