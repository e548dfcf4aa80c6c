/* compare_run.h: the comparison harness that `restir compare` and its planned form (compare_plan.c)
 * share: compare_setup.c turns a description into specs, compare_run.c runs a spec, compare_schedule.c
 * runs them all within an equal-time budget, compare_reference.c renders the references,
 * compare_table.c writes the table. Must never implement a method. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_RUN_H
#define RESTIR_EXPERIMENTS_COMPARE_RUN_H

#include "experiments/compare_track.h"
#include "experiments/reference_halves.h"
#include "experiments/options.h"
#include "experiments/stats.h"
#include "methods/renderer.h"
#include "restir/metrics.h"
#include "scene/scene.h"

#define MAX_METHODS 16
#define MAX_INSTANCES 16 /* independently seeded renderers one row may average */
#define COMPARE_GRAD_TRIM 0.01 /* the share of gradient pairs the trimmed relMSE leaves out */
#define SPEC_MAX 200 /* characters of one spec; its folder name stays under NAME_MAX */

/* One row of the comparison: a method with the command's parameters and then the spec's own
 * key=value settings. The spec text labels the row; dir is its folder name under DIR. */
struct compare_spec {
    char label[SPEC_MAX + 1];
    char dir[SPEC_MAX + 16];
    const struct method *method;
    struct render_params p;
    int instances; /* independently seeded renderers the row averages (key instances=N; default 1) */
};

struct compare_result {
    const struct method *method;
    double ms_per_frame;
    double ms_pass[PASS_MAX]; /* each pass's mean time per frame by pass id (run 0), as ms_per_frame counts */
    int spp;
    int instances;           /* independently seeded renderers averaged per run (equal time) */
    int runs;                /* independently seeded runs measured (--runs) */
    struct restir_metrics_error err; /* of the last frame, the mean over the runs */
    struct restir_metrics_error sem; /* the standard error of that mean over the runs (NaN with one run) */
    /* 004 Sec. 6.2: MAPE over the last frame's disoccluded pixels (renderer_disoccluded: history
     * rejected in any of the last DISOCCLUSION_FRAMES frames), its standard error over the runs, and
     * the disoccluded share of the image's pixels (mean over the runs); NaN for methods without a
     * G-buffer history (pt, gpt), MAPE also when no pixel is disoccluded */
    double mape_dis, mape_dis_sem, dis_share;
    /* methods with forward-difference outputs (signed dx, dy: the gradient methods; 002 Fig. 7):
     * restir_metrics_gradient_relmse of the last frame's (instance-averaged) gradients, mean over the
     * runs, and its standard error; NaN for the other methods */
    double grad_relmse, grad_relmse_sem;
    /* the same gradients' relMSE without the worst COMPARE_GRAD_TRIM of the pairs
     * (restir_metrics_gradient_relmse_trimmed) and their MAPE (restir_metrics_gradient_mape), means over
     * the runs and standard errors; NaN for the other methods */
    double grad_relmse_trim, grad_relmse_trim_sem, grad_mape, grad_mape_sem;
    /* HDR-FLIP (Andersson et al. 2021; compare_flip) of the last frame against the reference, the mean over the
     * runs, and its standard error (NaN with one run) */
    double flip, flip_sem;
    /* denoise=svgf|atrous: the errors of the last frame denoised (instance-averaged), the mean
     * over the runs and its standard error; NaN without denoising. BIASED by nature. */
    struct restir_metrics_error err_dn, sem_dn;
    double mape_dis_dn, mape_dis_dn_sem; /* MAPE of the denoised frame over the disoccluded pixels */
    float *denoised; /* a planned job's denoised last frame for the merge (else NULL; caller frees) */
    unsigned char *mask; /* a planned job's disocclusion mask for the merge (else NULL; caller frees) */
    float *grad; /* a planned job's forward differences for the merge: dx then dy, 3 x width x height floats
                    each (else NULL; caller frees) */
    double temporal_cov;     /* 000 Eq. 17 over the runs (compare_track.h); NaN with one run */
    double temporal_cov_dn;  /* the same of the denoised frames; NaN without denoising */
    /* flicker at 1, 4 and 16 px and the boiling index (compare_track_flicker) over the second half's
     * frames, of the frames as rendered and denoised (NaN without denoising or a reference) */
    double flicker[FLICKER_COLS], flicker_dn[FLICKER_COLS];
    /* frames until relMSE settles after each change of an animated scene's lights (compare_track_lag; NaN
     * where it cannot be measured) */
    double lag[COMPARE_MAX_CHANGES], lag_dn[COMPARE_MAX_CHANGES]; /* as rendered, denoised */
    double lag_block[COMPARE_MAX_CHANGES], lag_block_dn[COMPARE_MAX_CHANGES]; /* the blocks' quantile */
    /* frames an old light shows (compare_track_ghost) */
    double ghost[COMPARE_MAX_CHANGES], ghost_dn[COMPARE_MAX_CHANGES];
    float *image;            /* the last frame, kept for --report (else NULL) */
    float *image_dn;         /* and the denoised one (else NULL) */
    /* Each run's own values, for pairing rows by seed (runs.csv): runs * COMPARE_RUN_COLS doubles,
     * run-major, in the order of compare_run_columns; owned (compare_result_free). NULL when none. */
    double *per_run;
    /* The reference's own error in relMSE, MAPE and SMAPE (half a of its two independent halves
     * against their mean: |a - r| = |a - b| / 2, distributed as |r - R|), NaN without halves; and
     * relmse_net, err.relmse without the reference's share (compare_reference_noise), NaN without. */
    double ref_own[3];
    double relmse_net;
    /* The reference's own MAPE over run 0's disoccluded pixels (half a against the mean, as ref_own),
     * NaN without halves or without a disocclusion mask: compare.csv's ref_mape_disoccluded, against
     * which a claim on mape_dis is checked. dis_mask: run 0's mask until compare_reference_noise has
     * used and freed it (NULL without). */
    double ref_own_dis;
    unsigned char *dis_mask;
};

