/* compare_track.c: per-frame statistics, errors along the sequence and temporal autocovariance of
 * `restir compare` (compare_track.h). Must never implement a method or call into cmd_compare.c. */
#include "experiments/compare_track.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/vec3.h"

#define COV_EPS 1e-4f /* 000 Appendix A */

void compare_track_init(struct compare_track *t, int frames, int runs, int ref_every, int w, int h,
                        float *last_ref)
{
    memset(t, 0, sizeof *t);
    t->frames = frames;
    t->runs = runs;
    t->width = w;
    t->height = h;
    t->ref_frame = xmalloc(sizeof(int) * (size_t)(frames + 1));
    t->ref = xcalloc((size_t)(frames + 1), sizeof(float *));
    if (last_ref) {
        for (int f = ref_every - 1; ref_every > 0 && f < frames - 1; f += ref_every)
            t->ref_frame[t->nref++] = f;
        t->ref_frame[t->nref] = frames - 1;
        t->ref[t->nref++] = last_ref;
    }
    t->blocks = (w / COMPARE_LAG_BLOCK) * (h / COMPARE_LAG_BLOCK);
    t->cov_first = frames / 2;
    t->sums = xcalloc((size_t)frames, sizeof *t->sums);
    const size_t window = (size_t)(frames - t->cov_first);
    /* every run's window: the autocovariance needs two runs, flicker one */
    t->seq = window >= 2 ? xmalloc(sizeof(float) * (size_t)runs * window * (size_t)w * (size_t)h) : NULL;
}

int compare_track_open(struct compare_track *t, const char *out_dir, char *msg)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/frames.csv", out_dir);
    if (csv_open(&t->csv, path,
                 "method,frame,runs,ms_frame,ms_temporal,temporal_accept,bp_received,bp_accepted,splat_received,"
                 "splat_accepted,relmse,mape,smape,luma_rmse",
                 msg) != 0)
        return -1;
    t->csv_open = 1;
    return 0;
}

void compare_track_begin(struct compare_track *t)
{
    memset(t->sums, 0, sizeof(*t->sums) * (size_t)t->frames);
    const size_t block_sums = sizeof(double) * (size_t)t->frames * (size_t)t->blocks;
    double *const block[4] = {t->block_err, t->block_err_dn, t->block_lum, t->block_lum_dn};
    for (int k = 0; k < 4; k++)
        if (block[k])
            memset(block[k], 0, block_sums);
    t->clamped = t->measured = 0;
    t->has_dn = 0;
}

void compare_track_stats(struct compare_track *t, int f, double ms, const struct frame_stats *st)
{
    struct compare_frame_sums *s = &t->sums[f];
    const double vp = st->valid_pixels > 0 ? (double)st->valid_pixels : 1.0;
    s->ms_frame += ms;
    s->ms_temporal += st->ms[PASS_TEMPORAL];
    s->accept += (double)st->temporal_accepted / vp;
    s->bp_received += (double)st->temporal.bp_received / vp;
    s->bp_accepted += (double)st->temporal.bp_accepted / vp;
    s->splat_received += (double)st->temporal.splat_received / vp;
    s->splat_accepted += (double)st->temporal.splat_accepted / vp;
}

/* The luminance (v3_luminance) of each of an RGB image's n pixels. */
static void luminance_map(const float *rgb, size_t n, float *out)
{
    for (size_t i = 0; i < n; i++)
        out[i] = v3_luminance(v3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]));
}

static int reference_index(const struct compare_track *t, int f)
{
    for (int k = 0; k < t->nref; k++)
        if (t->ref_frame[k] == f)
            return k;
    return -1;
}

int compare_track_wants_image(const struct compare_track *t, int f)
{
    return reference_index(t, f) >= 0 || (t->seq && f >= t->cov_first);
}

/* Frame f's luminance, clamped at 0, into its place in seq (a window frame; see compare_track_image). */
static void store_luminance(struct compare_track *t, float *seq, int run, int f, const float *image)
{
    const size_t npix = (size_t)t->width * (size_t)t->height, window = (size_t)(t->frames - t->cov_first);
    float *out = &seq[((size_t)run * window + (size_t)(f - t->cov_first)) * npix];
    for (size_t i = 0; i < npix; i++) {
        const float l = v3_luminance(v3(image[3 * i], image[3 * i + 1], image[3 * i + 2]));
        t->clamped += l < 0.0f;
        out[i] = l < 0.0f ? 0.0f : l;
    }
    t->measured += npix;
}

