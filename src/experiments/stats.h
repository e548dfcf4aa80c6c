/* experiments/stats.h: the statistics of the experiment harness, as functions of numbers only, so
 * they are tested in-process: running means with standard errors (Welford), jackknife standard
 * errors, Student t quantiles, paired changes of a configuration against its baseline with 95%
 * intervals (Student t over seeds, a bootstrap over seeds, a paired jackknife for statistics of the
 * whole ensemble), the verdict on a paper's claim with the seeds that would decide it, the error of
 * a reference estimated from its two independent halves, and the equal-time budget of a method that
 * fits it by paths per pixel. Must never render, read files or print. */
#ifndef RESTIR_EXPERIMENTS_STATS_H
#define RESTIR_EXPERIMENTS_STATS_H

#include <stddef.h>
#include <stdint.h>

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

/* Student's t distribution with df >= 1 degrees of freedom: P(T <= t), and the two-sided quantile
 * q with P(|T| <= q) = level (0 < level < 1; 0.95 gives the half-width factor of a 95% interval,
 * 3.182 for df = 3). NaN for df < 1 or a level outside (0, 1). Accurate to ~1e-10. */
double student_t_cdf(double t, int df);
double student_t_quantile(double level, int df);

#define STATS_LEVEL 0.95        /* every interval of the harness */
#define STATS_BOOTSTRAP 4000    /* bootstrap resamples */
#define STATS_MAX_SEEDS 100000  /* what stats_seeds_to_decide searches up to */

/* How a change's interval was found. */
enum change_interval {
    INTERVAL_NONE,      /* one value, or values without spread: no interval */
    INTERVAL_T,         /* Student t over the paired seeds, n - 1 degrees of freedom */
    INTERVAL_BOOTSTRAP, /* percentile bootstrap over the seeds, wider than the t interval */
    INTERVAL_JACKKNIFE, /* paired jackknife over the seeds (ensemble statistics), with Student t */
    INTERVAL_UNPAIRED,  /* two means and their standard errors, first-order propagation, Student t */
};

/* A change of ours against a baseline as a percentage, with its 95% interval [lo, hi] (NaN: no
 * interval). Paired changes are estimated on the log scale, lr = mean over seeds of log(ours_i /
 * base_i), and reported as 100 (exp(lr) - 1), so the interval is that of a ratio of geometric means. */
struct rel_change {
    double pct, lo, hi;
    double log_mean, log_se; /* the estimate and its standard error on the log scale (NaN: none) */
    int n;                   /* the seeds behind it */
    enum change_interval interval;
    int no_base; /* a value is not positive (a covariance can be): a relative change means nothing */
    /* the reference's own error in the metric (its halves: reference_halves.h) over the difference
     * of the two values judged; at least 1 (the reference's noise is as large as the difference)
     * refuses the claim for that reference. 0 or NaN: not known, or negligible */
    double ref_ratio;
    /* 1: the step measured the reference's own error in other metrics but not in this one (a table
     * merged before that metric's column existed): the claim could not be checked against it, and
     * claim_verdict's why says so */
    int ref_unchecked;
};

/* The change of ours[i] against base[i], i < n, values of the same seed i (common random numbers),
 * from the per-seed log ratios: the Student t interval with n - 1 degrees of freedom and, with
 * heavy_tailed (relMSE-like metrics), also a percentile bootstrap over the seeds (STATS_BOOTSTRAP
 * resamples of a fixed pseudo-random stream, so the result is reproducible), reporting the wider of
 * the two. A NaN value leaves the change not measured (pct NaN); a value <= 0 sets no_base. */
struct rel_change paired_change(const double *ours, const double *base, int n, int heavy_tailed);

/* The change of an ensemble statistic (one value from all n seeds together, e.g. a covariance over
 * runs) ours against base, paired by the jackknife: ours_loo[i] and base_loo[i] are the statistics
 * without seed i, the estimate is log(ours / base), its standard error the jackknife's of the
 * leave-one-out log ratios, and the interval Student t with n - 1 degrees of freedom. NULL loo
 * arrays or n < 3 give the estimate without an interval. */
