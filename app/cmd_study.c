/* cmd_study.c: `restir study`: its usage, and its options into the study harness's description
 * (src/experiments/study.h), unsplit, planned or merged. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "experiments/study.h"

static void study_usage(FILE *out)
{
    fprintf(out,
            "usage: restir study --scene NAME --method restir-di|restir-pt --configs LIST [--radii LIST]\n"
            "                    [--runs N] [--warmup N] [--frames F] [--res WxH] [--ref FILE.exr | --ref-spp N]\n"
            "                    [--set key=value]... [--report [--self-contained]] --out DIR [--force]\n"
            "The error-correlation study of 000 (Sec. 6-7, Appendix A): N independently seeded sequences per\n"
            "configuration (static camera, confidence cap 20, --warmup frames before measuring, default 40),\n"
            "then --frames measured frames (default 16). LIST: bitterli, bitterli-rR (at radius R),\n"
            "fast, balanced, conservative, compat, compat-binary, compat-rR-kK (compat at radius R with K\n"
            "candidates: 000 Table 2's grid), spatial-off (no spatial reuse), bitterli-history-temporal and\n"
            "fast-history-temporal (the spatial output shown, the temporal one kept as history).\n"
            "--radii R1,R2,... adds bitterli and compat at each radius.\n"
            "Spatial neighbors M: --set spatial.neighbors=M. Default --res 320x180, --runs 8.\n"
            "Writes DIR/study.csv, study.md, pareto.svg (000 Figure 3: SMAPE against spatial covariance of\n"
            "every bitterli configuration and every compat one with K = 32, by radius), hard_pixels.png,\n"
            "strip.png; with --report also DIR/index.html, a page showing them with the command, commit\n"
            "and machine, which loads the images beside it (with --self-contained it holds them all,\n"
            "base64 data: URIs, so the one file holds everything).\n"
            "SMAPE (all and hard pixels) comes with its standard error over the runs (smape_all_sem,\n"
            "smape_hard_sem: the runs' SMAPEs, each the mean over its frames), the covariances with their\n"
            "jackknife standard errors over the runs (temporal_cov_sem, spatial_cov_sem; nan under 3 runs);\n"
            "temporal_cov_hard (with temporal_cov_hard_sem) is temporal_cov over the hard pixels only.\n"
            "--plan DIR (instead of --out) writes DIR/jobs.txt (one command per configuration and run, and\n"
            "one for the reference without --ref), DIR/plan.json and DIR/slurm.sh (sbatch --array) instead\n"
            "of running; run the jobs in any order and anywhere (`parallel -j N < DIR/jobs.txt`, `sbatch\n"
            "DIR/slurm.sh`), then `restir study --merge DIR` writes into DIR what the study writes, with the\n"
            "same numbers (the pass times are those the jobs measured). docs/CLUSTER.md.\n"
            "--out DIR must be new or empty (one run per folder): --force empties it first. A --plan DIR\n"
            "may also hold the same plan, planned again with its finished jobs kept; --force empties one\n"
            "that holds another. --force empties only a folder restir wrote (summary.json, plan.json,\n"
            "study.csv, frame_NNNN.*, ...), never /, $HOME or the current folder, and follows no link.\n"
            "--ref FILE.exr without --res: the study runs at the reference's size.\n");
    cli_options_help(out, "study");
}

int cmd_study(int argc, char **argv)
{
    char msg[RESTIR_MSG_LEN];
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge")) {
            if (argc != 2) {
                cli_error("study --merge DIR takes no other option (the plan holds them)");
                return EXIT_USAGE;
            }
            return study_merge(argv[i + 1]);
        }
    struct cli_options desc;
    if (cli_parse_options("study", argc, argv, &desc, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (desc.help) {
        study_usage(stdout);
        return 0;
    }
    if (!desc.plan && desc.out && out_dir_check("--out", desc.out, desc.force, msg) != 0) {
        cli_error("%s", msg); /* a folder of its own: nothing is touched */
        return EXIT_USAGE;
    }
    static struct study_setup st;
    int rc = study_setup(&desc, 1, &st);
    if (rc != 0)
        return rc;
    if (st.o.plan) {
        rc = study_plan(&st, argc, argv);
        scene_destroy(&st.s);
        return rc;
    }
    char command[8192];
    cli_command_line("study", argc, argv, command, sizeof command);
    return study_run(&st, command);
}
