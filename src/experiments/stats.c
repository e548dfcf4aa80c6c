/* experiments/stats.c: the harness's statistics (stats.h). */
#include "experiments/stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"

void running_mean_add(struct running_mean *r, double x)
{
    r->n++;
    const double d = x - r->mean;
    r->mean += d / (double)r->n;
    r->m2 += d * (x - r->mean);
}

double running_mean_sem(const struct running_mean *r)
{
    return r->n > 1 ? sqrt(r->m2 / (double)(r->n - 1) / (double)r->n) : NAN;
}

double jackknife_se(const double *theta, int n)
{
    if (n < 2)
        return NAN;
    double mean = 0.0, ss = 0.0;
    for (int i = 0; i < n; i++)
        mean += theta[i] / n;
    for (int i = 0; i < n; i++)
        ss += (theta[i] - mean) * (theta[i] - mean);
    return sqrt((n - 1.0) / n * ss);
}

/* The continued fraction of the regularized incomplete beta function I_x(a, b), evaluated by the
 * modified Lentz method; converges fast for x < (a + 1) / (a + b + 2). */
static double beta_fraction(double a, double b, double x)
{
    const double tiny = 1e-300;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    d = fabs(d) < tiny ? tiny : d;
    d = 1.0 / d;
    double f = d;
    for (int m = 1; m <= 500; m++) {
        for (int odd = 0; odd < 2; odd++) {
            /* the even term m (b - m) x / ((a + 2m - 1)(a + 2m)), then the odd one
             * -(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)) */
            const double num = odd ? -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0))
                                   : m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
            d = 1.0 + num * d;
            d = fabs(d) < tiny ? tiny : d;
            c = 1.0 + num / c;
            c = fabs(c) < tiny ? tiny : c;
            d = 1.0 / d;
            f *= d * c;
            if (odd && fabs(d * c - 1.0) < 1e-15)
                return f;
        }
    }
    return f;
}

/* I_x(a, b) = B(x; a, b) / B(a, b) for 0 <= x <= 1, through the symmetry I_x(a, b) = 1 - I_{1-x}(b, a)
 * where the fraction would converge slowly. */
static double incomplete_beta(double a, double b, double x)
{
    if (x <= 0.0)
        return 0.0;
    if (x >= 1.0)
        return 1.0;
    const double front = exp(lgamma(a + b) - lgamma(a) - lgamma(b) + a * log(x) + b * log1p(-x));
    if (x < (a + 1.0) / (a + b + 2.0))
        return front * beta_fraction(a, b, x) / a;
    return 1.0 - front * beta_fraction(b, a, 1.0 - x) / b;
}

double student_t_cdf(double t, int df)
{
    if (df < 1 || isnan(t))
        return NAN;
    if (isinf(t))
        return t > 0.0 ? 1.0 : 0.0;
    /* P(|T| > |t|) = I_{df / (df + t^2)}(df / 2, 1 / 2) */
    const double tail = 0.5 * incomplete_beta(0.5 * df, 0.5, df / (df + t * t));
    return t >= 0.0 ? 1.0 - tail : tail;
}

