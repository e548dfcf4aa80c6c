/* cmd_evaluate.c: `restir evaluate PAPER`: its usage, and its options into the evaluation harness
 * (src/experiments/evaluate.h): plan, run, merge. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/evaluate.h"
#include "experiments/evaluate_check.h"
#include "experiments/options.h"

static void evaluate_usage(void)
{
    printf("usage: restir evaluate 000|004|002|all (--out DIR | --plan DIR) [--res WxH] [--runs N] [--scenes LIST]\n"
           "                       [--configs LIST] [--frames N] [--warmup N] [--ref-spp N] [--threads N] [--report]\n"
           "                       [--force | --resume]\n"
           "       restir evaluate --merge DIR [--partial]\n"
           "       restir evaluate --tables DIR [--partial]     restir evaluate --check DIR [--threads N]\n"
           "A paper's evaluation at its own scale (1920x1080 unless --res) with its own parameters, as `restir\n"
           "study` (000) and `restir compare` (004, 002) commands, one folder each under DIR:\n"
           "  000  compatibility-guided neighbor selection: study of restir-pt, M = 1, static camera, 40\n"
           "       warm-up frames, Bitterli R = 30 vs FAST / BALANCED / CONSERVATIVE (Table 1); on the first\n"
           "       scene also the R x K grid of Table 2 and Figure 3's Pareto points (Bitterli and K = 32 at\n"
           "       R 10, 30, 50, 100) and no spatial reuse, Bitterli and FAST with the temporal history.\n"
           "       Scenes forest (for EMERALD SQUARE), ajar (VEACH AJAR).\n"
           "  004  stochastic pairwise MIS: compare of standard reuse, SPMIS and SPMIS with the compatibility-\n"
           "       scored cell search, the own cell only and the low-confidence search, restir-pt and\n"
           "       restir-di, the last of 50 frames of the camera path:\n"
           "       MAPE overall and over disoccluded pixels. Scenes pillars, forest.\n"
           "  002  gradient-domain ReSTIR PT at the paper's equal-time ratios (ours x 1, Gradient after ReSTIR\n"
           "       x 2, Area ReSTIR x 4, G-PT 3 spp), L2 and L1 reconstructions, camera path, and Gradient\n"
           "       after ReSTIR x 1 (equal samples). Scenes ajar, cornell.\n"
           "Every configuration runs --runs independently seeded times (default per paper: 000 and 004 4,\n"
           "002 8, where 4 runs left the gradient errors with standard errors of 15-40%%): every number comes\n"
           "with its standard error. --scenes replaces the paper's scenes; --frames, --warmup and --ref-spp\n"
           "replace its frame counts (000: 16 measured after 40 warm-up; 004: 50; 002: 16) and the\n"
           "references' 1024 paths per pixel: the tables say so. --configs runs a subset of 000's\n"
           "configurations (bitterli, fast, balanced, conservative; on the first scene also compat-rR-kK for\n"
           "R 30, 50, 100 and K 8, 128, bitterli-rR for R 10, 50, 100, compat-r10-k32, spatial-off,\n"
           "bitterli-history-temporal, fast-history-temporal), bitterli among them:\n"
           "the claims of the others read \"not measured\". A --res below the paper's largest pixel\n"
           "radius (000: 100, 004 and 002: 30) is refused; smaller images keep the papers' pixel radii.\n"
           "--plan DIR writes the plan (DIR/jobs.txt: one `restir job DIR K` per configuration, run and\n"
           "reference; DIR/slurm.sh) for GNU parallel or Slurm; `restir evaluate --merge DIR` then merges\n"
           "every step and writes the tables (--partial: the steps whose jobs are all done; the tables name\n"
           "the others). --out DIR plans, runs every job not yet done (so a stopped\n"
           "evaluation resumes; --resume insists on it: exit 2 when DIR holds no such evaluation) and merges.\n"
           "A folder that holds another evaluation, another command's plan or anything else is refused, and\n"
           "nothing in it is touched; --force empties it first (only a folder restir wrote, never /, $HOME or\n"
           "the current folder) and starts the evaluation over.\n"
           "Writes DIR/evaluation.md (the paper's tables with spreads and one line per claim: our change\n"
           "against the baseline paired by seed, its 95%% interval (Student t over the seeds; relMSE also a\n"
           "bootstrap, the wider kept) and a verdict: reproduced, partly, not reproduced, opposite,\n"
           "undecided (with the seeds that would decide it), refused (the reference's own error exceeds\n"
           "the change), undefined (a baseline <= 0); the paper's figure, the differences), DIR/claims.csv,\n"
           "each step's study.csv / compare.csv and with --report DIR/index.html (and each step's page).\n"
           "docs/EVALUATION.md is made from docs/evaluation/data (scripts/evaluation_doc.sh).\n");
    printf(/* two strings: ISO C bounds a string literal's length */
           "Provenance: a campaign runs on one commit (jobs and merges of a plan made by another build are\n"
           "refused); each merged step records STEP/provenance.json (build, machines, date, resolution, runs,\n"
           "seeds, reference paths, scene) and STEP/settings.json (per row: the method, every setting in\n"
           "effect, the hash of a 48x32 render of 2 frames with them). scripts/evaluation_export.sh copies\n"
           "these small files; --tables DIR writes DIR/evaluation.md and claims.csv again from them alone\n"
           "(exit 2, nothing written: a step without its table unless --partial, steps of different commits or\n"
           "another resolution); --check DIR renders every row under DIR again and exits 1 naming the tables\n"
           "today's code renders differently (2: a step without settings.json).\n");
    cli_options_help(stdout, "evaluate");
}

int cmd_evaluate(int argc, char **argv)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge")) {
            const int partial = argc == 3 && !strcmp(argv[i ? 0 : 2], "--partial");
            if (argc != 2 && !partial) {
                cli_error("evaluate --merge DIR takes no other option than --partial (the plan holds them)");
                return EXIT_USAGE;
            }
            return evaluate_merge(argv[i + 1], partial);
        }
    struct eval_options o;
    const char *dir = NULL;
    int mode = 0, help = 0;
    const int rc = evaluate_parse(argc, argv, &o, &dir, &mode, &help);
    if (rc != 0)
        return rc;
    if (help) {
        evaluate_usage();
        return 0;
    }
    if (mode == 'c')
        return evaluate_check(dir, o.threads);
    if (mode == 't')
        return evaluate_tables(dir, o.partial);
    return evaluate_run(&o, dir, mode);
}
