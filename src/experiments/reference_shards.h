/* reference_shards.h: `restir reference` split into shards (reference_shards.c): the plan, one shard, the merge.
 * Must never implement a method; only cmd_reference.c and cmd_job.c call it. */
#ifndef RESTIR_EXPERIMENTS_REFERENCE_SHARDS_H
#define RESTIR_EXPERIMENTS_REFERENCE_SHARDS_H

struct plan;
struct reference_setup;

/* --shards N --plan DIR: writes the plan. Returns an exit code. */
int reference_plan(const struct reference_setup *st, int argc, char **argv);
/* Job k (0-based) of a reference's plan: renders shard k into its output under runs/, or says it
 * is done already. Returns an exit code. */
int reference_run_job(const struct plan *pl, int k);
/* --merge DIR --out FILE.exr. Returns an exit code. */
int reference_merge(int argc, char **argv);

#endif
