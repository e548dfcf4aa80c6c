/* test_evaluate_provenance.c: an evaluation's provenance and its checks, on 004 at 64x64. The merge
 * records each step's provenance.json and settings.json and names the build in evaluation.md;
 * scripts/evaluation_export.sh copies only the small files; `restir evaluate --tables` on the copy
 * writes the merge's evaluation.md and claims.csv byte for byte; `restir evaluate --check` passes on
 * the copy with 1 and 2 threads, and exits 1 naming the table when a recorded setting or hash is
 * changed, 2 when a step has no settings.json; --tables exits 2 naming the step, writing nothing,
 * for a step of another commit, another resolution or without its CSV (--partial then names it as
 * not finished); `restir job` and the merge refuse a plan made by another commit, or written before
 * plans recorded their build, with exit 2; `restir --version` names the commit. */
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "test_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 40

static char tmp[CLI_PATH_MAX];
static char err[CLI_ERR_MAX], out[CLI_ERR_MAX];

#define DIR_LEN (CLI_PATH_MAX + 64)      /* a folder under tmp */
#define FILE_LEN (CLI_PATH_MAX + 256)    /* a file under such a folder */
#define ARGS_LEN (3 * CLI_PATH_MAX + 512) /* arguments naming a few of them */

#define STEP_PT "004-cornell-restir-pt"
#define STEP_DI "004-cornell-restir-di"

/* Replaces the first occurrence of `from` in the file at path by `to` (every one with all). Returns
 * how many it replaced. */
static int replace_in_file(const char *path, const char *from, const char *to, int all)
{
    static char text[1 << 18], result[1 << 18];
    cli_read_text(path, text, sizeof text);
    size_t o = 0;
    int n = 0;
    const char *p = text;
    for (const char *at; (at = strstr(p, from)) && (all || n == 0); p = at + strlen(from), n++)
        o += (size_t)snprintf(result + o, sizeof result - o, "%.*s%s", (int)(at - p), p, to);
    snprintf(result + o, sizeof result - o, "%s", p);
    if (n > 0 && cli_write_text(path, result) != 0)
        return 0;
    return n;
}

/* `"commit":\t"X"` of the file at path (the first) into pattern, X into commit. */
static void commit_of(const char *path, char *pattern, size_t n, char *commit, size_t m)
{
    static char text[1 << 18];
    cli_read_text(path, text, sizeof text);
    const char *at = strstr(text, "\"commit\":\t\"");
    commit[0] = pattern[0] = '\0';
    if (!at)
        return;
    at += strlen("\"commit\":\t\"");
    const char *end = strchr(at, '"');
    snprintf(commit, m, "%.*s", end ? (int)(end - at) : 0, at);
    snprintf(pattern, n, "\"commit\":\t\"%s\"", commit);
}

static int run_with_threads(const char *threads, const char *args)
{
    setenv("OMP_NUM_THREADS", threads, 1);
    const int rc = cli_run_capture(tmp, args, out, err);
    setenv("OMP_NUM_THREADS", "1", 1);
    return rc;
}