double student_t_quantile(double level, int df)
{
    if (df < 1 || !(level > 0.0 && level < 1.0))
        return NAN;
    const double target = 0.5 + 0.5 * level; /* P(T <= q) */
    double lo = 0.0, hi = 1.0;
    while (student_t_cdf(hi, df) < target && hi < 1e12)
        hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; i++) {
        const double mid = 0.5 * (lo + hi);
        if (student_t_cdf(mid, df) < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

static double pct_of_log(double x) { return 100.0 * expm1(x); }

/* A change with its estimate m and standard error se on the log scale, the interval from Student t
 * with df degrees of freedom (none when se is not finite or positive). */
static struct rel_change change_from_log(double m, double se, int n, int df, enum change_interval how)
{
    struct rel_change c = {pct_of_log(m), NAN, NAN, m, NAN, n, INTERVAL_NONE, 0, 0.0, 0};
    if (df >= 1 && isfinite(se) && se > 0.0) {
        const double h = student_t_quantile(STATS_LEVEL, df) * se;
        c.lo = pct_of_log(m - h);
        c.hi = pct_of_log(m + h);
        c.log_se = se;
        c.interval = how;
    } else if (df >= 1 && se == 0.0) { /* no spread at all: a point */
        c.lo = c.hi = c.pct;
        c.log_se = 0.0;
        c.interval = how;
    }
    return c;
}

static struct rel_change not_measured(int n, int no_base)
{
    return (struct rel_change){NAN, NAN, NAN, NAN, NAN, n, INTERVAL_NONE, no_base, 0.0, 0};
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The percentile bootstrap interval of the mean of lr[0..n) on the log scale, from STATS_BOOTSTRAP
 * resamples of a fixed stream: [lo, hi] at STATS_LEVEL. */
static void bootstrap_mean(const double *lr, int n, double *lo, double *hi)
{
    double *means = malloc(sizeof(double) * STATS_BOOTSTRAP);
    if (!means) {
        *lo = *hi = NAN;
        return;
    }
    pcg32 r = pcg32_make(0x0b5eed5ull, (uint64_t)n);
    for (int b = 0; b < STATS_BOOTSTRAP; b++) {
        double s = 0.0;
        for (int i = 0; i < n; i++)
            s += lr[pcg32_next(&r) % (uint32_t)n];
        means[b] = s / n;
    }
    qsort(means, STATS_BOOTSTRAP, sizeof(double), cmp_double);
    const double tail = 0.5 * (1.0 - STATS_LEVEL) * (STATS_BOOTSTRAP - 1);
    *lo = means[(int)floor(tail)];
    *hi = means[(int)ceil((STATS_BOOTSTRAP - 1) - tail)];
    free(means);
}

struct rel_change paired_change(const double *ours, const double *base, int n, int heavy_tailed)
{
    if (n < 1 || !ours || !base)
        return not_measured(0, 0);
    double *lr = malloc(sizeof(double) * (size_t)n);
    if (!lr)
        return not_measured(n, 0);
    int no_base = 0, missing = 0;
    struct running_mean rm = {0};
    for (int i = 0; i < n; i++) {
        missing |= !isfinite(ours[i]) || !isfinite(base[i]);
        no_base |= !(ours[i] > 0.0) || !(base[i] > 0.0);
        lr[i] = log(ours[i] / base[i]);
        running_mean_add(&rm, lr[i]);
    }
    if (missing || no_base) {
        free(lr);
        return not_measured(n, !missing && no_base);
    }
    struct rel_change c = change_from_log(rm.mean, running_mean_sem(&rm), n, n - 1, INTERVAL_T);
    if (heavy_tailed && n >= 2 && c.interval == INTERVAL_T) {
        double blo, bhi;
        bootstrap_mean(lr, n, &blo, &bhi);
        const double tlo = log1p(c.lo / 100.0), thi = log1p(c.hi / 100.0);
        if (isfinite(blo) && bhi - blo > thi - tlo) {
            c.lo = pct_of_log(blo);
            c.hi = pct_of_log(bhi);
            c.interval = INTERVAL_BOOTSTRAP;
        }
    }
    free(lr);
    return c;
}

struct rel_change jackknife_change(double ours, double base, const double *ours_loo, const double *base_loo, int n)
{
    if (!isfinite(ours) || !isfinite(base))
        return not_measured(n, 0);
    if (!(ours > 0.0) || !(base > 0.0))
        return not_measured(n, 1);
    const double m = log(ours / base);
    if (!ours_loo || !base_loo || n < 3)
        return change_from_log(m, NAN, n, 0, INTERVAL_NONE);
    double *theta = malloc(sizeof(double) * (size_t)n);
    if (!theta)
        return change_from_log(m, NAN, n, 0, INTERVAL_NONE);
    int ok = 1;
    for (int i = 0; i < n; i++) {
        ok &= ours_loo[i] > 0.0 && base_loo[i] > 0.0 && isfinite(ours_loo[i]) && isfinite(base_loo[i]);
        theta[i] = ok ? log(ours_loo[i] / base_loo[i]) : 0.0;
    }
    const double se = ok ? jackknife_se(theta, n) : NAN;
    free(theta);
    return change_from_log(m, se, n, n - 1, INTERVAL_JACKKNIFE);
}

struct rel_change unpaired_change(double ours, double ours_sem, double base, double base_sem, int n)
{
    if (!isfinite(ours) || !isfinite(base))
        return not_measured(n, 0);
    if (!(ours > 0.0) || !(base > 0.0))
        return not_measured(n, 1);
    const double se = sqrt(ours_sem * ours_sem / (ours * ours) + base_sem * base_sem / (base * base));
    return change_from_log(log(ours / base), se, n, n - 1, INTERVAL_UNPAIRED);
}

/* The paper's effect of a reduction or cost claim on the log scale. */
static double claim_log_effect(struct claim k)
{
    return k.kind == CLAIM_REDUCTION ? log1p(-k.limit / 100.0) : log1p(k.limit / 100.0);
}

const char *claim_verdict(struct rel_change c, struct claim k, char *why, size_t len)
{
    why[0] = '\0';
    if (c.no_base) {
        snprintf(why, len, "a value is not positive: no relative change");
        return "undefined";
    }
    if (!isfinite(c.pct)) {
        snprintf(why, len, "not measured");
        return "not measured";
    }
    if (c.ref_ratio >= 1.0) {
        snprintf(why, len, "the reference's own error is %.1fx the difference judged: render it longer", c.ref_ratio);
        return "refused";
    }
    const int spread = c.interval != INTERVAL_NONE;
    const double lo = spread ? c.lo : c.pct, hi = spread ? c.hi : c.pct;
    const char *point = spread ? "" : "no spread";
    const char *verdict;
    switch (k.kind) {
    case CLAIM_SMALL:
        verdict = lo >= -k.limit && hi <= k.limit ? "reproduced"
                  : lo > k.limit || hi < -k.limit ? "not reproduced"
                                                  : "undecided";
        break;
    case CLAIM_COST:
        verdict = hi <= k.limit ? "reproduced" : lo > k.limit ? "not reproduced" : "undecided";
        break;
    case CLAIM_NONE:
        verdict = hi < 0.0 ? "lower" : lo > 0.0 ? "higher" : "no difference";
        break;
    case CLAIM_REDUCTION:
    default: {
        const double e = -k.limit; /* the paper's effect; with limit 0 any reduction */
        const int reaches = k.limit > 0.0 ? lo <= e : lo < 0.0;
        verdict = lo > 0.0                 ? "opposite"
                  : hi < 0.0 && reaches    ? "reproduced"
                  : hi < 0.0               ? "partly"
                  : reaches                ? "undecided"
                                           : "not reproduced";
        break;
    }
    }
    if (!spread)
        snprintf(why, len, "%s", point);
    else if (verdict[0] == 'u') {
        const int seeds = stats_seeds_to_decide(c, k);
        if (seeds > 0)
            snprintf(why, len, "about %d seeds would decide it at the measured spread", seeds);
        else
            snprintf(why, len, "more than %d seeds would be needed at the measured spread", STATS_MAX_SEEDS);
    }
    if (c.ref_unchecked) {
        const size_t used = strlen(why);
        snprintf(why + used, len - used, "%snot checked against the reference's own error in this metric (its step "
                 "did not record it)", used ? "; " : "");
    }
    return verdict;
}

/* The interval's half-width on the log scale with n seeds of per-seed spread s. */
static double half_width(double s, int n) { return student_t_quantile(STATS_LEVEL, n - 1) * s / sqrt((double)n); }

int stats_seeds_to_decide(struct rel_change c, struct claim k)
{
    if (!isfinite(c.log_mean) || !isfinite(c.log_se) || !(c.log_se > 0.0) || c.n < 1)
        return -1;
    const double m = c.log_mean, s = c.log_se * sqrt((double)c.n);
    double d; /* how far the interval may reach and still decide */
    switch (k.kind) {
    case CLAIM_SMALL: {
        const double up = log1p(k.limit / 100.0), down = log1p(-k.limit / 100.0);
        d = m > up || m < down ? fmin(fabs(m - up), fabs(m - down)) : fmin(up - m, m - down);
        break;
    }
    case CLAIM_COST:
        d = fabs(m - claim_log_effect(k));
        break;
    case CLAIM_NONE:
        d = fabs(m);
        break;
    case CLAIM_REDUCTION:
    default:
        d = k.limit > 0.0 ? fmax(fabs(m), fabs(m - claim_log_effect(k))) : fabs(m);
        break;
    }
    if (!(d > 0.0) || half_width(s, STATS_MAX_SEEDS) >= d)
        return -1;
    int lo = 1, hi = STATS_MAX_SEEDS; /* half_width(lo) >= d (or lo = 1), half_width(hi) < d */
    if (half_width(s, 2) < d)
        return 2;
    lo = 2;
    while (hi - lo > 1) {
        const int mid = lo + (hi - lo) / 2;
        if (half_width(s, mid) < d)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

double reference_halves_relmse(const float *a, const float *b, size_t n_pixels)
{
    if (!a || !b || n_pixels == 0)
        return NAN;
    double sum = 0.0;
    for (size_t i = 0; i < 3 * n_pixels; i++) {
        const double r = 0.5 * ((double)a[i] + (double)b[i]), d = (double)a[i] - (double)b[i];
        sum += 0.25 * d * d / (r * r + 1e-3);
    }
    return sum / (3.0 * (double)n_pixels);
}

int equal_time_spp(double budget_ms, double ms_1spp, double ms_4spp)
{
    const double diff = (ms_4spp - ms_1spp) / 3.0;
    const double per_spp = diff > 0.25 * ms_1spp ? diff : ms_1spp;
    const double fixed = ms_1spp - per_spp > 0.0 ? ms_1spp - per_spp : 0.0;
    if (!(per_spp > 0.0) || !isfinite(budget_ms))
        return 1;
    const double spp = (budget_ms - fixed) / per_spp;
    return spp < 1.0 ? 1 : spp > 1e6 ? 1000000 : (int)spp;
}
