/* compare_run.c: a comparison's runner (compare_run.h): one spec's runs, each as instances of
 * independently seeded renderers averaged, measured against the reference, with the runs' means and
 * standard errors. Must never implement a method. */
#include "experiments/compare_run.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_report.h"
#include "experiments/compare_worst.h"
#include "experiments/options.h"
#include "experiments/reference_checkpoint.h"
#include "io/atomic_file.h"
#include "io/report.h"
#include "scene/scene_file.h"

int compare_budget_by_spp(const struct method *m) { return method_has(m, METHOD_BUDGET_BY_SPP); }

/* The instances average their last frames: the image and the method's radiance and signed outputs
 * (method.h); a method with a reconstruct (the gradient methods) then rebuilds its image from the
 * means once (002 Sec. 5, Figure 8), and the frame time counts the instances' passes and one
 * reconstruction. */
/* The instances' average image (denoised: of their denoised frames) of a frame before the last (the
 * last frame averages in place). */
static const float *instances_mean(const struct renderer *r, int instances, size_t n3, int denoised, float *scratch)
{
    if (instances == 1)
        return denoised ? r[0].denoised : r[0].image;
    const float inv = 1.0f / (float)instances;
    for (size_t i = 0; i < n3; i++) {
        float sum = 0.0f;
        for (int k = 0; k < instances; k++)
            sum += denoised ? r[k].denoised[i] : r[k].image[i];
        scratch[i] = sum * inv;
    }
    return scratch;
}

/* The mean of the instances' images (output < 0) or of their output `output` (n floats each) into the
 * first instance's; left alone where the first has none this frame. */
static void average_into_first(struct renderer *r, int instances, int output, size_t n)
{
    float *buf[MAX_INSTANCES];
    for (int k = 0; k < instances; k++)
        if (!(buf[k] = output < 0 ? r[k].image : renderer_output(&r[k], output)))
            return;
    const float inv = 1.0f / (float)instances;
    for (size_t i = 0; i < n; i++) {
        float sum = 0.0f;
        for (int k = 0; k < instances; k++)
            sum += buf[k][i];
        buf[0][i] = sum * inv;
    }
}

void compare_forward_differences(const struct renderer *r, const float **dx, const float **dy)
{
    const int x = method_output_find(r->method, "dx", METHOD_OUTPUT_SIGNED);
    const int y = method_output_find(r->method, "dy", METHOD_OUTPUT_SIGNED);
    *dx = x >= 0 && y >= 0 ? renderer_output(r, x) : NULL;
    *dy = *dx ? renderer_output(r, y) : NULL;
    if (!*dy)
        *dx = NULL;
}

void compare_disoccluded_error(const float *image, const float *ref, const unsigned char *mask, size_t npix,
                               double *mape, double *share)
{
    *mape = *share = NAN;
    if (!mask)
        return;
    size_t marked = 0;
    for (size_t i = 0; i < npix; i++)
        marked += mask[i] != 0;
    *share = npix ? (double)marked / (double)npix : NAN;
    struct restir_metrics_error e;
    if (marked > 0 && restir_metrics_compute(image, ref, npix, mask, &e) == 0)
        *mape = e.mape;
}

void compare_gradient_errors(const float *dx, const float *dy, const float *ref, int width, int height,
                             struct compare_result *res)
{
    res->grad_relmse = res->grad_relmse_trim = res->grad_mape = NAN;
    if (!dx)
        return;
    res->grad_relmse = restir_metrics_gradient_relmse(dx, dy, ref, width, height);
    res->grad_relmse_trim = restir_metrics_gradient_relmse_trimmed(dx, dy, ref, width, height, COMPARE_GRAD_TRIM);
    res->grad_mape = restir_metrics_gradient_mape(dx, dy, ref, width, height);
}

double compare_flip(const float *image, const float *ref, int width, int height)
{
    double mean = NAN;
    if (restir_metrics_flip(image, ref, width, height, RESTIR_METRICS_FLIP_PPD, NULL, &mean) != 0)
        return NAN;
    return mean;
}

void compare_denoised_errors(const float *denoised, const float *ref, const unsigned char *mask, size_t npix,
                             struct compare_result *res)
{
    res->err_dn = (struct restir_metrics_error){NAN, NAN, NAN, NAN};
    res->mape_dis_dn = NAN;
    if (!denoised)
        return;
    restir_metrics_compute(denoised, ref, npix, NULL, &res->err_dn);
    double share;
    compare_disoccluded_error(denoised, ref, mask, npix, &res->mape_dis_dn, &share);
}