/* The export's --check: passes, then a tampered setting, a tampered hash and a missing settings.json. */
static void test_check(const char *data)
{
    char args[ARGS_LEN], path[FILE_LEN], copy[DIR_LEN];
    snprintf(args, sizeof args, "evaluate --check '%s'", data);
    for (int t = 1; t <= 2; t++) {
        EXPECT(run_with_threads(t == 1 ? "1" : "2", args) == 0 && strstr(out, "ok: table e004/" STEP_PT),
               "--check on the export, %d threads: %s%s", t, out, err);
    }
    printf("--check on the export (1 and 2 threads):\n%s", out);
    snprintf(copy, sizeof copy, "%s/tampered", tmp);
    EXPECT(cli_sh("cp -r '%s' '%s'", data, copy) == 0, "cannot copy the export");
    snprintf(path, sizeof path, "%s/e004/" STEP_PT "/settings.json", copy);
    EXPECT(replace_in_file(path, "\"pt.max_bounces\":\t8,", "\"pt.max_bounces\":\t7,", 0) == 1,
           "settings.json has no pt.max_bounces of 8");
    snprintf(args, sizeof args, "evaluate --check '%s'", copy);
    EXPECT(cli_run_capture(tmp, args, out, err) == 1 && strstr(out, "STALE: table e004/" STEP_PT ", row restir-pt ") &&
               strstr(out, "ok: table e004/" STEP_DI),
           "--check with a changed setting: %s%s", out, err);
    printf("a recorded setting changed (pt.max_bounces 8 -> 7):\n%s", out);
    EXPECT(replace_in_file(path, "\"pt.max_bounces\":\t7,", "\"pt.max_bounces\":\t8,", 0) == 1, "cannot restore");
    EXPECT(cli_run_capture(tmp, args, out, err) == 0, "--check after restoring the setting: %s%s", out, err);
    static char text[1 << 18];
    cli_read_text(path, text, sizeof text);
    char *hash = strstr(text, "\"hash\":\t\"");
    EXPECT(hash != NULL, "settings.json has no hash");
    if (hash) { /* the first row's hash, one hex digit changed */
        hash += strlen("\"hash\":\t\"");
        *hash = *hash == '0' ? '1' : '0';
        EXPECT(cli_write_text(path, text) == 0, "cannot write %s", path);
    }
    EXPECT(cli_run_capture(tmp, args, out, err) == 1 && strstr(out, "STALE: table e004/" STEP_PT ", row restir-pt "),
           "--check with a changed hash: %s%s", out, err);
    EXPECT(remove(path) == 0, "cannot remove %s", path);
    EXPECT(cli_run_capture(tmp, args, out, err) == 2 && strstr(err, STEP_PT) && strstr(err, "no settings.json"),
           "--check of a step without settings.json: %s%s", out, err);
    snprintf(path, sizeof path, "%s/empty", tmp);
    EXPECT(cli_sh("mkdir -p '%s'%s", path, "") == 0, "cannot make a folder");
    snprintf(args, sizeof args, "evaluate --check '%s'", path);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "no step under"), "--check of a folder without steps: %s",
           err);
}

/* --tables refuses, writing nothing: run it on a copy of the export broken by `broken` (a shell
 * command on the copy's folder, %s), expecting exit 2 and `says` in its message. */
static void expect_tables_refused(const char *data, const char *broken, const char *says, const char *what)
{
    char copy[DIR_LEN], cmd[ARGS_LEN], args[ARGS_LEN], md[FILE_LEN], claims[FILE_LEN], text[256];
    snprintf(copy, sizeof copy, "%s/refused", tmp);
    EXPECT(cli_sh("cp -r '%s/e004' '%s'", data, copy) == 0, "cannot copy the export");
    snprintf(cmd, sizeof cmd, broken, copy);
    EXPECT(system(cmd) == 0, "%s: cannot break the copy (%s)", what, cmd);
    snprintf(md, sizeof md, "%s/evaluation.md", copy);
    snprintf(claims, sizeof claims, "%s/claims.csv", copy);
    EXPECT(cli_write_text(md, "untouched\n") == 0 && cli_write_text(claims, "untouched\n") == 0, "cannot write");
    snprintf(args, sizeof args, "evaluate --tables '%s'", copy);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, says), "--tables, %s: %s", what, err);
    printf("--tables, %s: %s", what, err);
    cli_read_text(md, text, sizeof text);
    EXPECT(!strcmp(text, "untouched\n"), "--tables, %s: evaluation.md was written", what);
    cli_read_text(claims, text, sizeof text);
    EXPECT(!strcmp(text, "untouched\n"), "--tables, %s: claims.csv was written", what);
    EXPECT(cli_sh("rm -rf '%s'%s", copy, "") == 0, "cannot remove the copy");
}

