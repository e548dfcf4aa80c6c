/* evaluate_tables.h: an evaluation's tables and verdicts from its steps' study.csv / compare.csv
 * (evaluate_tables.c). Must never run a command: it reads what the merges wrote. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_TABLES_H
#define RESTIR_EXPERIMENTS_EVALUATE_TABLES_H

#include "experiments/evaluate_papers.h"

/* Writes DIR/evaluation.md, DIR/claims.csv and with o->report DIR/index.html from the merged steps
 * (folders DIR/NAME; merged[k] == 0: step k is not finished, and is named as such). Returns an exit
 * code. */
int evaluate_write_tables(const char *dir, const char *command, const struct eval_options *o,
                          const struct eval_step *steps, int n, const int *merged);

#endif
