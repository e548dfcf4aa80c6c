/* test_params_replay.c: settings round-trip through files: `restir render --params DIR/summary.json`
 * reruns a run byte for byte (every frame's EXR and PNG), a plain JSON of --set keys equals the
 * same --set options, later options override the file, and bad files are refused by name.
 * Must never call the renderer directly (CLI only). */
#include "cli_util.h"
#include "test_util.h"

static int run(const char *tmp, const char *args)
{
    char err[CLI_ERR_MAX];
    int rc = cli_run(tmp, args, err);
    if (rc != 0)
        printf("restir %s exited %d:\n%s", args, rc, err);
    return rc;
}

/* Every frame file of a 3-frame render equal between dirs a and b. */
static void expect_same_frames(const char *a, const char *b, const char *what)
{
    const char *files[] = {"frame_0000.exr", "frame_0001.exr", "frame_0002.exr", "frame_0002.png"};
    for (int k = 0; k < 4; k++) {
        char fa[2 * CLI_PATH_MAX], fb[2 * CLI_PATH_MAX];
        snprintf(fa, sizeof(fa), "%s/%s", a, files[k]);
        snprintf(fb, sizeof(fb), "%s/%s", b, files[k]);
        long size = 0;
        int same = cli_files_equal(fa, fb, &size);
        EXPECT(same == 1 && size > 1000, "%s: %s %s", what, files[k], same < 0 ? "missing" : "differs");
    }
}

static void write_text(const char *path, const char *text)
{
    EXPECT(cli_write_text(path, text) == 0, "cannot write %s", path);
}

