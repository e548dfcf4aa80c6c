/* test_determinism.c: same seed, same bytes: `restir render` writes identical EXR frames with 1 and 2
 * threads for pt, ris-di, restir-di and restir-pt (standard and spmis spatial reuse), and another
 * seed changes them. Must never call the renderer directly (CLI only). */
#include "cli_util.h"
#include "test_util.h"

/* One render into dir; returns the exit code (stderr printed on failure). */
static int render(const char *tmp, const char *method, int threads, int seed, const char *dir)
{
    char args[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof(args),
             "render --scene cornell --method %s --res 64x36 --frames 3 --threads %d --seed %d --out '%s'", method,
             threads, seed, dir);
    int rc = cli_run(tmp, args, err);
    if (rc != 0)
        printf("restir %s exited %d:\n%s", args, rc, err);
    return rc;
}

static void check_method(const char *tmp, const char *method)
{
    char d1[CLI_PATH_MAX], d2[CLI_PATH_MAX], d3[CLI_PATH_MAX];
    snprintf(d1, sizeof(d1), "%s/%s-t1", tmp, method);
    snprintf(d2, sizeof(d2), "%s/%s-t2", tmp, method);
    snprintf(d3, sizeof(d3), "%s/%s-seed2", tmp, method);
    EXPECT(render(tmp, method, 1, 1, d1) == 0, "%s: render with 1 thread failed", method);
    EXPECT(render(tmp, method, 2, 1, d2) == 0, "%s: render with 2 threads failed", method);
    EXPECT(render(tmp, method, 2, 2, d3) == 0, "%s: render with seed 2 failed", method);
    /* summary.json reports the process's peak memory */
    char summary[2 * CLI_PATH_MAX], text[4096];
    snprintf(summary, sizeof(summary), "%s/summary.json", d1);
    cli_read_text(summary, text, sizeof(text));
    const char *peak = strstr(text, "\"peak_memory_mb\":");
    EXPECT(peak && atof(peak + 17) > 1.0, "%s: summary.json has no plausible peak_memory_mb", method);
    /* Every frame is written (--save all is the default); frame 2 of restir-di carries two
     * frames of temporal history, so it sees every pass. */
    const char *frames[] = {"frame_0000.exr", "frame_0002.exr", "frame_0002.png"};
    for (int k = 0; k < 3; k++) {
        char a[2 * CLI_PATH_MAX], b[2 * CLI_PATH_MAX], c[2 * CLI_PATH_MAX];
        snprintf(a, sizeof(a), "%s/%s", d1, frames[k]);
        snprintf(b, sizeof(b), "%s/%s", d2, frames[k]);
        snprintf(c, sizeof(c), "%s/%s", d3, frames[k]);
        long size = 0, size_c = 0;
        int same = cli_files_equal(a, b, &size);
        EXPECT(same == 1, "%s: %s differs between 1 and 2 threads (%s)", method, frames[k],
               same < 0 ? "missing" : "bytes differ");
        /* A 64x36 RGB half/float image cannot fit in a few bytes: guards against empty files. */
        EXPECT(size > 1000, "%s: %s has only %ld bytes", method, frames[k], size);
        int same_c = cli_files_equal(a, c, &size_c);
        EXPECT(same_c == 0, "%s: %s is %s with seed 2", method, frames[k],
               same_c < 0 ? "missing" : "identical to seed 1's");
        printf("%s %s: %ld bytes, 1 vs 2 threads %s, seed 2 %s\n", method, frames[k], size,
               same == 1 ? "identical" : "DIFFERENT", same_c == 0 ? "differs" : "SAME/missing");
    }
}

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    check_method(tmp, "pt");
    check_method(tmp, "ris-di");
    check_method(tmp, "restir-di");
    check_method(tmp, "restir-pt");
    /* spmis builds cells in parallel over tiles and searches per pixel: still thread-count free */
    check_method(tmp, "restir-di --set spatial.reuse=spmis");
    check_method(tmp, "restir-pt --set spatial.reuse=spmis");
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
