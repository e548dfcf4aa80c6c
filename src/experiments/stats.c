/* experiments/stats.c: the harness's statistics (stats.h). */
#include "experiments/stats.h"

#include <math.h>
#include <stdio.h>

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

struct rel_change rel_change_of(double ours, double ours_sem, double base, double base_sem)
{
    struct rel_change c = {100.0 * (ours / base - 1.0), NAN, base <= 0.0};
    if (c.no_base) {
        c.pct = NAN;
        return c;
    }
    if (isfinite(ours_sem) && isfinite(base_sem))
        c.sd = 100.0 * sqrt(ours_sem * ours_sem / (base * base) +
                            ours * ours * base_sem * base_sem / (base * base * base * base));
    return c;
}

const char *claim_verdict(struct rel_change c, struct claim k, char *why, size_t len)
{
    const double sd = isfinite(c.sd) ? c.sd : 0.0;
    why[0] = '\0';
    if (c.no_base) {
        snprintf(why, len, "the baseline is not positive: no relative change");
        return "undefined";
    }
    if (!isfinite(c.pct)) {
        snprintf(why, len, "not measured");
        return "not measured";
    }
    switch (k.kind) {
    case CLAIM_SMALL: {
        const int small = c.pct - 2.0 * sd >= -k.limit && c.pct + 2.0 * sd <= k.limit;
        if (!small)
            snprintf(why, len, "the change may exceed %g%%", k.limit);
        return small ? "reproduced" : "not reproduced";
    }
    case CLAIM_COST:
        if (c.pct > k.limit)
            snprintf(why, len, "costs more");
        return c.pct <= k.limit ? "reproduced" : "not reproduced";
    case CLAIM_NONE:
        snprintf(why, len, "%s", isfinite(c.sd) ? "" : "no spread");
        return c.pct + 2.0 * sd < 0.0 ? "lower" : c.pct - 2.0 * sd > 0.0 ? "higher" : "no difference";
    case CLAIM_REDUCTION:
        break;
    }
    const char *spread = isfinite(c.sd) ? "" : " (no spread)";
    if (c.pct + 2.0 * sd < 0.0 && c.pct - 2.0 * sd <= -k.limit) {
        snprintf(why, len, "%s", isfinite(c.sd) ? "" : "no spread");
        return "reproduced";
    }
    if (c.pct + 2.0 * sd < 0.0) {
        snprintf(why, len, "a smaller gain than the paper's%s", spread);
        return "partly";
    }
    if (c.pct - 2.0 * sd > 0.0)
        snprintf(why, len, "worse%s", spread);
    else
        snprintf(why, len, "within the noise");
    return "not reproduced";
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
