/* test_cli_errors.c: bad input to `restir` gets exit 2 (usage) or 1 (runtime), a "restir: " message naming
 * the problem, and no output files; plus list, bare `restir` and --help. Must never render in-process. */
#include <dirent.h>

#include "cli_util.h"
#include "methods/renderer.h"
#include "scene/scene.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 23

static char tmp[CLI_PATH_MAX];
static int case_no;

/* No entries (or no folder) at dir: a failed run must not leave frames, reports or temp files. */
static void expect_no_output(const char *what, const char *dir)
{
    int all = cli_count_entries(dir, ""), frames = cli_count_entries(dir, "frame_"),
        temps = cli_count_entries(dir, ".tmp-");
    EXPECT(frames <= 0, "%s: %d frame files left in %s", what, frames, dir);
    EXPECT(temps <= 0, "%s: %d temporary files left in %s", what, temps, dir);
    EXPECT(all <= 0, "%s: %d files left in %s", what, all, dir);
}

/* Runs `restir <args>`; args may use %1$s for a fresh output folder path (never created here).
 * Checks the exit code, the "restir: " prefix, that stderr names the problem (need1, need2), and
 * that the output folder holds nothing. */
static void expect_failure(const char *what, const char *args_fmt, int want_rc, const char *need1,
                           const char *need2)
{
    char out[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(out, sizeof(out), "%s/out-%d", tmp, ++case_no);
    if (snprintf(args, sizeof(args), args_fmt, out) >= (int)sizeof(args)) {
        EXPECT(0, "%s: command line too long", what);
        return;
    }
    int rc = cli_run(tmp, args, err);
    printf("[%s] exit %d: %s", what, rc, err[0] ? err : "(no message)\n");
    EXPECT(rc == want_rc, "%s: exit code %d, want %d (restir %s)", what, rc, want_rc, args);
    EXPECT(strncmp(err, "restir: ", 8) == 0, "%s: stderr does not start with 'restir: ': %s", what, err);
    EXPECT(strstr(err, need1) != NULL, "%s: message does not mention '%s': %s", what, need1, err);
    if (need2)
        EXPECT(strstr(err, need2) != NULL, "%s: message does not mention '%s': %s", what, need2, err);
    EXPECT(strstr(err, "internal error") == NULL, "%s: bad input hit an internal check: %s", what, err);
    expect_no_output(what, out);
    EXPECT(cli_count_entries(tmp, ".tmp-") == 0, "%s: temporary files left in %s", what, tmp);
}

/* The line of text that contains `part`, copied into line (empty when absent). */
static void line_with(const char *text, const char *part, char *line, size_t n)
{
    line[0] = '\0';
    const char *p = strstr(text, part);
    if (!p)
        return;
    const char *b = p, *e = p;
    while (b > text && b[-1] != '\n')
        b--;
    while (*e && *e != '\n')
        e++;
    size_t len = (size_t)(e - b) < n - 1 ? (size_t)(e - b) : n - 1;
    memcpy(line, b, len);
    line[len] = '\0';
}

/* A setting the chosen method does not read is refused by name, nothing written (the registry's
 * settings lists): for render, for a compare spec's own settings, and for a common --set that no
 * listed method reads; and a method name that is not registered. */
static void check_settings_per_method(void)
{
    expect_failure("render: pt with a spatial setting",
                   "render --scene cornell --method pt --res 16x16 --set spatial.radius=8 --out '%s'", 2,
                   "spatial.radius", "pt does not read");
    expect_failure("render: restir-pt with gi.radiance",
                   "render --scene cornell --method restir-pt --res 16x16 --set gi.radiance=stored --out '%s'", 2,
                   "gi.radiance", "restir-pt");
    expect_failure("compare: a spec's own unused setting",
                   "compare --scene cornell --res 16x16 --methods 'pt,restir-di:shift=replay' --out '%s'", 2, "shift",
                   "restir-di");
    expect_failure("compare: a common setting no method reads",
                   "compare --scene cornell --res 16x16 --methods pt,restir-di --set grad.search=3 --out '%s'", 2,
                   "grad.search", "nor does any other method");
    expect_failure("render: an unregistered method", "render --scene cornell --method restir-xyz --out '%s'", 2,
                   "restir-xyz", NULL);
}

static void check_bad_render_input(void)
{
    char path[2 * CLI_PATH_MAX], fmt[4 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    const char *base = "render --scene cornell --method pt --res 16x16";
#define RENDER_ARGS(extra) "render --scene cornell --method pt --res 16x16 " extra " --out '%1$s'"
    expect_failure("unknown scene", "render --scene no-such-scene --method pt --res 16x16 --out '%1$s'", 2,
                   "no-such-scene", NULL);
    expect_failure("unknown method", "render --scene cornell --method no-such-method --res 16x16 --out '%1$s'", 2,
                   "no-such-method", NULL);
    expect_failure("zero width", "render --scene cornell --method pt --res 0x10 --out '%1$s'", 2, "--res", "0");
    /* a render that does not fit the memory allowed: refused before allocating, both numbers said */
    expect_failure("too large for --max-memory",
                   "render --scene cornell --method restir-pt --res 4000x4000 --max-memory 200 --out '%1$s'", 1,
                   "needs about", "than the 200 MB that --max-memory allows");
    expect_failure("compare too large for --max-memory",
                   "compare --scene cornell --methods restir-di,pt --res 4000x4000 --max-memory 200 --out '%1$s'", 1,
                   "restir-di", "needs about");
    expect_failure("reference too large for --max-memory",
                   "reference --scene cornell --method pt --res 8000x6000 --max-memory 200 --out '%1$s/r.exr'", 1,
                   "reference at 8000x6000 needs about", "than the 200 MB that --max-memory allows");
    expect_failure("bad --checkpoint-every",
                   "reference --scene cornell --method pt --checkpoint-every -1 --out '%1$s/r.exr'", 2,
                   "--checkpoint-every", "-1");
    expect_failure("--checkpoint-every outside reference", RENDER_ARGS("--checkpoint-every 5"), 2,
                   "--checkpoint-every", NULL);
    const char *const bad_targets[] = {"0", "-0.01", "nan", "2", "abc", "1e-3x"};
    for (int k = 0; k < 6; k++) {
        char args[256], what[64];
        snprintf(args, sizeof args, "reference --scene cornell --method pt --target-relmse %s --out '%%1$s/r.exr'",
                 bad_targets[k]);
        snprintf(what, sizeof what, "bad --target-relmse %s", bad_targets[k]);
        expect_failure(what, args, 2, "--target-relmse", bad_targets[k]);
    }
    expect_failure("--target-relmse outside reference", RENDER_ARGS("--target-relmse 0.01"), 2, "--target-relmse",
                   NULL);
    expect_failure("unknown lights.select", RENDER_ARGS("--set lights.select=tree"), 2, "lights.select", "tree");
    /* restir-di's candidates come from the frame's light pool, drawn before any shading point */
    expect_failure("lights.select for a method that does not read it",
                   "render --scene cornell --method restir-di --res 16x9 --set lights.select=bvh --out '%1$s'", 2,
                   "lights.select", "restir-di");
    expect_failure("huge width", "render --scene cornell --method pt --res 100000x10 --out '%1$s'", 2, "--res",
                   "100000");
    expect_failure("malformed resolution", "render --scene cornell --method pt --res abc --out '%1$s'", 2, "--res",
                   "abc");
    expect_failure("unknown --set key", RENDER_ARGS("--set nosuchkey=1"), 2, "nosuchkey", NULL);
    expect_failure("NaN parameter", RENDER_ARGS("--set spatial.radius=nan"), 2, "spatial.radius", "nan");
    expect_failure("unknown MIS", RENDER_ARGS("--set mis=foo"), 2, "mis", "foo");
    expect_failure("fractional integer parameter", RENDER_ARGS("--set spp=1.5"), 2, "spp", "1.5");
    expect_failure("zero frames", RENDER_ARGS("--frames 0"), 2, "--frames", NULL);
    expect_failure("missing value", "render --scene cornell --method pt --res 16x16 --out '%1$s' --frames", 2,
                   "--frames", NULL);

    /* References: missing, not an EXR, wrong size. */
    snprintf(path, sizeof(path), "%s/missing.exr", tmp);
    snprintf(fmt, sizeof(fmt), "%s --ref '%s' --out '%%1$s'", base, path);
    expect_failure("missing reference", fmt, 1, path, NULL);
    snprintf(path, sizeof(path), "%s/text.exr", tmp);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs("this is not an image\n", f);
        fclose(f);
    }
    snprintf(fmt, sizeof(fmt), "%s --ref '%s' --out '%%1$s'", base, path);
    expect_failure("text file as reference", fmt, 1, path, NULL);
    snprintf(path, sizeof(path), "%s/ref16.exr", tmp);
    snprintf(fmt, sizeof(fmt), "reference --scene cornell --method pt --res 16x16 --spp 1 --out '%s'", path);
    EXPECT(cli_run(tmp, fmt, err) == 0, "cannot make a 16x16 reference: %s", err);
    snprintf(fmt, sizeof(fmt), "render --scene cornell --method pt --res 32x16 --ref '%s' --out '%%1$s'", path);
    expect_failure("reference of the wrong size", fmt, 1, "16x16", "32x16");

    /* Output under a regular file, and the regular file itself as the folder. */
    snprintf(path, sizeof(path), "%s/regular", tmp);
    f = fopen(path, "w");
    if (f)
        fclose(f);
    snprintf(fmt, sizeof(fmt), "%s --out '%s/sub'", base, path);
    expect_failure("output under a regular file", fmt, 1, path, NULL);
    snprintf(fmt, sizeof(fmt), "%s --out '%s'", base, path);
    expect_failure("output is a regular file", fmt, 1, path, NULL);
}

/* A write that fails mid-run (frame 300's EXR path taken by a folder made once frame 0 is written):
 * exit 1 naming the file, no temporary files, no metrics.csv / summary.json, and no frame after the
 * failing one. The frames before it, written whole, may stay. */
static void check_failed_write(void)
{
    char out[2 * CLI_PATH_MAX], blocker[3 * CLI_PATH_MAX], started[3 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX],
        log[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(out, sizeof(out), "%s/blocked", tmp);
    snprintf(blocker, sizeof(blocker), "%s/frame_0300.exr", out);
    snprintf(started, sizeof(started), "%s/frame_0000.exr", out);
    snprintf(log, sizeof(log), "%s/blocked.log", tmp);
    snprintf(args, sizeof(args), "render --scene cornell --method restir-di --res 32x32 --frames 600 --out '%s'", out);
    int rc = cli_run_blocked(args, log, started, blocker, 1, err, sizeof err);
    printf("[failed write] exit %d: %s", rc, err);
    EXPECT(rc == 1, "failed frame write: exit %d", rc);
    EXPECT(strncmp(err, "restir: ", 8) == 0 && strstr(err, "frame_0300.exr"), "message: %s", err);
    EXPECT(cli_count_entries(out, ".tmp-") == 0, "temporary files left in %s", out);
    EXPECT(cli_count_entries(out, "metrics.csv") == 0 && cli_count_entries(out, "summary.json") == 0,
           "reports of a failed run were committed in %s", out);
    EXPECT(cli_count_entries(out, "frame_0301") == 0, "frames after the failure were written");
}

/* `restir compare` with no usable method list, and with a method's folder blocked by a file. */
static void check_compare(void)
{
    char fmt[4 * CLI_PATH_MAX], out[2 * CLI_PATH_MAX], blocker[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    expect_failure("compare with no runs", "compare --scene cornell --methods pt --runs 0 --res 16x16 --out '%1$s'", 2,
                   "--runs", NULL);
    expect_failure("compare with --ref-every 0",
                   "compare --scene cornell --methods pt --ref-every 0 --res 16x16 --out '%1$s'", 2, "--ref-every",
                   NULL);
    expect_failure("compare --ref-every planned",
                   "compare --scene cornell --methods pt --ref-every 2 --frames 4 --res 16x16 --plan '%1$s'", 2,
                   "--ref-every", "unsplit");
    expect_failure("compare instances= with --equal-time",
                   "compare --scene cornell --methods restir-di,pt:instances=2 --equal-time --res 16x16 --out '%1$s'",
                   2, "instances=", "--equal-time");
    expect_failure("compare instances=0",
                   "compare --scene cornell --methods restir-di:instances=0 --res 16x16 --out '%1$s'", 2, "instances",
                   "[1, 16]");
    expect_failure("study with --ref-every",
                   "study --scene cornell --method restir-pt --configs bitterli --ref-every 4 --res 16x16 --out '%1$s'",
                   2, "--ref-every", NULL);
    expect_failure("compare with an empty method list", "compare --scene cornell --methods '' --res 16x16 --out '%1$s'",
                   2, "--methods", NULL);
    expect_failure("compare with only commas", "compare --scene cornell --methods , --res 16x16 --out '%1$s'", 2,
                   "--methods", NULL);
    expect_failure("compare with an unknown method",
                   "compare --scene cornell --methods pt,no-such-method --res 16x16 --out '%1$s'", 2,
                   "no-such-method", NULL);
    expect_failure("compare spec with an unknown key",
                   "compare --scene cornell --methods 'restir-pt,restir-pt:nosuchkey=1' --res 16x16 --out '%1$s'", 2,
                   "restir-pt:nosuchkey=1", "'nosuchkey'");
    expect_failure("compare spec with a bad value",
                   "compare --scene cornell --methods 'restir-pt:mis=foo' --res 16x16 --out '%1$s'", 2,
                   "restir-pt:mis=foo", "'foo'");
    expect_failure("compare spec with an unknown method",
                   "compare --scene cornell --methods 'pt,no-such-method:mis=balance' --res 16x16 --out '%1$s'", 2,
                   "no-such-method", NULL);
    /* a method's folder blocked by a file made once the reference is written, before the method runs */
    char started[3 * CLI_PATH_MAX], log[3 * CLI_PATH_MAX];
    snprintf(out, sizeof(out), "%s/compare-blocked", tmp);
    snprintf(started, sizeof(started), "%s/reference.exr", out);
    snprintf(blocker, sizeof(blocker), "%s/pt", out);
    snprintf(log, sizeof(log), "%s/compare-blocked.log", tmp);
    snprintf(fmt, sizeof(fmt), "compare --scene cornell --methods pt --res 32x32 --frames 300 --ref-spp 1 --out '%s'",
             out);
    int rc = cli_run_blocked(fmt, log, started, blocker, 0, err, sizeof err);
    printf("[compare, method folder blocked] exit %d: %s", rc, err[0] ? err : "(no message)\n");
    EXPECT(rc == 1, "compare could not write %s but exited %d", blocker, rc);
    EXPECT(strstr(err, blocker) != NULL, "message does not name %s: %s", blocker, err);
    EXPECT(cli_count_entries(out, ".tmp-") == 0, "temporary files left in %s", out);
}

/* `restir compare` with method specs NAME[:key=value]...: each spec labels its row of the table and
 * of compare.csv, and gets its own folder (the label with [^A-Za-z0-9._-] as '_', then _2, _3). */
static void check_compare_specs(void)
{
    static char out_text[CLI_ERR_MAX], csv[CLI_ERR_MAX];
    char dir[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX], err[CLI_ERR_MAX], line[512];
    snprintf(dir, sizeof(dir), "%s/compare-specs", tmp);
    snprintf(args, sizeof(args),
             "compare --scene cornell --res 16x12 --frames 2 --ref-spp 4 --threads 2 "
             "--methods 'restir-pt,restir-pt:mis=balance,restir-pt:mis=balance' --out '%s'",
             dir);
    int rc = cli_run_capture(tmp, args, out_text, err);
    printf("[compare with specs] exit %d: %s", rc, err[0] ? err : "(no message)\n");
    EXPECT(rc == 0, "compare with specs exited %d: %s", rc, err);
    line_with(out_text, "restir-pt:mis=balance ", line, sizeof(line));
    EXPECT(line[0] != '\0', "the table has no row labelled restir-pt:mis=balance:\n%s", out_text);
    snprintf(path, sizeof(path), "%s/compare.csv", dir);
    cli_read_text(path, csv, sizeof(csv));
    EXPECT(strncmp(csv, "method,", 7) == 0, "%s has no header: %s", path, csv);
    EXPECT(strstr(csv, "\nrestir-pt,") != NULL, "%s has no row labelled restir-pt:\n%s", path, csv);
    const char *first = strstr(csv, "\nrestir-pt:mis=balance,");
    EXPECT(first != NULL && strstr(first + 1, "\nrestir-pt:mis=balance,") != NULL,
           "%s has not two rows labelled restir-pt:mis=balance:\n%s", path, csv);
    const char *folders[] = {"restir-pt", "restir-pt_mis_balance", "restir-pt_mis_balance_2"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof(path), "%s/%s", dir, folders[k]);
        int frames = cli_count_entries(path, "frame_0001.exr");
        EXPECT(frames == 1, "no last frame in %s (%d)", path, frames);
    }
    EXPECT(cli_count_entries(dir, "") == 10,
           "%s holds %d entries, want compare.csv, frames.csv, passes.csv, runs.csv, reference.exr, its two halves "
           "and 3 folders",
           dir, cli_count_entries(dir, ""));
}

static void check_study(void)
{
    expect_failure("study with an unknown --hard-neighbors",
                   "study --scene cornell --method restir-pt --configs bitterli --hard-neighbors sky --res 16x16 "
                   "--out '%1$s'",
                   2, "--hard-neighbors", "sky");
    expect_failure("unknown spmis.confidence_update",
                   "render --scene cornell --method restir-pt --res 16x16 --set spatial.reuse=spmis --set "
                   "spmis.confidence_update=max --out '%1$s'",
                   2, "spmis.confidence_update", "max");
    expect_failure("unknown shift.distance_mode",
                   "render --scene cornell --method restir-pt --res 16x16 --set shift.distance_mode=pixels "
                   "--out '%1$s'",
                   2, "shift.distance_mode", "pixels");
    expect_failure("unknown temporal.subpixel",
                   "render --scene cornell --method restir-pt --res 16x16 --set temporal.subpixel=nearest --out '%1$s'",
                   2, "temporal.subpixel", "nearest");
    expect_failure("temporal.subpixel=search without jitter",
                   "render --scene cornell --method restir-pt --res 16x16 --set temporal.subpixel=search --set "
                   "jitter=off --out '%1$s'",
                   2, "temporal.subpixel=search", "jitter=on");
    expect_failure("grad.inner_jacobian_ratio below 1",
                   "render --scene cornell --method grestir-pt --res 16x16 --set grad.inner_jacobian_ratio=0.5 --out "
                   "'%1$s'",
                   2, "grad.inner_jacobian_ratio", "at least 1");
    expect_failure("study with an unknown configuration",
                   "study --scene cornell --method restir-pt --configs bitterli,no-such-config --res 16x16 "
                   "--out '%1$s'",
                   2, "no-such-config", NULL);
    expect_failure("study with a Bitterli radius out of range",
                   "study --scene cornell --method restir-pt --configs bitterli-r0 --res 16x16 --out '%1$s'", 2,
                   "bitterli-r0", NULL);
    expect_failure("study of a method without spatial reuse",
                   "study --scene cornell --method pt --configs bitterli --res 16x16 --out '%1$s'", 2, "restir-di",
                   NULL);
    expect_failure("study with a bad radius",
                   "study --scene cornell --method restir-di --radii 10,abc --res 16x16 --out '%1$s'", 2, "abc", NULL);
    expect_failure("study with too few frames",
                   "study --scene cornell --method restir-di --configs fast --frames 2 --res 16x16 --out '%1$s'", 2,
                   "--frames", NULL);
    expect_failure("unknown neighbor selection",
                   "render --scene cornell --method restir-di --set spatial.select=magic --res 16x16 --out '%1$s'", 2,
                   "magic", NULL);
    expect_failure("unknown spatial reuse",
                   "render --scene cornell --method restir-pt --set spatial.reuse=cells --res 16x16 --out '%1$s'", 2,
                   "spatial.reuse", NULL);
    expect_failure("spmis candidates out of range",
                   "render --scene cornell --method restir-pt --set spmis.candidates=-2 --res 16x16 --out '%1$s'", 2,
                   "or M", NULL);
    expect_failure("compare spec that changes the integrand",
                   "compare --scene cornell --res 16x12 --frames 1 --ref-spp 1 --methods 'pt,pt:pt.max_bounces=2' "
                   "--out '%1$s'",
                   2, "integrand", NULL);
    expect_failure("spmis tile too large",
                   "render --scene cornell --method restir-di --set spmis.tile=64 --res 16x16 --out '%1$s'", 2,
                   "spmis.tile", NULL);
    /* camera effects and reservoir splatting */
    expect_failure("shutter above 1", RENDER_ARGS("--set camera.shutter=1.5"), 2, "camera.shutter", "1.5");
    expect_failure("negative shutter", RENDER_ARGS("--set camera.shutter=-0.1"), 2, "camera.shutter", NULL);
    expect_failure("negative aperture", RENDER_ARGS("--set camera.aperture=-1"), 2, "camera.aperture", "-1");
    expect_failure("negative focus distance", RENDER_ARGS("--set camera.focus_distance=-2"), 2,
                   "camera.focus_distance", NULL);
    expect_failure("NaN aperture", RENDER_ARGS("--set camera.aperture=nan"), 2, "camera.aperture", NULL);
    expect_failure("unknown temporal reuse", RENDER_ARGS("--set temporal.reuse=forward"), 2, "temporal.reuse",
                   "forward");
    expect_failure("splat with restir-di",
                   "render --scene cornell --method restir-di --set temporal.reuse=splat --res 16x16 --out '%1$s'", 2,
                   "temporal.reuse=splat", "restir-di");
    expect_failure("both with pt",
                   "render --scene cornell --method pt --set temporal.reuse=both --res 16x16 --out '%1$s'", 2,
                   "temporal.reuse=both", "pt");
    expect_failure("splat without jitter",
                   "render --scene cornell --method restir-pt --set temporal.reuse=splat --set jitter=off --res 16x16 "
                   "--out '%1$s'",
                   2, "temporal.reuse=splat", "jitter");
    expect_failure("aperture with restir-di",
                   "render --scene cornell --method restir-di --set camera.aperture=0.1 --res 16x16 --out '%1$s'", 2,
                   "camera.aperture", "restir-di");
    expect_failure("shutter with gpt",
                   "render --scene cornell --method gpt --set camera.shutter=0.5 --res 16x16 --out '%1$s'", 2,
                   "camera.shutter", "gpt");
    expect_failure("compare spec that changes the shutter",
                   "compare --scene cornell --res 16x12 --frames 1 --ref-spp 1 "
                   "--methods 'pt,restir-pt:camera.shutter=0.5' --out '%1$s'",
                   2, "integrand", NULL);
    expect_failure("reference of restir-di with a lens",
                   "reference --scene cornell --method restir-di --set camera.aperture=0.1 --res 16x16 --spp 1 "
                   "--out '%1$s/r.exr'",
                   2, "camera.aperture", NULL);
}

static void check_list_and_help(void)
{
    char out[CLI_ERR_MAX], err[CLI_ERR_MAX], line[512], want[128];
    int rc = cli_run_capture(tmp, "list", out, err);
    EXPECT(rc == 0, "restir list exited %d: %s", rc, err);
    for (int i = 0; scene_builtins[i].name; i++) {
        snprintf(want, sizeof(want), "scene %s\t", scene_builtins[i].name);
        EXPECT(strstr(out, want) != NULL, "restir list does not list scene %s", scene_builtins[i].name);
    }
    for (int k = 0; k < method_count(); k++) {
        snprintf(want, sizeof(want), "method %s\t", method_at(k)->name);
        EXPECT(strstr(out, want) != NULL, "restir list does not list method %s", method_at(k)->name);
    }
    /* --json: the registry for scripts (scripts/registry.py; lint.method_lists reads every field) */
    rc = cli_run_capture(tmp, "list --json", out, err);
    EXPECT(rc == 0 && out[0] == '{', "restir list --json exited %d: %s", rc, err);
    for (int k = 0; k < method_count(); k++) {
        snprintf(want, sizeof(want), "\"name\":\t\"%s\"", method_at(k)->name);
        EXPECT(strstr(out, want) != NULL, "restir list --json does not list method %s", method_at(k)->name);
    }
    rc = cli_run_capture(tmp, "list --yaml", out, err);
    EXPECT(rc == 2 && strstr(err, "--yaml") != NULL, "restir list --yaml exited %d without naming it: %s", rc, err);

    rc = cli_run_capture(tmp, "", out, err);
    EXPECT(rc == 2, "bare restir exited %d", rc);
    EXPECT(strstr(err, "usage") != NULL, "bare restir prints no usage on stderr: %s", err);

    rc = cli_run_capture(tmp, "no-such-command", out, err);
    EXPECT(rc == 2, "unknown command exited %d", rc);
    EXPECT(strstr(err, "no-such-command") != NULL, "unknown command not named: %s", err);

    rc = cli_run_capture(tmp, "render --help", out, err);
    EXPECT(rc == 0, "restir render --help exited %d", rc);
    EXPECT(strstr(out, "spatial.radius") != NULL, "render --help does not list spatial.radius");
    line_with(out, "1/M", line, sizeof(line));
    EXPECT(strstr(line, "BIASED") != NULL, "render --help does not call 1/M BIASED: '%s'", line);
}

/* Each command accepts only the options it reads: another command's option is refused (exit 2,
 * nothing written) naming the option, the command and the commands that read it; a misspelt one
 * gets the nearest option of the command; `restir help CMD` prints what `restir CMD --help` prints,
 * and no --help lists an option its command refuses. */
static void check_option_scope(void)
{
    static const char *const refused[][3] = {
        {"render", "--report", "render --scene cornell --method pt --res 16x16 --report --out '%1$s'"},
        {"render", "--configs", "render --scene cornell --method pt --res 16x16 --configs bitterli --out '%1$s'"},
        {"render", "--equal-time", "render --scene cornell --method pt --res 16x16 --equal-time --out '%1$s'"},
        {"render", "--methods", "render --scene cornell --method pt --res 16x16 --methods pt,restir-di --out '%1$s'"},
        {"reference", "--frames", "reference --scene cornell --method pt --res 16x16 --frames 4 --out '%1$s/r.exr'"},
        {"compare", "--method", "compare --scene cornell --methods pt --method pt --res 16x16 --out '%1$s'"},
        {"study", "--camera", "study --scene cornell --method restir-di --configs fast --camera path --out '%1$s'"},
        {"view", "--frames", "view --scene cornell --res 16x16 --frames 3 --out '%1$s'"},
        {"scene info", "--res", "scene info cornell --res 16x16"},
        {"evaluate", "--scene", "evaluate 004 --res 64x64 --scene cornell --out '%1$s'"},
    };
    char what[128], need[128], out[CLI_ERR_MAX], err[CLI_ERR_MAX], args[256];
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        snprintf(what, sizeof what, "%s %s refused", refused[k][0], refused[k][1]);
        snprintf(need, sizeof need, "option '%s' is not read by %s (it is an option of: ", refused[k][1],
                 refused[k][0]);
        expect_failure(what, refused[k][2], 2, need, NULL);
    }
    expect_failure("misspelt option", "render --scen cornell --method pt --res 16x16 --out '%1$s'", 2,
                   "unknown option '--scen'", "did you mean --scene?");
    expect_failure("another command's option, near one of this", "render --scene cornell --methods pt --out '%1$s'",
                   2, "is not read by render", "did you mean --method?");
    static const char *const commands[] = {"render", "reference", "compare", "study", "view", "evaluate", "scene",
                                           "job", "list"};
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) {
        static char help[CLI_ERR_MAX];
        snprintf(args, sizeof args, "%s --help", commands[k]);
        const int rc = cli_run_capture(tmp, args, help, err);
        snprintf(args, sizeof args, "help %s", commands[k]);
        const int rc_help = cli_run_capture(tmp, args, out, err);
        EXPECT(rc == 0 && rc_help == 0 && help[0] && !strcmp(help, out),
               "restir help %s (exit %d) does not print what restir %s --help (exit %d) prints", commands[k], rc_help,
               commands[k], rc);
    }
    for (size_t k = 0; k < sizeof refused / sizeof refused[0]; k++) {
        snprintf(args, sizeof args, "help %s", refused[k][0]);
        cli_run_capture(tmp, args, out, err);
        const char *opts = strstr(out, "Options of restir");
        snprintf(need, sizeof need, "\n  %s ", refused[k][1]);
        EXPECT(!opts || !strstr(opts, need), "restir %s --help lists %s, which it refuses", refused[k][0],
               refused[k][1]);
    }
    EXPECT(cli_run(tmp, "help no-such-command", err) == 2, "restir help of an unknown command must exit 2");
}

