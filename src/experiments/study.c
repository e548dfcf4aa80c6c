/* study.c: the error-correlation study of 000 Sec. 6-7 and Appendices A-B as a harness (study.h): its
 * setup from a description, the unsplit run, the plan, its jobs and merge, and the outputs. Per
 * configuration of spatial neighbor selection, N independently seeded static-camera sequences after a
 * warm-up; SMAPE over all and over hard pixels, temporal and spatial relative covariance, pass times.
 * Writes study.csv, study.md, pareto.svg, hard_pixels.png and strip.png. Must never implement a method:
 * it drives the renderer through study_run.h. */
#include "experiments/study.h"
#include "scene/scene_animation.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/out_dir.h"
#include "experiments/reference_checkpoint.h"
#include "experiments/reference_halves.h"
#include "methods/settings.h"
#include "experiments/reference_size.h"
#include "experiments/run_prepare.h"
#include "experiments/study_denoised.h"
#include "experiments/study_report.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"
#include "io/report.h"
#include "io/svg_plot.h"
#include "scene/scene_file.h"

#define STRIP_SCALE 4 /* strip plot: rows per frame */

static float luminance_at(const float *rgb, size_t i)
{
    return v3_luminance(v3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]));
}

/* "+x.x%" for value against a positive base, "-" otherwise. */
static void relative_change(double value, double base, char *out, size_t len)
{
    if (base > 0.0 && isfinite(value))
        snprintf(out, len, "%+.1f%%", 100.0 * (value / base - 1.0));
    else
        snprintf(out, len, "-");
}

/* DIR/runs.csv: each configuration's values per run (study_run_columns), so that `restir evaluate`
 * pairs configurations by seed: run r of every configuration renders with the same seed. */
_Static_assert(STUDY_RUN_COLS == 8, "write_runs prints eight columns");
static int write_runs(const char *dir, const struct study_config *cfg, const struct study_result *res, int n, char *msg)
{
    char path[4200], header[512] = "config,run";
    for (int c = 0; c < STUDY_RUN_COLS; c++)
        snprintf(header + strlen(header), sizeof header - strlen(header), ",%s", study_run_columns[c]);
    snprintf(path, sizeof(path), "%s/runs.csv", dir);
    struct csv_writer csv;
    if (csv_open(&csv, path, header, msg) != 0)
        return -1;
    for (int k = 0; k < n; k++)
        for (int r = 0; r < res[k].runs; r++) {
            const double *v = &res[k].per_run[(size_t)r * STUDY_RUN_COLS];
            csv_row(&csv, "%s,%d,%.9g,%.9g,%.6g,%.6g,%.6g,%.9g,%.9g,%.9g", cfg[k].name, r, v[0], v[1], v[2], v[3], v[4],
                    v[5], v[6], v[7]);
        }
    return csv_close(&csv, msg);
}

