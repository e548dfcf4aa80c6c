/* test_out_folder.c: one run, one folder. A second run into the same --out is refused (exit 2, the
 * folder named, --force suggested) with the first run's files untouched; --force empties the folder
 * first, so it then holds only the new run's files, never follows a link out of it and refuses the
 * current folder; a run without --out gets a new folder each time; a reference's output file is
 * never replaced without --force while an interrupted one still continues (the same command, or
 * --resume); a plan folder takes only its own plan again. metrics.csv leaves its error columns
 * empty without --ref, and compare --ref without --res renders at the reference's size. */
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 8

#define MSG_LEN 512 /* RESTIR_MSG_LEN: the test sees the program from outside */
#define RENDER "render --scene cornell --method pt --seed 3"

static char tmp[CLI_PATH_MAX];

static void path_of(char *out, const char *name)
{
    snprintf(out, 2 * CLI_PATH_MAX, "%s/%s", tmp, name);
}

/* Runs `restir fmt` with the one %s of fmt set to arg; stdout into out, stderr into err. */
static int run(const char *fmt, const char *arg, char *out, char *err)
{
    char args[6 * CLI_PATH_MAX];
    snprintf(args, sizeof args, fmt, arg);
    return cli_run_capture(tmp, args, out, err);
}

/* A second render into a folder that holds the first: refused, nothing touched; --force: only the
 * new run's files. */
/* Whether the EXR at path is w x h. */
static void expect_exr_size(const char *what, const char *path, int w, int h)
{
    float *img = NULL;
    int iw = 0, ih = 0;
    char msg[MSG_LEN] = "";
    EXPECT(exr_read_rgb(path, &img, &iw, &ih, msg) == 0 && iw == w && ih == h, "%s: %s is %dx%d, not %dx%d %s", what,
           path, iw, ih, w, h, msg);
    free(img);
}

static void test_second_run(char *out, char *err)
{
    char dir[2 * CLI_PATH_MAX], frame[3 * CLI_PATH_MAX], copy[3 * CLI_PATH_MAX];
    path_of(dir, "render");
    EXPECT(run(RENDER " --res 32x18 --frames 2 --out '%s'", dir, out, err) == 0, "first render: %s", err);
    snprintf(frame, sizeof frame, "%s/frame_0001.exr", dir);
    path_of(copy, "frame_0001.copy");
    EXPECT(cli_sh("cp '%s' '%s'", frame, copy) == 0, "cannot copy %s", frame);
    const int before = cli_count_entries(dir, "");

    int rc = run(RENDER " --res 16x9 --frames 1 --out '%s'", dir, out, err);
    printf("[second render] exit %d: %s", rc, err);
    EXPECT(rc == 2, "a second render into a full folder: exit %d, want 2", rc);
    EXPECT(strncmp(err, "restir: ", 8) == 0 && strstr(err, dir) && strstr(err, "not empty") && strstr(err, "--force"),
           "the refusal does not name the folder and --force: %s", err);
    long size = 0;
    EXPECT(cli_count_entries(dir, "") == before && cli_files_equal(frame, copy, &size) == 1,
           "a refused render changed %s", dir);
    EXPECT(cli_count_entries(dir, ".tmp-") == 0, "a refused render left temporary files");

    rc = run(RENDER " --res 16x9 --frames 1 --out '%s' --force", dir, out, err);
    EXPECT(rc == 0, "render --force: exit %d: %s", rc, err);
    EXPECT(cli_count_entries(dir, "") == 4 && cli_count_entries(dir, "frame_0000.") == 2 &&
               cli_count_entries(dir, "frame_0001") == 0,
           "after --force %s holds %d entries, not the new run's 4 (frame_0000.exr, .png, metrics.csv, "
           "summary.json)",
           dir, cli_count_entries(dir, ""));
    snprintf(frame, sizeof frame, "%s/frame_0000.exr", dir);
    expect_exr_size("frame after --force", frame, 16, 9);

    /* links inside are removed, never followed; the current folder is never emptied */
    char outside[2 * CLI_PATH_MAX], keep[3 * CLI_PATH_MAX];
    path_of(outside, "outside");
    snprintf(keep, sizeof keep, "%s/keep.txt", outside);
    EXPECT(cli_sh("mkdir -p '%s' && echo keep > '%s'", outside, keep) == 0, "cannot make %s", keep);
    EXPECT(cli_sh("ln -s '%s' '%s/link'", outside, dir) == 0, "cannot make a link in %s", dir);
    EXPECT(run(RENDER " --res 16x9 --frames 1 --out '%s' --force", dir, out, err) == 0, "--force with a link: %s",
           err);
    EXPECT(cli_exists(keep) && cli_count_entries(dir, "link") == 0, "--force followed a link or kept it");
    char cmd[4 * CLI_PATH_MAX];
    snprintf(cmd, sizeof cmd, "cd '%%s' && '%%s' " RENDER " --res 16x9 --out . --force >/dev/null 2>&1");
    EXPECT(cli_sh(cmd, dir, cli_bin()) == 2 && cli_count_entries(dir, "") == 4, "--out . --force was not refused");
    snprintf(cmd, sizeof cmd, "cd '%%s' && '%%s' " RENDER " --res 16x9 --out notes --force >/dev/null 2>&1");
    EXPECT(cli_sh("mkdir -p '%s/notes' && touch '%s/notes/mine.txt'", tmp, tmp) == 0, "cannot make notes");
    char notes[2 * CLI_PATH_MAX];
    path_of(notes, "notes");
    EXPECT(cli_sh(cmd, tmp, cli_bin()) == 2 && cli_count_entries(notes, "mine.txt") == 1,
           "--force emptied a folder restir did not write");
}

