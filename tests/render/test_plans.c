/* test_plans.c: long commands split into jobs. A study planned with --plan, its jobs
 * run by GNU parallel in shuffled order and merged, equals the unsplit study (study.csv except
 * its timing columns, pareto.svg, hard_pixels.png, strip.png byte for byte); a reference split
 * into shards, run with xargs -P and merged, equals the unsplit one within the summation-order
 * bound (2 C + 1) 2^-24 of reference_shards.c; merges with a job missing or corrupt are refused
 * naming its line; a finished job run again says so; a comparison planned per method and run
 * (--runs 2) and merged equals the unsplit one (compare.csv except ms_per_frame, reference and
 * frames byte for byte) and its merge refuses a plan reference whose halves are gone; a plan's
 * reference job stopped by SIGTERM or killed keeps a checkpoint, and run
 * again continues from it to the bytes of an uninterrupted job (a 1080p reference outlives a session). */
#include <math.h>
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

#define MSG_LEN 512

static char tmp[CLI_PATH_MAX];

#define STUDY                                                                                                          \
    "study --scene cornell --method restir-di --configs bitterli,compat --radii 12 --res 48x27 "                       \
    "--frames 5 --warmup 3 --runs 3 --ref-spp 32 --seed 11"
#define REF "reference --scene cornell --method restir-di --res 64x36 --spp 1000 --seed 4"

static int have(const char *tool)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return system(cmd) == 0;
}

static void test_study(char *err)
{
    char unsplit[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX];
    snprintf(unsplit, sizeof unsplit, "%s/study", tmp);
    snprintf(plan, sizeof plan, "%s/study_plan", tmp);
    snprintf(args, sizeof args, STUDY " --out '%s'", unsplit);
    EXPECT(cli_run(tmp, args, err) == 0, "unsplit study: %s", err);
    snprintf(args, sizeof args, STUDY " --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "study --plan: %s", err);
    static const char *const files[] = {"plan.json", "jobs.txt", "slurm.sh", "runs/logs"};
    for (int i = 0; i < 4; i++) {
        char path[3 * CLI_PATH_MAX];
        snprintf(path, sizeof path, "%s/%s", plan, files[i]);
        struct stat st;
        EXPECT(stat(path, &st) == 0, "the plan has no %s", files[i]);
    }
    /* 1 reference + 4 configurations x 3 runs, in shuffled order, two at a time */
    EXPECT(cli_sh("test $(wc -l < '%s/jobs.txt') -eq 13", plan, "") == 0, "jobs.txt does not hold 13 jobs");
    EXPECT(cli_sh("shuf '%s/jobs.txt' | OMP_NUM_THREADS=1 parallel --halt now,fail=1 -j 2 > '%s/parallel.log' 2>&1",
                  plan, plan) == 0,
           "GNU parallel: a job failed (%s/parallel.log)", plan);
    snprintf(args, sizeof args, "study --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "study --merge: %s", err);
    static char a[1 << 16], b[1 << 16];
    char pa[3 * CLI_PATH_MAX], pb[3 * CLI_PATH_MAX];
    snprintf(pa, sizeof pa, "%s/study.csv", unsplit);
    snprintf(pb, sizeof pb, "%s/study.csv", plan);
    cli_csv_without_columns(pa, 8, 1000, a, sizeof a); /* all but the pass times */
    cli_csv_without_columns(pb, 8, 1000, b, sizeof b); /* all but the pass times */
    EXPECT(a[0] && strcmp(a, b) == 0, "merged study.csv differs from the unsplit one:\n%s\nvs\n%s", a, b);
    static const char *const same[] = {"pareto.svg", "hard_pixels.png", "strip.png"};
    for (int i = 0; i < 3; i++) {
        long size = 0;
        snprintf(pa, sizeof pa, "%s/%s", unsplit, same[i]);
        snprintf(pb, sizeof pb, "%s/%s", plan, same[i]);
        EXPECT(cli_files_equal(pa, pb, &size) == 1, "merged %s differs from the unsplit one", same[i]);
    }
    printf("study: 13 jobs shuffled under GNU parallel, merged: study.csv (all but the times), pareto.svg, "
           "hard_pixels.png and strip.png equal the unsplit study's\n%s",
           b);

    /* a job run again: already done; a missing or corrupt result: refused, named by its line (jobs
     * are run-major: line 1 the reference, then run 0 of the 4 configurations, run 1, ...) */
    static char out[CLI_ERR_MAX];
    snprintf(args, sizeof args, "job '%s' 7", plan);
    EXPECT(cli_run_capture(tmp, args, out, err) == 0 && strstr(out, "already done"), "job 7 again: %s%s", out, err);
    EXPECT(cli_sh("mv '%s/runs/study_c01_r00002.bin' '%s/moved.bin'", plan, plan) == 0, "cannot move a result");
    snprintf(args, sizeof args, "study --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "line 11 (config compat, run 2)"),
           "merge with a missing job: %s", err);
    EXPECT(cli_sh("mv '%s/moved.bin' '%s/runs/study_c01_r00002.bin'", plan, plan) == 0, "cannot move it back");
    EXPECT(cli_sh("printf 'X' | dd of='%s/runs/study_c02_r00001.bin' bs=1 seek=200 conv=notrunc 2>/dev/null%s", plan,
                  "") == 0,
           "cannot corrupt");
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "line 8 (config bitterli@12, run 1)") && strstr(err, "corrupt"),
           "merge with a corrupt job: %s", err);
    printf("refused: %s", err);
    snprintf(args, sizeof args, "job '%s' 8", plan); /* run again, it replaces the corrupt result */
    EXPECT(cli_run(tmp, args, err) == 0, "job 8 again: %s", err);
    snprintf(args, sizeof args, "study --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "merge after the rerun: %s", err);
    snprintf(pb, sizeof pb, "%s/study.csv", plan);
    cli_csv_without_columns(pb, 8, 1000, b, sizeof b); /* all but the pass times */
    EXPECT(strcmp(a, b) == 0, "study.csv after rerunning a corrupt job differs:\n%s\nvs\n%s", a, b);
    snprintf(args, sizeof args, "job '%s' 14", plan);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "13 jobs"), "job 14 of 13: %s", err);
}

