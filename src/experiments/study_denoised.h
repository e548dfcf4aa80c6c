/* study_denoised.h: a study's outputs after denoising: study_denoised.csv and .md (every
 * configuration's SMAPE and 000's covariances before and after denoising, and how well the
 * covariances before denoising rank the error after it) and pareto_denoised.svg (the SMAPE after
 * denoising against the spatial covariance before it, 000 Sec. 1's motivation). Must never render. */
#ifndef RESTIR_EXPERIMENTS_STUDY_DENOISED_H
#define RESTIR_EXPERIMENTS_STUDY_DENOISED_H

#include "experiments/study_run.h"

/* Writes the three files into dir for n configurations: raw[k] the statistics of configuration k's
 * frames, dn[k] of the same frames denoised by `denoiser` (its name); m is the spatial neighbours per
 * pixel the table states. Returns 0, or -1 with msg. */
int study_write_denoised(const char *dir, const char *denoiser, const struct study_config *cfg,
                         const struct study_result *raw, const struct study_result *dn, int n, int m, char *msg);

/* Spearman's rank correlation of x and y (n pairs, ties given their mean rank); NaN under 3 pairs or
 * when one side is constant. */
double study_rank_correlation(const double *x, const double *y, int n);

#endif
