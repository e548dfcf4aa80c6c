/* study.h: the study harness of 000 (study.c): the setup every mode derives from a description, the
 * unsplit run, the plan, a plan's job and its merge. The `restir study` subcommand turns options into
 * the description and prints its usage. Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_STUDY_H
#define RESTIR_EXPERIMENTS_STUDY_H

#include "experiments/options.h"
#include "experiments/plan.h"
#include "experiments/study_run.h"
#include "scene/scene.h"

/* What every mode of the study (run, plan, job, merge) derives from its options. */
struct study_setup {
    struct cli_options o;
    const struct method *method;
    struct study_config cfg[STUDY_MAX_CONFIGS];
    int ncfg;
    struct scene s;
};

/* The study from its description (struct cli_options as the option table parsed it): method,
 * configurations, the scene loaded (st->s, to destroy). need_out: --out (or --plan or --merge) is
 * required. Returns 0, or an exit code having said why. */
int study_setup(const struct cli_options *desc, int need_out, struct study_setup *st);
/* The unsplit study into st->o.out: its reference (or --ref), every configuration's runs, the
 * outputs; command is the command line reports show. Returns an exit code. */
int study_run(struct study_setup *st, const char *command);
/* Writes the plan of the study into st->o.plan (argv: the command's arguments, stored as the plan's
 * description). Returns an exit code. */
int study_plan(const struct study_setup *st, int argc, char **argv);
/* Job k (0-based) of a study plan: computes it into its output under runs/, or says it is done
 * already. Returns an exit code. */
int study_run_job(const struct plan *pl, int k);
/* Merges the finished jobs of the study plan in dir into its outputs. Returns an exit code. */
int study_merge(const char *dir);

#endif
