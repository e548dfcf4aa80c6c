/* compare_track.h: what `restir compare` measures along a sequence besides its last frame
 * (compare_track.c): every frame's pass times and temporal shares, the error of every K-th frame
 * against that frame's own reference (--ref-every K), and over N independently seeded runs of
 * each spec (--runs N) the mean errors and 000's relative autocovariance (Appendix A, Eq. 17, lag
 * 3). Must never implement a method or call into cmd_compare.c: it measures frames it is given. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_TRACK_H
#define RESTIR_EXPERIMENTS_COMPARE_TRACK_H

#include <stddef.h>
#include <stdint.h>

#include "experiments/flicker_scales.h"
#include "io/report.h"
#include "methods/renderer.h"
#include "restir/metrics.h"

/* Run n of a spec renders with seed + n * COMPARE_RUN_SEED_STRIDE (its instances then add
 * k * COMPARE_INSTANCE_SEED_STRIDE), so runs and equal-time instances never share a seed. */
#define COMPARE_RUN_SEED_STRIDE 0x9E3779B97F4A7C15ull
#define COMPARE_INSTANCE_SEED_STRIDE 1000003ull
#define COMPARE_COV_LAG 3 /* 000 Appendix A: autocovariance at a lag of 3 frames */
#define COMPARE_MAX_CHANGES 8 /* lights' changes a lag is measured after */
#define COMPARE_LAG_TOLERANCE 0.1 /* back "within 10%" of the steady state */
#define COMPARE_LAG_BLOCK 16        /* the blocks whose lag compare_track_lag measures too, in pixels */
#define COMPARE_LAG_QUANTILE 0.9    /* ... and the quantile of their lags it reports */
#define COMPARE_GHOST_DARK 0.01     /* compare_track_ghost leaves out blocks darker than this share of the mean */

/* One frame of one spec, summed over its runs (compare_track_end divides). */
struct compare_frame_sums {
    double ms_frame, ms_temporal;
    double accept, bp_received, bp_accepted, splat_received, splat_accepted; /* shares of valid pixels */
    struct restir_metrics_error err; /* at frames with a reference */
    double relmse_dn;                /* ... and of the denoised frame there (0 without denoising) */
};

struct compare_track {
    int frames, runs, width, height;
    int nref;          /* frames measured against a reference of their own; the last one is frames - 1 */
    int *ref_frame;    /* their indices, ascending */
    float **ref;       /* their references; ref[nref - 1] is the comparison's reference (not owned) */
    int cov_first;     /* the autocovariance window: frames cov_first .. frames - 1 (the second half) */
    struct compare_frame_sums *sums; /* frames entries for the spec being run */
    float *seq;        /* runs * (frames - cov_first) * w * h luminance clamped at 0, run-major then frame (NULL
                          when the window holds one frame) */
    float *seq_dn;     /* the same of the denoised frames (denoise=svgf|atrous; allocated by the first) */
    size_t clamped, measured; /* of the spec's luminance values stored in seq: the negative ones, all */
    int has_dn;        /* the spec being run measured denoised frames */
    int nchanges;      /* animated emitters: frames at which the lights stop changing (scene_animation_changes) */
    int change[COMPARE_MAX_CHANGES];
    int lights_change_in_window; /* the lights differ between two of the window's frames: no flicker */
    int blocks;        /* whole COMPARE_LAG_BLOCK blocks from the top-left corner (0: the image is smaller) */
    double *block_err, *block_err_dn; /* with changes: frames x blocks, each block's mean relMSE summed over
                                         the runs at every reference frame (allocated by the first) */
    double *block_lum, *block_lum_dn; /* ... and each block's mean luminance, the same way */
    float *err_map;    /* scratch: one frame's per-pixel relMSE terms */
    struct csv_writer csv; /* DIR/frames.csv */
    int csv_open;
};

/* Sets up tracking of `frames` frames of `runs` runs at w x h, with references at frames K - 1,
 * 2K - 1, ... before the last (ref_every = K; 0: the last frame only), whose images the caller then
 * fills into t->ref[0 .. nref - 2] (compare_track_reference_frame says which). last_ref is the
 * reference of the last frame (may be NULL: no errors measured). */
void compare_track_init(struct compare_track *t, int frames, int runs, int ref_every, int w, int h,
                        float *last_ref);
