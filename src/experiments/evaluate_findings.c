/* evaluate_findings.c: what the deciding rows of an evaluation show about a claim (issue 42), as the
 * text of its "why" column (evaluate_findings.h). */
#include "experiments/evaluate_findings.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void eval_fmt_change(struct rel_change c, char *out, size_t len)
{
    if (!isfinite(c.pct))
        snprintf(out, len, "-");
    else if (isfinite(c.sd))
        snprintf(out, len, "%+.1f%% +- %.1f", c.pct, c.sd);
    else
        snprintf(out, len, "%+.1f%%", c.pct);
}

/* Appends to out (len bytes, NUL-terminated) what a deciding pair of rows shows: "what: +x% +- sd,
 * reading" with reading[0] when the change is above zero at two standard deviations, reading[1]
 * when below, "no significant difference" otherwise; nothing when either row is missing. */
static void finding(char *out, size_t len, const char *what, struct rel_change c, const char *const reading[2])
{
    if (!isfinite(c.pct))
        return;
    char ch[64];
    eval_fmt_change(c, ch, sizeof ch);
    const double sd = isfinite(c.sd) ? c.sd : 0.0;
    const char *r = c.pct - 2.0 * sd > 0.0   ? reading[0]
                    : c.pct + 2.0 * sd < 0.0 ? reading[1]
                                             : "no significant difference";
    const size_t used = strlen(out);
    snprintf(out + used, len - used, "%s%s: %s, %s", used ? "; " : "", what, ch, r);
}

void eval_deciding_000(const struct csv_table *t, int bit, int fast, char *out, size_t len)
{
    const int off = csv_table_find(t, "spatial-off"), bt = csv_table_find(t, "bitterli-history-temporal"),
              ft = csv_table_find(t, "fast-history-temporal");
    static const char *const reuse[2] = {"spatial reuse itself hurts on this scene with our base",
                                         "spatial reuse helps on this scene"};
    static const char *const fed[2] = {"FAST loses without the feedback too", "FAST gains without the feedback"};
    static const char *const feedback[2] = {"feeding the spatial output back costs FAST",
                                            "feeding the spatial output back helps FAST"};
    out[0] = '\0';
#define CHANGE(a, b, col)                                                                                          \
    rel_change_of(csv_table_num(t, a, col), csv_table_num(t, a, col "_sem"), csv_table_num(t, b, col),              \
                  csv_table_num(t, b, col "_sem"))
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

void eval_deciding_004(const struct csv_table *t, int standard, int spmis, int own_cell, const char *col, char *out,
                       size_t len)
{
    static const char *const search_costs[2] = {"the cell search costs SPMIS", "the cell search helps SPMIS"};
    static const char *const own_vs_std[2] = {"SPMIS loses to standard reuse even without the search",
                                              "SPMIS with the own cell beats standard reuse"};
    char sem[64];
    snprintf(sem, sizeof sem, "%s_sem", col);
    out[0] = '\0';
    finding(out, len, "SPMIS (12-tap search) vs own cell only",
            rel_change_of(csv_table_num(t, spmis, col), csv_table_num(t, spmis, sem), csv_table_num(t, own_cell, col),
                          csv_table_num(t, own_cell, sem)),
            search_costs);
    finding(out, len, "own cell only vs standard",
            rel_change_of(csv_table_num(t, own_cell, col), csv_table_num(t, own_cell, sem),
                          csv_table_num(t, standard, col), csv_table_num(t, standard, sem)),
            own_vs_std);
}

void eval_gradient_findings(const struct csv_table *t, int me, int r, char *out, size_t len)
{
    static const char *const cols[2][3] = {{"gradient relMSE without the worst 1% of pairs", "gradient_relmse_trim1",
                                            "gradient_relmse_trim1_sem"},
                                           {"gradient MAPE", "gradient_mape", "gradient_mape_sem"}};
    static const char *const reading[2] = {"our gradients are worse there too", "our gradients are better there"};
    out[0] = '\0';
    for (int m = 0; m < 2; m++)
        finding(out, len, cols[m][0],
                rel_change_of(csv_table_num(t, me, cols[m][1]), csv_table_num(t, me, cols[m][2]),
                              csv_table_num(t, r, cols[m][1]), csv_table_num(t, r, cols[m][2])),
                reading);
}