int main(void)
{
    char tmp[CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        printf("RESTIR_BIN is not set or no temporary folder\n");
        return 1;
    }
    char a[CLI_PATH_MAX + 32], b[CLI_PATH_MAX + 32], c[CLI_PATH_MAX + 32], d[CLI_PATH_MAX + 32], e[CLI_PATH_MAX + 32];
    char args[8 * CLI_PATH_MAX], path[2 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    snprintf(a, sizeof(a), "%s/original", tmp);
    snprintf(b, sizeof(b), "%s/replayed", tmp);
    snprintf(c, sizeof(c), "%s/plain", tmp);
    snprintf(d, sizeof(d), "%s/plain-file", tmp);
    snprintf(e, sizeof(e), "%s/overridden", tmp);

    /* Non-default settings of every kind: names, floats with more digits than %g shows, counts,
     * booleans, a shorthand (spatial.preset), a camera path, another seed and resolution. */
    snprintf(args, sizeof(args),
             "render --scene cornell --method restir-pt --res 40x24 --frames 3 --camera path --seed 7 "
             "--set spatial.preset=balanced --set spatial.radius=17.123457 --set mis=balance "
             "--set shift=reconnection --set temporal.normal=0.7654321 --set pt.max_bounces=4 --out '%s'",
             a);
    EXPECT(run(tmp, args) == 0, "original render failed");
    snprintf(path, sizeof(path), "%s/summary.json", a);
    char summary[16384];
    cli_read_text(path, summary, sizeof(summary));
    EXPECT(strstr(summary, "\"provenance\"") && strstr(summary, "\"version\"") && strstr(summary, "\"commit\""),
           "summary.json does not say which build ran:\n%s", summary);
    EXPECT(strstr(summary, "\"settings\"") && strstr(summary, "\"spatial.radius\":\t17.123457") &&
               strstr(summary, "\"spatial.select\":\t\"compat\"") && strstr(summary, "\"biased\":\t\"\""),
           "summary.json does not record the settings:\n%s", summary);
    /* With nothing but the summary. */
    snprintf(args, sizeof(args), "render --params '%s/summary.json' --out '%s'", a, b);
    EXPECT(run(tmp, args) == 0, "replay from summary.json failed");
    expect_same_frames(a, b, "--params summary.json");

    /* A plain object of --set keys equals the same --set options. */
    snprintf(path, sizeof(path), "%s/settings.json", tmp);
    write_text(path, "{\"mis\": \"balance\", \"spatial.radius\": 12.5, \"temporal\": false, \"spmis.candidates\": \"M\","
                     " \"spatial.reuse\": \"spmis\"}");
    snprintf(args, sizeof(args),
             "render --scene foliage --method restir-di --res 40x24 --frames 3 --camera path --set mis=balance "
             "--set spatial.radius=12.5 --set temporal=off --set spmis.candidates=M --set spatial.reuse=spmis "
             "--out '%s'",
             c);
    EXPECT(run(tmp, args) == 0, "render with --set failed");
    snprintf(args, sizeof(args),
             "render --scene foliage --method restir-di --res 40x24 --frames 3 --camera path --params '%s' "
             "--out '%s'",
             path, d);
    EXPECT(run(tmp, args) == 0, "render with a settings file failed");
    expect_same_frames(c, d, "plain settings file");

    /* Options after --params override the file: the summary with the original's seed given again
     * is the original, with another seed it is not. */
    snprintf(args, sizeof(args), "render --params '%s/summary.json' --seed 8 --out '%s'", a, e);
    EXPECT(run(tmp, args) == 0, "replay with --seed failed");
    char fa[2 * CLI_PATH_MAX], fe[2 * CLI_PATH_MAX];
    snprintf(fa, sizeof(fa), "%s/frame_0002.exr", a);
    snprintf(fe, sizeof(fe), "%s/frame_0002.exr", e);
    long size = 0;
    EXPECT(cli_files_equal(fa, fe, &size) == 0, "--seed after --params was ignored");
    snprintf(path, sizeof(path), "%s/summary.json", e);
    cli_read_text(path, summary, sizeof(summary));
    EXPECT(strstr(summary, "\"seed\":\t8"), "the overridden run's summary does not say seed 8");

    /* BIASED settings are listed in the summary. */
    snprintf(args, sizeof(args),
             "render --scene cornell --method restir-di --res 16x16 --set mis=1/M --set temporal.ratio_guard=on "
             "--out '%s/biased'",
             tmp);
    EXPECT(run(tmp, args) == 0, "biased render failed");
    snprintf(path, sizeof(path), "%s/biased/summary.json", tmp);
    cli_read_text(path, summary, sizeof(summary));
    EXPECT(strstr(summary, "\"biased\":\t\"mis=1/M, temporal.ratio_guard=on\""), "biased settings not listed:\n%s",
           summary);

    /* Bad files: named, exit 2, nothing written. */
    struct {
        const char *text, *expect;
    } bad[] = {
        {"{\"no.such.key\": 1}", "no.such.key"},
        {"{\"spatial.radius\": -3}", "spatial.radius"},
        {"{\"mis\": [1, 2]}", "\"mis\" must be"},
        {"[1, 2, 3]", "not a JSON object"},
        {"{\"settings\": 4}", "\"settings\" must be an object"},
        {"{\"settings\": {}, \"width\": 0}", "width"},
        {"{\"settings\": {}, \"frames\": 2.5}", "frames"},
        {"{\"spatial.radius\": 1e999}", "spatial.radius"},
    };
    for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
        snprintf(path, sizeof(path), "%s/bad%zu.json", tmp, k);
        write_text(path, bad[k].text);
        snprintf(args, sizeof(args), "render --scene cornell --method pt --res 16x16 --params '%s' --out '%s/bad%zu'",
                 path, tmp, k);
        int rc = cli_run(tmp, args, err);
        EXPECT(rc == 2 && strstr(err, bad[k].expect) && strstr(err, path), "%s: exit %d, stderr: %s", bad[k].text,
               rc, err);
        char out[2 * CLI_PATH_MAX];
        snprintf(out, sizeof(out), "%s/bad%zu", tmp, k);
        EXPECT(cli_count_entries(out, "") == -1, "%s: output written", bad[k].text);
    }
    snprintf(args, sizeof(args), "render --scene cornell --method pt --params '%s/missing.json'", tmp);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 2 && strstr(err, "missing.json"), "missing file: exit %d, %s", rc, err);
    if (test_failed_count == 0)
        cli_remove_tree(tmp);
    return test_finish();
}
