/* evaluate_change.c: a claim's change from a step's tables (evaluate_change.h). */
#include "experiments/evaluate_change.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The values of column col in runs.csv's rows of configuration label, by run (run r into out[r]);
 * returns the number of runs 0..n-1 all present, 0 when any is missing. */
static int run_values(const struct csv_table *runs, const char *label, const char *col, double *out, int max)
{
    int n = 0;
    for (int r = 0; r < runs->nrow; r++) {
        if (strcmp(runs->cell[(size_t)(r + 1) * runs->ncol], label) != 0)
            continue;
        const double run = csv_table_num(runs, r, "run");
        if (!(run >= 0.0 && run < max) || run != floor(run))
            return 0;
        out[(int)run] = csv_table_num(runs, r, col);
        n = (int)run + 1 > n ? (int)run + 1 : n;
    }
    for (int i = 0; i < n; i++)
        if (isnan(out[i]))
            return 0;
    return n;
}

/* 1 when the table (compare.csv, study.csv, runs.csv) has column col. */
static int has_column(const struct csv_table *runs, const char *col)
{
    for (int c = 0; c < runs->ncol; c++)
        if (!strcmp(runs->cell[c], col))
            return 1;
    return 0;
}

#define MAX_SEEDS 1024

/* The reference's own error in col (t's column ref_COL of row ours) over |ours - base|; 0 when the
 * table has none. *unchecked: 1 when it has none for col but has the reference's own MAPE (its
 * reference had halves, but the step's commit did not record col's: a claim on it goes unchecked). */
static double reference_ratio(const struct csv_table *t, int ours, int base, const char *col, int *unchecked)
{
    char ref[96];
    snprintf(ref, sizeof ref, "ref_%s", col);
    const double own = csv_table_num(t, ours, ref), diff = fabs(csv_table_num(t, ours, col) - csv_table_num(t, base, col));
    *unchecked = !isfinite(own) && isfinite(csv_table_num(t, ours, "ref_mape")) && !has_column(t, ref);
    return isfinite(own) && isfinite(diff) ? (diff > 0.0 ? own / diff : INFINITY) : 0.0;
}

/* 1 when t has column col with a number in row r. */
static int has_value(const struct csv_table *t, int r, const char *col) { return isfinite(csv_table_num(t, r, col)); }

struct rel_change eval_change(const struct step_tables *d, int ours, int base, const char *col)
{
    /* relMSE is judged without the reference's own share where the table has it (compare.csv's
     * relmse_net); the reference check compares the difference with that share (ref_relmse) */
    const int net = !strcmp(col, "relmse") && ours >= 0 && base >= 0 && has_value(d->t, ours, "relmse_net") &&
                    has_value(d->t, base, "relmse_net");
    struct rel_change c = eval_change_unchecked(d, ours, base, net ? "relmse_net" : col);
    if (ours >= 0 && base >= 0)
        c.ref_ratio = reference_ratio(d->t, ours, base, col, &c.ref_unchecked);
    return c;
}

struct rel_change eval_change_unchecked(const struct step_tables *d, int ours, int base, const char *col)
{
    const struct csv_table *t = d->t;
    if (ours < 0 || base < 0)
        return unpaired_change(NAN, NAN, NAN, NAN, 0);
    char loo[96], sem[96];
    snprintf(loo, sizeof loo, "%s_loo", col);
    snprintf(sem, sizeof sem, "%s_sem", col);
    const double a = csv_table_num(t, ours, col), b = csv_table_num(t, base, col);
    const char *la = t->cell[(size_t)(ours + 1) * t->ncol], *lb = t->cell[(size_t)(base + 1) * t->ncol];
    static _Thread_local double x[MAX_SEEDS], y[MAX_SEEDS];
    if (d->runs && has_column(d->runs, loo)) { /* an ensemble statistic: the paired jackknife */
        const int n = run_values(d->runs, la, loo, x, MAX_SEEDS), m = run_values(d->runs, lb, loo, y, MAX_SEEDS);
        return jackknife_change(a, b, n == m && n >= 3 ? x : NULL, n == m && n >= 3 ? y : NULL, n == m ? n : 0);
    }
    if (d->runs && has_column(d->runs, col)) {
        const int n = run_values(d->runs, la, col, x, MAX_SEEDS), m = run_values(d->runs, lb, col, y, MAX_SEEDS);
        if (n > 0 && n == m)
            return paired_change(x, y, n, strstr(col, "relmse") != NULL);
    }
    return unpaired_change(a, csv_table_num(t, ours, sem), b, csv_table_num(t, base, sem), d->n_runs);
}

void eval_fmt_change(struct rel_change c, char *out, size_t len)
{
    if (!isfinite(c.pct))
        snprintf(out, len, "-");
    else if (c.interval != INTERVAL_NONE)
        snprintf(out, len, "%+.1f%% [%+.1f, %+.1f]", c.pct, c.lo, c.hi);
    else
        snprintf(out, len, "%+.1f%%", c.pct);
}
