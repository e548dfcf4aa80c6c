/* evaluate_claims.c: the markdown text and the claims' table of an evaluation
 * (evaluate_claims.h). */
#include "experiments/evaluate_claims.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/evaluate_change.h"

void md_put(struct md_text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        const int n = vsnprintf(t->s ? t->s + t->len : NULL, t->s ? t->cap - t->len : 0, fmt, ap);
        va_end(ap);
        RESTIR_CHECK(n >= 0);
        if (t->s && t->len + (size_t)n < t->cap) {
            t->len += (size_t)n;
            return;
        }
        t->cap = 2 * (t->cap + (size_t)n + 256);
        t->s = realloc(t->s, t->cap);
        RESTIR_CHECK(t->s != NULL);
    }
}

void claim(struct claims *cl, const char *paper, const char *what, const char *where, struct rel_change c,
           const char *paper_figure, struct claim k, const char *differences)
{
    claim_found(cl, paper, what, where, c, paper_figure, k, "", differences);
}

void claim_found(struct claims *cl, const char *paper, const char *what, const char *where, struct rel_change c,
                 const char *paper_figure, struct claim k, const char *findings, const char *differences)
{
    char ours[64], why[160], f[4][1100];
    eval_fmt_change(c, ours, sizeof ours);
    const char *v = claim_verdict(c, k, why, sizeof why);
    const int ok = !strcmp(v, "reproduced") || !strcmp(v, "undefined") || k.kind == CLAIM_NONE;
    char reason[1100];
    snprintf(reason, sizeof reason, "%s%s%s", why, why[0] && findings[0] ? "; " : "", findings);
    if (!ok) {
        const size_t used = strlen(reason);
        snprintf(reason + used, sizeof reason - used, "%s%s", used ? "; " : "", differences);
    }
    md_put(&cl->md, "| %s | %s | %s | %s | **%s** | %s |\n", what, where, ours, paper_figure, v,
           reason[0] ? reason : "-");
    if (cl->csv_ok) {
        csv_field(f[0], sizeof f[0], what);
        csv_field(f[1], sizeof f[1], where);
        csv_field(f[2], sizeof f[2], paper_figure);
        csv_field(f[3], sizeof f[3], reason);
        static const char *const how[] = {"none", "t", "bootstrap", "jackknife", "unpaired"};
        csv_row(&cl->csv, "%s,%s,%s,%.4g,%.4g,%.4g,%s,%d,%s,%s,%s", paper, f[0], f[1], c.pct, c.lo, c.hi,
                how[c.interval], c.n, f[2], v, f[3]);
    }
}

/* Ends a paper's section: its claims' table, then empties the claims' lines. */
void flush_claims(struct md_text *md, struct claims *cl, const char *paper)
{
    md_put(md,
           "\nRendering time of the measured configurations: %.3g hours of wall "
           "time (frame times as measured by "
           "the jobs, times frames and runs; references not counted).\n",
           cl->render_ms / 3.6e6);
    cl->render_ms = 0.0;
    md_put(md,
           "\n#### Claims of %s\n\nOurs: the change of the configuration against "
           "its baseline, paired by seed "
           "(run r of both rendered with the same seed), as the geometric mean "
           "of the per-seed ratios with its 95%% "
           "interval (Student t over the seeds; for relMSE also a bootstrap over "
           "the seeds, the wider reported; for "
           "the covariances a paired jackknife). Verdicts (docs/EVALUATION.md): "
           "reproduced, partly, not reproduced, "
           "opposite, undecided (the interval holds both zero and the paper's "
           "effect).\n\n"
           "| claim | where | ours (change) | paper | verdict | why / "
           "differences |\n|---|---|---|---|---|---|\n%s",
           paper, cl->md.s ? cl->md.s : "");
    cl->md.len = 0;
    if (cl->md.s)
        cl->md.s[0] = '\0';
}
