/* test_ris_gi_unbiased.c: ris-gi (RIS over K BSDF directions at the primary hit, no reuse) is unbiased:
 * the mean of independently seeded runs along the camera path matches as many runs of the path tracer
 * per pixel (Welch t-test, Sidak-corrected) and over the whole image (pooled z): on cornell (a glossy
 * block) with the default K = 4 and with K = 1 (plain BSDF sampling of the secondary vertex), and on
 * ajar (light through a door gap, nearly all of it indirect) with K = 1 at 4096 runs. ajar's tails are
 * heavy: at 1024 runs two of its dark pixels reached |t| 4.82 and 4.16 (limit 4.10; pooled z 1.87), at
 * 4096 runs of the same seeds none fails (worst |t| 3.05, pooled z 0.94), as heavy tails and not a bias
 * would have it. Times on one thread: 4.3, 0.5 and 22.5 CPU-s.
 * Usage for experiments: render_test_ris_gi_unbiased [SCENE RUNS key=value...]. */
#include <stdlib.h>

#include "unbiased_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 30

#define RUNS 1024

static int check(const char *scene_name, int runs, const char *const *sets, int nsets)
{
    return unbiased_check_path(scene_name, method_named("ris-gi"), runs, sets, nsets, 1);
}

int main(int argc, char **argv)
{
    if (argc >= 3) {
        check(argv[1], atoi(argv[2]), (const char *const *)argv + 3, argc - 3);
        return test_finish();
    }
    const char *defaults[] = {"risgi.candidates=4"};
    check("cornell", RUNS, defaults, 1);
    const char *bsdf_only[] = {"risgi.candidates=1"};
    check("cornell", RUNS / 2, bsdf_only, 1);
    check("ajar", 4 * RUNS, bsdf_only, 1);
    return test_finish();
}