#define COMPARE_RUN_COLS 10
/* The names of per_run's columns, as runs.csv heads them. */
extern const char *const compare_run_columns[COMPARE_RUN_COLS];
/* Sets the measures a planned merge cannot take (they need every run's frame sequence) to NaN:
 * temporal_cov, flicker and lag, as rendered and denoised. */
void compare_result_clear_sequence(struct compare_result *res);
/* Frees res's images and per-run values. */
void compare_result_free(struct compare_result *res);

struct compare_setup {
    struct cli_options o;
    struct compare_spec specs[MAX_METHODS];
    int n;
    /* the method whose integrand every row and the reference estimate: the first METHOD_DIRECT_ONLY
     * spec when there is one (then every row uses 1 bounce), else the first spec */
    const struct method *integrand;
    struct render_params p; /* the common parameters */
    struct scene s;
};

/* 1 for the methods that reach a time budget by paths per pixel (pt, gpt); the others do by
 * averaging independently seeded instances (002 Sec. 5). */
int compare_budget_by_spp(const struct method *m);

/* MAPE of image over the pixels mask marks (NaN when mask is NULL or marks none) and the share of
 * the npix pixels it marks (NaN when mask is NULL), into *mape and *share. */
void compare_disoccluded_error(const float *image, const float *ref, const unsigned char *mask, size_t npix,
                               double *mape, double *share);

/* The forward differences of r's last frame that the gradient columns measure (002 Fig. 7): its
 * method's signed outputs named "dx" and "dy" (method.h), borrowed; both NULL unless it has both. */
void compare_forward_differences(const struct renderer *r, const float **dx, const float **dy);

/* The gradient errors of res (grad_relmse, grad_relmse_trim, grad_mape) from the gradients dx, dy (3 floats per
 * pixel each) against ref; all NaN when dx is NULL (not a gradient method). */
void compare_gradient_errors(const float *dx, const float *dy, const float *ref, int width, int height,
                             struct compare_result *res);

/* The mean HDR-FLIP of image against ref (restir_metrics_flip at RESTIR_METRICS_FLIP_PPD: FLIP's default monitor
 * and distance), NaN when it cannot be computed (no memory). */
double compare_flip(const float *image, const float *ref, int width, int height);

/* compare_run_method's result when a stop signal arrived before the method's last frame. */
#define RUN_STOPPED 1

/* The errors after denoising of res (err_dn, and mape_dis_dn over the pixels mask marks) of the
 * denoised frame against ref; all NaN when denoised is NULL (no denoising). */
void compare_denoised_errors(const float *denoised, const float *ref, const unsigned char *mask, size_t npix,
                             struct compare_result *res);
/* A comparison from its description (struct cli_options as the option table parsed it, from argv or
 * a plan's JSON): the specs, the common parameters and integrand, the scene loaded (st->s, to
 * destroy), memory checked. Returns 0, or an exit code having said why. */
int compare_setup(const struct cli_options *desc, struct compare_setup *st);
/* The comparison's own reference (independently seeded, from the last frame's camera) as two
 * independent halves and their mean (reference_halves.h): in memory when out is NULL, else resumably
 * as a plan's job writing out's halves. Returns 0, or -1 with msg (a stop signal; a failed save). */
int compare_render_reference_pair(const struct compare_setup *st, const char *out, struct reference_pair *r,
                                  char *msg);
