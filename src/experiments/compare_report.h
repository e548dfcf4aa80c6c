/* compare_report.h: `restir compare --report`: DIR/index.html (compare_report.c), a page that loads the
 * images beside it, or with --self-contained holds them all itself (data: URIs).
 * Must never depend on the renderer or on how a comparison runs: it shows what it is given. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_REPORT_H
#define RESTIR_EXPERIMENTS_COMPARE_REPORT_H

#include "methods/method.h"
#include "restir/metrics.h"

/* The page: the run's command, commit and machine, its table and a relMSE bar plot (each denoised
 * row right after its method's), relMSE against frame from frames.csv, flicker against block size (a
 * static camera's), the time per pass from passes.csv as stacked bars, every method's image (and
 * denoised image) and the reference in a synchronized viewer with an A/B flip, per-pixel
 * relative-error and HDR-FLIP heat maps with colour bars, and crops of the regions where the first two
 * methods' errors differ most. */

struct compare_report_method {
    const char *label;  /* the method spec */
    const char *png;    /* its last frame, relative to the output folder */
    const char *dir;    /* its folder, relative to the output folder (its outputs' PNGs live there); NULL for a
                           row's denoised frame, which has none */
    const struct method *method; /* whose outputs (method.h) the report shows beside the image; NULL: none */
    const float *image; /* its last frame, linear RGB */
    double ms_per_frame;
    int spp, instances;
    struct restir_metrics_error err;
    double flip;           /* mean HDR-FLIP (the table's; NaN: not measured, shown as '-') */
    int denoised;          /* 1: the denoised last frame of the method in the row before (BIASED) */
    const double *ms_pass; /* the method's ms per frame of each pass (passes.csv's row); NULL: none */
    int nframes;           /* frames with an error in frames.csv: their numbers and relMSE */
    const double *frame, *frame_relmse;
    int nflicker;               /* block sizes with a flicker (0: not measured, as for a moving camera) */
    const int *flicker_block;   /* their sizes in pixels, ascending, the first 1 */
    const double *flicker;      /* the row's flicker at each (restir_metrics_flicker; NaN: not measured) */
};

struct compare_report_run {
    const char *out_dir, *command, *scene;
    int width, height, frame, moving, equal_time;
    const float *reference;
    int self_contained;             /* every image inside index.html (base64 data: URIs) */
    int passes;                     /* passes.csv's passes: their names */
    const char *const *pass_names;
};

/* Writes out_dir/index.html and the images it shows (reference.png, report/heat_K.png, report/flip_K.png,
 * report/crop_R_K.png; with self_contained they are written too, and embedded). Returns 0, or -1 with msg. */
int compare_write_report(const struct compare_report_run *run, int n, const struct compare_report_method *m,
                         char *msg);

#endif