/* The instances' denoised last frames averaged into a new buffer; NULL without denoising. */
static float *instances_denoised(const struct renderer *r, int instances, size_t n3)
{
    if (!r[0].denoised)
        return NULL;
    float *out = xmalloc(sizeof(float) * n3);
    const float inv = 1.0f / (float)instances;
    for (size_t i = 0; i < n3; i++) {
        float sum = 0.0f;
        for (int k = 0; k < instances; k++)
            sum += r[k].denoised[i];
        out[i] = instances == 1 ? sum : sum * inv;
    }
    return out;
}

int compare_run_method(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                       int instances, const float *ref, const char *out_dir, int keep_image,
                       struct compare_track *track, int run, struct compare_result *res, char *msg)
{
    const struct method *m = c->method;
    struct renderer r[MAX_INSTANCES];
    for (int k = 0; k < instances; k++) {
        struct render_params q = *p;
        q.seed = p->seed + COMPARE_INSTANCE_SEED_STRIDE * (uint64_t)k;
        renderer_init(&r[k], s, m, &q);
    }
    const size_t npix = (size_t)p->width * (size_t)p->height, n3 = 3 * npix;
    float *scratch = track && instances > 1 ? xmalloc(sizeof(float) * n3) : NULL;
    double ms = 0.0, ms_pass[PASS_MAX] = {0};
    struct progress pg;
    progress_begin(&pg, c->label, frames);
    for (int f = 0; f < frames; f++) {
        if (cli_stop_signal) { /* stopped: this method's result would be incomplete, so none */
            progress_end(&pg);
            for (int k = 0; k < instances; k++)
                renderer_fini(&r[k]);
            free(scratch);
            return RUN_STOPPED;
        }
        struct camera cam = scene_camera_at(s, p->camera_path, (float)f);
        struct frame_stats st0;
        double ms_frame = 0.0;
        for (int k = 0; k < instances; k++) {
            struct frame_stats st;
            renderer_render(&r[k], f, &cam, &st);
            double ms_recon = 0.0; /* the instances after the first reconstruct nothing: the mean is */
            for (int q = 0; q < pass_count(); q++)
                if (st.reconstructed >> q & 1)
                    ms_recon += st.ms[q];
            ms_frame += st.ms_total - (k > 0 ? ms_recon : 0.0);
            for (int q = 0; q < pass_count(); q++) /* as the frame time: one reconstruction */
                ms_pass[q] += k > 0 && (st.reconstructed >> q & 1) ? 0.0 : st.ms[q];
            if (k == 0)
                st0 = st;
        }
        ms += ms_frame;
        if (track) {
            compare_track_stats(track, f, ms_frame, &st0);
            if (f < frames - 1 && compare_track_wants_image(track, f)) {
                compare_track_image(track, run, f, instances_mean(r, instances, n3, 0, scratch));
                if (r[0].denoised)
                    compare_track_denoised(track, run, f, instances_mean(r, instances, n3, 1, scratch));
            }
        }
        progress_update(&pg, f + 1);
    }
    progress_end(&pg);
    free(scratch);
    if (instances > 1) {
        average_into_first(r, instances, -1, n3);
        for (int k = 0; k < method_output_count(m); k++)
            if (m->outputs[k].kind != METHOD_OUTPUT_DEBUG)
                average_into_first(r, instances, k, (size_t)m->outputs[k].channels * npix);
        struct frame_stats st;
        memset(&st, 0, sizeof(st));
        renderer_reconstruct(&r[0], &st); /* what the method derives, from the means (nothing for most) */
    }
    float *denoised = instances_denoised(r, instances, n3); /* each instance's denoised frame, averaged */
    if (track && compare_track_wants_image(track, frames - 1)) {
        compare_track_image(track, run, frames - 1, r[0].image);
        if (denoised)
            compare_track_denoised(track, run, frames - 1, denoised);
    }
    res->method = m;
    res->ms_per_frame = ms / frames;
    for (int q = 0; q < PASS_MAX; q++)
        res->ms_pass[q] = ms_pass[q] / frames;
    res->spp = compare_budget_by_spp(m) ? p->spp : 1;
    res->instances = instances;
    unsigned char *mask = NULL;
    if (method_has(m, METHOD_HISTORY)) { /* the first instance's history decides (004 Sec. 6.2) */
        mask = xmalloc(npix);
        renderer_disoccluded(&r[0], DISOCCLUSION_FRAMES, mask);
    }
    res->mask = NULL;
    res->dis_mask = NULL;
    res->per_run = NULL; /* compare_runs_finish's, so that compare_result_free is safe on any result */
    res->grad = NULL;
    res->denoised = NULL;
    res->grad_relmse = res->grad_relmse_trim = res->grad_mape = NAN;
    res->flip = NAN;
    res->err_dn = res->sem_dn = (struct restir_metrics_error){NAN, NAN, NAN, NAN};
    res->mape_dis_dn = res->mape_dis_dn_sem = NAN;
    const float *dx, *dy; /* the forward differences the gradient columns measure, NULL without */
    compare_forward_differences(&r[0], &dx, &dy);
    if (ref) { /* a planned job measures nothing: the merge does, from the frame, mask and gradients it writes */
        restir_metrics_compute(r[0].image, ref, npix, NULL, &res->err);
        res->flip = compare_flip(r[0].image, ref, p->width, p->height);
        compare_denoised_errors(denoised, ref, mask, npix, res);
        if (!keep_image)
            free(denoised);
        compare_disoccluded_error(r[0].image, ref, mask, npix, &res->mape_dis, &res->dis_share);
        compare_gradient_errors(dx, dy, ref, p->width, p->height, res);
        if (run == 0) /* for the reference's own error over these pixels (compare_reference_noise) */
            res->dis_mask = mask;
        else
            free(mask);
    } else {
        res->mask = mask;
        res->denoised = denoised;
        if (dx) {
            res->grad = xmalloc(2 * sizeof(float) * n3);
            memcpy(res->grad, dx, sizeof(float) * n3);
            memcpy(res->grad + n3, dy, sizeof(float) * n3);
        }
    }
    res->image = NULL;
    res->image_dn = ref && keep_image ? denoised : NULL; /* --report's */
    if (keep_image) {
        res->image = xmalloc(sizeof(float) * n3);
        memcpy(res->image, r[0].image, sizeof(float) * n3);
    }
    if (run > 0) { /* a later run is measured only: run 0's frame is the one written */
        for (int k = 0; k < instances; k++)
            renderer_fini(&r[k]);
        return 0;
    }
    char path[4400];
    snprintf(path, sizeof(path), "%s/%s", out_dir, c->dir);
    int rc = io_make_dirs(path, msg);
    if (rc == 0)
        rc = cli_write_frame(path, frames - 1, &r[0], msg);
    if (rc == 0 && ref && dx) /* where the gradient relMSE's worst 1% of pixel pairs are */
        rc = compare_write_worst_pairs(out_dir, c->dir, dx, dy, ref, p->width, p->height, COMPARE_GRAD_TRIM, msg);
    for (int k = 0; k < instances; k++)
        renderer_fini(&r[k]);
    return rc;
}