static void test_reference(char *err)
{
    char unsplit[2 * CLI_PATH_MAX], merged[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
    char msg[MSG_LEN];
    snprintf(unsplit, sizeof unsplit, "%s/ref.exr", tmp);
    snprintf(merged, sizeof merged, "%s/merged.exr", tmp);
    snprintf(plan, sizeof plan, "%s/ref_plan", tmp);
    snprintf(args, sizeof args, REF " --out '%s'", unsplit);
    EXPECT(cli_run(tmp, args, err) == 0, "unsplit reference: %s", err);
    snprintf(args, sizeof args, REF " --shards 5 --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "reference --plan: %s", err);
    /* the documented alternative to GNU parallel: xargs, one line per shell */
    EXPECT(cli_sh("tac '%s/jobs.txt' | OMP_NUM_THREADS=1 xargs -d '\\n' -n 1 -P 2 sh -c > '%s/xargs.log' 2>&1", plan,
                  plan) == 0,
           "xargs: a shard failed");
    snprintf(args, sizeof args, "reference --merge '%s' --out '%s'", plan, merged);
    EXPECT(cli_run(tmp, args, err) == 0, "reference --merge: %s", err);
    float *a = NULL, *b = NULL;
    int w = 0, h = 0, w2 = 0, h2 = 0;
    EXPECT(exr_read_rgb(unsplit, &a, &w, &h, msg) == 0 && exr_read_rgb(merged, &b, &w2, &h2, msg) == 0 && w == w2 &&
               h == h2,
           "cannot read the references: %s", msg);
    if (a && b && w == w2 && h == h2) {
        const int chunks = (1000 + 15) / 16;
        const double bound = (2.0 * chunks + 1.0) * ldexp(1.0, -24);
        double worst = 0.0;
        long differ = 0;
        for (size_t i = 0; i < 3 * (size_t)w * h; i++) {
            double d = fabs((double)a[i] - (double)b[i]), rel = a[i] != 0.0f ? d / fabs((double)a[i]) : d;
            differ += d != 0.0;
            worst = rel > worst ? rel : worst;
            if (rel > bound)
                EXPECT(0, "merged reference value %zu: %.9g vs unsplit %.9g (relative %.3g > %.3g)", i, b[i], a[i], rel,
                       bound);
        }
        printf("reference: 5 shards merged; %ld of %zu values differ from the unsplit reference in their last bits, "
               "largest relative difference %.3g (bound %.3g)\n",
               differ, 3 * (size_t)w * h, worst, bound);
    }
    free(a);
    free(b);
    EXPECT(cli_sh("rm '%s/runs/shard_0003.exr'%s", plan, "") == 0, "cannot remove a shard");
    snprintf(args, sizeof args, "reference --merge '%s' --out '%s/never.exr'", plan, tmp);
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "line 4 (shard 3"), "merge with a shard missing: %s", err);
    char never[3 * CLI_PATH_MAX];
    snprintf(never, sizeof never, "%s/never.exr", tmp);
    struct stat st;
    EXPECT(stat(never, &st) != 0, "a refused merge wrote its output");
    snprintf(args, sizeof args, "study --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "not of a study"), "study --merge of a reference plan: %s", err);
}

#define COMPARE                                                                                                        \
    "compare --scene cornell --methods restir-di,pt,restir-di:mis=balance --res 48x27 --frames 3 "                     \
    "--ref-spp 32 --seed 9 --runs 2"

/* plan.json holds the command's JSON description, not its arguments: a job reads it back through the
 * option table; a plan written with an argument list (an older restir), a description with an
 * unknown key or a value of the wrong type are refused with exit 2, naming the problem, and the job
 * writes nothing. plan is a finished compare plan; its plan.json is restored at the end. */
static void test_plan_descriptions(const char *plan, char *err)
{
    char path[3 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX];
    static char original[1 << 16], text[1 << 16];
    snprintf(path, sizeof path, "%s/plan.json", plan);
    cli_read_text(path, original, sizeof original);
    EXPECT(strstr(original, "\"options\"") &&
               strstr(original, "\"methods\":\t\"restir-di,pt,restir-di:mis=balance\"") &&
               !strstr(original, "\"args\""),
           "plan.json holds no JSON description of the compare:\n%s", original);
    static const struct {
        const char *from, *to, *says;
    } broken[] = {
        {"\"options\"", "\"args\": [\"--scene\", \"cornell\"], \"old_options\"", "older restir"},
        {"\"methods\":", "\"no_such_key\": 1, \"methods\":", "unknown key \"no_such_key\""},
        {"\"frames\":\t3", "\"frames\":\t\"three\"", "\"frames\" must be a number"},
    };
    for (int k = 0; k < 3; k++) {
        char *at = strstr(original, broken[k].from);
        EXPECT(at != NULL, "plan.json has no %s to break", broken[k].from);
        if (!at)
            continue;
        snprintf(text, sizeof text, "%.*s%s%s", (int)(at - original), original, broken[k].to,
                 at + strlen(broken[k].from));
        EXPECT(cli_write_text(path, text) == 0, "cannot write %s", path);
        EXPECT(cli_sh("rm -f '%s/runs/reference.exr'%s", plan, "") == 0, "cannot remove a result");
        snprintf(args, sizeof args, "job '%s' 1", plan);
        EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, broken[k].says), "plan.json with %s: job says %s",
               broken[k].to, err);
        snprintf(args, sizeof args, "%s/runs/reference.exr", plan);
        EXPECT(access(args, F_OK) != 0, "a refused job wrote %s", args);
    }
    EXPECT(cli_write_text(path, original) == 0, "cannot restore %s", path);
}