static void test_tables(const char *eval, const char *data)
{
    char args[ARGS_LEN], a[FILE_LEN], b[FILE_LEN], cmd[ARGS_LEN];
    snprintf(args, sizeof args, "evaluate --tables '%s/e004'", data);
    EXPECT(cli_run(tmp, args, err) == 0, "--tables on the export: %s", err);
    static const char *const same[] = {"evaluation.md", "claims.csv"};
    for (int k = 0; k < 2; k++) {
        long size = 0;
        snprintf(a, sizeof a, "%s/%s", eval, same[k]);
        snprintf(b, sizeof b, "%s/e004/%s", data, same[k]);
        EXPECT(cli_files_equal(a, b, &size) == 1, "--tables wrote another %s than the merge", same[k]);
    }
    char pattern[128], commit[64], other[128];
    snprintf(a, sizeof a, "%s/e004/" STEP_DI "/provenance.json", data);
    commit_of(a, pattern, sizeof pattern, commit, sizeof commit);
    EXPECT(commit[0], "provenance.json names no commit");
    snprintf(other, sizeof other, "\"commit\":\t\"0123456789ab\"");
    snprintf(cmd, sizeof cmd, "sed -i 's/%s/%s/g' '%%s/" STEP_DI "/provenance.json'", pattern, other);
    expect_tables_refused(data, cmd, STEP_DI " was made by commit 0123456789ab", "a step of another commit");
    expect_tables_refused(data, "rm '%s/" STEP_DI "/compare.csv'", STEP_DI " has no compare.csv", "a missing CSV");
    expect_tables_refused(data, "sed -i 's/\"width\":\t64,/\"width\":\t32,/' '%s/" STEP_DI "/provenance.json'",
                          STEP_DI " is of another resolution", "a step of another resolution");
    expect_tables_refused(data, "rm '%s/" STEP_DI "/provenance.json'", STEP_DI " has no provenance",
                          "a step without provenance.json");
    /* --partial names the step without its table */
    char partial[DIR_LEN];
    snprintf(partial, sizeof partial, "%s/partial", tmp);
    EXPECT(cli_sh("cp -r '%s/e004' '%s'", data, partial) == 0, "cannot copy the export");
    EXPECT(cli_sh("rm '%s/" STEP_DI "/compare.csv'%s", partial, "") == 0, "cannot remove a CSV");
    snprintf(args, sizeof args, "evaluate --tables '%s' --partial", partial);
    EXPECT(cli_run(tmp, args, err) == 0, "--tables --partial: %s", err);
    static char md[1 << 16];
    snprintf(b, sizeof b, "%s/evaluation.md", partial);
    cli_read_text(b, md, sizeof md);
    EXPECT(strstr(md, "### " STEP_DI ": not finished") && strstr(md, "Provenance: commit"),
           "--tables --partial: evaluation.md does not name the step left out");
}

/* The one-commit rule: plans record their build, and jobs and merges of another build's plan are refused. */
static void test_one_commit(const char *eval)
{
    char path[FILE_LEN], args[ARGS_LEN], pattern[128], commit[64];
    static char original[1 << 18], text[1 << 18];
    snprintf(path, sizeof path, "%s/plan.json", eval);
    cli_read_text(path, original, sizeof original);
    commit_of(path, pattern, sizeof pattern, commit, sizeof commit);
    EXPECT(commit[0] && strstr(original, "\"provenance\":"), "plan.json records no build:\n%.400s", original);
    EXPECT(cli_run_capture(tmp, "--version", out, err) == 0 && strstr(out, commit), "restir --version: %s%s", out,
           err);
    EXPECT(replace_in_file(path, pattern, "\"commit\":\t\"deadbeef0000\"", 0) == 1, "cannot edit plan.json");
    snprintf(args, sizeof args, "job '%s' 1", eval);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "one commit") && strstr(err, "made by deadbeef0000") &&
               strstr(err, commit),
           "job of a plan of another commit: %s", err);
    printf("job of a plan of another commit: %s", err);
    snprintf(args, sizeof args, "evaluate --merge '%s'", eval);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "one commit"), "merge of a plan of another commit: %s", err);
    /* a plan written before plans recorded their build */
    snprintf(text, sizeof text, "%s", original);
    char *at = strstr(text, "\"provenance\":");
    EXPECT(at != NULL, "no provenance to remove");
    if (at)
        memcpy(at, "\"provenancX\":", 13);
    EXPECT(cli_write_text(path, text) == 0, "cannot write plan.json");
    snprintf(args, sizeof args, "job '%s' 1", eval);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "without build provenance"), "job of an old plan: %s", err);
    EXPECT(cli_write_text(path, original) == 0, "cannot restore plan.json");
    /* a step's own plan of another commit: its job is refused too */
    snprintf(path, sizeof path, "%s/" STEP_PT "/plan.json", eval);
    cli_read_text(path, original, sizeof original);
    EXPECT(replace_in_file(path, pattern, "\"commit\":\t\"deadbeef0000\"", 0) == 1, "cannot edit the step's plan");
    snprintf(args, sizeof args, "job '%s/" STEP_PT "' 1", eval);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, "made by deadbeef0000"), "job of a step of another commit: %s",
           err);
    snprintf(args, sizeof args, "evaluate --merge '%s' --partial", eval);
    EXPECT(cli_run(tmp, args, err) == 2 && strstr(err, STEP_PT "/plan.json: a campaign runs on one commit"),
           "--partial merge with a step of another commit: %s", err);
    EXPECT(cli_write_text(path, original) == 0, "cannot restore the step's plan");
}

