/* study_report.h: the page of `restir study --report` (study_report.c).
 * Must never depend on the renderer or the study's computation: it reads what the study wrote. */
#ifndef RESTIR_EXPERIMENTS_STUDY_REPORT_H
#define RESTIR_EXPERIMENTS_STUDY_REPORT_H

struct study_report_run {
    const char *out_dir, *command, *scene, *method;
    int width, height, runs, warmup, frames, hard_pixels, strip_row;
    const float *reference;
};

/* Writes out_dir/index.html (and reference.png) from the files the study wrote there. Returns 0,
 * or -1 with msg. */
int study_write_report(const struct study_report_run *run, char *msg);

#endif