/* The mean of map (w wide) over block b (COMPARE_LAG_BLOCK wide, bw of them per row). */
static double block_mean(const float *map, int w, int bw, int b)
{
    const int x0 = (b % bw) * COMPARE_LAG_BLOCK, y0 = (b / bw) * COMPARE_LAG_BLOCK;
    double e = 0.0;
    for (int y = y0; y < y0 + COMPARE_LAG_BLOCK; y++)
        for (int x = x0; x < x0 + COMPARE_LAG_BLOCK; x++)
            e += map[(size_t)y * (size_t)w + (size_t)x];
    return e / (COMPARE_LAG_BLOCK * COMPARE_LAG_BLOCK);
}

/* With changes of the lights, frame f's relMSE and mean luminance per COMPARE_LAG_BLOCK block added to
 * *sums and *lum (frames x blocks each, allocated here at the first). */
static void add_block_errors(struct compare_track *t, double **sums, double **lum, int f, const float *image,
                             const float *ref)
{
    if (t->nchanges < 1 || t->blocks < 1 || t->nref < t->frames) /* the lag needs every frame's error */
        return;
    const int w = t->width, bw = w / COMPARE_LAG_BLOCK;
    const size_t n = (size_t)w * (size_t)t->height;
    if (!*sums) {
        *sums = xcalloc((size_t)t->frames * (size_t)t->blocks, sizeof(double));
        *lum = xcalloc((size_t)t->frames * (size_t)t->blocks, sizeof(double));
    }
    if (!t->err_map)
        t->err_map = xmalloc(sizeof(float) * n);
    restir_metrics_relmse_map(image, ref, n, t->err_map);
    double *out = *sums + (size_t)f * (size_t)t->blocks, *out_lum = *lum + (size_t)f * (size_t)t->blocks;
    for (int b = 0; b < t->blocks; b++)
        out[b] += block_mean(t->err_map, w, bw, b);
    luminance_map(image, n, t->err_map);
    for (int b = 0; b < t->blocks; b++)
        out_lum[b] += block_mean(t->err_map, w, bw, b);
}

void compare_track_denoised(struct compare_track *t, int run, int f, const float *denoised)
{
    if (reference_index(t, f) >= 0) {
        struct restir_metrics_error e;
        restir_metrics_compute(denoised, t->ref[reference_index(t, f)], (size_t)t->width * (size_t)t->height, NULL, &e);
        t->sums[f].relmse_dn += e.relmse;
        t->has_dn = 1;
        add_block_errors(t, &t->block_err_dn, &t->block_lum_dn, f, denoised, t->ref[reference_index(t, f)]);
    }
    if (!t->seq || f < t->cov_first)
        return;
    if (!t->seq_dn)
        t->seq_dn = xmalloc(sizeof(float) * (size_t)t->runs * (size_t)(t->frames - t->cov_first) * (size_t)t->width *
                            (size_t)t->height);
    store_luminance(t, t->seq_dn, run, f, denoised);
}

void compare_track_image(struct compare_track *t, int run, int f, const float *image)
{
    const size_t npix = (size_t)t->width * (size_t)t->height;
    const int k = reference_index(t, f);
    if (k >= 0) {
        struct restir_metrics_error e;
        restir_metrics_compute(image, t->ref[k], npix, NULL, &e);
        struct restir_metrics_error *s = &t->sums[f].err;
        s->relmse += e.relmse;
        s->mape += e.mape;
        s->smape += e.smape;
        s->luma_rmse += e.luma_rmse;
        add_block_errors(t, &t->block_err, &t->block_lum, f, image, t->ref[k]);
    }
    if (t->seq && f >= t->cov_first) {
        /* Rec. 709 luminance, as restir_metrics_luminance, clamped at 0. 000 Eq. 17 divides each pixel's deviation
         * by its mean over the runs (+ 1e-4): for radiance, which is never negative, |z| <= N - 1. The L2 and L1
         * reconstructions of the gradient methods (002 Sec. 5) are signed, and where a pixel's mean over the runs
         * crosses 0 the ratio is unbounded with either sign: on ajar at 96x64 a few dark pixels with means of
         * +-1e-3 and values of +-1 made tcov -27 with 16 runs (0.51 clamped). Clamping is the identity for every
         * other method and measures the image as it is displayed; a NaN stays NaN. */
        store_luminance(t, t->seq, run, f, image);
    }
}

