/* test_spmis_unbiased_di.c: spatial.reuse=spmis (004 Algorithm 2) is unbiased in restir-di with
 * temporal and spatial reuse on (spmis_runs.h), with the confidence adjustment on and off, with
 * N = 1, N = N_c = M, confidence-proportional canonical draws, the compatibility-scored search
 * (ours), the stored confidence from the drawn pixels, taps that move pixels to other cells and
 * the history taken before spatial reuse, on `pillars` (disocclusion) and `cornell`. The BIASED
 * sparse search is measured and reported, not asserted. restir-pt: test_spmis_unbiased.c.
 * Usage for experiments: render_test_spmis_unbiased_di SCENE RUNS key=value... */
#include <stdlib.h>

#include "spmis_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 125

int main(int argc, char **argv)
{
    if (argc >= 3) {
        spmis_check(method_named("restir-di"), argv[1], atoi(argv[2]), (const char *const *)argv + 3, argc - 3, 1);
        return test_finish();
    }
    const char *none[] = {"spmis.candidates=3"};
    const char *no_adjust[] = {"spmis.confidence_adjust=off"};
    const char *one[] = {"spmis.candidates=1"};
    const char *all_cell[] = {"spmis.candidates=M", "spmis.canonical_candidates=M"};
    const char *by_conf[] = {"spmis.canonical_pick=confidence", "spmis.canonical_candidates=2"};
    const char *sparse[] = {"spmis.search=sparse"};
    const char *hist_temporal[] = {"history=temporal"};
    /* the stored confidence from the drawn pixels, with taps that move pixels to other cells */
    const char *drawn[] = {"spmis.confidence_update=drawn", "spmis.search_radius=4", "spmis.search_growth=1.5"};
    /* taps from 4 px growing by 1.5 stay mostly inside 24 x 16 (test_spmis_unbiased.c) */
    const char *far_cells[] = {"spmis.search_radius=4", "spmis.search_growth=1.5"};
    const char *compat[] = {"spmis.search_radius=4", "spmis.search_growth=1.5", "spmis.search_score=compat"};

    spmis_check(method_named("restir-di"), "pillars", 2048, none, 1, 1);
    spmis_check(method_named("restir-di"), "cornell", 2048, none, 1, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, no_adjust, 1, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, one, 1, 1);
    spmis_check(method_named("restir-di"), "cornell", 2048, one, 1, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, far_cells, 2, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, all_cell, 2, 1);
    /* worst |t| 5.5 at 1024 runs, 3.6 at 4096 */
    spmis_check(method_named("restir-di"), "cornell", 4096, by_conf, 2, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, hist_temporal, 1, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, compat, 3, 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, drawn, 3, 1);
    /* BIASED option: its bias is printed (pooled z, relative bias of the image mean), not asserted. */
    spmis_check(method_named("restir-di"), "pillars", 2048, sparse, 1, 0);
    return test_finish();
}
