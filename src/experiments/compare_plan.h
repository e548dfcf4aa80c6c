/* compare_plan.h: `restir compare` split into jobs (compare_plan.c): --plan DIR, `restir job`, --merge DIR.
 * Must never implement a method; only compare_command.c, cmd_compare.c (--merge) and
 * cmd_job.c call it. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_PLAN_H
#define RESTIR_EXPERIMENTS_COMPARE_PLAN_H

struct compare_setup;
struct plan;

/* --plan DIR: writes the plan (one job per SPEC, and one for the reference without --ref).
 * Returns an exit code. */
int compare_plan(const struct compare_setup *st, int argc, char **argv);
/* Job k (0-based) of a comparison's plan: computes it into its output under runs/, or says it is
 * done already. Returns an exit code. */
int compare_run_job(const struct plan *pl, int k);
/* --merge DIR: the table and outputs of a plan's finished jobs. Returns an exit code. */
int compare_merge(const char *dir);

#endif
