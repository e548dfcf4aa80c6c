/* test_study.c: `restir study` runs end to end on a tiny image and writes what 000's study needs:
 * study.csv with the documented header and one row per configuration (named ones plus bitterli
 * and compat per radius) holding finite, sensible values, study.md, pareto.svg with both curves,
 * hard_pixels.png and strip.png. Must never call the renderer directly (CLI only). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "test_util.h"

static long file_size(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

static char *read_text(const char *path)
{
    long n = file_size(path);
    if (n < 0)
        return NULL;
    FILE *f = fopen(path, "rb");
    char *buf = calloc((size_t)n + 1, 1);
    if (f && buf && fread(buf, 1, (size_t)n, f) != (size_t)n)
        buf[0] = '\0';
    if (f)
        fclose(f);
    return buf;
}

/* The point labels (radii) of the polyline drawn in color, in order, each followed by a comma. */
static void pareto_labels(const char *svg, const char *color, char *out, size_t len)
{
    out[0] = '\0';
    char key[64], fill[64];
    snprintf(key, sizeof key, "<polyline fill=\"none\" stroke=\"%s\"", color);
    snprintf(fill, sizeof fill, "fill=\"%s\"", color);
    const char *p = svg ? strstr(svg, key) : NULL;
    const char *end = p ? strstr(p + 1, "<polyline") : NULL;
    size_t used = 0;
    while (p && (p = strstr(p + 1, "<text")) && (!end || p < end)) {
        const char *gt = strchr(p, '>'), *lt = gt ? strchr(gt, '<') : NULL;
        if (!lt)
            break;
        const char *f = strstr(p, fill);
        if (!f || f > gt) /* not a point label of this curve (the legend's text has no fill) */
            continue;
        used += (size_t)snprintf(out + used, len > used ? len - used : 0, "%.*s,", (int)(lt - gt - 1), gt + 1);
        if (used >= len)
            break;
    }
}

