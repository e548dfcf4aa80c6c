/* compare_table.c: a comparison's output: the printed table ('-' where a metric does not apply),
 * compare.csv, passes.csv and the report page (compare_run.h). Must never render. */
#include "experiments/compare_run.h"
#include "scene/scene_animation.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_report.h"
#include "experiments/csv_table.h"
#include "io/report.h"

/* One cell of a printed table: v by fmt, or '-' right-aligned in width characters when v is NaN or
 * infinite (a metric that does not apply to the row). */
static void table_cell(char *out, size_t n, const char *fmt, int width, double v)
{
    if (isfinite(v))
        snprintf(out, n, fmt, v);
    else
        snprintf(out, n, "%*s", width, "-");
}

/* DIR/passes.csv: each row's mean time per frame of every pass (the fastest run; its instances summed, one
 * reconstruction), the breakdown of 004 Table 2 and 000 Table 1. Returns 0, or -1 with msg. */
static int write_passes(const char *out_dir, const struct compare_spec *specs, const struct compare_result *res, int n,
                        char *msg)
{
    char path[4200], header[2048] = "method";
    size_t used = strlen(header);
    for (int q = 0; q < pass_count(); q++) /* pass ids in order (methods/passes.h) */
        used += (size_t)snprintf(header + used, sizeof header - used, ",%s", pass_name(q));
    snprintf(path, sizeof path, "%s/passes.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, path, header, msg) != 0)
        return -1;
    for (int k = 0; k < n; k++) {
        char row[4096];
        csv_field(row, sizeof row, specs[k].label);
        used = strlen(row);
        for (int q = 0; q < pass_count(); q++)
            used += (size_t)snprintf(row + used, sizeof row - used, ",%.4f", res[k].ms_pass[q]);
        csv_row(&csv, "%s", row);
    }
    return csv_close(&csv, msg);
}

/* The errors after denoising (denoise=svgf|atrous), a block of their own under the table (BIASED by nature). */
static void print_denoised(const struct compare_spec *specs, const struct compare_result *res, int n, int w, int runs,
                           int method)
{
    int any = 0;
    for (int k = 0; k < n; k++)
        any |= isfinite(res[k].err_dn.relmse);
    if (!any)
        return;
    printf("after denoising (denoise=%s unless the row sets another; BIASED by nature):\n", denoise_names[method]);
    printf("%-*s %12s%s %10s%s %8s%s %10s%s%s\n", w, "method", "relMSE", runs ? "       +-" : "", "MAPE",
           runs ? "       +-" : "", "SMAPE", runs ? "     +-" : "", "MAPE dis", runs ? "       +-" : "",
           runs ? "         tcov" : "");
    for (int k = 0; k < n; k++) {
        const struct compare_result *c = &res[k];
        char v[4][32], se[4][32] = {"", "", "", ""}, tcov[32] = "";
        table_cell(v[0], sizeof v[0], "%12.5g", 12, c->err_dn.relmse);
        table_cell(v[1], sizeof v[1], "%10.5g", 10, c->err_dn.mape);
        table_cell(v[2], sizeof v[2], "%8.3f", 8, c->err_dn.smape);
        table_cell(v[3], sizeof v[3], "%10.5g", 10, c->mape_dis_dn);
        if (runs) {
            table_cell(se[0], sizeof se[0], " %8.2g", 9, c->sem_dn.relmse);
            table_cell(se[1], sizeof se[1], " %8.2g", 9, c->sem_dn.mape);
            table_cell(se[2], sizeof se[2], " %6.2g", 7, c->sem_dn.smape);
            table_cell(se[3], sizeof se[3], " %8.2g", 9, c->mape_dis_dn_sem);
            table_cell(tcov, sizeof tcov, " %12.5g", 13, c->temporal_cov_dn);
        }
        printf("%-*s %s%s %s%s %s%s %s%s%s\n", w, specs[k].label, v[0], se[0], v[1], se[1], v[2], se[2], v[3], se[3],
               tcov);
    }
}

/* Flicker at 1, 4 and 16 px and the boiling index over the second half's frames (compare_track_flicker),
 * as rendered and, for rows that denoise, denoised; a static camera's only. */
static void print_flicker(const struct compare_spec *specs, const struct compare_result *res, int n, int w,
                          int frames)
{
    int any = 0, any_dn = 0;
    for (int k = 0; k < n; k++) {
        any |= isfinite(res[k].flicker[0]);
        any_dn |= isfinite(res[k].flicker_dn[0]);
    }
    if (!any)
        return;
    printf("flicker over frames %d-%d (variance of s x s block means over the frames / reference block mean^2; "
           "boiling index = 256 flicker16 / flicker1: ~1 for independent noise, up to 256 for blotches):\n",
           frames / 2, frames - 1);
    printf("%-*s %11s %11s %11s %8s%s\n", w, "method", "flicker1", "flicker4", "flicker16", "boiling",
           any_dn ? "   denoised: flicker1   flicker4  flicker16  boiling" : "");
    for (int k = 0; k < n; k++) {
        char v[2][FLICKER_COLS][32];
        for (int d = 0; d < 2; d++) {
            const double *f = d ? res[k].flicker_dn : res[k].flicker;
            for (int j = 0; j < FLICKER_SCALES; j++)
                table_cell(v[d][j], sizeof v[d][j], " %10.4g", 11, f[j]);
            table_cell(v[d][FLICKER_SCALES], sizeof v[d][FLICKER_SCALES], " %8.2f", 9,
                       f[FLICKER_SCALES]);
        }
        printf("%-*s %s%s%s%s", w, specs[k].label, v[0][0], v[0][1], v[0][2], v[0][3]);
        if (any_dn)
            printf("           %s%s%s%s", v[1][0], v[1][1], v[1][2], v[1][3]);
        printf("\n");
    }
}

/* The lag tables: the whole image's (compare_track_lag), the COMPARE_LAG_QUANTILE quantile of the blocks' own, and
 * the ghost (compare_track_ghost). */
enum lag_kind { LAG_IMAGE, LAG_BLOCKS, LAG_GHOST };

static const double *lag_values(const struct compare_result *r, enum lag_kind kind, int denoised)
{
    if (kind == LAG_BLOCKS)
        return denoised ? r->lag_block_dn : r->lag_block;
    if (kind == LAG_GHOST)
        return denoised ? r->ghost_dn : r->ghost;
    return denoised ? r->lag_dn : r->lag;
}

/* One table of the lags after each change. */
static void print_lag_table(const struct compare_setup *st, const struct compare_result *res, int w, const int *changes,
                            int nc, enum lag_kind kind)
{
    int any = 0, any_dn = 0;
    for (int k = 0; k < st->n; k++)
        for (int c = 0; c < nc; c++) {
            any |= isfinite(lag_values(&res[k], kind, 0)[c]);
            any_dn |= isfinite(lag_values(&res[k], kind, 1)[c]);
        }
    if (!any && !any_dn)
        return;
    if (kind == LAG_BLOCKS)
        printf("lag of %d px blocks: the same measured on each block's own relMSE, the %.0f%% quantile over the "
               "blocks:\n%-*s",
               COMPARE_LAG_BLOCK, 100.0 * COMPARE_LAG_QUANTILE, w, "method");
    else if (kind == LAG_GHOST)
        printf("ghost: frames from a change until %.0f%% of the %d px blocks' means stay within %.0f%% of the "
               "reference above their steady deviation (an old light's trace, apart from noise and bias):\n%-*s",
               100.0 * COMPARE_LAG_QUANTILE, COMPARE_LAG_BLOCK, 100.0 * COMPARE_LAG_TOLERANCE, w, "method");
    else
        printf("lag: frames from a change of the lights until relMSE is within %.0f%% of its steady state (the mean "
               "of the last quarter of the frames before the next change):\n%-*s",
               100.0 * COMPARE_LAG_TOLERANCE, w, "method");
    for (int d = 0; d <= any_dn; d++)
        for (int c = 0; c < nc; c++)
            printf("  %s frame %3d", d ? "denoised, after" : "after", changes[c]);
    printf("\n");
    for (int k = 0; k < st->n; k++) {
        printf("%-*s", w, st->specs[k].label);
        for (int d = 0; d <= any_dn; d++)
            for (int c = 0; c < nc; c++) {
                const double v = lag_values(&res[k], kind, d)[c];
                char cell[32];
                table_cell(cell, sizeof cell, d ? " %24.0f" : " %14.0f", d ? 25 : 15, v);
                printf(" %s", cell);
            }
        printf("\n");
    }
}

/* The lag after each change of an animated scene's lights: the image's, its blocks', the ghost. */
static void print_lag(const struct compare_setup *st, const struct compare_result *res, int w)
{
    int changes[COMPARE_MAX_CHANGES];
    const int nc = scene_animation_changes(&st->s, changes, COMPARE_MAX_CHANGES);
    if (nc == 0)
        return;
    if (st->o.ref_every != 1) {
        printf("(the scene's lights change: --ref-every 1 measures the lag after each change)\n");
        return;
    }
    print_lag_table(st, res, w, changes, nc, LAG_IMAGE);
    print_lag_table(st, res, w, changes, nc, LAG_BLOCKS);
    print_lag_table(st, res, w, changes, nc, LAG_GHOST);
}

/* The largest of a row's lags (NaN without one). */
static double worst_lag(const double *lag)
{
    double worst = NAN;
    for (int k = 0; k < COMPARE_MAX_CHANGES; k++)
        if (isfinite(lag[k]) && !(worst >= lag[k]))
            worst = lag[k];
    return worst;
}

/* DIR/runs.csv: each row's values per run (compare_run_columns), so that `restir evaluate` pairs rows
 * by seed: run r of every row renders with compare_run_seed(seed, r). Returns 0, or -1 with msg. */
static int write_runs(const char *out_dir, const struct compare_spec *specs, const struct compare_result *res, int n,
                      char *msg)
{
    char path[4200], header[512] = "method,run";
    for (int q = 0; q < COMPARE_RUN_COLS; q++)
        snprintf(header + strlen(header), sizeof header - strlen(header), ",%s", compare_run_columns[q]);
    snprintf(path, sizeof path, "%s/runs.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, path, header, msg) != 0)
        return -1;
    for (int k = 0; k < n; k++)
        for (int r = 0; res[k].per_run && r < res[k].runs; r++) {
            char row[2048];
            csv_field(row, sizeof row, specs[k].label);
            snprintf(row + strlen(row), sizeof row - strlen(row), ",%d", r);
            for (int q = 0; q < COMPARE_RUN_COLS; q++) {
                const double v = res[k].per_run[(size_t)r * COMPARE_RUN_COLS + q];
                if (isfinite(v))
                    snprintf(row + strlen(row), sizeof row - strlen(row), ",%.9g", v);
                else
                    snprintf(row + strlen(row), sizeof row - strlen(row), ",");
            }
            csv_row(&csv, "%s", row);
        }
    return csv_close(&csv, msg);
}

/* frames.csv's relMSE of row `label` at the frames that have one, into frame and relmse (at most max);
 * returns how many. */
static int frame_errors(const struct csv_table *t, const char *label, int max, double *frame, double *relmse)
{
    int n = 0;
    for (int r = 0; r < t->nrow && n < max; r++) {
        if (strcmp(t->cell[(size_t)(r + 1) * t->ncol], label) != 0)
            continue;
        frame[n] = csv_table_num(t, r, "frame");
        relmse[n] = csv_table_num(t, r, "relmse");
        n += isfinite(frame[n]) && isfinite(relmse[n]);
    }
    return n;
}

/* DIR/index.html: each method's row, then its denoised frame's as a row of its own; the time per pass
 * of passes.csv; the errors along the sequence read back from frames.csv (none where it is missing, as
 * after a merge). Returns 0 or EXIT_RUNTIME. */
static int write_report(const struct compare_setup *st, const char *out_dir, const char *command,
                        const struct compare_result *res, const float *ref)
{
    const struct cli_options *o = &st->o;
    const struct render_params *p = &st->p;
    const struct compare_spec *specs = st->specs;
    const int n = st->n;
    char msg[RESTIR_MSG_LEN], path[4200];
    char pngs[2 * MAX_METHODS][SPEC_MAX + 64], labels[MAX_METHODS][SPEC_MAX + 40]; /* dir + "/frame_..." */
    struct compare_report_method rm[2 * MAX_METHODS];
    double *errs = xmalloc(sizeof(double) * 2 * (size_t)n * (size_t)o->frames);
    struct csv_table frames;
    snprintf(path, sizeof path, "%s/frames.csv", out_dir);
    const int have_frames = csv_table_read(path, &frames, msg) == 0;
    int nr = 0;
    for (int k = 0; k < n; k++) {
        double *fx = errs + 2 * (size_t)k * o->frames, *fy = fx + o->frames;
        const int nframes = have_frames ? frame_errors(&frames, specs[k].label, o->frames, fx, fy) : 0;
        int i = nr++;
        snprintf(pngs[i], sizeof pngs[i], "%s/frame_%04d.png", specs[k].dir, o->frames - 1);
        rm[i] = (struct compare_report_method){.label = specs[k].label, .png = pngs[i], .dir = specs[k].dir,
                                               .method = specs[k].method, .image = res[k].image,
                                               .ms_per_frame = res[k].ms_per_frame,
                                               .spp = res[k].spp, .instances = res[k].instances, .err = res[k].err,
                                               .flip = res[k].flip, .ms_pass = res[k].ms_pass, .nframes = nframes,
                                               .frame = fx, .frame_relmse = fy,
                                               .nflicker = p->camera_path ? 0 : FLICKER_SCALES,
                                               .flicker_block = flicker_block, .flicker = res[k].flicker};
        if (!res[k].image_dn)
            continue;
        snprintf(labels[k], sizeof labels[k], "%.*s, denoised (BIASED)", SPEC_MAX, specs[k].label);
        i = nr++;
        snprintf(pngs[i], sizeof pngs[i], "%s/frame_%04d_denoised.png", specs[k].dir, o->frames - 1);
        rm[i] = (struct compare_report_method){.label = labels[k], .png = pngs[i], .image = res[k].image_dn,
                                               .ms_per_frame = res[k].ms_per_frame, .spp = res[k].spp,
                                               .instances = res[k].instances, .err = res[k].err_dn, .flip = NAN,
                                               .denoised = 1, .nflicker = p->camera_path ? 0 : FLICKER_SCALES,
                                               .flicker_block = flicker_block, .flicker = res[k].flicker_dn};
    }
    if (have_frames)
        csv_table_free(&frames);
    const char *names[PASS_MAX];
    for (int q = 0; q < pass_count(); q++)
        names[q] = pass_name(q);
    const struct compare_report_run run = {out_dir, command, st->s.name, p->width, p->height, o->frames - 1,
                                           p->camera_path, o->equal_time, ref, o->self_contained, pass_count(),
                                           names};
    int rc = 0;
    if (compare_write_report(&run, nr, rm, msg) != 0) {
        cli_error("--report: %s", msg);
        rc = EXIT_RUNTIME;
    }
    free(errs);
    return rc;
}

int compare_write_table(const struct compare_setup *st, const char *out_dir, const char *command,
                        const struct compare_result *res, const float *ref)
{
    char msg[RESTIR_MSG_LEN];
    const struct cli_options *o = &st->o;
    const struct render_params *p = &st->p;
    const struct compare_spec *specs = st->specs;
    const int n = st->n;
    int rc = 0;
    char csv_path[4200];
    snprintf(csv_path, sizeof(csv_path), "%s/compare.csv", out_dir);
    struct csv_writer csv;
    if (csv_open(&csv, csv_path,
                 "method,ms_per_frame,spp,instances,relmse,mape,smape,luma_rmse,runs,temporal_cov,relmse_sem,mape_sem,"
                 "smape_sem,mape_disoccluded,mape_disoccluded_sem,disoccluded_share,gradient_relmse,"
                 "gradient_relmse_sem,gradient_relmse_trim1,gradient_relmse_trim1_sem,gradient_mape,gradient_mape_sem,"
                 "relmse_denoised,relmse_denoised_sem,mape_denoised,mape_denoised_sem,smape_denoised,"
                 "smape_denoised_sem,mape_disoccluded_denoised,mape_disoccluded_denoised_sem,temporal_cov_denoised,"
                 "ref_relmse,ref_mape,ref_smape,relmse_net,flip,flip_sem,ref_mape_disoccluded,flicker1,flicker4,"
                 "flicker16,boiling_index,flicker1_denoised,flicker4_denoised,flicker16_denoised,"
                 "boiling_index_denoised,lag_frames,lag_frames_denoised,lag_frames_blocks,lag_frames_blocks_denoised,"
                 "ghost_frames,ghost_frames_denoised",
                 msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    int w = 12;
    for (int k = 0; k < n; k++)
        if ((int)strlen(specs[k].label) > w)
            w = (int)strlen(specs[k].label);
    printf("%s, %dx%d, %s camera, error at frame %d%s:\n", o->scene, p->width, p->height,
           p->camera_path ? "moving" : "static", o->frames - 1, o->equal_time ? ", equal time" : "");
    const int runs = o->runs > 1;
    int any_grad = 0; /* a gradient method's row: the table gets 002 Fig. 7's gradient relMSE, trimmed and MAPE */
    for (int k = 0; k < n; k++)
        any_grad |= isfinite(res[k].grad_relmse);
    if (runs)
        printf("(errors: means of %d independently seeded runs, +- their standard error; tcov: 000 Eq. 17 at lag %d "
               "over frames %d-%d)\n",
               o->runs, COMPARE_COV_LAG, o->frames / 2, o->frames - 1);
    printf("%-*s %10s %6s %5s %12s%s %10s%s %8s%s %8s%s %12s %14s %10s%s %6s%s%s%s%s%s%s%s\n", w, "method",
           "ms/frame", "spp", "inst", "relMSE", runs ? "       +-" : "", "MAPE", runs ? "       +-" : "", "SMAPE",
           runs ? "     +-" : "", "FLIP", runs ? "     +-" : "", "relMSE/first", "relMSE*t/first", "MAPE dis",
           runs ? "       +-" : "",
           "dis", runs ? "         tcov" : "",
           any_grad ? "  grad relMSE" : "", any_grad && runs ? "       +-" : "", any_grad ? "   grad trim1" : "",
           any_grad && runs ? "       +-" : "", any_grad ? "    grad MAPE" : "", any_grad && runs ? "       +-" : "");
    for (int k = 0; k < n; k++) {
        const struct compare_result *c = &res[k];
        /* a metric that does not apply to the row (no history, no gradients, one run) prints '-' */
        char tcov[32] = "", se[4][32] = {"", "", "", ""}, grad[6][32] = {"", "", "", "", "", ""}, dis[2][32],
             flip[2][32] = {"", ""};
        const double gv[3] = {c->grad_relmse, c->grad_relmse_trim, c->grad_mape};
        const double gs[3] = {c->grad_relmse_sem, c->grad_relmse_trim_sem, c->grad_mape_sem};
        for (int j = 0; j < 3; j++) {
            if (any_grad)
                table_cell(grad[2 * j], sizeof grad[2 * j], " %12.5g", 13, gv[j]);
            if (any_grad && runs)
                table_cell(grad[2 * j + 1], sizeof grad[2 * j + 1], " %8.2g", 9, gs[j]);
        }
        if (runs) {
            table_cell(tcov, sizeof tcov, " %12.5g", 13, c->temporal_cov);
            table_cell(se[0], sizeof se[0], " %8.2g", 9, c->sem.relmse);
            table_cell(se[1], sizeof se[1], " %8.2g", 9, c->sem.mape);
            table_cell(se[2], sizeof se[2], " %6.2g", 7, c->sem.smape);
            table_cell(se[3], sizeof se[3], " %8.2g", 9, c->mape_dis_sem);
            table_cell(flip[1], sizeof flip[1], " %6.2g", 7, c->flip_sem);
        }
        table_cell(flip[0], sizeof flip[0], "%8.4f", 8, c->flip);
        table_cell(dis[0], sizeof dis[0], " %10.5g", 11, c->mape_dis);
        table_cell(dis[1], sizeof dis[1], " %6.3f", 7, c->dis_share);
        /* relMSE x frame time: the error an equal budget would give if variance falls as 1/time, which
         * an integer spp cannot always spend (pt's 1 spp may take less than the budget) */
        const double first_t = res[0].err.relmse * res[0].ms_per_frame;
        printf("%-*s %10.2f %6d %5d %12.5g%s %10.5g%s %8.3f%s %s%s %12.3f %14.3f%s%s%s%s%s%s%s%s%s%s\n", w,
               specs[k].label, c->ms_per_frame, c->spp, c->instances, c->err.relmse, se[0], c->err.mape, se[1],
               c->err.smape, se[2], flip[0], flip[1], res[0].err.relmse > 0 ? c->err.relmse / res[0].err.relmse : 0.0,
               first_t > 0 ? c->err.relmse * c->ms_per_frame / first_t : 0.0, dis[0], se[3], dis[1], tcov, grad[0],
               grad[1], grad[2], grad[3], grad[4], grad[5]);
        if (rc == 0) {
            char field[2 * SPEC_MAX + 4], cov[32] = "", sem[4][32] = {"", "", "", ""}, dis[2][32] = {"", ""},
                                          gr[6][32] = {"", "", "", "", "", ""};
            csv_field(field, sizeof(field), specs[k].label);
            if (isfinite(c->temporal_cov))
                snprintf(cov, sizeof cov, "%.6g", c->temporal_cov);
            if (c->runs > 1) {
                snprintf(sem[0], sizeof sem[0], "%.6g", c->sem.relmse);
                snprintf(sem[1], sizeof sem[1], "%.6g", c->sem.mape);
                snprintf(sem[2], sizeof sem[2], "%.6g", c->sem.smape);
                if (isfinite(c->mape_dis_sem))
                    snprintf(sem[3], sizeof sem[3], "%.6g", c->mape_dis_sem);
            }
            if (isfinite(c->mape_dis))
                snprintf(dis[0], sizeof dis[0], "%.6g", c->mape_dis);
            if (isfinite(c->dis_share))
                snprintf(dis[1], sizeof dis[1], "%.6g", c->dis_share);
            for (int j = 0; j < 3; j++) { /* gradient relMSE, its 1%-trimmed mean, gradient MAPE; each + sem */
                if (isfinite(gv[j]))
                    snprintf(gr[2 * j], sizeof gr[2 * j], "%.6g", gv[j]);
                if (c->runs > 1 && isfinite(gs[j]))
                    snprintf(gr[2 * j + 1], sizeof gr[2 * j + 1], "%.6g", gs[j]);
            }
            char dn[9][32] = {"", "", "", "", "", "", "", "", ""}; /* after denoising: relMSE, MAPE, SMAPE, MAPE
                                                                     disoccluded, each + sem; tcov */
            if (isfinite(c->temporal_cov_dn))
                snprintf(dn[8], sizeof dn[8], "%.6g", c->temporal_cov_dn);
            const double dv[4] = {c->err_dn.relmse, c->err_dn.mape, c->err_dn.smape, c->mape_dis_dn};
            const double ds[4] = {c->sem_dn.relmse, c->sem_dn.mape, c->sem_dn.smape, c->mape_dis_dn_sem};
            for (int j = 0; j < 4; j++) {
                if (isfinite(dv[j]))
                    snprintf(dn[2 * j], sizeof dn[2 * j], "%.6g", dv[j]);
                if (c->runs > 1 && isfinite(ds[j]))
                    snprintf(dn[2 * j + 1], sizeof dn[2 * j + 1], "%.6g", ds[j]);
            }
            char own[4][32] = {"", "", "", ""}; /* the reference's own errors (its halves); empty without */
            const double own_v[4] = {c->ref_own[0], c->ref_own[1], c->ref_own[2], c->ref_own_dis};
            for (int j = 0; j < 4; j++)
                if (isfinite(own_v[j]))
                    snprintf(own[j], sizeof own[j], "%.6g", own_v[j]);
            char net[32] = ""; /* relMSE without the reference's own share */
            if (isfinite(c->relmse_net))
                snprintf(net, sizeof net, "%.6g", c->relmse_net);
            char fl[2][32] = {"", ""}; /* HDR-FLIP and its standard error */
            if (isfinite(c->flip))
                snprintf(fl[0], sizeof fl[0], "%.6g", c->flip);
            if (c->runs > 1 && isfinite(c->flip_sem))
                snprintf(fl[1], sizeof fl[1], "%.6g", c->flip_sem);
            /* the largest lag after a change of the lights, then denoised; the same of the blocks', the ghost's */
            char lag[6][32] = {"", "", "", "", "", ""};
            const double *lags[6] = {c->lag, c->lag_dn, c->lag_block, c->lag_block_dn, c->ghost, c->ghost_dn};
            for (int d = 0; d < 6; d++)
                if (isfinite(worst_lag(lags[d])))
                    snprintf(lag[d], sizeof lag[d], "%.0f", worst_lag(lags[d]));
            char fk[2 * FLICKER_COLS][32]; /* flicker and boiling index, as rendered then denoised */
            for (int j = 0; j < 2 * FLICKER_COLS; j++) {
                const double v = j < FLICKER_COLS ? c->flicker[j] : c->flicker_dn[j - FLICKER_COLS];
                fk[j][0] = '\0';
                if (!p->camera_path && isfinite(v))
                    snprintf(fk[j], sizeof fk[j], "%.6g", v);
            }
            csv_row(&csv,
                    "%s,%.3f,%d,%d,%.6g,%.6g,%.6g,%.6g,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,"
                    "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s",
                    field, c->ms_per_frame, c->spp, c->instances, c->err.relmse, c->err.mape, c->err.smape,
                    c->err.luma_rmse, c->runs > 0 ? c->runs : 1, cov, sem[0], sem[1], sem[2], dis[0], sem[3], dis[1],
                    gr[0], gr[1], gr[2], gr[3], gr[4], gr[5], dn[0], dn[1], dn[2], dn[3], dn[4], dn[5], dn[6], dn[7],
                    dn[8], own[0], own[1], own[2], net, fl[0], fl[1], own[3], fk[0], fk[1], fk[2], fk[3], fk[4], fk[5],
                    fk[6], fk[7], lag[0], lag[1], lag[2], lag[3], lag[4], lag[5]);
        }
    }
    print_denoised(specs, res, n, w, runs, p->denoise.method);
    if (!p->camera_path)
        print_flicker(specs, res, n, w, o->frames);
    print_lag(st, res, w);
    if (rc == 0 && csv_close(&csv, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (isfinite(res[0].ref_own[0]))
        printf("(the reference's own relMSE %.4g, from its two independent halves: compare.csv's relmse_net is relMSE "
               "without it; its own MAPE %.4g, SMAPE %.4g)\n",
               res[0].ref_own[0], res[0].ref_own[1], res[0].ref_own[2]);
    if (rc == 0 && (write_passes(out_dir, specs, res, n, msg) != 0 || write_runs(out_dir, specs, res, n, msg) != 0)) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0 && o->report)
        rc = write_report(st, out_dir, command, res, ref);
    if (rc == 0)
        printf("output: %s%s\n", out_dir, o->report ? " (report: index.html)" : "");
    return rc;
}
