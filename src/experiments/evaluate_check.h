/* evaluate_check.h: an evaluation's recorded data without its jobs' outputs (evaluate_check.c):
 * `restir evaluate --check DIR` renders every row of every step under DIR tiny with the settings
 * its settings.json records and compares the hash, and `restir evaluate --tables DIR` writes the
 * tables again from the steps' small files (the CSVs, provenance.json). Both work on a copy made by
 * scripts/evaluation_export.sh. Must never implement a method or measure an image. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_CHECK_H
#define RESTIR_EXPERIMENTS_EVALUATE_CHECK_H

/* Every step folder under dir (any depth: a folder holding settings.json, provenance.json,
 * study.csv or compare.csv), one line each: "ok" or "STALE: table STEP, row LABEL renders
 * differently since commit X". threads > 0: OpenMP threads of the renders (the hashes do not
 * depend on it). Returns 0 when every row renders as recorded, 1 when one does not (or its setting
 * or method is no longer known, or the scene's content changed), 2 having said why on bad input (no
 * step under dir, a step without settings.json or with one that is malformed, a scene that cannot
 * be loaded): then nothing is rendered. */
int evaluate_check(const char *dir, int threads);

/* dir/evaluation.md and dir/claims.csv from the files of the evaluation in dir (its plan.json, each
 * step's study.csv or compare.csv (with passes.csv), runs.csv when there, provenance.json) through
 * evaluate_write_tables. Refuses with exit 2, naming the step, and writes nothing: a step without
 * its table (unless partial: it is named as not finished), a step without provenance.json, steps
 * of different builds (or of another build than the plan), a step of another resolution or number
 * of runs than the evaluation. Returns an exit code. */
int evaluate_tables(const char *dir, int partial);

#endif
