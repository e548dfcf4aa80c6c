/* test_reference_target.c: `restir reference --target-relmse X`. It stops at a chunk boundary once
 * its estimate is at most X, records the estimate (restir.relmse_estimate) and the samples it
 * holds, stops later for a smaller X, gives the same bytes at 1 and 2 threads, continues a
 * checkpoint killed mid-run (with or without the variance state) to the bytes of an uninterrupted
 * run, and works through a plan: shards stop early, the merge weights them by what they hold. */
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

#define MSG_LEN 512 /* RESTIR_MSG_LEN: the test sees the program from outside */
#define REF "reference --scene cornell --method pt --res 64x36 --seed 3"

static char tmp[CLI_PATH_MAX];

static void path_of(char *out, const char *name) { snprintf(out, 2 * CLI_PATH_MAX, "%s/%s", tmp, name); }

/* A text attribute of tmp/name as a number, or -1. */
static double attribute(const char *name, const char *attr)
{
    char path[2 * CLI_PATH_MAX], text[64], msg[MSG_LEN];
    path_of(path, name);
    return exr_read_attribute(path, attr, text, sizeof text, msg) == 0 ? atof(text) : -1.0;
}

static int reference(const char *extra, const char *name, char *out, char *err)
{
    char args[3 * CLI_PATH_MAX];
    snprintf(args, sizeof args, REF " %s --out '%s/%s'", extra, tmp, name);
    return cli_run_capture(tmp, args, out, err);
}

static void expect_same(const char *a_name, const char *b_name, const char *what)
{
    char a[2 * CLI_PATH_MAX], b[2 * CLI_PATH_MAX];
    path_of(a, a_name);
    path_of(b, b_name);
    long size = 0;
    const int same = cli_files_equal(a, b, &size);
    EXPECT(same == 1, "%s: %s and %s differ (%d)", what, a_name, b_name, same);
}

static void test_stop_rule(char *out, char *err)
{
    EXPECT(reference("--target-relmse 0.01 --threads 2", "t01.exr", out, err) == 0, "target 0.01: %s", err);
    EXPECT(reference("--target-relmse 0.01 --threads 1", "t01_1.exr", out, err) == 0, "target 0.01, 1 thread: %s",
           err);
    expect_same("t01.exr", "t01_1.exr", "target 0.01 at 1 and 2 threads");
    EXPECT(reference("--target-relmse 0.003 --threads 2", "t003.exr", out, err) == 0, "target 0.003: %s", err);
    const double n01 = attribute("t01.exr", "restir.samples"), n003 = attribute("t003.exr", "restir.samples");
    const double e01 = attribute("t01.exr", "restir.relmse_estimate");
    const double e003 = attribute("t003.exr", "restir.relmse_estimate");
    printf("target 0.01: %.0f samples, estimate %.4g; target 0.003: %.0f samples, estimate %.4g\n", n01, e01, n003,
           e003);
    EXPECT(n01 >= 128 && (int)n01 % 16 == 0, "target 0.01 stopped at %.0f samples", n01);
    EXPECT(n003 > n01 && (int)n003 % 16 == 0, "target 0.003 stopped at %.0f samples (0.01: %.0f)", n003, n01);
    EXPECT(e01 > 0.0 && e01 <= 0.01 && e003 > 0.0 && e003 <= 0.003, "estimates %.4g, %.4g above their targets", e01,
           e003);
    EXPECT(attribute("t01.exr", "restir.spp") == n01, "restir.spp is not the samples held");
    /* --spp caps it: a target it cannot reach stops at --spp and says so */
    EXPECT(reference("--target-relmse 1e-7 --spp 96", "cap.exr", out, err) == 0 && strstr(out, "not reached"),
           "an unreachable target: %s%s", out, err);
    EXPECT(attribute("cap.exr", "restir.samples") == 96, "the capped run holds %.0f samples",
           attribute("cap.exr", "restir.samples"));
}