double compare_track_end(struct compare_track *t, const char *label)
{
    const double k = 1.0 / t->runs;
    char field[2 * 256 + 4];
    csv_field(field, sizeof field, label);
    for (int f = 0; t->csv_open && f < t->frames; f++) {
        const struct compare_frame_sums *s = &t->sums[f];
        char err[160] = ",,,";
        if (reference_index(t, f) >= 0)
            snprintf(err, sizeof err, "%.6g,%.6g,%.6g,%.6g", s->err.relmse * k, s->err.mape * k, s->err.smape * k,
                     s->err.luma_rmse * k);
        csv_row(&t->csv, "%s,%d,%d,%.3f,%.3f,%.4f,%.4f,%.4f,%.4f,%.4f,%s", field, f, t->runs, s->ms_frame * k,
                s->ms_temporal * k, s->accept * k, s->bp_received * k, s->bp_accepted * k, s->splat_received * k,
                s->splat_accepted * k, err);
    }
    const int window = t->frames - t->cov_first;
    if (!t->seq || t->runs < 2 || window < COMPARE_COV_LAG + 1)
        return NAN;
    if (t->clamped > 0)
        fprintf(stderr, "restir: compare: %s: tcov of the luminance clamped at 0 (%.2f%% of its values were negative: "
                "a signed reconstruction)\n", label, 100.0 * (double)t->clamped / (double)t->measured);
    return restir_metrics_temporal_autocovariance(t->seq, t->runs, window, t->width, t->height, COMPARE_COV_LAG, COV_EPS,
                                          NULL);
}

/* The frames from `from` until series[f * stride] (f in [from, end)) is within COMPARE_LAG_TOLERANCE of
 * its steady state, the mean of the segment's last quarter. */
static double settle_frames(const double *series, size_t stride, int from, int end)
{
    const int tail = (end - from) / 4 > 1 ? (end - from) / 4 : 1;
    double steady = 0.0;
    for (int f = end - tail; f < end; f++)
        steady += series[(size_t)f * stride] / tail;
    for (int f = from; f < end; f++)
        if (series[(size_t)f * stride] <= (1.0 + COMPARE_LAG_TOLERANCE) * steady)
            return f - from;
    return NAN; /* only where the series holds a NaN */
}

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The COMPARE_LAG_QUANTILE quantile of vals[0 .. n-1] (n >= 1; sorts them). */
static double quantile(double *vals, int n)
{
    qsort(vals, (size_t)n, sizeof(double), by_value);
    const int q = (int)ceil(COMPARE_LAG_QUANTILE * n) - 1;
    return vals[q < 0 ? 0 : q];
}

void compare_track_lag(const struct compare_track *t, int denoised, double *lag, double *block)
{
    const double *block_err = denoised ? t->block_err_dn : t->block_err;
    double *image = xmalloc(sizeof(double) * (size_t)t->frames);
    double *lags = xmalloc(sizeof(double) * (size_t)(t->blocks + 1));
    for (int f = 0; f < t->frames; f++)
        image[f] = (denoised ? t->sums[f].relmse_dn : t->sums[f].err.relmse) / t->runs;
    for (int c = 0; c < t->nchanges; c++) {
        const int next = c + 1 < t->nchanges ? t->change[c + 1] : t->frames;
        const int from = t->change[c], end = next < t->frames ? next : t->frames;
        lag[c] = block[c] = NAN;
        if (end - from < 4 || from < 0 || (denoised && !t->has_dn))
            continue;
        int measured = 1;
        for (int f = from; f < end; f++)
            measured &= reference_index(t, f) >= 0;
        if (!measured)
            continue;
        lag[c] = settle_frames(image, 1, from, end);
        if (!block_err)
            continue;
        int n = 0;
        for (int b = 0; b < t->blocks; b++) {
            const double l = settle_frames(block_err + b, (size_t)t->blocks, from, end);
            if (isfinite(l))
                lags[n++] = l;
        }
        if (n > 0) /* the quantile: the smallest lag at least that share of the blocks reach */
            block[c] = quantile(lags, n);
    }
    free(image);
    free(lags);
}