int main(void)
{
    const char *data_dir = getenv("RESTIR_TEST_DATA");
    if (!cli_bin() || !data_dir || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN, RESTIR_TEST_DATA or temporary folder)");
        return test_finish();
    }
    setenv("OMP_NUM_THREADS", "1", 1);
    char eval[DIR_LEN], data[DIR_LEN], args[ARGS_LEN], path[FILE_LEN];
    snprintf(eval, sizeof eval, "%s/eval", tmp);
    snprintf(data, sizeof data, "%s/data", tmp);
    snprintf(args, sizeof args, "evaluate 004 --res 64x64 --runs 2 --frames 4 --ref-spp 8 --scenes cornell --out '%s'",
             eval);
    EXPECT(cli_run(tmp, args, err) == 0, "evaluate 004: %s", err);
    static const char *const steps[] = {STEP_PT, STEP_DI, "004-cornell-ablation"};
    static const char *const recorded[] = {"provenance.json", "settings.json"};
    for (int k = 0; k < 3; k++)
        for (int f = 0; f < 2; f++) {
            snprintf(path, sizeof path, "%s/%s/%s", eval, steps[k], recorded[f]);
            EXPECT(cli_exists(path), "the merge wrote no %s", path);
        }
    static char md[1 << 16];
    snprintf(path, sizeof path, "%s/evaluation.md", eval);
    cli_read_text(path, md, sizeof md);
    EXPECT(strstr(md, "Provenance: commit ") && strstr(md, "64x64, 2 runs per configuration") &&
               strstr(md, "references of 8 paths per pixel") && strstr(md, "jobs: 35 on "),
           "evaluation.md names no provenance:\n%.2000s", md);

    char script[FILE_LEN];
    snprintf(script, sizeof script, "%s/../../scripts/evaluation_export.sh", data_dir);
    snprintf(path, sizeof path, "%s/e004", data);
    EXPECT(cli_sh("sh '%s' '%s' ", script, eval) == 2, "the export without a destination did not exit 2");
    char cmd[ARGS_LEN + FILE_LEN];
    snprintf(cmd, sizeof cmd, "sh '%s' '%s' '%s' > '%s/export.log' 2>&1", script, eval, path, tmp);
    EXPECT(system(cmd) == 0, "evaluation_export.sh failed");
    EXPECT(cli_sh("test -z \"$(find '%s' -name '*.exr' -o -name runs -o -name jobs.txt -o -name '*.bin'%s)\"", data, "") ==
               0,
           "the export holds images, jobs or runs");
    snprintf(path, sizeof path, "%s/e004/" STEP_PT "/compare.csv", data);
    EXPECT(cli_exists(path), "the export has no %s", path);
    test_tables(eval, data);
    test_check(data);
    test_one_commit(eval);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
