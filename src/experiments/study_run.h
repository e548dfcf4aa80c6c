/* study_run.h: the pieces of `restir study` (000 Sec. 6-7, Appendix A) that a job runs alone (study_run.c).
 * Must never implement a method or call into cmd_study.c: it drives the renderer. */
#ifndef RESTIR_EXPERIMENTS_STUDY_RUN_H
#define RESTIR_EXPERIMENTS_STUDY_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "experiments/flicker_scales.h"
#include "experiments/options.h"
#include "methods/renderer.h"
#include "scene/scene.h"

/* The configurations, one run of one configuration (a "unit"), the unit's result file, and the
 * combination of a configuration's runs into its row. The unsplit study and a merged plan both
 * call these same functions on the same data, so they write the same numbers. */

#define STUDY_MAX_CONFIGS 64
#define STUDY_COV_LAG 3 /* 000 Appendix A: autocovariance at a lag of 3 frames */

struct study_config {
    char name[40];
    enum spatial_select_mode select;
    float radius;
    int candidates;
    int spatial_off;      /* no spatial reuse at all (does spatial reuse itself help?) */
    int history_temporal; /* the next frame's history is the temporal output (history=temporal) */
};

struct study_result {
    double smape_all, smape_hard, temporal_cov, spatial_cov, ms_select, ms_spatial, ms_frame;
    double temporal_cov_hard; /* temporal_cov over the hard pixels only (000 Sec. 7.1: "43-57%") */
    /* standard errors of smape_all and smape_hard over the runs (each run's SMAPE its frames' mean;
     * NaN with one run) */
    double smape_all_sem, smape_hard_sem;
    /* jackknife standard errors of temporal_cov, spatial_cov and temporal_cov_hard over the runs (NaN
     * under 3 runs) */
    double temporal_cov_sem, spatial_cov_sem, temporal_cov_hard_sem;
    /* Each run's own values, for pairing configurations by seed (runs.csv): runs * STUDY_RUN_COLS
     * doubles, run-major, in the order of study_run_columns (SMAPE all and hard, means over the run's
     * frames; the mean select, spatial and frame times; the three covariances without that run, NaN
     * under 3 runs). Allocated by study_row_end; study_result_free frees it. */
    int runs;
    double *per_run;
    /* flicker at flicker_block's sizes and the boiling index over the measured frames of every run
     * (flicker_measure; NaN under 2 frames or below 16 x 16 pixels) */
    double flicker[FLICKER_COLS];
    /* the reference's own SMAPE over all and the hard pixels, from its halves (NaN without): the
     * share of smape_all and smape_hard that is the reference's noise, the same for every row */
    double ref_smape[2];
};

#define STUDY_RUN_COLS 8
/* The names of per_run's columns, as runs.csv heads them ("_loo": the covariance without the run). */
extern const char *const study_run_columns[STUDY_RUN_COLS];
void study_result_free(struct study_result *res);

/* One run of one configuration: what its measured frames leave for the study's statistics. */
struct study_unit {
    int frames;
    size_t npix;
    double *luminance; /* frames * npix: L of each measured frame (restir_metrics_luminance) */
    double *ms;        /* frames * 3: the select pass, the spatial pass, the whole frame */
    double *luminance_dn; /* denoise=svgf|atrous: the same of each denoised frame; else NULL */
};

/* The curve of 000 Figure 3 (error against covariance over radii) configuration c is a point of: 0
 * for Bitterli's selection, 1 for compat with K = 32 (the presets, compat-rR-k32, compat@R), -1
 * for none. */
int study_pareto_series(const struct study_config *c);
/* --configs and --radii into cfg (at most STUDY_MAX_CONFIGS). Returns 0, or -1 with msg. */
int study_parse_configs(const struct cli_options *o, struct study_config *cfg, int *n, char *msg);
/* The hard-pixel mask of the static view (000 Sec. 7), the ratio counting the neighbors as
 * `counting` (enum restir_hard_neighbors) says. Returns the number of hard pixels. */
int study_hard_pixel_mask(const struct scene *s, const struct render_params *p, const struct camera *cam,
                          int counting, unsigned char *mask);
/* The row the strip plot shows: the one with the most hard pixels. */
int study_strip_row(const unsigned char *hard, int w, int h);
/* The static camera every study run uses. */
struct camera study_camera(const struct scene *s);

/* Configuration c's settings (selection, radius, candidates, spatial reuse, history) over p: what
 * every run of c renders with, but the seed. */
void study_config_apply(const struct study_config *c, struct render_params *p);
/* Run r of a study configuration renders with seed base->seed + r * STUDY_RUN_SEED_STRIDE. */
#define STUDY_RUN_SEED_STRIDE 1000003ull
/* Renders run `run` (seed base->seed + STUDY_RUN_SEED_STRIDE run) of configuration c: o->warmup frames, then
 * o->frames measured into u (allocated here). Returns 0, or -1 when a stop signal arrived (u is
 * then freed). */
int study_run_unit(const struct scene *s, const struct method *method, const struct render_params *base,
                   const struct study_config *c, const struct cli_options *o, int run, struct study_unit *u);
void study_unit_free(struct study_unit *u);
/* A unit's result file (plan.h blobs, tagged with plan id). Returns 0, or -1 with msg; read: 1 when
 * the file does not exist, -1 when it is corrupt or of another shape than frames x npix. */
int study_unit_write(const char *path, uint64_t id, const struct study_unit *u, char *msg);
int study_unit_read(const char *path, uint64_t id, int frames, size_t npix, struct study_unit *u, char *msg);

/* A configuration's row, built from its runs' units one at a time, in run order, so only one
 * unit's double luminance is held at once: SMAPE over all and hard pixels against ref and the mean
 * pass times as units arrive; the temporal and spatial relative covariances at the end, from the
 * float luminance of every run. Run 0's row strip_y of each measured frame goes to strip
 * (frames * w; NULL: nowhere). */
struct study_row {
    int runs, frames, w, h, added;
    float *seq;       /* runs * frames * w * h, run-major then frame */
    const float *ref; /* the reference (RGB) study_row_add was given */
    double *run_smape; /* runs * 2: each run's SMAPE all and hard, means over its frames */
    double *run_ms;    /* runs * 3: each run's mean select, spatial and frame times */
    struct study_result res;
};
void study_row_begin(struct study_row *row, int runs, int frames, int w, int h);
void study_row_add(struct study_row *row, const struct study_unit *u, const float *ref, const unsigned char *hard,
                   int strip_y, float *strip);
/* u's denoised frames as a unit of their own (sharing u's buffers: never free it), for a second row
 * that measures the study's statistics after denoising. u must have luminance_dn. */
struct study_unit study_unit_denoised(const struct study_unit *u);
/* Completes res (every run added; hard: the mask study_row_add got) and frees the row. */
void study_row_end(struct study_row *row, const unsigned char *hard, struct study_result *res);
/* Frees a row given up before its end. */
void study_row_free(struct study_row *row);

#endif
