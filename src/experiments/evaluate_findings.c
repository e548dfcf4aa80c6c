/* evaluate_findings.c: what the deciding rows of an evaluation show about a claim (the ablation rows beside it), as the
 * text of its "why" column (evaluate_findings.h). */
#include "experiments/evaluate_findings.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Appends to out (len bytes, NUL-terminated) what a deciding pair of rows shows: "what: +x% [lo, hi],
 * reading" with reading[0] when the 95% interval lies above zero, reading[1] when below, "no
 * significant difference" otherwise; nothing when either row is missing. */
static void finding(char *out, size_t len, const char *what, struct rel_change c, const char *const reading[2])
{
    if (!isfinite(c.pct))
        return;
    char ch[64];
    eval_fmt_change(c, ch, sizeof ch);
    const int spread = c.interval != INTERVAL_NONE;
    const double lo = spread ? c.lo : c.pct, hi = spread ? c.hi : c.pct;
    const char *r = lo > 0.0 ? reading[0] : hi < 0.0 ? reading[1] : "no significant difference";
    const size_t used = strlen(out);
    snprintf(out + used, len - used, "%s%s: %s, %s", used ? "; " : "", what, ch, r);
}

void eval_deciding_000(const struct step_tables *d, int bit, int fast, char *out, size_t len)
{
    const struct csv_table *t = d->t;
    const int off = csv_table_find(t, "spatial-off"), bt = csv_table_find(t, "bitterli-history-temporal"),
              ft = csv_table_find(t, "fast-history-temporal");
    static const char *const reuse[2] = {"spatial reuse itself hurts on this scene with our base",
                                         "spatial reuse helps on this scene"};
    static const char *const fed[2] = {"FAST loses without the feedback too", "FAST gains without the feedback"};
    static const char *const feedback[2] = {"feeding the spatial output back costs FAST",
                                            "feeding the spatial output back helps FAST"};
    out[0] = '\0';
#define CHANGE(a, b, col) eval_change(d, a, b, col)
    if (off >= 0 && bit >= 0)
        finding(out, len, "Bitterli vs no spatial reuse, SMAPE", CHANGE(bit, off, "smape_all"), reuse);
    if (bt >= 0 && ft >= 0) {
        finding(out, len, "FAST vs Bitterli, both with the temporal history, SMAPE", CHANGE(ft, bt, "smape_all"), fed);
        finding(out, len, "the same, temporal covariance", CHANGE(ft, bt, "temporal_cov"), fed);
    }
    if (fast >= 0 && ft >= 0)
        finding(out, len, "FAST (spatial history) vs FAST (temporal history), SMAPE", CHANGE(fast, ft, "smape_all"),
                feedback);
#undef CHANGE
}

void eval_deciding_004(const struct step_tables *d, int standard, int spmis, int own_cell, const char *col, char *out,
                       size_t len)
{
    static const char *const search_costs[2] = {"the cell search costs SPMIS", "the cell search helps SPMIS"};
    static const char *const own_vs_std[2] = {"SPMIS loses to standard reuse even without the search",
                                              "SPMIS with the own cell beats standard reuse"};
    out[0] = '\0';
    finding(out, len, "SPMIS (12-tap search) vs own cell only", eval_change(d, spmis, own_cell, col), search_costs);
    finding(out, len, "own cell only vs standard", eval_change(d, own_cell, standard, col), own_vs_std);
}

void eval_gradient_findings(const struct step_tables *d, int me, int r, char *out, size_t len)
{
    static const char *const cols[2][2] = {{"gradient relMSE without the worst 1% of pairs", "gradient_relmse_trim1"},
                                           {"gradient MAPE", "gradient_mape"}};
    static const char *const reading[2] = {"our gradients are worse there too", "our gradients are better there"};
    out[0] = '\0';
    for (int m = 0; m < 2; m++)
        finding(out, len, cols[m][0], eval_change(d, me, r, cols[m][1]), reading);
}

