/* test_denoise.c: the denoisers through the command line: SVGF lowers restir-di's relMSE
 * on many-lights at least 3x against the same reference (compare, 320x180, 16 frames, two seeds);
 * the raw frame of a denoised render is byte for byte the frame rendered without --denoise; a method
 * without a G-buffer of its own (pt) is denoised through one traced for it; a study measures its
 * statistics after denoising, planned and merged as unsplit; bad values are refused by name with
 * exit 2 and nothing written. */
#include <math.h>
#include <string.h>

#include "render/cli_util.h"
#include "test_util.h"

#define DIR_MAX (4 * CLI_PATH_MAX)

/* Row 1's value of column name in dir/compare.csv (NaN when absent). */
static double compare_value(const char *dir, const char *name)
{
    static char csv[CLI_ERR_MAX];
    char path[DIR_MAX + 32];
    snprintf(path, sizeof path, "%s/compare.csv", dir);
    cli_read_text(path, csv, sizeof csv);
    const int col = cli_csv_column(csv, name);
    const char *row = cli_next_line(csv);
    return col >= 0 && row ? cli_csv_number(row, col) : NAN;
}

int main(void)
{
    char tmp[CLI_PATH_MAX], dir[DIR_MAX], other[DIR_MAX], args[8 * CLI_PATH_MAX], err[CLI_ERR_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    /* 1. 3x lower relMSE after SVGF, for two seeds */
    for (int seed = 1; seed <= 2; seed++) {
        snprintf(dir, sizeof dir, "%s/compare%d", tmp, seed);
        snprintf(args, sizeof args,
                 "compare --scene many-lights --methods restir-di --res 320x180 --frames 16 --ref-spp 256 --seed %d "
                 "--denoise svgf --out '%s'",
                 seed, dir);
        int rc = cli_run(tmp, args, err);
        EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
        const double raw = compare_value(dir, "relmse"), dn = compare_value(dir, "relmse_denoised");
        const double mape = compare_value(dir, "mape"), mape_dn = compare_value(dir, "mape_denoised");
        printf("seed %d: relMSE %g raw, %g after SVGF (%.2fx); MAPE %g, %g\n", seed, raw, dn, raw / dn, mape, mape_dn);
        EXPECT(isfinite(raw) && isfinite(dn) && dn > 0.0 && raw >= 3.0 * dn,
               "seed %d: relMSE after SVGF %g is not 3x below the raw %g", seed, dn, raw);
    }
    /* 2. the raw frame is the frame rendered without denoising, byte for byte */
    snprintf(dir, sizeof dir, "%s/denoised", tmp);
    snprintf(other, sizeof other, "%s/plain", tmp);
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "render --scene cornell --method restir-pt --res 64x36 --frames 3 --seed 4 "
                                    "--out '%s'%s", k ? other : dir, k ? "" : " --denoise svgf");
        int rc = cli_run(tmp, args, err);
        EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    }
    char a[DIR_MAX + 40], b[DIR_MAX + 40];
    for (int f = 0; f < 3; f++) {
        snprintf(a, sizeof a, "%s/frame_%04d.exr", dir, f);
        snprintf(b, sizeof b, "%s/frame_%04d.exr", other, f);
        long size = 0;
        EXPECT(cli_files_equal(a, b, &size) == 1 && size > 0, "%s differs from %s", a, b);
    }
    EXPECT(cli_count_entries(dir, "_denoised.") == 6 && cli_count_entries(other, "_denoised.") == 0,
           "denoised files: %d with --denoise, %d without", cli_count_entries(dir, "_denoised."),
           cli_count_entries(other, "_denoised."));
    snprintf(a, sizeof a, "%s/summary.json", dir);
    cli_read_text(a, err, sizeof err);
    EXPECT(strstr(err, "\"denoised\"") && strstr(err, "BIASED"), "summary.json says nothing of the denoised layer");
    /* 3. pt keeps no G-buffer: one is traced for the denoiser */
    snprintf(dir, sizeof dir, "%s/pt", tmp);
    snprintf(args, sizeof args, "render --scene cornell --method pt --res 64x36 --frames 2 --denoise atrous --out '%s'",
             dir);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0 && cli_count_entries(dir, "_denoised.") == 4, "restir %s exited %d:\n%s", args, rc, err);
    /* 4. a study after denoising: its table, plot and rank correlations, planned and merged as unsplit */
    const char *study = "study --scene cornell --method restir-di --configs bitterli,fast,spatial-off --res 48x27 "
                        "--runs 3 --warmup 2 --frames 4 --ref-spp 16 --denoise svgf";
    snprintf(dir, sizeof dir, "%s/study", tmp);
    snprintf(other, sizeof other, "%s/study_plan", tmp);
    snprintf(args, sizeof args, "%s --out '%s'", study, dir);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    snprintf(args, sizeof args, "%s --plan '%s'", study, other);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    for (int k = 1; k <= 10 && rc == 0; k++) { /* the reference and 3 x 3 units */
        snprintf(args, sizeof args, "job '%s' %d", other, k);
        rc = cli_run(tmp, args, err);
        EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    }
    snprintf(args, sizeof args, "study --merge '%s'", other);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d:\n%s", args, rc, err);
    static char ta[CLI_ERR_MAX], tb[CLI_ERR_MAX];
    snprintf(a, sizeof a, "%s/study_denoised.csv", dir);
    snprintf(b, sizeof b, "%s/study_denoised.csv", other);
    cli_read_text(a, ta, sizeof ta);
    cli_read_text(b, tb, sizeof tb);
    EXPECT(ta[0] && !strcmp(ta, tb), "merged study_denoised.csv differs from the unsplit one:\n%s\nvs\n%s", ta, tb);
    EXPECT(strstr(ta, "\nbitterli,") && strstr(ta, "\nfast,") && strstr(ta, "\nspatial-off,"), "rows: %s", ta);
    snprintf(a, sizeof a, "%s/study_denoised.md", dir);
    cli_read_text(a, ta, sizeof ta);
    EXPECT(strstr(ta, "rank correlation") != NULL, "%s: %.200s", a, ta);
    EXPECT(cli_count_entries(dir, "pareto_denoised.svg") == 1, "no pareto_denoised.svg in %s", dir);
    /* 5. bad values: exit 2, the key named, nothing written */
    const char *bad[][2] = {{"--denoise bilateral", "denoise"},
                            {"--set denoise=svgf --set denoise.svgf.feedback=6", "denoise.svgf.feedback"},
                            {"--set denoise.svgf.alpha=0", "denoise.svgf.alpha"}};
    for (int k = 0; k < 3; k++) {
        snprintf(dir, sizeof dir, "%s/bad%d", tmp, k);
        snprintf(args, sizeof args, "render --scene cornell --method restir-di --res 64x36 %s --out '%s'", bad[k][0],
                 dir);
        rc = cli_run(tmp, args, err);
        EXPECT(rc == 2 && strstr(err, bad[k][1]), "restir %s: exit %d, want 2 naming %s:\n%s", args, rc, bad[k][1],
               err);
        EXPECT(cli_count_entries(tmp, dir + strlen(tmp) + 1) == 0, "restir %s made %s", args, dir);
    }
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
