/* spmis_runs.h: one unbiasedness case of spatial.reuse=spmis (004 Algorithm 2: stochastic pairwise
 * MIS over one reuse cell), shared by test_spmis_unbiased.c (restir-pt) and
 * test_spmis_unbiased_di.c (restir-di): K independently seeded camera-path runs against K runs of
 * the path tracer per pixel (Welch, Sidak-corrected) and over the image (pooled z), on 24 x 16
 * pixels (3 x 2 full 8 x 8 tiles, so cells, the search and exclusions all take part). */
#ifndef RESTIR_TEST_SPMIS_RUNS_H
#define RESTIR_TEST_SPMIS_RUNS_H

#include "unbiased_runs.h"

#define SPMIS_FRAMES 4
#define SPMIS_FRAME_STEP 6

/* Pass rate: family-wise alpha = 0.01 over all pixels per case, pooled |z| < 4.5 (~1e-5); the
 * seeds are fixed, so the outcome is deterministic. */
#define SPMIS_ALPHA 0.01
#define SPMIS_POOLED_Z_MAX 4.5

/* The settings the restir-pt and restir-di cases share (after spatial.reuse=spmis). */
static const char *const spmis_none[] = {"spmis.candidates=3"};
static const char *const spmis_no_adjust[] = {"spmis.confidence_adjust=off"};
static const char *const spmis_one[] = {"spmis.candidates=1"};
static const char *const spmis_hist_temporal[] = {"history=temporal"};
/* the stored confidence from the drawn pixels, with taps that move pixels to other cells */
static const char *const spmis_drawn[] = {"spmis.confidence_update=drawn", "spmis.search_radius=4",
                                          "spmis.search_growth=1.5"};
/* A 4 px start growing by 1.5 per tap keeps most taps inside 24 x 16, so pixels really move to
 * other cells (with the paper's 30 px most taps fall outside and the own cell is the fallback). */
static const char *const spmis_far_cells[] = {"spmis.search_radius=4", "spmis.search_growth=1.5"};
static const char *const spmis_compat[] = {"spmis.search_radius=4", "spmis.search_growth=1.5",
                                           "spmis.search_score=compat"};

/* A settings array and its length, as spmis_check takes them. */
#define SPMIS_SETS(a) (a), (int)(sizeof(a) / sizeof((a)[0]))

/* Returns the number of pixels that fail (unbiased_check); expect: assert unbiasedness. */
static inline int spmis_check(const struct method *m, const char *scene, int runs, const char *const *sets,
                              int nsets, int expect)
{
    const int pt = m == method_named("restir-pt"), ref_spp = pt ? 8 : 16;
    const struct unbiased_case c = {scene,   m,           24, 16, runs, SPMIS_FRAMES, SPMIS_FRAME_STEP,
                                    ref_spp, SPMIS_ALPHA, SPMIS_POOLED_Z_MAX};
    const char *all[16] = {"spatial.reuse=spmis", pt ? "pt.max_bounces=4" : "mis=pairwise"};
    for (int k = 0; k < nsets && k < 14; k++)
        all[k + 2] = sets[k];
    return unbiased_check(&c, all, nsets + 2, expect);
}

#endif