/* Opens DIR/frames.csv. Returns 0, or -1 with msg. */
int compare_track_open(struct compare_track *t, const char *out_dir, char *msg);
/* Starts a spec: clears the sums and the luminance sequences. */
void compare_track_begin(struct compare_track *t);
/* Frame f of run `run`: adds its statistics (instance 0's shares; ms = the instances' summed
 * frame time) and, at a reference frame or in the covariance window, measures `image` (the
 * instances' average). */
void compare_track_stats(struct compare_track *t, int f, double ms, const struct frame_stats *st);
void compare_track_image(struct compare_track *t, int run, int f, const float *image);
/* The same frame denoised: its relMSE at a reference frame, its luminance in the covariance window. */
void compare_track_denoised(struct compare_track *t, int run, int f, const float *denoised);
/* 1 when frame f of the sequence needs its image measured (a reference frame or in the window). */
int compare_track_wants_image(const struct compare_track *t, int f);
/* Ends a spec: writes its rows (means over runs) to frames.csv labelled `label` and returns the
 * relative autocovariance over the runs of the luminance clamped at 0 (the gradient methods' reconstructions
 * are signed, and 000 Eq. 17's division by each pixel's mean is unbounded where that mean crosses 0; stderr
 * says how many values were clamped) (NaN with fewer than 2 runs or a window under lag + 1 frames). */
double compare_track_end(struct compare_track *t, const char *label);
/* Before the next spec's compare_track_begin: the lag after each change of the lights (t->change):
 * the frames from the change until the image's relMSE (mean over the runs, against each frame's own
 * reference) is within COMPARE_LAG_TOLERANCE of its steady state, the mean relMSE of the last quarter
 * of the frames before the next change (or the end). Since that quarter holds the steady state, some
 * frame always qualifies: a method still drifting at the segment's end is measured against its own
 * drift (compare its last frame's error). NaN without a reference at every frame (--ref-every 1) or
 * a segment of under 4 frames. block: the same measured on each COMPARE_LAG_BLOCK x COMPARE_LAG_BLOCK
 * block's own relMSE, and its COMPARE_LAG_QUANTILE quantile over the blocks (a change seen by a part of
 * the image lags there, however little it moves the whole image's error); NaN without a whole block.
 * denoised: of the denoised frames (NaN without them). Writes t->nchanges values into lag and block. */
void compare_track_lag(const struct compare_track *t, int denoised, double *lag, double *block);
/* Before the next spec's compare_track_begin: the ghost after each change of the lights, the frames from
 * the change until, in COMPARE_LAG_QUANTILE of the COMPARE_LAG_BLOCK blocks (those at least
 * COMPARE_GHOST_DARK of the image's mean then or in the frame before the change), the deviation of the
 * block's mean luminance (over the runs) from the reference's, relative to the brighter of the block's
 * reference then and before the change, is at most COMPARE_LAG_TOLERANCE above the block's own steady
 * deviation (the mean of the segment's last quarter, which holds the noise of its mean and a denoiser's
 * bias), from that frame to the next change: how long an old light shows, apart from the noise that
 * compare_track_lag's relMSE counts (a denoiser that starts its history again after a change has no
 * ghost, and lags while its history regrows). NaN as compare_track_lag's, and where a frame has no such
 * block. Writes t->nchanges values into ghost. */
void compare_track_ghost(const struct compare_track *t, int denoised, double *ghost);
/* Before compare_track_end_denoised: flicker at flicker_block's scales and the boiling index
 * (restir_metrics_flicker, _boiling_index) of the window's frames (denoised: the denoised ones)
 * against the last frame's reference, over the runs; NaN without a reference or those frames, or when
 * the lights change in the window (lights_change_in_window). Meant for a static camera (a moving one's
 * block means change with the view). */
void compare_track_flicker(const struct compare_track *t, int denoised, double out[FLICKER_COLS]);
/* After compare_track_end: the relative autocovariance of the denoised frames, as compare_track_end's
 * (NaN without them). */
double compare_track_end_denoised(struct compare_track *t);
/* Commits frames.csv. Returns 0, or -1 with msg. */
int compare_track_close(struct compare_track *t, char *msg);
/* Frees what init allocated (the references the caller filled in too, not last_ref); aborts an
 * unclosed frames.csv. */
void compare_track_fini(struct compare_track *t);

#endif
