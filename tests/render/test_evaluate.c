/* test_evaluate.c: `restir evaluate` at small resolution. Each paper's evaluation run unsplit (--out)
 * equals the same evaluation planned, its jobs run by GNU parallel in shuffled order and merged (every
 * step's table but its timing columns, and every claim but the timed ones); the whole evaluation
 * planned with --report measures every paper's claims and its report links every step's page; a step's
 * table equals what `restir compare` writes
 * for the same command, and the evaluation's tables and claims show its numbers; bad input (an unknown paper or
 * scene, a resolution below the paper's radii, a folder of another evaluation or of another command's plan, a
 * non-empty folder) exits 2 and leaves the folder as it was; an unfinished evaluation merges only with --partial,
 * which names the steps left out; --configs runs a subset of 000's configurations with the same numbers; 002 plans
 * 8 runs by default and 004 4. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_util.h"
#include "test_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 125

static char tmp[CLI_PATH_MAX];

#define SMALL_ARGS "--runs 2 --frames 4 --warmup 1 --ref-spp 4 --scenes cornell"
#define EVAL_ARGS "--res 208x208 " SMALL_ARGS
/* 000's configurations in the whole evaluation: the baseline, a preset and the one its finding on spatial
 * reuse needs (all 17 would triple the test's time for the same code paths) */
#define EVAL_CONFIGS "--configs bitterli,fast,spatial-off"

/* The lines of a text file that do not contain `skip`, concatenated. */
static void lines_without(const char *path, const char *skip, char *out, size_t n)
{
    static char text[1 << 17];
    cli_read_text(path, text, sizeof text);
    size_t o = 0;
    for (char *line = text, *next; line && *line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        if (!strstr(line, skip))
            o += (size_t)snprintf(out + o, n - o, "%s\n", line);
    }
    out[o < n ? o : n - 1] = '\0';
}