/* Progress when stderr is no terminal (a log file): a line per step with RESTIR_PROGRESS_SECONDS=0,
 * "restir: LABEL: DONE/TOTAL (P%), Es elapsed, ETA Ts"; none for a run shorter than the default 10 s
 * and none with off. */
static void check_progress_lines(void)
{
    char args[2 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    const char *const values[] = {"0", NULL, "off"};
    for (int k = 0; k < 3; k++) {
        if (values[k])
            setenv("RESTIR_PROGRESS_SECONDS", values[k], 1);
        else
            unsetenv("RESTIR_PROGRESS_SECONDS");
        snprintf(args, sizeof args, "render --scene cornell --method pt --res 16x16 --frames 3 --out '%s/progress-%d'",
                 tmp, k);
        const int rc = cli_run(tmp, args, err);
        const int lines = strstr(err, "restir: pt: 1/3 (33%), ") && strstr(err, "restir: pt: 3/3 (100%), ") &&
                          strstr(err, "s elapsed, ETA ");
        printf("[progress, RESTIR_PROGRESS_SECONDS=%s] exit %d, stderr: %s", values[k] ? values[k] : "(unset)", rc,
               err[0] ? err : "(nothing)\n");
        EXPECT(rc == 0, "render with stderr to a file exited %d: %s", rc, err);
        if (k == 0)
            EXPECT(lines, "RESTIR_PROGRESS_SECONDS=0: no progress line per frame on stderr: %s", err);
        else
            EXPECT(!strstr(err, "elapsed"), "a short render printed progress (RESTIR_PROGRESS_SECONDS=%s): %s",
                   values[k] ? values[k] : "unset", err);
    }
    unsetenv("RESTIR_PROGRESS_SECONDS");
}

/* Scene files: every command that takes --scene refuses a bad one before writing anything. */
static void write_text(const char *path, const char *text)
{
    EXPECT(cli_write_text(path, text) == 0, "cannot write %s", path);
}

static void check_scene_files(void)
{
    char bad[2 * CLI_PATH_MAX], dark[2 * CLI_PATH_MAX], junk[2 * CLI_PATH_MAX], fmt[6 * CLI_PATH_MAX];
    snprintf(bad, sizeof bad, "%s/typo.json", tmp);
    write_text(bad, "{\"camera\": {\"position\": [0, 0, 1], \"look_at\": [0, 0, 0]}, \"shapes\": [],"
                    " \"materails\": []}");
    snprintf(dark, sizeof dark, "%s/dark.obj", tmp);
    write_text(dark, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    snprintf(junk, sizeof junk, "%s/junk.ply", tmp);
    write_text(junk, "ply\nformat nonsense\n");
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --out '%%1$s'", bad);
    expect_failure("JSON scene with an unknown key", fmt, 2, "typo.json", "materails");
    snprintf(fmt, sizeof fmt, "compare --scene '%s' --methods pt --res 16x16 --out '%%1$s'", bad);
    expect_failure("compare of a JSON scene with an unknown key", fmt, 2, "typo.json", "materails");
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --env none --out '%%1$s'", dark);
    expect_failure("mesh file without emitters, --env none", fmt, 2, "dark", "no emitter");
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --out '%%1$s'", junk);
    expect_failure("broken mesh file", fmt, 2, "junk.ply", NULL);
    expect_failure("missing scene file", "render --scene /nonexistent/room.json --method pt --res 16x16 --out '%1$s'",
                   2, "/nonexistent/room.json", NULL);
    expect_failure("scene info of a missing file", "scene info /nonexistent/room.gltf", 2, "/nonexistent/room.gltf",
                   NULL);
    expect_failure("export of an unknown scene", "scene export no-such-scene --out '%1$s'", 2, "no-such-scene", NULL);
    /* A texture that cannot be read: refused by default; scene.missing_textures=warn renders with
     * the factor, saying which file on stderr. */
    char missing[2 * CLI_PATH_MAX], out[3 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(missing, sizeof missing, "%s/missing-texture.json", tmp);
    write_text(missing,
               "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 0.5, 0]},"
               " \"materials\": [{\"name\": \"wall\", \"base_color_texture\": \"no-such-image.png\"},"
               " {\"name\": \"lamp\", \"emission\": [1, 1, 1]}], \"shapes\": ["
               " {\"type\": \"quads\", \"material\": \"wall\", \"quads\": [[[-1, 0, -1], [1, 0, -1], [1, 2, -1], [-1, "
               "2, -1]]]},"
               " {\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[-1, 2, 1], [1, 2, 1], [1, 2, -1], [-1, 2, "
               "-1]]]}]}");
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --out '%%1$s'", missing);
    expect_failure("scene with a missing texture", fmt, 2, "no-such-image.png", "base_color_texture");
    snprintf(fmt, sizeof fmt,
             "render --scene '%s' --method pt --res 16x16 --set scene.missing_textures=warn --out '%s/warned'", missing,
             tmp);
    int rc = cli_run(tmp, fmt, err);
    EXPECT(rc == 0 && strstr(err, "warning") && strstr(err, "no-such-image.png"),
           "scene.missing_textures=warn must render and warn naming the file: exit %d, %s", rc, err);
    snprintf(out, sizeof out, "%s/warned", tmp);
    EXPECT(cli_count_entries(out, "frame_0000.exr") == 1, "the warned render wrote no frame");
    snprintf(fmt, sizeof fmt, "scene info '%s' --set scene.missing_textures=warn", missing);
    EXPECT(cli_run(tmp, fmt, err) == 0 && strstr(err, "no-such-image.png"), "scene info with warn: %s", err);
    /* Animated emitters: bad keys are refused by the reader with the file and the key; a
     * method whose history would keep old lights refuses the scene by name */
    static const struct {
        const char *what, *animation, *material, *key, *why;
    } anim[] = {
        {"keys out of order", "{\"keys\": [{\"frame\": 4, \"strength\": 1}, {\"frame\": 2, \"strength\": 0}]}",
         "lamp", "materials[1].animation.keys[1].frame", "in order"},
        {"a negative strength", "{\"keys\": [{\"frame\": 0, \"strength\": -1}]}", "lamp",
         "materials[1].animation.keys[0].strength", "out of range"},
        {"an animation on a non-emitter", "{\"keys\": [{\"frame\": 0, \"strength\": 1}]}", "wall",
         "materials[0].animation", "emits nothing"},
        {"a whole-animation transform", "{\"keys\": [{\"frame\": 0, \"strength\": 1}], \"transform\": {}}",
         "lamp", "materials[1].animation.transform", "per key"},
        {"a scale key", "{\"keys\": [{\"frame\": 0, \"scale\": [2, 2, 2]}]}", "lamp",
         "materials[1].animation.keys[0].scale", "rigidly"},
        {"a channel missing from a key",
         "{\"keys\": [{\"frame\": 0, \"translate\": [0, 0, 0]}, {\"frame\": 2, \"strength\": 1}]}", "lamp",
         "materials[1].animation.keys[1].strength", "every key"},
        {"a key with no channel", "{\"keys\": [{\"frame\": 0}]}", "lamp", "materials[1].animation.keys[0]",
         "besides its frame"},
        {"a translation out of range", "{\"keys\": [{\"frame\": 0, \"translate\": [0, 1e30, 0]}]}", "lamp",
         "materials[1].animation.keys[0].translate", NULL},
        {"a moving emitter with motion blur", "{\"keys\": [{\"frame\": 0, \"rotate\": [0, 0, 0]}]}", "lamp",
         "camera.shutter", "one instant"},
        {"an unknown interpolation", "{\"keys\": [{\"frame\": 0, \"strength\": 1}], \"interpolation\": \"cubic\"}",
         "lamp", "materials[1].animation.interpolation", "step"},
    };
    for (size_t k = 0; k < sizeof anim / sizeof anim[0]; k++) {
        char file[2 * CLI_PATH_MAX], text[2048], what[128];
        snprintf(file, sizeof file, "%s/animated-%zu.json", tmp, k);
        const int on_wall = !strcmp(anim[k].material, "wall");
        snprintf(text, sizeof text,
                 "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 0.5, 0]},"
                 " \"materials\": [{\"name\": \"wall\"%s%s},"
                 " {\"name\": \"lamp\", \"emission\": [1, 1, 1]%s%s}], \"shapes\": ["
                 " {\"type\": \"quads\", \"material\": \"wall\", \"quads\": [[[-1, 0, -1], [1, 0, -1], [1, 2, -1], [-1, "
                 "2, -1]]]},"
                 " {\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[-1, 2, 1], [1, 2, 1], [1, 2, -1], [-1, 2, "
                 "-1]]]}]}",
                 on_wall ? ", \"animation\": " : "", on_wall ? anim[k].animation : "", on_wall ? "" : ", \"animation\": ",
                 on_wall ? "" : anim[k].animation);
        write_text(file, text);
        snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --out '%%1$s'%s", file,
                 strstr(anim[k].what, "motion blur") ? " --set camera.shutter=0.5" : "");
        snprintf(what, sizeof what, "animated emitter with %s", anim[k].what);
        expect_failure(what, fmt, 2, anim[k].key, anim[k].why);
    }
    /* Environment light: an unreadable --env names the file; every kind of method
     * renders an environment-lit scene. */
    expect_failure("--env of a missing image",
                   "render --scene cornell --method pt --res 16x16 --env /nonexistent/sky.hdr "
                   "--out '%1$s'",
                   2, "/nonexistent/sky.hdr", "--env");
    char sky[2 * CLI_PATH_MAX];
    snprintf(sky, sizeof sky, "%s/sky.json", tmp);
    write_text(sky, "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 1, 3], \"look_at\": [0, 0, 0]},"
                    " \"environment\": {\"color\": [0.5, 0.6, 0.8], \"intensity\": 2},"
                    " \"materials\": [{\"name\": \"ground\", \"base_color\": [0.5, 0.5, 0.5]}],"
                    " \"shapes\": [{\"type\": \"quads\", \"material\": \"ground\", \"quads\": [[[-1, 0, 1], [1, 0, 1], "
                    "[1, 0, -1], [-1, 0, -1]]]}]}");
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method pt --res 16x16 --env none --out '%%1$s'", sky);
    expect_failure("--env none leaving no light", fmt, 2, "--env none", NULL);
    /* ReGIR's cells hold emitter samples: a sky-only scene is refused by the key; grid settings out
     * of range are refused by name */
    snprintf(fmt, sizeof fmt, "render --scene '%s' --method restir-di --res 16x16 --set di.initial=regir --out '%%1$s'",
             sky);
    expect_failure("di.initial=regir without emitters", fmt, 2, "di.initial=regir", "no emissive");
    expect_failure("di.regir_grid out of range",
                   "render --scene cornell --method restir-di --res 16x16 --set di.initial=regir "
                   "--set di.regir_grid=0 --out '%1$s'",
                   2, "di.regir_grid", NULL);
    expect_failure("di.regir_slots out of range",
                   "render --scene cornell --method ris-di --res 16x16 --set di.regir_slots=100000 --out '%1$s'", 2,
                   "di.regir_slots", NULL);
    expect_failure("di.regir_candidates out of range",
                   "render --scene cornell --method restir-di --res 16x16 --set di.regir_candidates=-3 --out '%1$s'",
                   2, "di.regir_candidates", NULL);
    expect_failure("ReGIR's reservoirs past the memory bound",
                   "render --scene cornell --method restir-di --res 1920x1080 --set di.initial=regir "
                   "--set di.regir_grid=64 --set di.regir_slots=1024 --out '%1$s'",
                   2, "di.regir_slots", "GiB");
    const char *methods[] = {"pt", "restir-di", "restir-pt", "grestir-pt"};
    for (int m = 0; m < 4; m++) {
        snprintf(fmt, sizeof fmt, "render --scene '%s' --method %s --res 16x16 --out '%s/sky-%s'", sky, methods[m],
                 tmp, methods[m]);
        EXPECT(cli_run(tmp, fmt, err) == 0, "%s under the scene's environment: %s", methods[m], err);
    }
    /* scene.alpha=off makes the leaf cards of leaves.json opaque, scene.shading_normals=off shades
     * smooth.json flat: other images; on is the default. */
    const char *data = getenv("RESTIR_TEST_DATA");
    const char *const knobs[2][2] = {{"alpha", "leaves"}, {"shading_normals", "smooth"}};
    for (int o = 0; data && o < 2; o++) {
        const char *value[] = {NULL, "on", "off"};
        char frames[3][3 * CLI_PATH_MAX];
        for (int k = 0; k < 3; k++) {
            char set[128] = "";
            if (value[k])
                snprintf(set, sizeof set, "--set scene.%s=%s", knobs[o][0], value[k]);
            snprintf(fmt, sizeof fmt, "render --scene '%s/scenes/%s.json' --method pt --res 24x16 %s --out '%s/%s-%d'",
                     data, knobs[o][1], set, tmp, knobs[o][0], k);
            EXPECT(cli_run(tmp, fmt, err) == 0, "restir %s: %s", fmt, err);
            snprintf(frames[k], sizeof frames[k], "%s/%s-%d/frame_0000.exr", tmp, knobs[o][0], k);
        }
        long size;
        EXPECT(cli_files_equal(frames[0], frames[1], &size) == 1, "scene.%s=on is not the default", knobs[o][0]);
        EXPECT(cli_files_equal(frames[0], frames[2], &size) == 0, "scene.%s=off changed nothing", knobs[o][0]);
    }
}

/* Every deliberately broken file of assimp-testmodels: `restir scene info` exits 1 or 2 with a
 * message naming the file, never crashes (the in-process checks are in tests/unit/test_scene_import.c). */
static void check_broken_assets(void)
{
    static const char *const dirs[] = {"invalid", "glTF2/wrongTypes", "glTF2/IndexOutOfRange", "glTF2/MissingBin",
                                       "glTF2/SchemaFailures", "glTF2/BoxBadNormals-glTF-Binary",
                                       "glTF2/BoxWithInfinites-glTF-Binary"};
    int files = 0;
    for (size_t d = 0; d < sizeof dirs / sizeof dirs[0]; d++) {
        char dir[512];
        snprintf(dir, sizeof dir, "/usr/share/assimp/models/%s", dirs[d]);
        DIR *dp = opendir(dir);
        EXPECT(dp != NULL, "%s is missing (make test installs assimp-testmodels)", dir);
        if (!dp)
            continue;
        struct dirent *e;
        while ((e = readdir(dp)) != NULL) {
            const char *dot = strrchr(e->d_name, '.');
            if (e->d_name[0] == '.' || !dot || !strcmp(dot, ".bin") || !strcmp(dot, ".png") || !strcmp(dot, ".jpg"))
                continue;
            char args[2 * CLI_PATH_MAX], out[CLI_ERR_MAX], err[CLI_ERR_MAX];
            /* --env none: a file assimp reads in part but that has no emitter is refused as before
             * the default sky lit such files */
            snprintf(args, sizeof args, "scene info '%s/%s' --env none", dir, e->d_name);
            int rc = cli_run_capture(tmp, args, out, err);
            files++;
            EXPECT(rc == 1 || rc == 2, "restir %s exited %d (want 1 or 2): %s", args, rc, err);
            EXPECT(strstr(err, e->d_name) != NULL, "restir %s: message does not name the file: %s", args, err);
            EXPECT(strstr(err, "internal error") == NULL, "restir %s hit an internal check", args);
        }
        closedir(dp);
    }
    printf("broken assets: %d files, each refused with exit 1 or 2\n", files);
    EXPECT(files >= 20, "only %d broken asset files found", files);
}

/* Every input fuzzing found (tests/data/fuzz/READER/, docs/FUZZING.md) is refused by the command
 * that reads it with exit 1 or 2 and a message naming the file, never a signal. mesh_import: the
 * crashes are assimp's, caught by scene_import_guard. */
static void check_fuzz_regressions(void)
{
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (!data)
        return;
    char dir[CLI_PATH_MAX];
    snprintf(dir, sizeof dir, "%s/fuzz/mesh_import", data);
    DIR *dp = opendir(dir);
    EXPECT(dp != NULL, "%s is missing", dir);
    if (!dp)
        return;
    int files = 0;
    struct dirent *e;
    while ((e = readdir(dp)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char args[2 * CLI_PATH_MAX], out[CLI_ERR_MAX], err[CLI_ERR_MAX];
        snprintf(args, sizeof args, "scene info '%s/%s'", dir, e->d_name);
        const int rc = cli_run_capture(tmp, args, out, err);
        files++;
        EXPECT((rc == 1 || rc == 2) && strstr(err, e->d_name) && !strstr(err, "internal error"),
               "restir %s: rc %d (want 1 or 2, a message naming the file): %s", args, rc, err);
    }
    closedir(dp);
    EXPECT(files >= 1, "no regression inputs in %s", dir);
}

/* A file assimp reads only in part: `scene info` says what was lost on stderr and on its
 * own line, and scene.strict=on refuses the file with exit 1 or 2, naming it. */
static void check_partial_load(void)
{
    const char *file = "/usr/share/assimp/models/glTF2/IndexOutOfRange/IndexOutOfRange.gltf";
    char args[2 * CLI_PATH_MAX], out[CLI_ERR_MAX], err[CLI_ERR_MAX];
    snprintf(args, sizeof args, "scene info '%s'", file);
    int rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc == 0 && strstr(err, "loads only in part") && strstr(err, "1 of 12 triangles dropped") &&
               strstr(out, "loaded in part:") && strstr(out, "1 of 12 triangles dropped"),
           "restir %s: rc %d, stderr '%s', stdout '%s'", args, rc, err, out);
    snprintf(args, sizeof args, "scene info '%s' --set scene.strict=on", file);
    rc = cli_run_capture(tmp, args, out, err);
    EXPECT((rc == 1 || rc == 2) && strstr(err, file) && strstr(err, "scene.strict=on refuses it"),
           "restir %s: rc %d, '%s'", args, rc, err);
}

int main(void)
{
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    check_settings_per_method();
    check_bad_render_input();
    check_failed_write();
    check_compare();
    check_compare_specs();
    check_study();
    check_scene_files();
    check_broken_assets();
    check_partial_load();
    check_fuzz_regressions();
    check_list_and_help();
    check_option_scope();
    check_progress_lines();
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
