/* compare_report.h: `restir compare --report`: DIR/index.html, one self-contained page (compare_report.c).
 * Must never depend on the renderer or on how a comparison runs: it shows what it is given. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_REPORT_H
#define RESTIR_EXPERIMENTS_COMPARE_REPORT_H

#include "restir/metrics.h"

/* The page: the run's command, commit and machine, its table and a bar plot, every method's image
 * and the reference in a synchronized viewer with an A/B flip, per-pixel relative-error and HDR-FLIP
 * heat maps with colour bars, and crops of the regions where the first two methods' errors differ most. */

struct compare_report_method {
    const char *label;  /* the method spec */
    const char *png;    /* its last frame, relative to the output folder */
    const char *dir;    /* its folder, relative to the output folder (gradient layers live there); NULL for a
                           row's denoised frame, which has none */
    const float *image; /* its last frame, linear RGB */
    double ms_per_frame;
    int spp, instances;
    struct restir_metrics_error err;
    double flip; /* mean HDR-FLIP (the table's; NaN: not measured, shown as '-') */
};

struct compare_report_run {
    const char *out_dir, *command, *scene;
    int width, height, frame, moving, equal_time;
    const float *reference;
};

/* Writes out_dir/index.html and the images it shows (reference.png, report/heat_K.png, report/flip_K.png,
 * report/crop_R_K.png). Returns 0, or -1 with msg. */
int compare_write_report(const struct compare_report_run *run, int n, const struct compare_report_method *m,
                         char *msg);

#endif