static int write_tables(const char *dir, const struct study_config *cfg, const struct study_result *res, int n, int m,
                        char *msg)
{
    char path[4200];
    snprintf(path, sizeof(path), "%s/study.csv", dir);
    struct csv_writer csv;
    if (csv_open(
            &csv, path,
            "config,radius,K,M,smape_all,smape_hard,temporal_cov,spatial_cov,ms_select,ms_spatial,ms_frame,"
            "smape_all_sem,smape_hard_sem,temporal_cov_sem,spatial_cov_sem,temporal_cov_hard,temporal_cov_hard_sem,"
            "ref_smape_all,ref_smape_hard,flicker1,flicker4,flicker16,boiling_index",
            msg) != 0)
        return -1;
    _Static_assert(FLICKER_COLS == 4, "study.csv's flicker columns");
    for (int k = 0; k < n; k++)
        csv_row(&csv,
                "%s,%g,%d,%d,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
                "%.6g,%.6g",
                cfg[k].name, cfg[k].radius, cfg[k].candidates, m, res[k].smape_all, res[k].smape_hard,
                res[k].temporal_cov, res[k].spatial_cov, res[k].ms_select, res[k].ms_spatial, res[k].ms_frame,
                res[k].smape_all_sem, res[k].smape_hard_sem, res[k].temporal_cov_sem, res[k].spatial_cov_sem,
                res[k].temporal_cov_hard, res[k].temporal_cov_hard_sem, res[k].ref_smape[0], res[k].ref_smape[1],
                res[k].flicker[0], res[k].flicker[1], res[k].flicker[2], res[k].flicker[3]);
    if (csv_close(&csv, msg) != 0 || write_runs(dir, cfg, res, n, msg) != 0)
        return -1;
    snprintf(path, sizeof(path), "%s/study.md", dir);
    char tmp[4300];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "w", msg);
    if (!f) {
        return -1;
    }
    /* 000 Table 2 layout (quality) and Table 1 (time), relative to the first bitterli row. */
    int base = -1;
    for (int k = 0; k < n && base < 0; k++)
        if (cfg[k].select == SELECT_BITTERLI)
            base = k;
    fprintf(f, "| config | R | K | M | SMAPE all | SMAPE hard | temporal cov | temporal cov hard | spatial cov | "
               "select ms | spatial ms | frame ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; k++) {
        fprintf(f,
                "| %s | %g | %d | %d | %.3f +- %.2g | %.3f +- %.2g | %.4g +- %.2g | %.4g +- %.2g | %.4g +- %.2g | "
                "%.2f | %.2f | %.2f |\n",
                cfg[k].name, cfg[k].radius, cfg[k].candidates, m, res[k].smape_all, res[k].smape_all_sem,
                res[k].smape_hard, res[k].smape_hard_sem, res[k].temporal_cov, res[k].temporal_cov_sem,
                res[k].temporal_cov_hard, res[k].temporal_cov_hard_sem, res[k].spatial_cov, res[k].spatial_cov_sem,
                res[k].ms_select, res[k].ms_spatial, res[k].ms_frame);
    }
    fprintf(f, "\nSMAPE: mean over the runs +- its standard error (the runs' SMAPEs, each over its frames); the "
               "covariances +- their jackknife standard errors over the runs (nan under 3 runs).\n");
    fprintf(f, "\nFlicker over the measured frames: the frame-to-frame variance of s x s block means over the "
               "reference's (restir_metrics_flicker); boiling index = 256 flicker16 / flicker1, about 1 for "
               "independent noise, up to 256 for blotches.\n\n| config | flicker 1 px | flicker 4 px | "
               "flicker 16 px | boiling index |\n|---|---|---|---|---|\n");
    for (int k = 0; k < n; k++)
        fprintf(f, "| %s | %.4g | %.4g | %.4g | %.2f |\n", cfg[k].name, res[k].flicker[0], res[k].flicker[1],
                res[k].flicker[2], res[k].flicker[3]);
    if (base >= 0) {
        const struct study_result *b = &res[base];
        fprintf(f,
                "\nChange against %s: SMAPE all, SMAPE hard, temporal covariance (all, hard), frame time; "
                "selection pass as a share of the frame.\n\n| config | SMAPE all | SMAPE hard | temporal cov | "
                "temporal cov hard | frame | select / frame |\n|---|---|---|---|---|---|---|\n",
                cfg[base].name);
        for (int k = 0; k < n; k++) {
            char cov[2][32]; /* a covariance can be <= 0: then a relative change means nothing */
            relative_change(res[k].temporal_cov, b->temporal_cov, cov[0], sizeof cov[0]);
            relative_change(res[k].temporal_cov_hard, b->temporal_cov_hard, cov[1], sizeof cov[1]);
            fprintf(f, "| %s | %+.1f%% | %+.1f%% | %s | %s | %+.1f%% | %.1f%% |\n", cfg[k].name,
                    100.0 * (res[k].smape_all / b->smape_all - 1.0), 100.0 * (res[k].smape_hard / b->smape_hard - 1.0),
                    cov[0], cov[1], 100.0 * (res[k].ms_frame / b->ms_frame - 1.0),
                    100.0 * res[k].ms_select / res[k].ms_frame);
        }
    }
    return io_close_commit(f, tmp, path, msg);
}