void compare_track_ghost(const struct compare_track *t, int denoised, double *ghost)
{
    const double *lum = denoised ? t->block_lum_dn : t->block_lum;
    double *dev = xmalloc(sizeof(double) * (size_t)t->frames * (size_t)(t->blocks + 1));
    double *excess = xmalloc(sizeof(double) * (size_t)t->frames), *vals = xmalloc(sizeof(double) * (t->blocks + 1));
    double *before = xmalloc(sizeof(double) * (size_t)(t->blocks + 1));
    double *now = xmalloc(sizeof(double) * (size_t)(t->blocks + 1));
    float *ref_lum = xmalloc(sizeof(float) * (size_t)t->width * (size_t)t->height);
    const int bw = t->width / COMPARE_LAG_BLOCK;
    for (int c = 0; c < t->nchanges; c++) {
        const int next = c + 1 < t->nchanges ? t->change[c + 1] : t->frames;
        const int from = t->change[c], end = next < t->frames ? next : t->frames;
        ghost[c] = NAN;
        if (!lum || end - from < 4 || from < 0 || (denoised && !t->has_dn))
            continue;
        /* each block's deviation |mean - reference| at every frame of the segment, over the brighter of
         * the block's reference then and just before the change (so that a block a switch-off leaves dark
         * is measured against the light it had); blocks dark at both, below COMPARE_GHOST_DARK of the
         * image's mean, are left out */
        int measured = 1;
        for (int f = from - (from > 0); f < end; f++)
            measured &= reference_index(t, f) >= 0;
        if (!measured)
            continue;
        const size_t npix = (size_t)t->width * (size_t)t->height;
        luminance_map(t->ref[reference_index(t, from > 0 ? from - 1 : from)], npix, ref_lum);
        double before_mean = 0.0;
        for (int b = 0; b < t->blocks; b++) {
            before[b] = block_mean(ref_lum, t->width, bw, b);
            before_mean += before[b] / t->blocks;
        }
        for (int f = from; f < end; f++) {
            luminance_map(t->ref[reference_index(t, f)], npix, ref_lum);
            double image_mean = 0.0;
            for (int b = 0; b < t->blocks; b++) {
                now[b] = block_mean(ref_lum, t->width, bw, b);
                image_mean += now[b] / t->blocks;
            }
            for (int b = 0; b < t->blocks; b++) {
                const double r = now[b], scale = fmax(r, before[b]);
                const int lit = r > COMPARE_GHOST_DARK * image_mean || before[b] > COMPARE_GHOST_DARK * before_mean;
                dev[(size_t)f * (size_t)t->blocks + (size_t)b] =
                    lit ? fabs(lum[(size_t)f * (size_t)t->blocks + (size_t)b] / t->runs - r) / scale : NAN;
            }
        }
        /* its excess over the block's own steady deviation (the mean of the segment's last quarter: noise and
         * a denoiser's bias stay in it), and the quantile of the excess over the blocks per frame */
        const int tail = (end - from) / 4 > 1 ? (end - from) / 4 : 1;
        for (int b = 0; b < t->blocks; b++) {
            double steady = 0.0;
            for (int f = end - tail; f < end; f++)
                steady += dev[(size_t)f * (size_t)t->blocks + (size_t)b] / tail;
            for (int f = from; f < end; f++)
                dev[(size_t)f * (size_t)t->blocks + (size_t)b] -= steady;
        }
        for (int f = from; f < end; f++) {
            int n = 0;
            for (int b = 0; b < t->blocks; b++)
                if (isfinite(dev[(size_t)f * (size_t)t->blocks + (size_t)b]))
                    vals[n++] = dev[(size_t)f * (size_t)t->blocks + (size_t)b];
            excess[f] = n > 0 ? quantile(vals, n) : NAN;
        }
        int settled = end; /* the first frame from which the quantile stays within the tolerance */
        while (settled > from && excess[settled - 1] <= COMPARE_LAG_TOLERANCE)
            settled--;
        ghost[c] = settled < end ? settled - from : NAN;
    }
    free(dev);
    free(excess);
    free(before);
    free(now);
    free(vals);
    free(ref_lum);
}

void compare_track_flicker(const struct compare_track *t, int denoised, double out[FLICKER_COLS])
{
    const float *seq = denoised ? t->seq_dn : t->seq;
    for (int k = 0; k < FLICKER_COLS; k++)
        out[k] = NAN;
    if (!seq || t->nref < 1 || t->lights_change_in_window)
        return;
    flicker_measure(seq, t->runs, t->frames - t->cov_first, t->width, t->height, t->ref[t->nref - 1], out);
}

double compare_track_end_denoised(struct compare_track *t)
{
    const int window = t->frames - t->cov_first;
    if (!t->seq_dn || window < COMPARE_COV_LAG + 1)
        return NAN;
    const double cov = restir_metrics_temporal_autocovariance(t->seq_dn, t->runs, window, t->width, t->height,
                                                              COMPARE_COV_LAG, COV_EPS, NULL);
    free(t->seq_dn); /* the next spec may not denoise */
    t->seq_dn = NULL;
    return cov;
}

int compare_track_close(struct compare_track *t, char *msg)
{
    t->csv_open = 0;
    return csv_close(&t->csv, msg);
}

void compare_track_fini(struct compare_track *t)
{
    if (t->csv_open)
        csv_abort(&t->csv);
    t->csv_open = 0;
    for (int k = 0; k + 1 < t->nref; k++)
        free(t->ref[k]);
    free(t->ref);
    free(t->ref_frame);
    free(t->sums);
    free(t->seq);
    free(t->seq_dn);
    free(t->block_err);
    free(t->block_err_dn);
    free(t->block_lum);
    free(t->block_lum_dn);
    free(t->err_map);
    memset(t, 0, sizeof *t);
}
