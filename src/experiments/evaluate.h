/* evaluate.h: the evaluation harness (evaluate.c): a paper's evaluation as a plan of study and
 * compare steps, its jobs and its merge. `restir evaluate` parses and prints its usage.
 * Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_H
#define RESTIR_EXPERIMENTS_EVALUATE_H

#include "experiments/evaluate_papers.h"
#include "experiments/plan.h"

/* The evaluation's options (argv without the command name) through the option table; dir and mode
 * (0 none, 'o' --out, 'p' --plan, 'c' --check, 't' --tables: then o holds only threads and partial)
 * may be NULL for a plan's stored arguments; *help (may be NULL)
 * is set when --help was given (nothing else is checked then). Returns 0, or an exit code having
 * said why. */
int evaluate_parse(int argc, char **argv, struct eval_options *o, const char **dir, int *mode, int *help);
/* Plans the evaluation into dir (mode 'p'), or plans, runs every job not yet done and merges
 * (mode 'o'). Returns an exit code. */
int evaluate_run(const struct eval_options *o, const char *dir, int mode);
/* The options and steps of a loaded evaluation plan (its stored options through evaluate_parse and
 * eval_steps). Returns 0, or an exit code having said why. */
int evaluate_plan_steps(const struct plan *pl, struct eval_options *o, struct eval_step *steps, int *n);
/* Job k (0-based) of an evaluation plan: the job of the study or compare step that holds it. */
int evaluate_run_job(const struct plan *pl, int k);
/* Merges every step, then writes the tables; partial: steps that cannot be merged yet are left out
 * (the tables say so). Returns an exit code. */
int evaluate_merge(const char *dir, int partial);

#endif