/* 000 Figure 3: SMAPE against spatial covariance over radii, Bitterli's selection and ours at K 32. */
static int write_pareto(const char *dir, const struct study_config *cfg, const struct study_result *res, int n,
                        char *msg)
{
    double x[2][STUDY_MAX_CONFIGS], y[2][STUDY_MAX_CONFIGS], r[2][STUDY_MAX_CONFIGS];
    int cnt[2] = {0, 0};
    for (int k = 0; k < n; k++) { /* 000 Figure 3's two curves: Bitterli's, and ours at K 32 */
        const int q = study_pareto_series(&cfg[k]);
        if (q < 0)
            continue;
        int at = cnt[q]++; /* by radius: the curve's points in order */
        for (; at > 0 && r[q][at - 1] > cfg[k].radius; at--) {
            x[q][at] = x[q][at - 1];
            y[q][at] = y[q][at - 1];
            r[q][at] = r[q][at - 1];
        }
        x[q][at] = res[k].spatial_cov;
        y[q][at] = res[k].smape_all;
        r[q][at] = cfg[k].radius;
    }
    struct plot_series series[2] = {{"bitterli", "#d62728", cnt[0], x[0], y[0], r[0]},
                                    {"compat (K 32)", "#1f77b4", cnt[1], x[1], y[1], r[1]}};
    char path[4200];
    snprintf(path, sizeof(path), "%s/pareto.svg", dir);
    return svg_write_xy_plot(path, "SMAPE against spatial covariance over reuse radii (labels: R)",
                             "average relative covariance (radius 8)", "SMAPE", series, 2, msg);
}

/* Hard pixels in white over the dimmed reference. */
static int write_mask(const char *dir, const float *ref, const unsigned char *hard, int w, int h, char *msg)
{
    size_t n = (size_t)w * h;
    float *rgb = xmalloc(sizeof(float) * 3 * n);
    for (size_t i = 0; i < n; i++) {
        float l = fminf(luminance_at(ref, i), 1.0f) * 0.3f;
        rgb[3 * i] = hard[i] ? 1.0f : l;
        rgb[3 * i + 1] = hard[i] ? 0.2f : l;
        rgb[3 * i + 2] = hard[i] ? 0.2f : l;
    }
    char path[4200];
    snprintf(path, sizeof(path), "%s/hard_pixels.png", dir);
    int rc = png_write_srgb(path, rgb, w, h, 0.0f, msg);
    free(rgb);
    return rc;
}

/* 000 Figure 5: (x, t) plot of one row over the measured frames of run 0, one panel per listed
 * configuration (up to 4), each pixel as luminance over the reference (0.5 gray = exact). */
static int write_strip(const char *dir, const float *strips, const float *ref_row, int w, int frames, int n, char *msg)
{
    int panels = n < 4 ? n : 4, gap = 4, width = panels * w + (panels - 1) * gap, height = frames * STRIP_SCALE;
    float *rgb = xcalloc((size_t)3 * width * height, sizeof(float));
    for (int k = 0; k < panels; k++)
        for (int t = 0; t < frames; t++)
            for (int x = 0; x < w; x++) {
                float v = strips[((size_t)k * frames + t) * w + x] / (ref_row[x] + 1e-4f);
                v = fminf(fmaxf(0.25f * v, 0.0f), 1.0f);
                for (int q = 0; q < STRIP_SCALE; q++) {
                    size_t o = 3 * ((size_t)(t * STRIP_SCALE + q) * width + (size_t)k * (w + gap) + x);
                    rgb[o] = rgb[o + 1] = rgb[o + 2] = v;
                }
            }
    char path[4200];
    snprintf(path, sizeof(path), "%s/strip.png", dir);
    int rc = png_write_srgb(path, rgb, width, height, 0.0f, msg);
    free(rgb);
    return rc;
}