const char *const compare_run_columns[COMPARE_RUN_COLS] = {
    "relmse",        "mape",         "smape", "mape_disoccluded", "gradient_relmse", "gradient_relmse_trim1",
    "gradient_mape", "ms_per_frame", "flip",  "relmse_net"};

void compare_result_free(struct compare_result *res)
{
    free(res->image);
    free(res->image_dn);
    free(res->per_run);
    free(res->dis_mask);
    res->image = res->image_dn = NULL;
    res->per_run = NULL;
    res->dis_mask = NULL;
}

void compare_runs_add(struct compare_runs *a, const struct compare_result *r)
{
    if (a->n == a->cap) {
        a->cap = a->cap ? 2 * a->cap : 8;
        a->per_run = realloc(a->per_run, sizeof(double) * COMPARE_RUN_COLS * (size_t)a->cap);
        RESTIR_CHECK(a->per_run != NULL);
    }
    const double v[COMPARE_RUN_COLS] = {r->err.relmse,   r->err.mape,        r->err.smape, r->mape_dis,
                                        r->grad_relmse, r->grad_relmse_trim, r->grad_mape, r->ms_per_frame,
                                        r->flip,        NAN}; /* relmse_net: compare_reference_noise */
    memcpy(&a->per_run[(size_t)a->n * COMPARE_RUN_COLS], v, sizeof v);
    const struct restir_metrics_error *e = &r->err;
    const double x[14] = {e->relmse,   e->mape,        e->smape,         e->luma_rmse, r->mape_dis,
                          r->dis_share, r->grad_relmse, r->grad_relmse_trim, r->grad_mape,
                          r->err_dn.relmse, r->err_dn.mape, r->err_dn.smape, r->mape_dis_dn, r->flip};
    a->n++;
    for (int k = 0; k < 14; k++)
        running_mean_add(&a->m[k], x[k]);
}

