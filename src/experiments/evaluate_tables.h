/* evaluate_tables.h: an evaluation's tables and verdicts from its steps' study.csv / compare.csv
 * (evaluate_tables.c). Must never run a command: it reads what the merges wrote. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_TABLES_H
#define RESTIR_EXPERIMENTS_EVALUATE_TABLES_H

#include "experiments/evaluate_papers.h"

/* Writes DIR/evaluation.md, DIR/claims.csv and with o->report DIR/index.html from the merged steps
 * (folders DIR/NAME; merged[k] == 0: step k is not finished, and is named as such): per paper its
 * setup, then each step's tables through its recipe's writer, then the paper's claims. Returns an
 * exit code. */
int evaluate_write_tables(const char *dir, const char *command, const struct eval_options *o,
                          const struct eval_step *steps, int n, const int *merged);

/* The recipes' table writers (eval_table_writer, evaluate_papers.h; evaluate_recipes.c names them).
 * Each reads the rows of its step's recipe by their place there, and aborts (RESTIR_CHECK) when
 * the recipe has another number of rows. */
/* 000: Table 1 (pass times), Table 2's layout of the quality metrics and their claims; with
 * s->all_configs also Table 2's R x K claims and Figure 3's radii. */
eval_table_writer eval_table_000;
/* 004: the main table (MAPE overall and over disoccluded pixels, FLIP), Table 2's pass times
 * (DIR/STEP/passes.csv) and the claims of each variant against standard reuse (its first row). */
eval_table_writer eval_table_004;
/* 004 Figures 2, 6 and 7: SPMIS's own variants on one scene and the claims the figures make. */
eval_table_writer eval_table_004_ablation;
/* 002: the equal-time table (L2 and L1 reconstructions) and its claims. */
eval_table_writer eval_table_002;

#endif