static void test_compare(char *err)
{
    char unsplit[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
    snprintf(unsplit, sizeof unsplit, "%s/compare", tmp);
    snprintf(plan, sizeof plan, "%s/compare_plan", tmp);
    snprintf(args, sizeof args, COMPARE " --out '%s'", unsplit);
    EXPECT(cli_run(tmp, args, err) == 0, "unsplit compare: %s", err);
    snprintf(args, sizeof args, COMPARE " --equal-time --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "--equal-time"), "an equal-time plan accepted: %s", err);
    snprintf(args, sizeof args, COMPARE " --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "compare --plan: %s", err);
    EXPECT(cli_sh("tac '%s/jobs.txt' | OMP_NUM_THREADS=1 parallel -j 2 > '%s/parallel.log' 2>&1", plan, plan) == 0,
           "GNU parallel: a compare job failed");
    snprintf(args, sizeof args, "compare --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "compare --merge: %s", err);
    static char a[1 << 16], b[1 << 16];
    char pa[3 * CLI_PATH_MAX], pb[3 * CLI_PATH_MAX];
    snprintf(pa, sizeof pa, "%s/compare.csv", unsplit);
    snprintf(pb, sizeof pb, "%s/compare.csv", plan);
    cli_csv_without_columns(pa, 1, 1, a, sizeof a); /* all but ms_per_frame */
    cli_csv_without_columns(pb, 1, 1, b, sizeof b); /* all but ms_per_frame */
    /* and but the flicker (columns 38-45 before ms_per_frame went): like temporal_cov it needs every run's
     * frames, which a plan's jobs do not keep; the unsplit compare has it, the merge leaves it empty */
    cli_csv_drop_columns(a, 37, 44);
    cli_csv_drop_columns(b, 37, 44);
    EXPECT(strstr(a, ",ref_mape_disoccluded,lag_frames,") != NULL, "the flicker columns moved: %.400s", a);
    EXPECT(a[0] && strcmp(a, b) == 0, "merged compare.csv differs:\n%s\nvs\n%s", a, b);
    static const char *const same[] = {"reference.exr", "restir-di/frame_0002.exr", "pt/frame_0002.png",
                                       "restir-di_mis_balance/frame_0002.exr"};
    for (int i = 0; i < 4; i++) {
        long size = 0;
        snprintf(pa, sizeof pa, "%s/%s", unsplit, same[i]);
        snprintf(pb, sizeof pb, "%s/%s", plan, same[i]);
        EXPECT(cli_files_equal(pa, pb, &size) == 1, "merged %s differs from the unsplit one", same[i]);
    }
    printf("compare: 7 jobs (3 specs x 2 runs, the reference) under GNU parallel, merged: compare.csv (all but "
           "ms_per_frame: means and standard errors over the runs), the reference and the frames equal the unsplit "
           "compare's\n%s",
           b);
    /* A plan reference without its halves (copied without them, or from before halves existed): the merge
     * cannot subtract the reference's own error and refuses, naming the file, writing nothing. */
    snprintf(pb, sizeof pb, "%s/compare.csv", plan);
    EXPECT(cli_sh("mkdir '%s/moved'%s", plan, "") == 0 &&
               cli_sh("mv '%s'/runs/reference.half_?.exr '%s/moved/'", plan, plan) == 0 && remove(pb) == 0,
           "cannot move the reference halves");
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "reference.half_a.exr is missing"),
           "merge without the halves: %s", err);
    EXPECT(!cli_exists(pb), "a merge refused for missing halves wrote compare.csv");
    EXPECT(cli_sh("mv '%s'/moved/* '%s/runs/'", plan, plan) == 0, "cannot restore the halves");
    EXPECT(cli_sh("rm '%s/runs/pt/run_1.bin'%s", plan, "") == 0, "cannot remove a result");
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "line 6 (pt, run 1)"), "merge with a missing job: %s", err);
    test_plan_descriptions(plan, err);
}