/* Without --out: a new folder per run, and stdout says which. */
static void test_default_folders(void)
{
    char work[2 * CLI_PATH_MAX], cmd[4 * CLI_PATH_MAX], text[CLI_ERR_MAX], path[3 * CLI_PATH_MAX];
    path_of(work, "cwd");
    EXPECT(cli_sh("mkdir -p '%s'%s", work, "") == 0, "cannot make %s", work);
    snprintf(cmd, sizeof cmd, "cd '%%s' && '%%s' " RENDER " --res 16x9 >> log.txt 2>&1");
    for (int k = 0; k < 2; k++)
        EXPECT(cli_sh(cmd, work, cli_bin()) == 0, "render without --out, run %d", k + 1);
    snprintf(cmd, sizeof cmd, "cd '%%s' && '%%s' compare --scene cornell --methods pt --res 16x9 --ref-spp 1 "
                              ">> log.txt 2>&1");
    for (int k = 0; k < 2; k++)
        EXPECT(cli_sh(cmd, work, cli_bin()) == 0, "compare without --out, run %d", k + 1);
    snprintf(path, sizeof path, "%s/log.txt", work);
    cli_read_text(path, text, sizeof text);
    printf("%s", text);
    static const char *const dirs[] = {"cornell-pt", "cornell-pt-2", "compare-cornell", "compare-cornell-2"};
    for (int k = 0; k < 4; k++) {
        char line[128];
        snprintf(line, sizeof line, "writing into out/%s ", dirs[k]);
        snprintf(path, sizeof path, "%s/out/%s", work, dirs[k]);
        EXPECT(strstr(text, line) && cli_count_entries(path, k < 2 ? "frame_0000.exr" : "compare.csv") == 1,
               "out/%s: not made or not said", dirs[k]);
    }
    snprintf(path, sizeof path, "%s/out", work);
    EXPECT(cli_count_entries(path, "") == 4, "%s holds %d folders, not 4", path, cli_count_entries(path, ""));
}

