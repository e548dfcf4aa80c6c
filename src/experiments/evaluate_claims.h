/* evaluate_claims.h: what evaluate_tables.c writes its evaluation.md and
 * claims.csv with: a growing markdown text, and the claims of one paper as
 * table lines with their verdicts (claim_verdict(), stats.h) and rows of
 * claims.csv. Single-threaded; aborts (RESTIR_CHECK) when memory runs out. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_CLAIMS_H
#define RESTIR_EXPERIMENTS_EVALUATE_CLAIMS_H

#include <stddef.h>

#include "experiments/stats.h"
#include "io/report.h"

/* A growing text; zero-initialised it is empty, s is owned (free(s) when done).
 */
struct md_text {
    char *s;
    size_t len, cap;
};

/* Appends printf(fmt, ...) to t. */
void md_put(struct md_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* What the paper claims of a change (struct claim, stats.h): a reduction by pct
 * percent, a change within
 * +-pct, a cost of at most +pct, or nothing (a row shown for context). */
#define REDUCTION(pct) ((struct claim){CLAIM_REDUCTION, (pct)})
#define SMALL_CHANGE(pct) ((struct claim){CLAIM_SMALL, (pct)})
#define COSTS_AT_MOST(pct) ((struct claim){CLAIM_COST, (pct)})
#define NO_CLAIM ((struct claim){CLAIM_NONE, 0.0})

/* The claims of one paper, as lines of evaluation.md (md) and rows of
 * claims.csv (csv when csv_ok). */
struct claims {
    struct md_text md;
    struct csv_writer csv;
    int csv_ok;
    double render_ms; /* the paper's frames: measured frame times x frames x runs,
                         summed over its steps */
};

/* One claim's line: what (the claim), where (scene, base), our change c, the
 * paper's figure, k as in what the paper claims (claim_verdict()), and the
 * setup's differences from the paper's (said when not reproduced). */
void claim(struct claims *cl, const char *paper, const char *what, const char *where, struct rel_change c,
           const char *paper_figure, struct claim k, const char *differences);

/* claim() with what the deciding rows show (evaluate_findings.h), said whatever
 * the verdict. */
void claim_found(struct claims *cl, const char *paper, const char *what, const char *where, struct rel_change c,
                 const char *paper_figure, struct claim k, const char *findings, const char *differences);

/* Ends a paper's section of md: the rendering time, the claims' table, then
 * empties the claims' lines. */
void flush_claims(struct md_text *md, struct claims *cl, const char *paper);

#endif
