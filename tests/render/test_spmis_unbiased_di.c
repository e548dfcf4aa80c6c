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
    const char *const all_cell[] = {"spmis.candidates=M", "spmis.canonical_candidates=M"};
    const char *const by_conf[] = {"spmis.canonical_pick=confidence", "spmis.canonical_candidates=2"};
    const char *const sparse[] = {"spmis.search=sparse"};

    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_none), 1);
    spmis_check(method_named("restir-di"), "cornell", 2048, SPMIS_SETS(spmis_none), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_no_adjust), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_one), 1);
    spmis_check(method_named("restir-di"), "cornell", 2048, SPMIS_SETS(spmis_one), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_far_cells), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(all_cell), 1);
    /* worst |t| 5.5 at 1024 runs, 3.6 at 4096 */
    spmis_check(method_named("restir-di"), "cornell", 4096, SPMIS_SETS(by_conf), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_hist_temporal), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_compat), 1);
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(spmis_drawn), 1);
    /* BIASED option: its bias is printed (pooled z, relative bias of the image mean), not asserted. */
    spmis_check(method_named("restir-di"), "pillars", 2048, SPMIS_SETS(sparse), 0);
    return test_finish();
}
