/* test_reference_resume.c: `restir reference --checkpoint-every`. A reference killed
 * with SIGKILL mid-run, or stopped by SIGINT, continues from its checkpoint when the same command
 * runs again and writes exactly the bytes of an uninterrupted run (also when --spp grows, and at
 * another thread count); checkpoints of other runs, with NaN or truncated are refused and kept;
 * without --checkpoint-every an interrupted reference writes nothing; no temporary is left. */
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 21

#define MSG_LEN 512 /* RESTIR_MSG_LEN: the test sees the program from outside */

#define REF "reference --scene cornell --method pt --res 96x54 --seed 5"

static char tmp[CLI_PATH_MAX];

static void path_of(char *out, const char *name)
{
    snprintf(out, 2 * CLI_PATH_MAX, "%s/%s", tmp, name);
}

/* restir.samples of a checkpoint, or -1. */
static int checkpoint_samples(const char *path)
{
    char text[64], msg[MSG_LEN];
    return exr_read_attribute(path, "restir.samples", text, sizeof text, msg) == 0 ? atoi(text) : -1;
}

/* Runs `REF extra --out tmp/name`; returns the exit code, stdout and stderr in out, err. */
static int reference(const char *extra, const char *name, char *out, char *err)
{
    char args[3 * CLI_PATH_MAX];
    snprintf(args, sizeof args, REF " %s --out '%s/%s'", extra, tmp, name);
    return cli_run_capture(tmp, args, out, err);
}

static pid_t spawn_reference(const char *extra, const char *name)
{
    char args[3 * CLI_PATH_MAX], err[2 * CLI_PATH_MAX];
    snprintf(args, sizeof args, REF " %s --out '%s/%s'", extra, tmp, name);
    path_of(err, "spawned_stderr.txt");
    return cli_spawn(args, err);
}

static void expect_same(const char *a_name, const char *b_name, const char *what)
{
    char a[2 * CLI_PATH_MAX], b[2 * CLI_PATH_MAX];
    path_of(a, a_name);
    path_of(b, b_name);
    long size = 0;
    int same = cli_files_equal(a, b, &size);
    EXPECT(same == 1, "%s: %s and %s differ (%d)", what, a_name, b_name, same);
    if (same == 1)
        printf("%s: %s equals %s byte for byte (%ld bytes)\n", what, b_name, a_name, size);
}

/* SIGKILL after the first checkpoints, then the same command. */
static void test_kill_and_resume(char *out, char *err)
{
    EXPECT(reference("--spp 960 --threads 2", "full.exr", out, err) == 0, "uninterrupted reference: %s", err);
    char ckpt[2 * CLI_PATH_MAX], final[2 * CLI_PATH_MAX];
    path_of(ckpt, "part.checkpoint.exr");
    path_of(final, "part.exr");
    pid_t pid = spawn_reference("--spp 960 --threads 1 --checkpoint-every 0", "part.exr");
    EXPECT(cli_wait_for_file(ckpt, 120000), "no checkpoint appeared");
    for (int waited = 0; waited < 12000 && checkpoint_samples(ckpt) < 240; waited++) /* a quarter in */
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    int status = cli_signal_and_wait(pid, SIGKILL);
    EXPECT(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL, "the reference finished before the kill");
    int n = checkpoint_samples(ckpt);
    EXPECT(n > 0 && n < 960 && n % 16 == 0, "checkpoint after the kill holds %d samples", n);
    EXPECT(!cli_exists(final), "a killed reference left its final image");
    /* a temporary of a writer that no longer exists (what a kill during a write leaves) */
    char stale[2 * CLI_PATH_MAX + 32];
    snprintf(stale, sizeof stale, "%s.tmp-2147483000", ckpt);
    FILE *f = fopen(stale, "w");
    if (f)
        fclose(f);
    EXPECT(reference("--spp 960 --threads 1 --checkpoint-every 0", "part.exr", out, err) == 0, "resume: %s", err);
    EXPECT(strstr(out, "resuming") != NULL, "the second run did not resume: %s", out);
    printf("killed at %d of 960 samples; %s", n, out);
    expect_same("full.exr", "part.exr", "SIGKILL + resume");
    EXPECT(!cli_exists(ckpt), "checkpoint kept after the reference finished");
    EXPECT(cli_count_entries(tmp, ".tmp-") == 0, "temporary files left");
}