void compare_runs_finish(struct compare_runs *a, struct compare_result *res)
{
    const int runs = a->n;
    double sem[14];
    for (int k = 0; k < 14; k++)
        sem[k] = running_mean_sem(&a->m[k]);
    if (runs > 1) { /* one run keeps its error bit for bit */
        res->err = (struct restir_metrics_error){a->m[0].mean, a->m[1].mean, a->m[2].mean, a->m[3].mean};
        res->mape_dis = a->m[4].mean;
        res->dis_share = a->m[5].mean;
        res->grad_relmse = a->m[6].mean;
        res->grad_relmse_trim = a->m[7].mean;
        res->grad_mape = a->m[8].mean;
        res->err_dn = (struct restir_metrics_error){a->m[9].mean, a->m[10].mean, a->m[11].mean, NAN};
        res->mape_dis_dn = a->m[12].mean;
        res->flip = a->m[13].mean;
    }
    res->mape_dis_dn_sem = sem[12];
    res->sem_dn = (struct restir_metrics_error){sem[9], sem[10], sem[11], NAN};
    res->sem = (struct restir_metrics_error){sem[0], sem[1], sem[2], sem[3]};
    res->mape_dis_sem = sem[4];
    res->grad_relmse_sem = sem[6];
    res->grad_relmse_trim_sem = sem[7];
    res->grad_mape_sem = sem[8];
    res->flip_sem = sem[13];
    res->runs = runs;
    free(res->per_run);
    res->per_run = a->per_run;
    a->per_run = NULL;
    a->cap = 0;
}

void compare_keep_fastest(struct compare_result *res, const struct compare_result *run)
{
    if (run->ms_per_frame < res->ms_per_frame) {
        res->ms_per_frame = run->ms_per_frame;
        memcpy(res->ms_pass, run->ms_pass, sizeof res->ms_pass);
    }
}

void compare_result_clear_sequence(struct compare_result *res)
{
    res->temporal_cov = res->temporal_cov_dn = NAN;
    for (int k = 0; k < FLICKER_COLS; k++)
        res->flicker[k] = res->flicker_dn[k] = NAN;
    for (int k = 0; k < COMPARE_MAX_CHANGES; k++) {
        res->lag[k] = res->lag_dn[k] = res->lag_block[k] = res->lag_block_dn[k] = NAN;
        res->ghost[k] = res->ghost_dn[k] = NAN;
    }
}

int compare_run_spec(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                     int instances, int runs, const float *ref, const char *out_dir, int keep_image,
                     struct compare_track *track, struct compare_result *res, char *msg)
{
    struct compare_runs acc = {0};
    if (track)
        compare_track_begin(track);
    for (int n = 0; n < runs; n++) {
        struct render_params q = *p;
        q.seed = compare_run_seed(p->seed, n);
        struct compare_result one;
        int rc = compare_run_method(s, c, &q, frames, instances, ref, out_dir, n == 0 && keep_image, track, n,
                                    n == 0 ? res : &one, msg);
        if (rc != 0) {
            if (n > 0) {
                free(res->image);
                free(res->image_dn);
                res->image = res->image_dn = NULL;
            }
            free(acc.per_run);
            return rc;
        }
        compare_runs_add(&acc, n == 0 ? res : &one);
        if (n > 0)
            compare_keep_fastest(res, &one);
    }
    compare_runs_finish(&acc, res);
    compare_result_clear_sequence(res);
    res->temporal_cov = track ? compare_track_end(track, c->label) : NAN;
    if (track) {
        compare_track_lag(track, 0, res->lag, res->lag_block);
        compare_track_lag(track, 1, res->lag_dn, res->lag_block_dn);
        compare_track_ghost(track, 0, res->ghost);
        compare_track_ghost(track, 1, res->ghost_dn);
    }
    if (track) {
        compare_track_flicker(track, 0, res->flicker);
        compare_track_flicker(track, 1, res->flicker_dn);
    }
    res->temporal_cov_dn = track ? compare_track_end_denoised(track) : NAN;
    return 0;
}
