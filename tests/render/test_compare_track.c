/* test_compare_track.c: `restir compare` along a sequence (--ref-every, --runs; app/compare_track.c).
 * frames.csv holds one row per spec and frame, with errors exactly at frames K-1, 2K-1, ... and the
 * last (each against its own reference file), and its last-frame errors are compare.csv's; run 0
 * of --runs N writes the frame a single run writes, byte for byte; 000's autocovariance (Eq. 17)
 * is near 0 for pt, whose frames are independent, and clearly positive for restir-pt, whose
 * reservoirs carry history; splat rows count splats and no backprojection; the standard errors of
 * --runs are those of the runs' errors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "test_util.h"

#define COMMON "compare --scene cornell --camera path --res 24x16 --frames 12 --ref-spp 16 --seed 5 --threads 1"
#define SPECS "restir-pt,restir-pt:temporal.reuse=splat,pt"

static char tmp[CLI_PATH_MAX];

/* The four values (raw and denoised after each of two changes) of the rows restir-di and
 * restir-di:denoise.svgf.temporal_gradient=on of compare's table titled `title` in out (NaN where absent). */
static void gradient_rows(const char *out, const char *title, double v[2][4])
{
    const char *table = strstr(out, title);
    for (int k = 0; k < 2; k++) {
        v[k][0] = v[k][1] = v[k][2] = v[k][3] = NAN;
        const char *row = table ? strstr(table, k ? "\nrestir-di:denoise.svgf.temporal_gradient=on " : "\nrestir-di ")
                                : NULL;
        if (row)
            sscanf(strchr(row + 1, ' '), "%lf %lf %lf %lf", &v[k][0], &v[k][1], &v[k][2], &v[k][3]);
    }
}

/* Field `col` (0-based) of a CSV line without quoted fields, into out (empty when missing). */
static void field(const char *line, int col, char *out, size_t n)
{
    out[0] = '\0';
    for (int c = 0; c < col && line; c++) {
        line = strchr(line, ',');
        line = line ? line + 1 : NULL;
    }
    if (!line)
        return;
    size_t len = strcspn(line, ",\n");
    if (len >= n)
        len = n - 1;
    memcpy(out, line, len);
    out[len] = '\0';
}

/* The line of csv that starts with `prefix` (NULL when none). */
static const char *row(const char *csv, const char *prefix)
{
    size_t len = strlen(prefix);
    for (const char *l = csv; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL)
        if (!strncmp(l, prefix, len))
            return l;
    return NULL;
}

static double number(const char *line, int col)
{
    char f[64];
    field(line, col, f, sizeof f);
    return f[0] ? strtod(f, NULL) : NAN;
}

