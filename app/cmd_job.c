/* cmd_job.c: `restir job DIR K`, line K of a plan folder's jobs.txt (plan.h): loads the plan and hands
 * job K to the command that planned it. Must never implement a method or know what a job computes. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_plan.h"
#include "experiments/evaluate.h"
#include "experiments/plan.h"
#include "experiments/reference_checkpoint.h"
#include "experiments/reference_shards.h"
#include "experiments/study.h"

int cmd_job(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "--help") || !strcmp(argv[0], "-h"))) {
        printf(
            "usage: restir job DIR K\n"
            "Runs job K (1-based: line K of DIR/jobs.txt) of a plan that `restir study|reference|compare|evaluate "
            "...\n"
            "--plan DIR` wrote. The job writes only its own result under DIR/runs/ (a temporary file, then a\n"
            "rename); a job whose result is there and sound says so and exits 0, so a plan can be run again.\n"
            "A reference job saves its running mean to runs/reference.checkpoint.exr every %.0f minutes (the\n"
            "environment's RESTIR_REFERENCE_CHECKPOINT_SECONDS sets another interval) and when SIGINT or SIGTERM\n"
            "stops it; run again, it continues from there (after a kill too) to the bytes of an uninterrupted "
            "job.\n"
            "A campaign runs on one commit: a plan made by another build (plan.json's \"provenance\") is refused\n"
            "(exit 2). A finished job records the machine that ran it in DIR/runs/logs/job_K.json.\n",
            PLAN_REFERENCE_CHECKPOINT_SECONDS / 60.0);
        return 0;
    }
    if (argc != 2) {
        cli_error("usage: restir job DIR K");
        return EXIT_USAGE;
    }
    char msg[RESTIR_MSG_LEN];
    struct plan pl;
    if (plan_load(argv[0], &pl, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (plan_check_build(&pl) != 0) { /* a campaign runs on one commit */
        plan_free(&pl);
        return EXIT_USAGE;
    }
    long long k = 0;
    if (cli_parse_int("job", argv[1], 1, pl.n_jobs, &k, msg) != 0) {
        cli_error("%s (%s has %d jobs)", msg, pl.dir, pl.n_jobs);
        plan_free(&pl);
        return EXIT_USAGE;
    }
    int rc;
    if (!strcmp(pl.kind, "study"))
        rc = study_run_job(&pl, (int)k - 1);
    else if (!strcmp(pl.kind, "reference"))
        rc = reference_run_job(&pl, (int)k - 1);
    else if (!strcmp(pl.kind, "compare"))
        rc = compare_run_job(&pl, (int)k - 1);
    else if (!strcmp(pl.kind, "evaluate"))
        rc = evaluate_run_job(&pl, (int)k - 1);
    else {
        cli_error("%s/plan.json: unknown kind '%s'", pl.dir, pl.kind);
        rc = EXIT_USAGE;
    }
    if (rc == 0)
        plan_note_job_machine(&pl, (int)k - 1, pl.threads);
    plan_free(&pl);
    return rc;
}