/* SIGINT writes a checkpoint; refusals keep it; a larger --spp continues it. */
static void test_interrupt_refusals_and_extension(char *out, char *err)
{
    char ckpt[2 * CLI_PATH_MAX], copy[2 * CLI_PATH_MAX], final[2 * CLI_PATH_MAX], ext[2 * CLI_PATH_MAX];
    path_of(ckpt, "int.checkpoint.exr");
    path_of(final, "int.exr");
    path_of(ext, "ext.exr");
    /* checkpoints after every chunk, so the test can wait for 48 samples (the refusal below asks
     * for fewer), however slow the build (ASan); the signal then writes one more */
    pid_t pid = spawn_reference("--spp 960 --threads 1 --checkpoint-every 0", "int.exr");
    EXPECT(cli_wait_for_file(ckpt, 120000), "no checkpoint appeared");
    for (int waited = 0; waited < 12000 && checkpoint_samples(ckpt) < 48; waited++)
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    int status = cli_signal_and_wait(pid, SIGINT);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT, "SIGINT: exit status %d, want %d",
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, 128 + SIGINT);
    int n = checkpoint_samples(ckpt);
    EXPECT(n >= 48 && n < 960, "the SIGINT checkpoint holds %d samples", n);
    EXPECT(!cli_exists(final), "an interrupted reference wrote its final image");
    char args[5 * CLI_PATH_MAX];
    path_of(copy, "int.copy");
    snprintf(args, sizeof args, "cp '%s' '%s'", ckpt, copy);
    EXPECT(system(args) == 0, "cannot copy the checkpoint");

    /* another run's checkpoint: refused, named, left alone */
    EXPECT(reference("--spp 960 --seed 6", "int.exr", out, err) == 1 && strstr(err, "seed"),
           "another seed's checkpoint accepted or not named: %s", err);
    EXPECT(reference("--spp 960 --camera path --frame 30", "int.exr", out, err) == 1 && strstr(err, "camera"),
           "another camera's checkpoint accepted or not named: %s", err);
    EXPECT(reference("--spp 16", "int.exr", out, err) == 1 && strstr(err, "more than --spp"),
           "a checkpoint above --spp accepted: %s", err);
    long size = 0;
    EXPECT(cli_files_equal(ckpt, copy, &size) == 1, "a refused resume changed the checkpoint");
    EXPECT(!cli_exists(final), "a refused resume wrote the image");

    /* continued to more samples than it was started with: the bytes of a run of that many */
    EXPECT(reference("--spp 1280 --threads 2", "ext.exr", out, err) == 0, "uninterrupted 1280: %s", err);
    EXPECT(reference("--spp 1280 --threads 2 --checkpoint-every 0", "int.exr", out, err) == 0,
           "extending resume: %s", err);
    expect_same("ext.exr", "int.exr", "SIGINT + resume with a larger --spp");
    EXPECT(!cli_exists(ckpt), "checkpoint kept after the reference finished");
}

/* Broken checkpoints are refused with the problem named. */
static void test_broken_checkpoints(char *out, char *err)
{
    char path[2 * CLI_PATH_MAX], run[1024], msg[MSG_LEN], ref[2 * CLI_PATH_MAX];
    path_of(ref, "full.exr"); /* a finished reference carries the run's attributes */
    EXPECT(exr_read_attribute(ref, "restir.run", run, sizeof run, msg) == 0, "restir.run of full.exr: %s", msg);
    float *img = NULL;
    int w = 0, h = 0;
    EXPECT(exr_read_rgb(ref, &img, &w, &h, msg) == 0, "%s", msg);
    if (!img)
        return;
    img[3 * (7 * w + 11) + 1] = 0.0f / 0.0f;
    const struct exr_attribute attrs[2] = {{"restir.samples", "32"}, {"restir.run", run}};
    const struct exr_layer layer = {NULL, img};
    path_of(path, "nan.checkpoint.exr");
    EXPECT(exr_write_layers_attrs(path, &layer, 1, attrs, 2, w, h, msg) == 0, "%s", msg);
    EXPECT(reference("--spp 960", "nan.exr", out, err) == 1 && strstr(err, "pixel (11, 7)"),
           "a NaN checkpoint accepted or the pixel not named: %s", err);
    free(img);

    char args[5 * CLI_PATH_MAX];
    path_of(path, "cut.checkpoint.exr");
    snprintf(args, sizeof args, "head -c 2000 '%s' > '%s'", ref, path);
    EXPECT(system(args) == 0, "cannot truncate");
    EXPECT(reference("--spp 960", "cut.exr", out, err) == 1 && strstr(err, "cut.checkpoint.exr"),
           "a truncated checkpoint accepted: %s", err);
    path_of(path, "other.checkpoint.exr");
    snprintf(args, sizeof args, "echo not an image > '%s'", path);
    EXPECT(system(args) == 0, "cannot write");
    EXPECT(reference("--spp 960", "other.exr", out, err) == 1 && strstr(err, "not a reference checkpoint"),
           "a foreign file at the checkpoint's name accepted: %s", err);
    printf("broken checkpoints refused, e.g. %s", err);
}

/* Without --checkpoint-every a stop leaves nothing. The signal goes once the render has started (its
 * first progress line, RESTIR_PROGRESS_SECONDS=0), when the handlers are in place: a fixed delay
 * signalled a start-up that a loaded machine had not finished, whose default action kills. */
static void test_interrupt_without_checkpoints(void)
{
    char final[2 * CLI_PATH_MAX], ckpt[2 * CLI_PATH_MAX], log[2 * CLI_PATH_MAX], text[CLI_ERR_MAX];
    path_of(final, "plain.exr");
    path_of(ckpt, "plain.checkpoint.exr");
    path_of(log, "spawned_stderr.txt");
    remove(log);
    setenv("RESTIR_PROGRESS_SECONDS", "0", 1);
    pid_t pid = spawn_reference("--spp 960 --threads 1", "plain.exr");
    unsetenv("RESTIR_PROGRESS_SECONDS");
    text[0] = '\0';
    for (int waited = 0; waited < 6000 && !strstr(text, "reference:"); waited++) {
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
        cli_read_text(log, text, sizeof text);
    }
    EXPECT(strstr(text, "reference:") != NULL, "no progress line from the reference in 60 s: %s", text);
    int status = cli_signal_and_wait(pid, SIGTERM);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM, "SIGTERM: exit status %d",
           WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    EXPECT(!cli_exists(final) && !cli_exists(ckpt), "an interrupted reference without checkpoints wrote a file");
    EXPECT(cli_count_entries(tmp, ".tmp-") == 0, "temporary files left");
}

int main(void)
{
    static char out[CLI_ERR_MAX], err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    test_kill_and_resume(out, err);
    test_interrupt_refusals_and_extension(out, err);
    test_broken_checkpoints(out, err);
    test_interrupt_without_checkpoints();
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
