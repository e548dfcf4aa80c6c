/* study_report.h: the page of `restir study --report` (study_report.c).
 * Must never depend on the renderer or the study's computation: it reads what the study wrote. */
#ifndef RESTIR_EXPERIMENTS_STUDY_REPORT_H
#define RESTIR_EXPERIMENTS_STUDY_REPORT_H

struct study_report_run {
    const char *out_dir, *command, *scene, *method;
    int width, height, runs, warmup, frames, hard_pixels, strip_row;
    const float *reference;
    int self_contained; /* every image inside index.html (base64 data: URIs) */
};

/* Writes out_dir/index.html (and reference.png) from the files the study wrote there, which it loads, or
 * with self_contained holds. Returns 0, or -1 with msg. */
int study_write_report(const struct study_report_run *run, char *msg);

#endif