static void test_bad_input(char *err)
{
    char dir[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX], before[1 << 14], after[1 << 14], path[3 * CLI_PATH_MAX];
    snprintf(dir, sizeof dir, "%s/bad", tmp);
    snprintf(args, sizeof args, "evaluate 007 --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "unknown paper '007'"), "unknown paper: %s", err);
    snprintf(args, sizeof args, "evaluate 000 --res 320x180 --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "CONSERVATIVE") && strstr(err, "201x201"),
           "000 below its radii: %s", err);
    snprintf(args, sizeof args, "evaluate 004 --res 48x48 --plan '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "61x61"), "004 below its radii: %s", err);
    snprintf(args, sizeof args, "evaluate 000 --configs fast --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "'bitterli'"), "--configs without bitterli: %s", err);
    snprintf(args, sizeof args, "evaluate 000 --configs bitterli,quick --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "'quick'"), "--configs, an unknown name: %s", err);
    snprintf(args, sizeof args, "evaluate 004 --configs bitterli --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "000's configurations"), "--configs with 004: %s", err);
    snprintf(args, sizeof args, "evaluate 004 --scenes nowhere --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "'nowhere'"), "unknown scene: %s", err);
    EXPECT(!cli_exists(dir), "a refused evaluation made its folder");

    /* a folder of another evaluation: refused, untouched */
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --runs 2 --frames 4 --scenes cornell --plan '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 0, "evaluate --plan: %s", err);
    snprintf(path, sizeof path, "%s/plan.json", dir);
    cli_read_text(path, before, sizeof before);
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --runs 3 --frames 4 --scenes cornell --plan '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "holds another evaluation"), "another evaluation: %s", err);
    cli_read_text(path, after, sizeof after);
    EXPECT(before[0] && !strcmp(before, after), "a refused evaluation rewrote plan.json");
    /* the same evaluation again: accepted (it resumes) */
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --runs 2 --frames 4 --scenes cornell --plan '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 0, "the same evaluation planned again: %s", err);

    /* only the first step's jobs done: a merge is refused, a --partial merge names the others */
    /* the reference and 5 reuse rows x 2 runs */
    EXPECT(cli_sh("head -n 11 '%s/jobs.txt' | OMP_NUM_THREADS=1 parallel -j 2 > '%s/parallel.log' 2>&1", dir, dir) == 0,
           "the first step's jobs failed");
    snprintf(args, sizeof args, "evaluate --merge '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "004-cornell-restir-di are missing"),
           "merge of an unfinished evaluation: %s", err);
    snprintf(args, sizeof args, "evaluate --merge '%s' --partial", dir);
    EXPECT(cli_run(tmp, args, err) == 0, "merge --partial: %s", err);
    static char md[1 << 16];
    snprintf(path, sizeof path, "%s/evaluation.md", dir);
    cli_read_text(path, md, sizeof md);
    EXPECT(strstr(md, "### 004-cornell-restir-di: not finished") && strstr(md, "SPMIS: MAPE overall vs standard"),
           "merge --partial: evaluation.md lacks the finished step's claims or the unfinished step's note");

    /* another command's plan, and a folder that is not empty */
    snprintf(path, sizeof path, "%s/compare_plan", tmp);
    snprintf(args, sizeof args, "compare --scene cornell --methods pt --res 16x16 --plan '%s'", path);
    EXPECT(cli_run(tmp, args, err) == 0, "compare --plan: %s", err);
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --scenes cornell --out '%s'", path);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "is the plan of `restir compare"), "a compare plan: %s",
           err);
    EXPECT(cli_sh("mkdir -p '%s/full' && touch '%s/full/notes.txt'", tmp, tmp) == 0, "cannot make a folder");
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --scenes cornell --out '%s/full'", tmp);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "not empty"), "a non-empty folder: %s", err);
    snprintf(path, sizeof path, "%s/full/plan.json", tmp);
    EXPECT(!cli_exists(path), "a refused evaluation wrote into a non-empty folder");
    snprintf(args, sizeof args, "evaluate --merge '%s/full'", tmp);
    EXPECT(cli_run(tmp, args, err) != 0, "merge of a folder without an evaluation succeeded");
}

/* The steps of `evaluate all` with --scenes cornell, and the columns of their tables that are times. */
static const struct {
    const char *name, *table;
    int first, last;
} steps[] = {{"000-cornell", "study", 8, 10},
             {"004-cornell-restir-pt", "compare", 1, 1},
             {"004-cornell-restir-di", "compare", 1, 1},
             {"004-cornell-ablation", "compare", 1, 1},
             {"002-cornell", "compare", 1, 1}};

/* 002 runs 8 runs per configuration by default, 004 keeps 4 (the default runs are per paper). The plans
 * count them: a reference job and one job per row and run. */
static void test_default_runs(char *err)
{
    char dir[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX];
    static const struct {
        const char *paper;
        int jobs;
    } want[2] = {{"002", 1 + 8 * 8}, /* 8 rows x 8 runs */
                 {"004", 1 + 5 * 4}}; /* 5 reuse rows x 4 runs (the first step's plan) */
    for (int k = 0; k < 2; k++) {
        snprintf(dir, sizeof dir, "%s/runs%s", tmp, want[k].paper);
        snprintf(args, sizeof args, "evaluate %s --res 64x64 --frames 4 --scenes cornell --plan '%s'", want[k].paper,
                 dir);
        EXPECT(cli_run(tmp, args, err) == 0, "evaluate %s --plan: %s", want[k].paper, err);
        char jobs[3 * CLI_PATH_MAX], count[16];
        snprintf(jobs, sizeof jobs, "%s/%s/jobs.txt", dir, k == 0 ? "002-cornell" : "004-cornell-restir-pt");
        snprintf(count, sizeof count, "%d", want[k].jobs);
        EXPECT(cli_sh("test $(wc -l < '%s') -eq %s", jobs, count) == 0, "%s has other than %d jobs (default runs)", jobs,
               want[k].jobs);
    }
}

/* The step tables of `paper` (a prefix of the steps' names, "" for all) and claims.csv but their times
 * in folders a and b are the same. */
static void expect_same_evaluation(const char *a_dir, const char *b_dir, const char *paper, const char *what)
{
    static char a[1 << 17], b[1 << 17];
    char pa[3 * CLI_PATH_MAX], pb[3 * CLI_PATH_MAX];
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
        if (strncmp(steps[k].name, paper, strlen(paper)) != 0)
            continue;
        snprintf(pa, sizeof pa, "%s/%s/%s.csv", a_dir, steps[k].name, steps[k].table);
        snprintf(pb, sizeof pb, "%s/%s/%s.csv", b_dir, steps[k].name, steps[k].table);
        cli_csv_without_columns(pa, steps[k].first, steps[k].last, a, sizeof a);
        cli_csv_without_columns(pb, steps[k].first, steps[k].last, b, sizeof b);
        EXPECT(a[0] && !strcmp(a, b), "%s: %s: the merged %s.csv differs from the unsplit one:\n%s\nvs\n%s", what,
               steps[k].name, steps[k].table, a, b);
    }
    snprintf(pa, sizeof pa, "%s/claims.csv", a_dir);
    snprintf(pb, sizeof pb, "%s/claims.csv", b_dir);
    lines_without(pa, "frame time", a, sizeof a);
    lines_without(pb, "frame time", b, sizeof b);
    EXPECT(strchr(a, '\n') && strchr(strchr(a, '\n') + 1, '\n') && !strcmp(a, b),
           "%s: merged claims.csv differs from the unsplit one (or holds no claim):\n%s\nvs\n%s", what, a, b);
}

/* Runs `evaluate ARGS` planned into plan_dir: its jobs in shuffled order under GNU parallel, then merged. */
static void evaluate_planned(const char *eval_args, const char *plan_dir, char *err)
{
    char args[6 * CLI_PATH_MAX];
    snprintf(args, sizeof args, "evaluate %s --plan '%s'", eval_args, plan_dir);
    EXPECT(cli_run(tmp, args, err) == 0, "evaluate --plan: %s", err);
    EXPECT(cli_sh("shuf '%s/jobs.txt' | OMP_NUM_THREADS=1 parallel -j 2 > '%s/parallel.log' 2>&1", plan_dir,
                  plan_dir) == 0,
           "GNU parallel: an evaluation job failed");
    snprintf(args, sizeof args, "evaluate --merge '%s'", plan_dir);
    EXPECT(cli_run(tmp, args, err) == 0, "evaluate --merge: %s", err);
}

/* Planned and unsplit, each paper gives the same tables and claims: 000 at its radii's 208x208, 004 and 002 at
 * 64x64 (the whole evaluation at 208x208 twice cost this test 100 of its 210 CPU-s, and the steps run the same code
 * planned or not). */
static void test_plan_equals_unsplit(char *err)
{
    static const char *const papers[3][2] = {{"000", "--res 208x208 " EVAL_CONFIGS}, {"004", "--res 64x64"},
                                             {"002", "--res 64x64"}};
    for (int k = 0; k < 3; k++) {
        char unsplit[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], eval[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
        snprintf(unsplit, sizeof unsplit, "%s/unsplit%s", tmp, papers[k][0]);
        snprintf(plan, sizeof plan, "%s/planned%s", tmp, papers[k][0]);
        snprintf(eval, sizeof eval, "%s %s " SMALL_ARGS, papers[k][0], papers[k][1]);
        snprintf(args, sizeof args, "evaluate %s --out '%s'", eval, unsplit);
        EXPECT(cli_run(tmp, args, err) == 0, "evaluate --out: %s", err);
        evaluate_planned(eval, plan, err);
        expect_same_evaluation(unsplit, plan, papers[k][0], papers[k][0]);
    }
    printf("evaluate 000 (3 configurations, 208x208), 004 and 002 (64x64) on cornell, 2 runs each: planned, the jobs "
           "run in shuffled order under GNU parallel, merged = unsplit (step tables but their times, claims.csv but its "
           "timed claims)\n");
}

/* The whole evaluation (000 with 3 configurations, 004 and 002 on cornell at 208x208), planned with --report:
 * every paper's claims, measured, with the findings the deciding rows show, and a report linking every step. The
 * later tests read its tables. */
static void test_whole_evaluation(char *err)
{
    static char a[1 << 17];
    char plan[2 * CLI_PATH_MAX], pa[3 * CLI_PATH_MAX], pb[3 * CLI_PATH_MAX];
    snprintf(plan, sizeof plan, "%s/planned", tmp);
    evaluate_planned("all " EVAL_ARGS " " EVAL_CONFIGS " --report", plan, err);
    snprintf(pa, sizeof pa, "%s/claims.csv", plan);
    lines_without(pa, "frame time", a, sizeof a);
    EXPECT(strstr(a, "\n004,") && strstr(a, "\n000,") && strstr(a, "\n002,"), "claims.csv misses a paper:\n%s", a);
    /* 002's gradient claims are measured (compare.csv's gradient_relmse reached the tables) */
    const char *g = strstr(a, "Fig. 7: gradient relMSE vs G-PT 3 spp");
    const char *g_end = g ? strchr(g, '\n') : NULL, *unmeasured = g ? strstr(g, "not measured") : NULL;
    EXPECT(g && (!unmeasured || (g_end && unmeasured > g_end)), "claims.csv: 002's gradient claim is missing or "
                                                                 "not measured:\n%s",
           a);
    /* and the trimmed gradient relMSE and gradient MAPE reached them too */
    static const char *const robust[2] = {"gradient relMSE trim 1% vs Gradient after ReSTIR x 2",
                                          "gradient MAPE vs Gradient after ReSTIR x 1"};
    for (int k = 0; k < 2; k++) {
        const char *r = strstr(a, robust[k]), *r_end = r ? strchr(r, '\n') : NULL;
        const char *r_un = r ? strstr(r, "not measured") : NULL;
        EXPECT(r && (!r_un || (r_end && r_un > r_end)), "claims.csv: \"%s\" is missing or not measured", robust[k]);
    }
    /* the claims' why column says what the deciding rows show (evaluate_findings.h) */
    static const char *const findings[3] = {"Bitterli vs no spatial reuse, SMAPE: ", "own cell only vs standard: ",
                                            "gradient relMSE without the worst 1% of pairs: "};
    for (int k = 0; k < 3; k++)
        EXPECT(strstr(a, findings[k]) != NULL, "claims.csv: no finding \"%s\"", findings[k]);
    snprintf(pa, sizeof pa, "%s/unsplit004/index.html", tmp);
    EXPECT(!cli_exists(pa), "index.html without --report");
    static char html[1 << 18];
    snprintf(pb, sizeof pb, "%s/index.html", plan);
    cli_read_text(pb, html, sizeof html);
    EXPECT(strstr(html, "href=\"004-cornell-ablation/index.html\"") && strstr(html, "Claims of 002"),
           "--report: index.html does not link the steps' pages or lacks the claims");
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
        snprintf(pb, sizeof pb, "%s/%s/index.html", plan, steps[k].name);
        EXPECT(cli_exists(pb), "--report: %s has no index.html", steps[k].name);
    }
    printf("evaluate all (000 with 3 configurations, 004, 002 on cornell at 208x208, 2 runs), planned: every paper's "
           "claims measured, the report links every step\n");
}

/* --configs: 000's study runs only the named configurations, each with the numbers it has in the whole
 * evaluation (the first two rows of its study.csv but their times), and the claims on the others read
 * "not measured". Needs test_whole_evaluation's. */
static void test_configs_subset(char *err)
{
    char out[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX];
    snprintf(out, sizeof out, "%s/subset", tmp);
    snprintf(args, sizeof args, "evaluate 000 " EVAL_ARGS " --configs fast,bitterli --out '%s'", out);
    EXPECT(cli_run(tmp, args, err) == 0, "evaluate 000 --configs: %s", err);
    static char a[1 << 16], b[1 << 16], md[1 << 16];
    snprintf(path, sizeof path, "%s/000-cornell/study.csv", out);
    cli_csv_without_columns(path, 8, 10, a, sizeof a);
    snprintf(path, sizeof path, "%s/planned/000-cornell/study.csv", tmp);
    cli_csv_without_columns(path, 8, 10, b, sizeof b);
    char *end = b;
    for (int line = 0; line < 3 && end; line++) /* the header, bitterli's row and fast's */
        end = strchr(end, '\n') ? strchr(end, '\n') + 1 : NULL;
    if (end)
        *end = '\0';
    EXPECT(a[0] && strstr(a, "\nbitterli,") && !strcmp(a, b),
           "--configs fast,bitterli: study.csv is not the whole evaluation's first two rows:\n%s\nvs\n%s", a, b);
    snprintf(path, sizeof path, "%s/evaluation.md", out);
    cli_read_text(path, md, sizeof md);
    EXPECT(strstr(md, "Configurations: only fast,bitterli"), "evaluation.md does not say which configurations ran");
    EXPECT(strstr(md, "| balanced: frame time vs Bitterli (cost) | cornell | - |") &&
               strstr(md, "**not measured**") && !strstr(md, "| FAST: SMAPE vs Bitterli R = 30 | cornell | - |"),
           "evaluation.md: a claim on a configuration not run is not 'not measured', or FAST's is:\n%s", md);
    printf("evaluate 000 --configs fast,bitterli: the whole evaluation's rows for those two, the others' claims "
           "not measured\n");
}

/* The 004 step's table is what `restir compare` writes for its command, and the evaluation's tables
 * and claims show those numbers. */
static void test_tables_are_compares(char *err)
{
    char out[2 * CLI_PATH_MAX], args[8 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX];
    snprintf(out, sizeof out, "%s/compare_004", tmp);
    snprintf(args, sizeof args,
             "compare --scene cornell --res 208x208 --runs 2 --ref-spp 4 --frames 4 --camera path --methods "
             "'restir-pt,restir-pt:spatial.reuse=spmis,restir-pt:spatial.reuse=spmis:spmis.search_score=compat,"
             "restir-pt:spatial.reuse=spmis:spmis.search_steps=0,restir-pt:spatial.reuse=spmis:spmis.search=low-"
             "confidence' "
             "--set spatial.neighbors=3 --set spatial.radius=30 --set mis=pairwise --set confidence_cap=20 --set "
             "pt.candidates=1 --set pt.max_bounces=8 --out '%s'",
             out);
    EXPECT(cli_run(tmp, args, err) == 0, "compare: %s", err);
    static char a[1 << 16], b[1 << 16], md[1 << 17];
    snprintf(path, sizeof path, "%s/compare.csv", out);
    cli_csv_without_columns(path, 1, 1, a, sizeof a);
    char step[3 * CLI_PATH_MAX];
    snprintf(step, sizeof step, "%s/planned/004-cornell-restir-pt/compare.csv", tmp);
    cli_csv_without_columns(step, 1, 1, b, sizeof b);
    EXPECT(a[0] && !strcmp(a, b), "the 004 step's compare.csv differs from restir compare's:\n%s\nvs\n%s", b, a);

    /* MAPE and its standard error of standard reuse and SPMIS, from compare.csv */
    double mape[2] = {NAN, NAN}, sem[2] = {NAN, NAN};
    cli_read_text(path, a, sizeof a);
    char *line = strchr(a, '\n');
    for (int k = 0; k < 2 && line; k++) {
        line++;
        double v[16];
        char *c = strchr(line, ',');
        for (int j = 0; j < 16 && c; j++) { /* columns 1.. */
            v[j] = strtod(c + 1, NULL);
            c = strchr(c + 1, ',');
        }
        mape[k] = v[4]; /* mape (column 5) */
        sem[k] = v[10]; /* mape_sem (column 11) */
        line = strchr(line, '\n');
    }
    char want[128];
    snprintf(path, sizeof path, "%s/planned/evaluation.md", tmp);
    cli_read_text(path, md, sizeof md);
    snprintf(want, sizeof want, "| standard (3 neighbors, 30 px) | ");
    EXPECT(strstr(md, want), "evaluation.md has no standard-reuse row");
    snprintf(want, sizeof want, "| %.4g +- %.2g |", mape[0], sem[0]);
    EXPECT(strstr(md, want), "evaluation.md does not show compare's MAPE of standard reuse '%s'", want);
    /* the claim pairs the runs by seed: the geometric mean of the per-run ratios, from runs.csv
     * (method,run,relmse,mape,...: rows of standard reuse first, then SPMIS, run 0 then run 1) */
    double run_mape[2][2] = {{NAN, NAN}, {NAN, NAN}};
    snprintf(path, sizeof path, "%s/runs.csv", out);
    cli_read_text(path, a, sizeof a);
    line = strchr(a, '\n');
    for (int k = 0; k < 4 && line; k++) {
        line++;
        const char *f = strchr(line, ','); /* run */
        const char *g = f ? strchr(f + 1, ',') : NULL; /* relmse */
        const char *h = g ? strchr(g + 1, ',') : NULL; /* mape */
        if (h)
            run_mape[k / 2][k % 2] = strtod(h + 1, NULL);
        line = strchr(line, '\n');
    }
    const double pct =
        100.0 * expm1(0.5 * (log(run_mape[1][0] / run_mape[0][0]) + log(run_mape[1][1] / run_mape[0][1])));
    snprintf(want, sizeof want, "| SPMIS: MAPE overall vs standard | cornell, restir-pt | %+.1f%% [", pct);
    EXPECT(strstr(md, want), "the SPMIS claim does not show the paired change of compare's runs '%s'", want);
    printf("the 004 step = restir compare of the same command; evaluation.md shows its MAPE (%.4g +- %.2g) and the "
           "SPMIS change %+.1f%%\n",
           mape[0], sem[0], pct);
}

int main(void)
{
    static char err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    EXPECT(system("command -v parallel >/dev/null 2>&1") == 0,
           "GNU parallel is not installed (make test-deps installs it)");
    test_bad_input(err);
    test_default_runs(err);
    test_plan_equals_unsplit(err);
    test_whole_evaluation(err);
    test_tables_are_compares(err);
    test_configs_subset(err);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
