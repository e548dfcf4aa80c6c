/* test_interrupt.c: SIGINT or SIGTERM during `restir render` finishes the frame being written,
 * keeps every complete output (the frames written, metrics.csv with their rows), leaves no
 * temporary file, says so and exits 128 + the signal; `compare` keeps its reference and writes no
 * table from a part, `study` writes nothing. (`reference`: test_reference_resume.c.) */
#include <dirent.h>
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli_util.h"
#include "io/exr.h"
#include "test_util.h"

/* Starts a long render into dir, signals it once frame 2 is on disk, returns its exit status. */
static int interrupted_render(const char *dir, int sig, const char *save)
{
    char first[3 * CLI_PATH_MAX];
    snprintf(first, sizeof first, "%s/frame_0002.exr", dir);
    pid_t pid = fork();
    if (pid == 0) {
        execl(cli_bin(), cli_bin(), "render", "--scene", "cornell", "--method", "restir-di", "--res", "64x36",
              "--frames", "100000", "--save", save, "--out", dir, (char *)NULL);
        _exit(127);
    }
    struct stat st;
    int waited = 0;
    /* --save all: wait for frame 2; --save last: give it a moment to render a few frames */
    while (waited < 3000 && (strcmp(save, "all") ? waited < 50 : stat(first, &st) != 0)) {
        nanosleep(&(struct timespec){0, 20000000L}, NULL);
        waited++;
    }
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    return status;
}

static void check(const char *tmp, int sig, const char *save)
{
    static char text[1 << 24]; /* metrics.csv of up to ~100k frames */
    char dir[2 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX], msg[512];
    snprintf(dir, sizeof dir, "%s/%s-%s", tmp, sig == SIGINT ? "int" : "term", save);
    int status = interrupted_render(dir, sig, save);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + sig, "%s: exit status %d (signalled %d), want %d", dir,
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, WIFSIGNALED(status), 128 + sig);
    EXPECT(cli_count_entries(dir, ".tmp-") == 0, "%s: temporary files left", dir);
    snprintf(path, sizeof path, "%s/summary.json", dir);
    struct stat st;
    EXPECT(stat(path, &st) != 0, "%s: an interrupted run wrote summary.json", dir);
    snprintf(path, sizeof path, "%s/metrics.csv", dir);
    cli_read_text(path, text, sizeof text);
    int rows = -1;
    for (const char *c = text; *c; c++)
        rows += *c == '\n';
    EXPECT(rows >= 1, "%s: metrics.csv has %d complete rows", dir, rows);
    /* every frame file there is complete: it reads back at the render's size */
    int frames = 0;
    DIR *dp = opendir(dir);
    for (struct dirent *e = dp ? readdir(dp) : NULL; e; e = readdir(dp)) {
        const char *dot = strrchr(e->d_name, '.');
        if (strncmp(e->d_name, "frame_", 6) != 0 || !dot || strcmp(dot, ".exr") != 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        float *img = NULL;
        int w = 0, h = 0;
        EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == 0 && w == 64 && h == 36, "%s: %s", path, msg);
        free(img);
        frames++;
    }
    if (dp)
        closedir(dp);
    EXPECT(frames >= 1, "%s: no complete frame kept", dir);
    printf("%s: exit %d, %d metric rows, %d frames kept, no temporary files\n", dir,
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, rows, frames);
}

/* compare: the reference and the finished methods' frames stay; no compare.csv from a part. */
static void check_compare(const char *tmp)
{
    char dir[2 * CLI_PATH_MAX], args[5 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX], err[3 * CLI_PATH_MAX], msg[512];
    static char text[CLI_ERR_MAX];
    snprintf(dir, sizeof dir, "%s/compare", tmp);
    snprintf(err, sizeof err, "%s/compare_stderr.txt", tmp);
    snprintf(args, sizeof args,
             "compare --scene cornell --methods pt,restir-di --res 96x54 --frames 100000 --ref-spp 16 --out '%s'", dir);
    pid_t pid = cli_spawn(args, err);
    snprintf(path, sizeof path, "%s/reference.exr", dir);
    EXPECT(cli_wait_for_file(path, 60000), "compare wrote no reference");
    nanosleep(&(struct timespec){0, 200000000L}, NULL);
    int status = cli_signal_and_wait(pid, SIGTERM);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM, "compare: exit status %d, want %d",
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, 128 + SIGTERM);
    float *img = NULL;
    int w = 0, h = 0;
    EXPECT(exr_read_rgb(path, &img, &w, &h, msg) == 0 && w == 96 && h == 54, "compare's reference: %s", msg);
    free(img);
    snprintf(path, sizeof path, "%s/compare.csv", dir);
    struct stat st;
    EXPECT(stat(path, &st) != 0, "an interrupted compare wrote compare.csv");
    EXPECT(cli_count_entries(dir, ".tmp-") == 0, "compare: temporary files left");
    cli_read_text(err, text, sizeof text);
    EXPECT(strstr(text, "interrupted by SIGTERM") && strstr(text, "reference.exr"), "compare said: %s", text);
    printf("compare: exit %d, %s", WIFEXITED(status) ? WEXITSTATUS(status) : -1, text);
}

/* study: its tables compare every configuration, so an interrupted study writes none. */
static void check_study(const char *tmp)
{
    char dir[2 * CLI_PATH_MAX], args[5 * CLI_PATH_MAX], err[3 * CLI_PATH_MAX];
    static char text[CLI_ERR_MAX];
    snprintf(dir, sizeof dir, "%s/study", tmp);
    snprintf(err, sizeof err, "%s/study_stderr.txt", tmp);
    snprintf(args, sizeof args,
             "study --scene cornell --method restir-di --configs bitterli,compat --res 64x36 --frames 8 "
             "--runs 100000 --ref-spp 16 --out '%s'", dir);
    pid_t pid = cli_spawn(args, err);
    EXPECT(cli_wait_for_file(dir, 60000), "study made no folder");
    nanosleep(&(struct timespec){0, 200000000L}, NULL);
    int status = cli_signal_and_wait(pid, SIGINT);
    EXPECT(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT, "study: exit status %d, want %d",
           WIFEXITED(status) ? WEXITSTATUS(status) : -1, 128 + SIGINT);
    EXPECT(cli_count_entries(dir, "") == 0, "an interrupted study wrote %d files", cli_count_entries(dir, ""));
    cli_read_text(err, text, sizeof text);
    EXPECT(strstr(text, "interrupted by SIGINT"), "study said: %s", text);
    printf("study: exit %d, %s", WIFEXITED(status) ? WEXITSTATUS(status) : -1, text);
}

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    check(tmp, SIGINT, "all");
    check(tmp, SIGTERM, "all");
    check(tmp, SIGINT, "last"); /* the frame being rendered when the signal came is written */
    check_compare(tmp);
    check_study(tmp);
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