/* The field of metrics.csv's column name in frame row 0 of dir, as text (NULL: no such column). */
static const char *metrics_field(const char *dir, const char *name, char *field, size_t n)
{
    static char text[1 << 15];
    char path[3 * CLI_PATH_MAX];
    snprintf(path, sizeof path, "%s/metrics.csv", dir);
    cli_read_text(path, text, sizeof text);
    const int col = cli_csv_column(text, name);
    const char *row = cli_next_line(text);
    if (col < 0 || !row)
        return NULL;
    for (int k = 0; k < col && row; k++) {
        row = strchr(row, ',');
        row = row ? row + 1 : NULL;
    }
    if (!row)
        return NULL;
    size_t len = strcspn(row, ",\n");
    len = len < n - 1 ? len : n - 1;
    memcpy(field, row, len);
    field[len] = '\0';
    return field;
}

/* metrics.csv: empty error fields without --ref, numbers with one. compare --ref of a 64x36
 * reference without --res renders at 64x36; a --res that differs is refused naming both. */
static void test_reference_size_and_metrics(char *out, char *err)
{
    char ref[2 * CLI_PATH_MAX], dir[2 * CLI_PATH_MAX], field[64], args[6 * CLI_PATH_MAX], frame[3 * CLI_PATH_MAX];
    path_of(ref, "ref64.exr");
    EXPECT(run("reference --scene cornell --method pt --res 64x36 --spp 16 --out '%s'", ref, out, err) == 0,
           "reference: %s", err);
    path_of(dir, "noref");
    EXPECT(run(RENDER " --res 32x18 --frames 2 --out '%s'", dir, out, err) == 0, "render: %s", err);
    static const char *const cols[] = {"relmse", "mape", "smape", "luma_rmse", "mape_disoccluded", "relmse_denoised"};
    for (int k = 0; k < 6; k++) {
        const char *v = metrics_field(dir, cols[k], field, sizeof field);
        EXPECT(v && !v[0], "metrics.csv without --ref: %s is '%s', not empty", cols[k], v ? v : "(no column)");
    }
    const char *ms = metrics_field(dir, "ms_total", field, sizeof field);
    EXPECT(ms && atof(ms) > 0.0, "metrics.csv without --ref: ms_total '%s'", ms ? ms : "(no column)");
    path_of(dir, "withref");
    snprintf(args, sizeof args, RENDER " --frames 2 --ref '%s' --out '%s'", ref, dir);
    EXPECT(cli_run_capture(tmp, args, out, err) == 0, "render --ref without --res: %s", err);
    const char *rel = metrics_field(dir, "relmse", field, sizeof field);
    EXPECT(rel && rel[0] && atof(rel) > 0.0, "metrics.csv with --ref: relmse '%s'", rel ? rel : "(no column)");

    path_of(dir, "compare");
    snprintf(args, sizeof args, "compare --scene cornell --methods pt,restir-di --ref '%s' --out '%s'", ref, dir);
    EXPECT(cli_run_capture(tmp, args, out, err) == 0, "compare --ref without --res: %s", err);
    EXPECT(strstr(out, "64x36") != NULL, "compare does not say 64x36:\n%s", out);
    snprintf(frame, sizeof frame, "%s/restir-di/frame_0000.exr", dir);
    expect_exr_size("compare's frame", frame, 64, 36);
    path_of(dir, "compare-32");
    snprintf(args, sizeof args, "compare --scene cornell --methods pt --res 32x18 --ref '%s' --out '%s'", ref, dir);
    const int rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc != 0 && strstr(err, "32x18") && strstr(err, "64x36"), "--res 32x18 with a 64x36 --ref: exit %d: %s", rc,
           err);
    EXPECT(!cli_exists(dir), "a refused compare made %s", dir);
}

/* reference --out FILE.exr: an existing image is kept unless --force; an interrupted reference
 * continues, by the same command or with --resume (which refuses when there is nothing to continue). */
