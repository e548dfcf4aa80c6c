/* evaluate_findings.h: what the deciding rows of an evaluation show about a claim, as
 * part of its "why / differences" column: each writes into out (len bytes, NUL-terminated) its
 * findings, "what: +x% [lo, hi], reading" from the change's 95% interval (evaluate_change.h), joined
 * by "; " (empty when none); a finding whose rows are missing (row -1 or NaN cells) is left out. No
 * state: thread-safe on distinct outputs. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_FINDINGS_H
#define RESTIR_EXPERIMENTS_EVALUATE_FINDINGS_H

#include <stddef.h>

#include "experiments/evaluate_change.h"

/* What 000's deciding rows (the first scene's) show about FAST's claims (rows bit and fast
 * of d->t), into out: whether spatial reuse itself helps on the scene (Bitterli against no spatial
 * reuse), and FAST against Bitterli when the spatial output is not fed back (both with the temporal
 * history). Empty when those rows were not run. */
void eval_deciding_000(const struct step_tables *d, int bit, int fast, char *out, size_t len);

/* What decides 004's SPMIS claim on column col ("mape" or "mape_disoccluded", with its "_sem"):
 * whether the 12-tap cell search costs SPMIS (its row against the own cell only), and where the own
 * cell stands against standard reuse (rows standard, spmis, own_cell of d->t). */
void eval_deciding_004(const struct step_tables *d, int standard, int spmis, int own_cell, const char *col, char *out,
                       size_t len);

/* What decides a 002 claim against a rival with gradients, into out: ours' gradients
 * (row me) against row r's without the worst 1% of pairs and as MAPE (the gradient relMSE is carried
 * by a few pairs, which an L2 reconstruction spreads). Rows without gradients add nothing. */
void eval_gradient_findings(const struct step_tables *d, int me, int r, char *out, size_t len);

#endif