/* SIGKILL once the checkpoint holds `at` samples of a run of `extra`; then the same command. */
static void kill_at(const char *extra, const char *name, int at)
{
    char args[3 * CLI_PATH_MAX], errp[2 * CLI_PATH_MAX], ckpt[2 * CLI_PATH_MAX], part[64];
    snprintf(args, sizeof args, REF " %s --checkpoint-every 0 --out '%s/%s.exr'", extra, tmp, name);
    path_of(errp, "spawned_stderr.txt");
    snprintf(part, sizeof part, "%s.checkpoint.exr", name);
    path_of(ckpt, part);
    pid_t pid = cli_spawn(args, errp);
    EXPECT(cli_wait_for_file(ckpt, 120000), "no checkpoint appeared");
    for (int waited = 0; waited < 12000 && attribute(part, "restir.samples") < at; waited++)
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    const int status = cli_signal_and_wait(pid, SIGKILL);
    EXPECT(WIFSIGNALED(status), "the reference finished before the kill");
}

static void test_resume(char *out, char *err)
{
    char part[2 * CLI_PATH_MAX];
    /* killed with a target: the checkpoint keeps the variance, the resumed run the bytes */
    kill_at("--target-relmse 0.003 --threads 1", "part", 96);
    path_of(part, "part.checkpoint.exr");
    float *m2 = NULL;
    int w = 0, h = 0;
    char msg[MSG_LEN];
    EXPECT(exr_read_layer(part, "m2", &m2, &w, &h, msg) == 0 && attribute("part.checkpoint.exr", "restir.var_obs") >= 2,
           "the checkpoint holds no variance state: %s", msg);
    free(m2);
    EXPECT(reference("--target-relmse 0.003 --threads 2 --checkpoint-every 0", "part.exr", out, err) == 0,
           "resume with a target: %s", err);
    expect_same("t003.exr", "part.exr", "kill + resume with --target-relmse");
    EXPECT(!cli_exists(part), "checkpoint kept after the reference finished");
    /* killed without a target, resumed with one: the variance is tracked from the resume on */
    kill_at("--spp 4096 --threads 1", "plain", 48);
    EXPECT(reference("--spp 4096 --target-relmse 0.003 --threads 2 --checkpoint-every 0", "plain.exr", out, err) == 0,
           "resume of a plain checkpoint with a target: %s", err);
    const double n = attribute("plain.exr", "restir.samples"), e = attribute("plain.exr", "restir.relmse_estimate");
    EXPECT(n >= 48 + 7 * 16 && n < 4096 && e > 0.0 && e <= 0.003, "plain checkpoint + target: %.0f samples, %.4g", n,
           e);
}

static void test_plan(char *out, char *err)
{
    char plan[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
    path_of(plan, "plan");
    snprintf(args, sizeof args, REF " --spp 4096 --target-relmse 0.003 --shards 2 --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "reference --plan with a target: %s", err);
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "job '%s' %d", plan, k + 1); /* jobs count from 1 */
        EXPECT(cli_run_capture(tmp, args, out, err) == 0, "job %d: %s", k, err);
    }
    double held = 0.0;
    for (int k = 0; k < 2; k++) {
        char shard[64];
        snprintf(shard, sizeof shard, "plan/runs/shard_%04d.exr", k);
        const double n = attribute(shard, "restir.samples");
        EXPECT(n >= 128 && n < 2048, "shard %d stopped at %.0f samples", k, n);
        held += n;
    }
    snprintf(args, sizeof args, "reference --merge '%s' --out '%s/merged.exr'", plan, tmp);
    EXPECT(cli_run_capture(tmp, args, out, err) == 0, "merge: %s", err);
    EXPECT(attribute("merged.exr", "restir.samples") == held, "merged: %.0f samples, shards hold %.0f",
           attribute("merged.exr", "restir.samples"), held);
    printf("plan of 2 shards, target 0.003 (each shard 0.006): %.0f samples merged\n", held);
}

int main(void)
{
    static char out[CLI_ERR_MAX], err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    test_stop_rule(out, err);
    test_resume(out, err);
    test_plan(out, err);
    EXPECT(cli_count_entries(tmp, ".tmp-") == 0, "temporary files left");
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