struct rel_change jackknife_change(double ours, double base, const double *ours_loo, const double *base_loo, int n);

/* A change from two independent means with their standard errors (no seed pairs): log-scale
 * first-order propagation, Student t with n - 1 degrees of freedom (n: the runs of each). A NaN
 * standard error gives the estimate without an interval. */
struct rel_change unpaired_change(double ours, double ours_sem, double base, double base_sem, int n);

/* What a paper claims about a change of ours against its baseline. */
enum claim_kind {
    CLAIM_REDUCTION, /* lower by at least limit percent (0: lower, no figure given) */
    CLAIM_SMALL,     /* a change within +-limit percent */
    CLAIM_COST,      /* at most limit percent more time */
    CLAIM_NONE,      /* no claim (our own variant): which way it went */
};
struct claim {
    enum claim_kind kind;
    double limit; /* percent */
};

/* The verdict on claim k from the change's 95% interval [lo, hi], E the paper's effect (-limit for a
 * reduction; for limit 0 any value below zero is the paper's side):
 *   reproduced     the interval is on the paper's side of zero and reaches its magnitude (lo <= E < hi < 0
 *                  or hi <= E);
 *   partly         on the paper's side of zero, short of its magnitude (E < lo, hi < 0);
 *   not reproduced the interval holds zero and excludes the paper's effect (E < lo <= 0 <= hi);
 *   opposite       the interval is on the other side of zero (lo > 0);
 *   undecided      the interval holds both zero and the paper's effect (lo <= E, hi >= 0): why says how
 *                  many seeds would decide it at the measured spread (stats_seeds_to_decide).
 * A small change: reproduced when the interval lies within +-limit, not reproduced when it lies
 * wholly outside, undecided when it straddles a bound. A cost: reproduced when hi <= limit, not
 * reproduced when lo > limit, undecided otherwise. No claim: "lower", "higher" or "no difference".
 * A change without an interval is judged on its estimate alone and why says "no spread".
 * "refused" when c.ref_ratio >= 1: the difference judged is no larger than the reference's own error
 * in that metric, so the reference cannot judge it (why says so: render the reference longer).
 * "undefined" without a positive baseline and "not measured" without a value. why (len bytes) gets
 * the reason, "" when none. Returns a static string. */
const char *claim_verdict(struct rel_change c, struct claim k, char *why, size_t len);

/* The seeds that would decide an undecided claim: the least n with t(n - 1) s / sqrt(n) below the
 * distance of the estimate to the farther of zero and the paper's effect, on the log scale, where s
 * = log_se sqrt(c.n) is the per-seed spread measured. -1 when it needs more than STATS_MAX_SEEDS or
 * the change has no spread. */
int stats_seeds_to_decide(struct rel_change c, struct claim k);

/* The error of a reference estimated from two independent halves a and b (n_pixels RGB pixels each,
 * the reference being their mean r = (a + b) / 2): the per-pixel variance of r is estimated without
 * bias by (a - b)^2 / 4 per channel, so
 *   var_relmse = mean over pixels and channels of ((a - b)^2 / 4) / (r^2 + 1e-3),
 * the share of a relMSE against r that the reference's own noise adds (E[(x - r)^2] = E[(x - R)^2] +
 * Var(r) for x independent of r), which restir relMSE subtracts. NaN for NULL inputs or no pixel. */
double reference_halves_relmse(const float *a, const float *b, size_t n_pixels);

/* Equal time by paths per pixel: the spp that fits budget_ms from the frame times of the same
 * method at 1 and 4 spp. Their difference gives the cost per path and removes the fixed per-frame
 * cost (G-buffer, reconstruction); when timing noise makes the difference under a quarter of the
 * 1-spp time, the whole 1-spp time counts as per-path cost. At least 1. */
int equal_time_spp(double budget_ms, double ms_1spp, double ms_4spp);

#endif