int main(void)
{
    char tmp[CLI_PATH_MAX], out[2 * CLI_PATH_MAX], args[4 * CLI_PATH_MAX], err[CLI_ERR_MAX], path[3 * CLI_PATH_MAX];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    snprintf(out, sizeof(out), "%s/study", tmp);
    snprintf(args, sizeof(args),
             "study --scene cornell --method restir-pt --configs bitterli,fast,compat-binary,bitterli-r6 --radii 4,8 --runs 3 "
             "--warmup 2 --frames 5 --res 32x18 --ref-spp 16 --set pt.max_bounces=2 --out '%s'",
             out);
    int rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d: %s", args, rc, err);

    snprintf(path, sizeof(path), "%s/study.csv", out);
    char *csv = read_text(path);
    EXPECT(csv != NULL, "no %s", path);
    if (csv) {
        const char *header = "config,radius,K,M,smape_all,smape_hard,temporal_cov,spatial_cov,ms_select,ms_spatial,"
                             "ms_frame,smape_all_sem,smape_hard_sem,temporal_cov_sem,spatial_cov_sem,temporal_cov_hard,"
                             "temporal_cov_hard_sem,ref_smape_all,ref_smape_hard,flicker1,flicker4,flicker16,"
                             "boiling_index\n";
        EXPECT(strncmp(csv, header, strlen(header)) == 0, "study.csv header: %.120s", csv);
        const char *names[] = {"bitterli,",    "fast,",     "compat-binary,", "bitterli-r6,6,",
                               "bitterli@4,", "compat@4,", "bitterli@8,",    "compat@8,"};
        int rows = 0;
        double ref_all = NAN;
        for (char *line = strchr(csv, '\n'); line && line[1]; line = strchr(line + 1, '\n')) {
            const char *row = line + 1;
            EXPECT(rows < 8 && strncmp(row, names[rows], strlen(names[rows])) == 0, "row %d: %.60s", rows, row);
            /* radius, K, M, then 7 metrics, 4 standard errors, the hard pixels' temporal covariance and
             * its standard error: all finite and not negative except the covariances */
            const char *p = strchr(row, ',');
            double v[22];
            int nv = 0;
            while (p && nv < 22) {
                v[nv++] = strtod(p + 1, NULL);
                p = strchr(p + 1, ',');
            }
            EXPECT(nv == 22, "row %d has %d numbers", rows, nv);
            /* flicker at 1, 4 and 16 px falls with the block size (means of more pixels vary less), and the
             * boiling index 256 flicker16 / flicker1 lies in (0, 256] */
            EXPECT(v[18] > 0.0 && v[19] < v[18] && v[20] <= v[19] && v[21] > 0.0 && v[21] <= 256.0,
                   "row %d: flicker %g %g %g, boiling index %g", rows, v[18], v[19], v[20], v[21]);
            /* the reference's own SMAPE (two independent halves, SMAPE(a, b) / 2): positive, and the same
             * for every row since all rows share the reference */
            EXPECT(v[16] > 0.0 && v[16] < 100.0 && v[17] > 0.0 && v[17] < 100.0,
                   "row %d: reference's own SMAPE %g / %g", rows, v[16], v[17]);
            if (rows == 0)
                ref_all = v[16];
            EXPECT(v[16] == ref_all, "row %d: reference's own SMAPE %g, row 0's %g", rows, v[16], ref_all);
            EXPECT(v[12] > 0.0 && v[13] > 0.0 && v[15] > 0.0,
                   "row %d: covariance standard errors %g / %g / %g (3 runs)", rows, v[12], v[13], v[15]);
            EXPECT(v[14] != v[5], "row %d: the hard pixels' temporal covariance is the whole image's (%g)", rows,
                   v[5]);
            EXPECT(v[10] > 0.0 && v[10] < v[3] && v[11] > 0.0 && v[11] < v[4],
                   "row %d: SMAPE standard errors %g / %g against SMAPE %g / %g (3 runs)", rows, v[10], v[11], v[3],
                   v[4]);
            EXPECT(v[2] == 3.0, "row %d: M = %g, want restir-pt's default 3", rows, v[2]);
            EXPECT(v[3] > 0.0 && v[3] < 100.0 && v[4] > 0.0 && v[4] < 100.0, "row %d: SMAPE %g / %g", rows, v[3],
                   v[4]);
            for (int k = 0; k < nv; k++)
                EXPECT(isfinite(v[k]), "row %d value %d not finite", rows, k);
            EXPECT(v[9] > 0.0 && v[7] >= 0.0 && v[8] >= 0.0, "row %d: times %g %g %g", rows, v[7], v[8], v[9]);
            rows++;
        }
        EXPECT(rows == 8, "study.csv has %d rows, want 8", rows);
        free(csv);
    }
    snprintf(path, sizeof(path), "%s/pareto.svg", out);
    char *svg = read_text(path);
    EXPECT(svg && strstr(svg, "<svg") && strstr(svg, "bitterli") && strstr(svg, "compat"),
           "pareto.svg missing or without both curves");
    /* 000 Figure 3's curves by radius: every Bitterli configuration (bitterli at 30, bitterli-r6,
     * bitterli@4, @8, given in that order) and every compat one with K = 32 (fast at 30, compat@4,
     * @8; not compat-binary) */
    char labels[2][64];
    pareto_labels(svg, "#d62728", labels[0], sizeof labels[0]);
    pareto_labels(svg, "#1f77b4", labels[1], sizeof labels[1]);
    EXPECT(!strcmp(labels[0], "4,6,8,30,"), "pareto.svg: the Bitterli curve's radii are '%s', want 4,6,8,30",
           labels[0]);
    EXPECT(!strcmp(labels[1], "4,8,30,"), "pareto.svg: the compat curve's radii are '%s', want 4,8,30", labels[1]);
    free(svg);
    const char *files[] = {"study.md", "hard_pixels.png", "strip.png"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof(path), "%s/%s", out, files[k]);
        EXPECT(file_size(path) > 100, "%s missing or empty", path);
    }
    EXPECT(cli_count_entries(out, ".tmp-") == 0, "temporary files left in %s", out);

    /* Issue 42's deciding rows: no spatial pass at all (no selection or spatial time), and Bitterli
     * and FAST with the temporal output as history. */
    snprintf(out, sizeof(out), "%s/study42", tmp);
    snprintf(args, sizeof(args),
             "study --scene cornell --method restir-pt --configs spatial-off,bitterli-history-temporal,"
             "fast-history-temporal --runs 2 --warmup 2 --frames 5 --res 32x18 --ref-spp 16 --set pt.max_bounces=2 "
             "--out '%s'",
             out);
    rc = cli_run(tmp, args, err);
    EXPECT(rc == 0, "restir %s exited %d: %s", args, rc, err);
    snprintf(path, sizeof(path), "%s/study.csv", out);
    csv = read_text(path);
    EXPECT(csv != NULL, "no %s", path);
    if (csv) {
        const char *names[] = {"spatial-off,", "bitterli-history-temporal,", "fast-history-temporal,"};
        int rows = 0;
        for (char *line = strchr(csv, '\n'); line && line[1] && rows < 3; line = strchr(line + 1, '\n'), rows++) {
            const char *row = line + 1;
            EXPECT(strncmp(row, names[rows], strlen(names[rows])) == 0, "row %d: %.60s", rows, row);
            double v[9];
            const char *q = strchr(row, ',');
            for (int k = 0; k < 9 && q; k++, q = strchr(q + 1, ','))
                v[k] = strtod(q + 1, NULL);
            /* v: radius, K, M, SMAPE, hard SMAPE, temporal cov, spatial cov, ms_select, ms_spatial */
            if (rows == 0)
                EXPECT(v[7] == 0.0 && v[8] == 0.0, "spatial-off: selection %g ms, spatial %g ms", v[7], v[8]);
            else
                EXPECT(v[8] > 0.0, "%s: no spatial pass time", names[rows]);
        }
        EXPECT(rows == 3, "study.csv has %d rows, want 3", rows);
        free(csv);
    }
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