/* A study plan's reference job saving after every chunk (RESTIR_REFERENCE_CHECKPOINT_SECONDS=0):
 * stopped by SIGTERM once its first half's first checkpoint exists, then killed with SIGKILL once a later one
 * exists, then run again, it writes the bytes of the same job uninterrupted (in another plan). */
#define SLOW_REF_STUDY                                                                                                 \
    "study --scene cornell --method restir-di --configs bitterli --res 96x54 --frames 4 "                              \
    "--warmup 1 --runs 2 --ref-spp 960 --seed 3 --threads 1"

/* restir.samples of a checkpoint, or -1. */
static int checkpoint_samples(const char *path)
{
    char text[64], msg[MSG_LEN];
    return exr_read_attribute(path, "restir.samples", text, sizeof text, msg) == 0 ? atoi(text) : -1;
}

/* Spawns `job DIR 1`, waits until its checkpoint holds more than `after` samples, sends sig; returns
 * the wait status, and the samples at the signal in *samples. */
static int stop_reference_job(const char *plan, const char *ckpt, int after, int sig, int *samples)
{
    char args[3 * CLI_PATH_MAX], log[3 * CLI_PATH_MAX];
    snprintf(args, sizeof args, "job '%s' 1", plan);
    snprintf(log, sizeof log, "%s/stopped_job.txt", tmp);
    pid_t pid = cli_spawn(args, log);
    for (int waited = 0; waited < 12000 && checkpoint_samples(ckpt) <= after; waited++)
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    *samples = checkpoint_samples(ckpt);
    return cli_signal_and_wait(pid, sig);
}