/* The reference's own noise out of the rows' errors: with halves a and b of the reference ref
 * (npix pixels; a NULL: none, every ref_own and relmse_net NaN), each res[k].ref_own gets the
 * reference's own relMSE, MAPE and SMAPE, and res[k].relmse_net and each run's relmse_net the relMSE
 * without the reference's share, E[(x - r)^2] - Var(r) per pixel with Var(r) estimated as
 * (a - b)^2 / 4. err.relmse stays the relMSE against r (DESIGN.md's definition; frames.csv's). */
void compare_reference_noise(struct compare_result *res, int n, const float *a, const float *b, const float *ref,
                             size_t npix);
/* Runs `frames` frames of spec c with parameters p (c->p, or with an equal-time spp) as `instances`
 * (at most MAX_INSTANCES) independently seeded renderers, measures the average of their last frames
 * against ref (none when ref is NULL: then res->mask gets the disocclusion mask, for gradient
 * methods res->grad the gradients, and with denoising res->denoised the denoised frame) and, for run 0,
 * writes it under out_dir/c->dir; keep_image keeps it in res->image. With a track
 * (may be NULL) every frame's statistics and the frames it asks for go to it as run `run`.
 * Returns 0, -1 with msg (the frame cannot be written), or RUN_STOPPED having written nothing. */
int compare_run_method(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                       int instances, const float *ref, const char *out_dir, int keep_image,
                       struct compare_track *track, int run, struct compare_result *res, char *msg);
/* The errors of a spec's runs as they arrive (run order), and their means and standard errors. */
struct compare_runs {
    int n, cap;
    double *per_run; /* n * COMPARE_RUN_COLS: each run's values, handed to the result by compare_runs_finish */
    struct running_mean m[14]; /* relMSE, MAPE, SMAPE, luma RMSE, disoccluded MAPE, disoccluded share,
                                  gradient relMSE, its 1%-trimmed mean, gradient MAPE, denoised
                                  relMSE, MAPE, SMAPE, disoccluded MAPE, and FLIP */
};
void compare_runs_add(struct compare_runs *a, const struct compare_result *r);
/* Into res: with more than one run the means (one run keeps its own errors bit for bit), the
 * standard errors (NaN with one run), the number of runs and each run's values (res->per_run, taken
 * from a). */
void compare_runs_finish(struct compare_runs *a, struct compare_result *res);
/* The times of res become run's (frame and passes) when run's frame time is shorter: a row reports
 * its fastest run, since other load on a machine only ever slows a run down. */
void compare_keep_fastest(struct compare_result *res, const struct compare_result *run);
/* Run n's seed: seed + n COMPARE_RUN_SEED_STRIDE. */
static inline uint64_t compare_run_seed(uint64_t seed, int n)
{
    return seed + COMPARE_RUN_SEED_STRIDE * (uint64_t)n;
}
/* --runs runs of spec c (compare_run_method with seed + n COMPARE_RUN_SEED_STRIDE for run n): res
 * gets run 0's frame, the fastest run's times, the last-frame error averaged over the runs and the temporal
 * autocovariance; the track's rows for c go to frames.csv. Returns as compare_run_method. */
int compare_run_spec(const struct scene *s, const struct compare_spec *c, const struct render_params *p, int frames,
                     int instances, int runs, const float *ref, const char *out_dir, int keep_image,
                     struct compare_track *track, struct compare_result *res, char *msg);
/* Runs every spec of st (compare_run_spec, --runs runs each) against ref into res[0 .. st->n - 1]
 * (zeroed by the caller), each writing its last frame under out_dir and its frames to track. With
 * --equal-time the first spec of a method with state between frames runs first and its frame time is
 * the budget: the methods that fit it by paths per pixel (compare_budget_by_spp) get the spp that fit
 * (equal_time_spp_for), the others as many averaged instances as fit (at least 1, at most
 * MAX_INSTANCES, timed on a short run of one). Returns 0; EXIT_RUNTIME with msg; or 128 + the signal
 * after a stop signal, having said which spec it stopped and what out_dir keeps. Not thread-safe
 * (the renderers use every thread). */
int compare_schedule(const struct compare_setup *st, const float *ref, const char *out_dir,
                     struct compare_track *track, struct compare_result *res, char *msg);
/* The comparison's reference at frame `frame` (the last frame's: compare_render_reference), or NULL
 * when a stop signal arrived. */
float *compare_render_reference_at(const struct compare_setup *st, int frame);
/* Prints the table, writes out_dir/compare.csv and, with --report, index.html. Returns an exit
 * code. */
int compare_write_table(const struct compare_setup *st, const char *out_dir, const char *command,
                        const struct compare_result *res, const float *ref);

#endif