int main(void)
{
    static char csv[CLI_ERR_MAX], frames[4 * CLI_ERR_MAX];
    char dir[2 * CLI_PATH_MAX], one[2 * CLI_PATH_MAX], args[8 * CLI_PATH_MAX], path[3 * CLI_PATH_MAX],
        path2[3 * CLI_PATH_MAX], err[CLI_ERR_MAX], prefix[128], a[64], b[64];
    if (cli_make_temp_dir(tmp) != 0)
        return test_skip("cannot create a temporary folder");
    snprintf(dir, sizeof dir, "%s/runs", tmp);
    snprintf(args, sizeof args, COMMON " --runs 4 --ref-every 4 --methods " SPECS " --out '%s'", dir);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "compare --runs 4 --ref-every 4 exited %d: %s", rc, err);

    /* references: frames 3 and 7 on their own, frame 11 is the comparison's reference.exr with its two halves */
    EXPECT(cli_count_entries(dir, "reference") == 5,
           "want reference.exr, reference.half_a.exr, reference.half_b.exr, reference_0003.exr, reference_0007.exr");
    snprintf(path, sizeof path, "%s/reference_0003.exr", dir);
    EXPECT(cli_count_entries(dir, "reference_0003.exr") == 1 && cli_count_entries(dir, "reference_0007.exr") == 1,
           "no %s or its frame-7 sibling", path);

    snprintf(path, sizeof path, "%s/compare.csv", dir);
    cli_read_text(path, csv, sizeof csv);
    snprintf(path, sizeof path, "%s/frames.csv", dir);
    cli_read_text(path, frames, sizeof frames);
    EXPECT(!strncmp(frames, "method,frame,runs,ms_frame,ms_temporal,temporal_accept,bp_received,bp_accepted,"
                            "splat_received,splat_accepted,relmse,mape,smape,luma_rmse\n", 120),
           "frames.csv header: %.200s", frames);
    const char *specs[] = {"restir-pt", "restir-pt:temporal.reuse=splat", "pt"};
    double tcov[3];
    for (int k = 0; k < 3; k++) {
        for (int f = 0; f < 12; f++) {
            snprintf(prefix, sizeof prefix, "%s,%d,4,", specs[k], f);
            const char *l = row(frames, prefix);
            EXPECT(l != NULL, "frames.csv has no row %s", prefix);
            if (!l)
                continue;
            const int measured = f == 3 || f == 7 || f == 11;
            field(l, 11, a, sizeof a);
            EXPECT(measured == (a[0] != '\0'), "%s: MAPE '%s' where %s", prefix, a, measured ? "wanted" : "none wanted");
            if (measured)
                EXPECT(number(l, 11) > 0.0 && number(l, 11) < 5.0, "%s: MAPE %g", prefix, number(l, 11));
            EXPECT(number(l, 3) > 0.0, "%s: frame time %g", prefix, number(l, 3));
            if (k == 1 && f > 0)
                EXPECT(number(l, 8) > 0.5 && number(l, 6) == 0.0,
                       "%s: splat rows must receive splats (%g) and no backprojection (%g)", prefix, number(l, 8),
                       number(l, 6));
            if (k == 0 && f > 0)
                EXPECT(number(l, 6) > 0.5 && number(l, 8) == 0.0, "%s: backproject shares %g / splat %g", prefix,
                       number(l, 6), number(l, 8));
            if (f == 11) { /* the last frame's errors are compare.csv's, as written */
                snprintf(prefix, sizeof prefix, "\n%s,", specs[k]);
                const char *c = strstr(csv, prefix);
                EXPECT(c != NULL, "compare.csv has no row %s", specs[k]);
                for (int col = 0; c && col < 4; col++) {
                    field(c + 1, 4 + col, a, sizeof a);
                    field(l, 10 + col, b, sizeof b);
                    EXPECT(!strcmp(a, b), "%s: compare.csv column %d '%s', frames.csv '%s'", specs[k], 4 + col, a, b);
                }
                tcov[k] = c ? number(c + 1, 9) : NAN;
                EXPECT(c && number(c + 1, 8) == 4.0, "%s: runs column", specs[k]);
            }
        }
    }
    printf("temporal autocovariance (lag 3, frames 6-11, 4 runs): restir-pt %.4f, splat %.4f, pt %.4f\n", tcov[0],
           tcov[1], tcov[2]);
    EXPECT(fabs(tcov[2]) < 0.03, "pt's frames are independent: autocovariance %g", tcov[2]);
    EXPECT(tcov[0] > 0.03 && tcov[0] > 3.0 * fabs(tcov[2]), "restir-pt carries history: %g (pt %g)", tcov[0], tcov[2]);
    EXPECT(tcov[1] > 0.03, "splat carries history: %g", tcov[1]);

    /* run 0 is the single run: same frame, bytes and all; a single run has no autocovariance */
    snprintf(one, sizeof one, "%s/one", tmp);
    snprintf(args, sizeof args, COMMON " --methods " SPECS " --ref '%s/reference.exr' --out '%s'", dir, one);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "single run exited %d: %s", rc, err);
    for (int k = 0; k < 2; k++) {
        const char *folder = k ? "restir-pt_temporal.reuse_splat" : "restir-pt";
        snprintf(path, sizeof path, "%s/%s/frame_0011.exr", dir, folder);
        snprintf(path2, sizeof path2, "%s/%s/frame_0011.exr", one, folder);
        long size = 0;
        EXPECT(cli_files_equal(path, path2, &size) == 1 && size > 0, "run 0's %s differs from the single run's",
               folder);
    }
    snprintf(path, sizeof path, "%s/compare.csv", one);
    cli_read_text(path, csv, sizeof csv);
    const char *c = strstr(csv, "\nrestir-pt,");
    field(c ? c + 1 : "", 9, a, sizeof a);
    EXPECT(c && number(c + 1, 8) == 1.0 && a[0] == '\0', "a single run: runs 1, no temporal_cov ('%s')", a);
    field(c ? c + 1 : "", 10, a, sizeof a);
    EXPECT(c && a[0] == '\0', "a single run has no standard error ('%s')", a);
    const double x0[4] = {c ? number(c + 1, 4) : NAN, c ? number(c + 1, 5) : NAN, c ? number(c + 1, 6) : NAN,
                          c ? number(c + 1, 13) : NAN};
    /* 004 Sec. 6.2's disocclusion columns: a share in (0, 1) and a MAPE for restir-pt along the
     * camera path; nothing for pt, which keeps no G-buffer history. */
    const double share = c ? number(c + 1, 15) : NAN;
    printf("single run: restir-pt disoccluded share %.4f, MAPE there %.4f (all pixels %.4f)\n", share, x0[3], x0[1]);
    EXPECT(share > 0.0 && share < 1.0 && x0[3] > 0.0, "restir-pt: disoccluded share %g, MAPE %g", share, x0[3]);
    const char *pt_row = strstr(csv, "\npt,");
    field(pt_row ? pt_row + 1 : "", 13, a, sizeof a);
    field(pt_row ? pt_row + 1 : "", 15, b, sizeof b);
    EXPECT(pt_row && a[0] == '\0' && b[0] == '\0', "pt has no disocclusion columns ('%s', '%s')", a, b);
    /* the reference's own MAPE over those pixels (its halves), against which a disocclusion claim is
     * checked: positive for restir-pt, nothing for pt */
    const double own_dis = c ? number(c + 1, 37) : NAN;
    printf("the reference's own MAPE over restir-pt's disoccluded pixels: %.4f\n", own_dis);
    EXPECT(own_dis > 0.0 && isfinite(own_dis), "restir-pt: ref_mape_disoccluded %g", own_dis);
    field(pt_row ? pt_row + 1 : "", 37, a, sizeof a);
    EXPECT(pt_row && a[0] == '\0', "pt has no ref_mape_disoccluded ('%s')", a);

    /* --runs 2: run 0 is the single run (x0), so the mean m and the standard error of two runs,
     * |x1 - x0| / 2, must satisfy sem = |m - x0| for relMSE, MAPE and SMAPE. */
    char two[2 * CLI_PATH_MAX];
    snprintf(two, sizeof two, "%s/two", tmp);
    snprintf(args, sizeof args, COMMON " --methods restir-pt --runs 2 --ref '%s/reference.exr' --out '%s'", dir, two);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "compare --runs 2 exited %d: %s", rc, err);
    snprintf(path, sizeof path, "%s/compare.csv", two);
    cli_read_text(path, csv, sizeof csv);
    EXPECT(strstr(csv, "temporal_cov,relmse_sem,mape_sem,smape_sem,mape_disoccluded,mape_disoccluded_sem,"
                       "disoccluded_share,gradient_relmse,gradient_relmse_sem,gradient_relmse_trim1,"
                       "gradient_relmse_trim1_sem,gradient_mape,gradient_mape_sem,relmse_denoised,relmse_denoised_sem,"
                       "mape_denoised,mape_denoised_sem,smape_denoised,smape_denoised_sem,mape_disoccluded_denoised,"
                       "mape_disoccluded_denoised_sem,temporal_cov_denoised,ref_relmse,ref_mape,ref_smape,relmse_net,flip,"
                       "flip_sem,ref_mape_disoccluded,flicker1,flicker4,flicker16,boiling_index,flicker1_denoised,"
                       "flicker4_denoised,flicker16_denoised,boiling_index_denoised,lag_frames,lag_frames_denoised,"
                       "lag_frames_blocks,lag_frames_blocks_denoised,ghost_frames,ghost_frames_denoised\n") !=
               NULL,
           "compare.csv header: %.300s", csv);
    c = strstr(csv, "\nrestir-pt,");
    static const int mean_col[4] = {4, 5, 6, 13}, sem_col[4] = {10, 11, 12, 14};
    for (int k = 0; k < 4; k++) {
        const double m = c ? number(c + 1, mean_col[k]) : NAN, sem = c ? number(c + 1, sem_col[k]) : NAN;
        const double want = fabs(m - x0[k]), tol = 2e-5 * (fabs(m) + fabs(x0[k])) + 1e-5 * want;
        printf("--runs 2, metric %d: mean %.6g, run 0 %.6g, standard error %.6g (want %.6g)\n", k, m, x0[k], sem, want);
        EXPECT(fabs(sem - want) <= tol && want > 0.0, "metric %d: standard error %g, |mean - run 0| = %g", k, sem, want);
    }
    /* flicker: a moving camera's rows leave it empty; a static camera's pt row has it, with
     * 16 px block means flickering far less than pixels (independent noise: about 1/256) */
    field(c ? c + 1 : "", 38, a, sizeof a);
    EXPECT(c && a[0] == '\0', "a moving camera has no flicker ('%s')", a);
    char still[2 * CLI_PATH_MAX];
    snprintf(still, sizeof still, "%s/still", tmp);
    snprintf(args, sizeof args,
             "compare --scene cornell --res 32x32 --frames 8 --ref-spp 8 --seed 5 --threads 1 --methods pt,restir-di "
             "--out '%s'", still);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "compare with a static camera exited %d: %s", rc, err);
    snprintf(path, sizeof path, "%s/compare.csv", still);
    cli_read_text(path, csv, sizeof csv);
    for (int k = 0; k < 2; k++) {
        const char *row = strstr(csv, k ? "\nrestir-di," : "\npt,");
        const double f1 = row ? number(row + 1, 38) : NAN, f4 = row ? number(row + 1, 39) : NAN;
        const double f16 = row ? number(row + 1, 40) : NAN, bi = row ? number(row + 1, 41) : NAN;
        printf("static camera, %s: flicker %.4g %.4g %.4g, boiling index %.3g\n", k ? "restir-di" : "pt", f1, f4, f16,
               bi);
        EXPECT(f1 > 0.0 && f4 > 0.0 && f4 < f1 && f16 > 0.0 && f16 < f4, "%s: flicker %g %g %g", k ? "restir-di" : "pt",
               f1, f4, f16);
        EXPECT(fabs(bi - 256.0 * f16 / f1) <= 1e-4 * bi, "%s: boiling index %g is not 256 flicker16 / flicker1",
               k ? "restir-di" : "pt", bi);
    }
    /* lag: an animated scene's lights change at frames 2, 5 and 6 (switch_lamp.json); with a
     * reference at every frame the segment after frame 6 (6 frames) has a lag in [0, 6], the shorter
     * ones none */
    const char *data = getenv("RESTIR_TEST_DATA");
    char lagdir[2 * CLI_PATH_MAX];
    static char out[CLI_ERR_MAX];
    snprintf(lagdir, sizeof lagdir, "%s/lag", tmp);
    snprintf(args, sizeof args,
             "compare --scene '%s/scenes/switch_lamp.json' --res 24x16 --frames 12 --ref-every 1 --ref-spp 8 --seed 5 "
             "--threads 1 --methods pt,restir-di --out '%s'",
             data ? data : ".", lagdir);
    rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc == 0, "compare of an animated scene exited %d: %s", rc, err);
    EXPECT(strstr(out, "after frame   2") && strstr(out, "after frame   6") && strstr(out, "lag of 16 px blocks"),
           "no lag tables: %s", out);
    snprintf(path, sizeof path, "%s/compare.csv", lagdir);
    cli_read_text(path, csv, sizeof csv);
    for (int k = 0; k < 2; k++) {
        const char *row = strstr(csv, k ? "\nrestir-di," : "\npt,");
        const double lag = row ? number(row + 1, 46) : NAN, block = row ? number(row + 1, 48) : NAN;
        printf("animated scene, %s: lag_frames %g, lag_frames_blocks %g\n", k ? "restir-di" : "pt", lag, block);
        EXPECT(lag >= 0.0 && lag <= 6.0, "%s: lag_frames %g, want a whole number of frames in [0, 6]",
               k ? "restir-di" : "pt", lag);
        /* 24 x 16 holds one whole 16 px block: its lag, also in [0, 6] (unit.compare_track_lag checks the
         * blocks' quantile) */
        EXPECT(block >= 0.0 && block <= 6.0 && block == floor(block), "%s: lag_frames_blocks %g",
               k ? "restir-di" : "pt", block);
    }
    /* A-SVGF (denoise.svgf.temporal_gradient): on switch_room.json (a lamp off at 16, on at 32) the
     * denoised frames settle sooner with the gradient where the raw frames allow it. Measured at 48x36
     * (compare's lag table, per change: raw after 16 and 32, denoised after 16 and 32): without the
     * gradient 13 2 13 3, with it 13 2 13 0 (pool candidates, di.initial=auto's choice at this size);
     * 11 2 13 3 and 11 2 9 0 with di.initial=regir. After the switch-off restir-di's raw frames stay
     * noisy for 11-13 frames (their histories keep confidence 20 though their samples died), which no
     * denoiser can beat; after the switch-on the gradient drops SVGF's stale history at once. */
    snprintf(lagdir, sizeof lagdir, "%s/asvgf", tmp);
    snprintf(args, sizeof args,
             "compare --scene '%s/scenes/switch_room.json' --res 48x36 --frames 40 --ref-every 1 --ref-spp 16 --seed 5 "
             "--threads 1 --set denoise=svgf --methods restir-di,restir-di:denoise.svgf.temporal_gradient=on "
             "--out '%s'",
             data ? data : ".", lagdir);
    rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc == 0, "compare with the temporal gradient exited %d: %s", rc, err);
    double lags[2][4];
    gradient_rows(out, "\nlag: frames", lags);
    printf("switch_room, denoised lag after the switch-off and the switch-on: %g %g without the temporal gradient, "
           "%g %g with it\n",
           lags[0][2], lags[0][3], lags[1][2], lags[1][3]);
    EXPECT(lags[1][3] >= 0.0 && lags[1][3] < lags[0][3] && lags[1][2] <= lags[0][2],
           "denoised lags %g %g with the gradient, %g %g without: not shorter after the switch-on, or longer after "
           "the switch-off",
           lags[1][2], lags[1][3], lags[0][2], lags[0][3]);
    /* The ghost (how long the old light shows in the 16 px blocks' means, apart from noise and the
     * denoiser's bias): measured at 48x36, raw 6 0, denoised 11 4 without the gradient and 0 0 with it
     * (at 160x120, 2 runs: denoised 11 10 and 0 0, docs/BENCHMARKS.md) */
    double ghosts[2][4];
    gradient_rows(out, "\nghost: frames", ghosts);
    printf("switch_room, denoised ghost after the switch-off and the switch-on: %g %g without the temporal gradient, "
           "%g %g with it\n",
           ghosts[0][2], ghosts[0][3], ghosts[1][2], ghosts[1][3]);
    EXPECT(ghosts[1][2] >= 0.0 && ghosts[1][2] < ghosts[0][2] && ghosts[1][3] >= 0.0 && ghosts[1][3] < ghosts[0][3],
           "denoised ghosts %g %g with the gradient, %g %g without: not shorter after both changes", ghosts[1][2],
           ghosts[1][3], ghosts[0][2], ghosts[0][3]);
    snprintf(lagdir, sizeof lagdir, "%s/asvgf-still", tmp);
    snprintf(args, sizeof args,
             "compare --scene cornell --res 32x24 --frames 6 --ref-spp 8 --seed 5 --threads 1 --set denoise=svgf "
             "--methods restir-di,restir-di:denoise.svgf.temporal_gradient=on --out '%s'",
             lagdir);
    rc = cli_run_capture(tmp, args, out, err);
    EXPECT(rc == 0, "compare of a still scene with the temporal gradient exited %d: %s", rc, err);
    snprintf(path, sizeof path, "%s/restir-di/frame_0005_denoised.exr", lagdir);
    snprintf(path2, sizeof path2, "%s/restir-di_denoise.svgf.temporal_gradient_on/frame_0005_denoised.exr", lagdir);
    long size = 0;
    EXPECT(cli_files_equal(path, path2, &size) == 1 && size > 0,
           "a still scene's denoised frame changes with the temporal gradient");
    cli_remove_tree(tmp);
    return test_finish();
}