static void test_reference_job_resumes(char *err)
{
    char plan[2 * CLI_PATH_MAX], whole[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX];
    snprintf(plan, sizeof plan, "%s/resumed_plan", tmp);
    snprintf(whole, sizeof whole, "%s/whole_plan", tmp);
    snprintf(args, sizeof args, SLOW_REF_STUDY " --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "study --plan: %s", err);
    snprintf(args, sizeof args, SLOW_REF_STUDY " --plan '%s'", whole);
    EXPECT(cli_run(tmp, args, err) == 0, "study --plan: %s", err);
    char ckpt[3 * CLI_PATH_MAX], ref[3 * CLI_PATH_MAX];
    /* the reference renders as two halves of 480 samples (reference_halves.h): the first half's checkpoint */
    snprintf(ckpt, sizeof ckpt, "%s/runs/reference.half_a.checkpoint.exr", plan);
    snprintf(ref, sizeof ref, "%s/runs/reference.exr", plan);
    setenv("RESTIR_REFERENCE_CHECKPOINT_SECONDS", "0", 1);
    int at_term = 0, at_kill = 0;
    int status = stop_reference_job(plan, ckpt, 0, SIGTERM, &at_term);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM, "SIGTERM at %d samples: exit status %d", at_term,
           WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    const int saved = checkpoint_samples(ckpt);
    EXPECT(saved >= at_term && saved < 480, "after SIGTERM the checkpoint holds %d samples", saved);
    status = stop_reference_job(plan, ckpt, saved, SIGKILL, &at_kill);
    EXPECT(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL, "the job finished before the SIGKILL");
    unsetenv("RESTIR_REFERENCE_CHECKPOINT_SECONDS");
    struct stat st;
    EXPECT(stat(ckpt, &st) == 0 && stat(ref, &st) != 0, "a killed reference job left no checkpoint, or its image");
    static char out[CLI_ERR_MAX];
    snprintf(args, sizeof args, "job '%s' 1", plan);
    EXPECT(cli_run_capture(tmp, args, out, err) == 0 && strstr(out, "resuming"), "the job run again: %s%s", out, err);
    EXPECT(stat(ckpt, &st) != 0, "the checkpoint outlived the finished job");
    snprintf(args, sizeof args, "job '%s' 1", whole);
    EXPECT(cli_run(tmp, args, err) == 0, "the uninterrupted job: %s", err);
    char ref_whole[3 * CLI_PATH_MAX];
    snprintf(ref_whole, sizeof ref_whole, "%s/runs/reference.exr", whole);
    long size = 0;
    const int same = cli_files_equal(ref, ref_whole, &size) == 1;
    EXPECT(same, "the resumed reference differs from the uninterrupted one");
    if (same)
        printf("a study plan's reference job stopped by SIGTERM (%d samples saved), then killed (%d), then run "
               "again equals the uninterrupted job (%ld bytes)\n%s",
               saved, at_kill, size, out);
}

/* A job refuses a scene file whose content changed after planning. */
static void test_changed_scene(char *err)
{
    char dir[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
    snprintf(dir, sizeof dir, "%s/scene", tmp);
    snprintf(plan, sizeof plan, "%s/changed_plan", tmp);
    snprintf(args, sizeof args, "scene export cornell --out '%s'", dir);
    EXPECT(cli_run(tmp, args, err) == 0, "scene export: %s", err);
    snprintf(args, sizeof args,
             "reference --scene '%s/cornell.json' --method pt --res 16x9 --spp 32 --shards 2 "
             "--plan '%s'",
             dir, plan);
    EXPECT(cli_run(tmp, args, err) == 0, "plan on a scene file: %s", err);
    EXPECT(cli_sh("sed -i 's/0.65, 0.05, 0.05/0.6, 0.05, 0.05/' '%s/cornell.json'%s", dir, "") == 0, "cannot edit");
    snprintf(args, sizeof args, "job '%s' 1", plan);
    EXPECT(cli_run(tmp, args, err) == 1 && strstr(err, "changed since the plan was made"),
           "a job on a changed scene ran: %s", err);
}

int main(void)
{
    static char err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    EXPECT(have("parallel"), "GNU parallel is not installed (make test-deps installs it)");
    test_study(err);
    test_reference(err);
    test_compare(err);
    test_reference_job_resumes(err);
    test_changed_scene(err);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