static void test_reference_file(char *out, char *err)
{
    char file[2 * CLI_PATH_MAX], ckpt[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX], errpath[2 * CLI_PATH_MAX];
    path_of(file, "ref.exr");
    path_of(ckpt, "ref.checkpoint.exr");
    path_of(errpath, "spawned.txt");
#define REF "reference --scene cornell --method pt --res 64x36 --threads 1 --spp 1024 --checkpoint-every 0"
    snprintf(args, sizeof args, REF " --out '%s'", file);
    const pid_t pid = cli_spawn(args, errpath);
    EXPECT(cli_wait_for_file(ckpt, 60000), "no checkpoint appeared");
    const int status = cli_signal_and_wait(pid, SIGINT);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT, "SIGINT: status %d", status);
    EXPECT(cli_exists(ckpt) && !cli_exists(file), "the interrupted reference left no checkpoint, or its image");
    EXPECT(run(REF " --resume --out '%s'", file, out, err) == 0 && strstr(out, "resuming"), "--resume: %s%s", out,
           err);
    EXPECT(cli_exists(file) && !cli_exists(ckpt), "the resumed reference wrote no image or kept its checkpoint");
    long size = 0;
    char copy[2 * CLI_PATH_MAX];
    path_of(copy, "ref.copy");
    EXPECT(cli_sh("cp '%s' '%s'", file, copy) == 0, "cannot copy %s", file);
    int rc = run(REF " --out '%s'", file, out, err);
    EXPECT(rc == 2 && strstr(err, file) && strstr(err, "--force") && cli_files_equal(file, copy, &size) == 1,
           "a reference over a finished one: exit %d: %s", rc, err);
    rc = run(REF " --resume --out '%s/none.exr'", tmp, out, err);
    EXPECT(rc == 2 && strstr(err, "--resume"), "--resume with nothing to continue: exit %d: %s", rc, err);
    EXPECT(run("reference --scene cornell --method pt --res 64x36 --spp 16 --force --out '%s'", file, out, err) == 0,
           "reference --force: %s", err);
    EXPECT(cli_files_equal(file, copy, &size) == 0, "--force did not replace %s", file);
#undef REF
}

/* A plan folder takes its own plan again (the jobs done stay done), refuses anything else, and
 * --force empties it. */
static void test_plan_folder(char *out, char *err)
{
    char plan[2 * CLI_PATH_MAX], done[3 * CLI_PATH_MAX];
#define STUDY "study --scene cornell --method restir-di --configs bitterli --runs 2 --warmup 1 --frames 5 --res 16x9 " \
              "--ref-spp 16"
    path_of(plan, "plan");
    EXPECT(run(STUDY " --plan '%s'", plan, out, err) == 0, "study --plan: %s", err);
    EXPECT(run("job '%s' 1", plan, out, err) == 0, "job 1: %s", err);
    snprintf(done, sizeof done, "%s/runs/reference.exr", plan);
    EXPECT(run(STUDY " --plan '%s'", plan, out, err) == 0 && cli_exists(done), "the same plan again: %s", err);
    int rc = run(STUDY " --seed 9 --plan '%s'", plan, out, err);
    EXPECT(rc == 2 && strstr(err, "holds the plan of") && strstr(err, "--force") && cli_exists(done),
           "another plan into the folder: exit %d: %s", rc, err);
    EXPECT(run(STUDY " --seed 9 --force --plan '%s'", plan, out, err) == 0 && !cli_exists(done),
           "--force into a plan folder: %s", err);
#undef STUDY
}

int main(void)
{
    static char out[CLI_ERR_MAX], err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    test_second_run(out, err);
    test_default_folders();
    test_reference_size_and_metrics(out, err);
    test_reference_file(out, err);
    test_plan_folder(out, err);
    EXPECT(cli_count_entries(tmp, ".tmp-") == 0, "temporary files left");
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