int study_setup(const struct cli_options *desc, int need_out, struct study_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    st->o = *desc;
    struct cli_options *o = &st->o;
    if (!o->res_given) {
        o->params.width = 320;
        o->params.height = 180;
    }
    if (o->ref && reference_size_adopt(o->ref, o->res_given, &o->params, msg) != 0) { /* --ref: its size */
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    if (need_out && !o->out && !o->plan && !o->merge) {
        cli_error("study: --out DIR (or --plan DIR, or --merge DIR) is required");
        return EXIT_USAGE;
    }
    const struct method *m = method_find(o->method);
    if (!m || !method_has(m, METHOD_SELECTION_STUDY)) {
        char names[256];
        method_names_with(METHOD_SELECTION_STUDY, names, sizeof names);
        cli_error("study: --method must be one of %s (methods with spatial reuse from the selection pass), got '%s'",
                  names, o->method ? o->method : "(none)");
        return EXIT_USAGE;
    }
    st->method = m;
    if (o->frames <= STUDY_COV_LAG || o->runs < 2) {
        cli_error("study: needs --frames > %d (autocovariance lag) and --runs >= 2", STUDY_COV_LAG);
        return EXIT_USAGE;
    }
    if (study_parse_configs(o, st->cfg, &st->ncfg, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    const int rc = run_prepare(o, st->method, RUN_CHECK_SETS | RUN_CHECK_MEMORY, &st->s);
    if (rc == 0 && scene_is_animated(&st->s)) { /* its reference is one still frame's */
        cli_error("study: scene %s has animated emitters; 000's study measures a still scene (restir compare "
                  "measures animated ones, --ref-every 1 for the lag)",
                  st->s.name);
        scene_destroy(&st->s);
        return EXIT_USAGE;
    }
    return rc;
}

/* The study's own reference: pt over the method's integrand from a still camera, independently
 * seeded. out: a plan job's output, which makes it resumable from out's checkpoint
 * (reference_render_resumable), else NULL. NULL after a stop signal or, with out, an error (msg). */
/* The study's reference as two independent halves (reference_halves.h): in memory (out NULL) or
 * resumably as a plan's job. Returns 0, or -1 with msg. */
static int study_render_reference(const struct study_setup *st, const char *out, struct reference_pair *r, char *msg)
{
    struct render_params rp = st->o.params;
    rp.seed = reference_seed(rp.seed);
    const struct camera cam = study_camera(&st->s);
    return reference_render_pair(&st->s, st->method, &rp, &cam, NULL, st->o.ref_spp, out, r, msg);
}

/* The reference's own SMAPE over the pixels mask marks (NULL: all): SMAPE(a, b) / 2, since |a - b| / 2
 * is distributed as |r - R| for r = (a + b) / 2 (reference_halves.h). NaN without halves. */
static double reference_own_smape(const float *a, const float *b, size_t npix, const unsigned char *mask)
{
    if (!a || !b)
        return NAN;
    double *lum = xmalloc(sizeof(double) * npix), smape = NAN;
    restir_metrics_luminance(a, npix, lum);
    if (restir_metrics_smape_luminance(lum, b, npix, mask, &smape) != 0)
        smape = NAN;
    free(lum);
    return 0.5 * smape;
}

/* Writes the study's tables, plots and report into dir and prints its summary. */
static int study_write_outputs(const struct study_setup *st, const char *dir, const char *command,
                               const struct study_result *res, const struct study_result *res_dn, const float *ref,
                               const unsigned char *hard, int nhard, int strip_y, const float *strips)
{
    char msg[RESTIR_MSG_LEN];
    const struct cli_options *o = &st->o;
    const int w = o->params.width, h = o->params.height;
    float *ref_row = xmalloc(sizeof(float) * (size_t)w);
    for (int x = 0; x < w; x++)
        ref_row[x] = luminance_at(ref, (size_t)strip_y * w + x);
    const int neighbors = render_params_spatial_neighbors(&o->params, method_has(st->method, METHOD_PATH_RESERVOIRS));
    int rc = 0;
    if (write_tables(dir, st->cfg, res, st->ncfg, neighbors, msg) != 0 ||
        write_pareto(dir, st->cfg, res, st->ncfg, msg) != 0 || write_mask(dir, ref, hard, w, h, msg) != 0 ||
        write_strip(dir, strips, ref_row, w, o->frames, st->ncfg, msg) != 0 ||
        (res_dn && study_write_denoised(dir, denoise_names[o->params.denoise.method], st->cfg, res, res_dn, st->ncfg,
                                        neighbors, msg) != 0)) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    free(ref_row);
    if (rc == 0) {
        printf("study of %s on %s, %dx%d, %d runs, %d warm-up + %d frames, %d hard pixels (row %d in strip.png)\n",
               o->method, o->scene, w, h, o->runs, o->warmup, o->frames, nhard, strip_y);
        for (int k = 0; k < st->ncfg; k++)
            printf("  %-16s R %-5g SMAPE %.3f +- %.2g hard %.3f +- %.2g  temporal cov %.4g  spatial cov %.4g  "
                   "boiling %.2f  select %.2f ms  frame %.2f ms\n",
                   st->cfg[k].name, st->cfg[k].radius, res[k].smape_all, res[k].smape_all_sem, res[k].smape_hard,
                   res[k].smape_hard_sem, res[k].temporal_cov, res[k].spatial_cov, res[k].flicker[FLICKER_SCALES],
                   res[k].ms_select, res[k].ms_frame);
        for (int k = 0; res_dn && k < st->ncfg; k++)
            printf("  %-16s after %s (BIASED): SMAPE %.3f +- %.2g hard %.3f  temporal cov %.4g  spatial cov %.4g  "
                   "flicker16 %.4g (raw %.4g)\n",
                   st->cfg[k].name, denoise_names[o->params.denoise.method], res_dn[k].smape_all,
                   res_dn[k].smape_all_sem, res_dn[k].smape_hard, res_dn[k].temporal_cov, res_dn[k].spatial_cov,
                   res_dn[k].flicker[FLICKER_SCALES - 1], res[k].flicker[FLICKER_SCALES - 1]);
        printf("output: %s\n", dir);
    }
    if (rc == 0 && o->report) {
        const struct study_report_run run = {dir,     command,   st->s.name, o->method, w,       h,
                                             o->runs, o->warmup, o->frames,  nhard,     strip_y, ref,
                                             o->self_contained};
        if (study_write_report(&run, msg) != 0) {
            cli_error("--report: %s", msg);
            rc = EXIT_RUNTIME;
        } else {
            printf("report: %s/index.html\n", dir);
        }
    }
    return rc;
}

/* Where a study plan keeps the result of run n of configuration k. */
static void unit_output(int k, int n, char *out, size_t len)
{
    snprintf(out, len, "runs/study_c%02d_r%05d.bin", k, n);
}

/* Reads a unit's file, for plan_check_jobs and the merge. */
struct study_merge_ctx {
    const struct study_setup *st;
    int has_reference_job;
};

static int study_job_valid(const struct plan *pl, int k, char *why, void *ctx)
{
    const struct study_merge_ctx *c = ctx;
    char path[PLAN_PATH_MAX + 200];
    plan_output_path(pl, k, path, sizeof path);
    const struct render_params *p = &c->st->o.params;
    if (c->has_reference_job && k == 0) {
        float *ref = NULL;
        int rc = cli_load_reference(path, p->width, p->height, &ref, why);
        free(ref);
        return rc;
    }
    struct study_unit u;
    int rc = study_unit_read(path, pl->id, c->st->o.frames, (size_t)p->width * p->height, &u, why);
    if (rc == 0)
        study_unit_free(&u);
    return rc == 0 ? 0 : -1;
}

/* Every configuration's row from its runs, one unit at a time: rendered (the unsplit study, pl
 * NULL) or read from the plan's results (the merge). */
static int study_rows(const struct study_setup *st, const struct plan *pl, const float *ref, const unsigned char *hard,
                      int strip_y, float *strips, struct study_result *res, struct study_result *res_dn)
{
    const struct cli_options *o = &st->o;
    const int w = o->params.width, h = o->params.height;
    struct progress pg;
    progress_begin(&pg, pl ? "merge" : "study", st->ncfg);
    int rc = 0;
    const int dn = o->params.denoise.method > 0; /* --denoise: a second row from the denoised frames */
    for (int k = 0; k < st->ncfg && rc == 0; k++) {
        struct study_row row, row_dn;
        study_row_begin(&row, o->runs, o->frames, w, h);
        if (dn)
            study_row_begin(&row_dn, o->runs, o->frames, w, h);
        for (int n = 0; n < o->runs && rc == 0; n++) {
            struct study_unit u;
            if (pl) {
                char rel[64], path[PLAN_PATH_MAX + 200], msg[RESTIR_MSG_LEN];
                unit_output(k, n, rel, sizeof rel);
                snprintf(path, sizeof path, "%s/%s", pl->dir, rel);
                if (study_unit_read(path, pl->id, o->frames, (size_t)w * h, &u, msg) != 0) {
                    cli_error("%s", msg);
                    rc = EXIT_RUNTIME;
                }
            } else if (study_run_unit(&st->s, st->method, &o->params, &st->cfg[k], o, n, &u) != 0) {
                cli_error("interrupted by %s in configuration %s (%d of %d); nothing written", cli_stop_signal_name(),
                          st->cfg[k].name, k + 1, st->ncfg);
                rc = 128 + (int)cli_stop_signal;
            }
            if (rc == 0 && dn && !u.luminance_dn) {
                cli_error("configuration %s, run %d: no denoised frames (a unit written without denoising)",
                          st->cfg[k].name, n);
                study_unit_free(&u);
                rc = EXIT_RUNTIME;
            }
            if (rc != 0)
                break;
            study_row_add(&row, &u, ref, hard, strip_y, &strips[(size_t)k * w * o->frames]);
            if (dn) {
                const struct study_unit ud = study_unit_denoised(&u);
                study_row_add(&row_dn, &ud, ref, hard, strip_y, NULL);
            }
            study_unit_free(&u);
        }
        if (rc == 0)
            study_row_end(&row, hard, &res[k]);
        else
            study_row_free(&row);
        if (dn && rc == 0)
            study_row_end(&row_dn, hard, &res_dn[k]);
        else if (dn)
            study_row_free(&row_dn);
        progress_update(&pg, k + 1);
    }
    progress_end(&pg);
    return rc;
}

/* Rows, then outputs, once the reference is known: shared by the unsplit study and the merge. */
static int study_finish(const struct study_setup *st, const struct plan *pl, const char *dir, const char *command,
                        const float *ref, const float *half_a, const float *half_b)
{
    const int w = st->o.params.width, h = st->o.params.height;
    const struct camera cam = study_camera(&st->s);
    unsigned char *hard = xcalloc((size_t)w * h, 1);
    const int nhard = study_hard_pixel_mask(&st->s, &st->o.params, &cam, st->o.hard_neighbors, hard);
    const int strip_y = study_strip_row(hard, w, h);
    float *strips = xmalloc(sizeof(float) * (size_t)w * st->o.frames * st->ncfg);
    static struct study_result res[STUDY_MAX_CONFIGS], res_dn[STUDY_MAX_CONFIGS];
    int rc = study_rows(st, pl, ref, hard, strip_y, strips, res, res_dn);
    const double ref_own[2] = {reference_own_smape(half_a, half_b, (size_t)w * h, NULL),
                               reference_own_smape(half_a, half_b, (size_t)w * h, hard)};
    for (int k = 0; k < st->ncfg; k++)
        for (int q = 0; q < 2; q++)
            res[k].ref_smape[q] = res_dn[k].ref_smape[q] = ref_own[q];
    if (rc == 0)
        rc = study_write_outputs(st, dir, command, res, st->o.params.denoise.method > 0 ? res_dn : NULL, ref, hard,
                                 nhard, strip_y, strips);
    for (int k = 0; k < st->ncfg; k++) {
        study_result_free(&res[k]);
        study_result_free(&res_dn[k]);
    }
    free(strips);
    free(hard);
    return rc;
}

int study_plan(const struct study_setup *st, int argc, char **argv)
{
    char name[PLAN_NAME_MAX], rel[64];
    struct plan pl;
    /* a new or empty folder, or this very plan's (finished jobs kept); --force empties another */
    int rc = plan_folder_claim(st->o.plan, "study", argc, argv, st->o.force);
    if (rc == 0)
        rc = plan_start(&pl, st->o.plan, "study", argc, argv, scene_content_hash(&st->s));
    if (rc != 0)
        return rc;
    if (!st->o.ref)
        plan_add_job(&pl, "the study's reference", "runs/reference.exr");
    /* run-major (run 0 of every configuration, then run 1, ...): jobs run one at a time in this
     * order time the configurations interleaved, A B A B, so slow drift of the machine's speed
     * falls on both sides of each run's pair of frame times alike */
    for (int n = 0; n < st->o.runs; n++)
        for (int k = 0; k < st->ncfg; k++) {
            snprintf(name, sizeof name, "config %s, run %d", st->cfg[k].name, n);
            unit_output(k, n, rel, sizeof rel);
            plan_add_job(&pl, name, rel);
        }
    return plan_finish(&pl);
}

/* study_setup from a plan's stored description. Returns 0 or an exit code having said why. */
static int study_setup_planned(const struct plan *pl, struct study_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("study", pl->argc, pl->argv, &desc, msg) != 0) {
        cli_error("%s/plan.json: %s", pl->dir, msg);
        return EXIT_USAGE;
    }
    return study_setup(&desc, 0, st);
}

int study_run_job(const struct plan *pl, int k)
{
    struct study_setup st;
    int rc = study_setup_planned(pl, &st);
    if (rc != 0)
        return rc;
    if ((rc = plan_check_scene(pl, scene_content_hash(&st.s))) != 0) {
        scene_destroy(&st.s);
        return rc;
    }
    cli_catch_stop_signals();
    char path[PLAN_PATH_MAX + 200], msg[RESTIR_MSG_LEN];
    plan_output_path(pl, k, path, sizeof path);
    const int has_ref = !st.o.ref;
    struct study_merge_ctx ctx = {&st, has_ref};
    int done_before = study_job_valid(pl, k, msg, &ctx) == 0;
    if (done_before) {
        printf("job %d of %d (%s): already done: %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
    } else if (has_ref && k == 0) {
        struct reference_pair pair;
        rc = reference_pair_finish(study_render_reference(&st, path, &pair, msg), &pair, path, st.o.params.width,
                                   st.o.params.height, msg);
    } else {
        const int unit = k - has_ref, cfg = unit % st.ncfg, run = unit / st.ncfg; /* run-major: study_plan */
        struct study_unit u;
        if (study_run_unit(&st.s, st.method, &st.o.params, &st.cfg[cfg], &st.o, run, &u) != 0) {
            cli_error("interrupted by %s; nothing written", cli_stop_signal_name());
            rc = 128 + (int)cli_stop_signal;
        } else {
            if (study_unit_write(path, pl->id, &u, msg) != 0) {
                cli_error("%s", msg);
                rc = EXIT_RUNTIME;
            }
            study_unit_free(&u);
        }
    }
    if (rc == 0 && !done_before)
        printf("job %d of %d (%s): %s\n", k + 1, pl->n_jobs, pl->jobs[k].name, path);
    scene_destroy(&st.s);
    return rc;
}

int study_merge(const char *dir)
{
    char msg[RESTIR_MSG_LEN];
    struct plan pl;
    int rc = plan_load_kind(dir, "study", "a study", &pl);
    if (rc != 0)
        return rc;
    struct study_setup st;
    rc = study_setup_planned(&pl, &st);
    if (rc != 0) {
        plan_free(&pl);
        return rc;
    }
    rc = plan_check_scene(&pl, scene_content_hash(&st.s));
    struct study_merge_ctx ctx = {&st, !st.o.ref};
    if (rc == 0 && plan_check_jobs(&pl, study_job_valid, &ctx, msg) != 0) {
        cli_error("cannot merge: %s", msg);
        rc = EXIT_RUNTIME;
    }
    struct reference_pair ref = {0};
    char path[PLAN_PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/runs/reference.exr", pl.dir);
    const char *ref_path = st.o.ref ? st.o.ref : path;
    if (rc == 0) {
        const int got = reference_pair_load(ref_path, st.o.params.width, st.o.params.height, !st.o.ref, &ref, msg);
        if (got != 0) {
            cli_error("cannot merge %s: %s", pl.dir, msg);
            rc = got == -2 ? EXIT_USAGE : EXIT_RUNTIME;
        }
    }
    if (rc == 0)
        rc = study_finish(&st, &pl, pl.dir, pl.command, ref.mean, ref.a, ref.b);
    reference_pair_free(&ref);
    scene_destroy(&st.s);
    plan_free(&pl);
    return rc;
}

int study_run(struct study_setup *st, const char *command)
{
    char msg[RESTIR_MSG_LEN];
    int rc = 0;
    cli_catch_stop_signals();
    struct reference_pair ref = {0};
    if (st->o.ref) {
        if (reference_pair_load(st->o.ref, st->o.params.width, st->o.params.height, 0, &ref, msg) != 0) {
            cli_error("%s", msg);
            scene_destroy(&st->s);
            return EXIT_RUNTIME;
        }
    } else if (study_render_reference(st, NULL, &ref, msg) != 0) {
        cli_error("interrupted by %s while rendering the reference; nothing written", cli_stop_signal_name());
        scene_destroy(&st->s);
        return 128 + (int)cli_stop_signal;
    }
    if (out_dir_prepare(st->o.out, st->o.force, msg) != 0) { /* out_dir_check accepted it */
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0)
        rc = study_finish(st, NULL, st->o.out, command, ref.mean, ref.a, ref.b);
    reference_pair_free(&ref);
    scene_destroy(&st->s);
    return rc;
}
