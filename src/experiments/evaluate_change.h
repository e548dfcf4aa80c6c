/* evaluate_change.h: a claim's change of one configuration against another from a step's tables
 * (evaluate_change.c): paired by seed from the step's runs.csv (one row per configuration and run,
 * run r of every configuration rendered with the same seed), Student t over the seeds, a bootstrap
 * for heavy-tailed metrics, a paired jackknife for ensemble statistics; from the means and standard
 * errors of the step's main table when it has no runs.csv (a step merged before runs.csv existed).
 * No state: thread-safe on distinct outputs. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_CHANGE_H
#define RESTIR_EXPERIMENTS_EVALUATE_CHANGE_H

#include <stddef.h>

#include "experiments/csv_table.h"
#include "experiments/stats.h"

/* A step's tables: t, one row per configuration (study.csv, compare.csv: means, COL and COL_sem),
 * and runs (NULL when absent), one row per configuration and run: first column the configuration,
 * column "run", each per-seed metric COL, and for an ensemble statistic (a covariance over the runs)
 * COL_loo, its value without that run. */
struct step_tables {
    const struct csv_table *t, *runs;
    int n_runs; /* the runs behind t's means (for the unpaired fallback's degrees of freedom) */
};

/* The change of t's row ours against row base in column col (row -1: not measured). Metrics whose
 * name holds "relmse" count as heavy-tailed (paired_change). When t has a column ref_COL (the
 * reference's own error in that metric, from its halves), ref_ratio is it over |ours - base|, and the
 * verdict refuses a claim the reference cannot judge. */
struct rel_change eval_change(const struct step_tables *d, int ours, int base, const char *col);
/* eval_change without the reference's check (ref_ratio 0). */
struct rel_change eval_change_unchecked(const struct step_tables *d, int ours, int base, const char *col);

/* A change as "-13.8% [-57.9, +30.3]" (its estimate and 95% interval), "-13.8%" without an
 * interval, "-" when not measured. */
void eval_fmt_change(struct rel_change c, char *out, size_t len);

#endif
