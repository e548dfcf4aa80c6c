/* test_splat_unbiased.c: temporal reuse by reservoir splatting (temporal.reuse=splat) and by
 * splatting and backprojection combined (both) is unbiased: the mean of K independently seeded
 * runs along the camera paths of foliage (thin geometry) and pillars (disocclusion) matches K
 * runs of the path tracer per pixel (Welch t-test, Sidak-corrected) and over the whole image
 * (pooled z); also with motion blur (camera.shutter, splatted into 2 shutter-time strata), with a
 * thin lens on cornell, and for area-restir (the gradient methods' primal). The BIASED 1/M
 * weights are caught on the same setup.
 * Usage for experiments: render_test_splat_unbiased [SCENE RUNS key=value...]. */
#include <stdio.h>
#include <stdlib.h>

#include "unbiased_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 80

#define RUNS 2048

static int check(const char *scene_name, const struct method *m, int runs, const char *const *sets, int nsets,
                 int expect_unbiased)
{
    return unbiased_check_path(scene_name, m, runs, sets, nsets, expect_unbiased);
}

int main(int argc, char **argv)
{
    if (argc >= 3) {
        check(argv[1], method_named("restir-pt"), atoi(argv[2]), (const char *const *)argv + 3, argc - 3, 1);
        return test_finish();
    }
    const char *scenes[] = {"foliage", "pillars"};
    const char *modes[] = {"temporal.reuse=splat", "temporal.reuse=both"};
    for (int sc = 0; sc < 2; sc++)
        for (int k = 0; k < 2; k++) {
            const char *sets[] = {modes[k], "mis=pairwise"};
            check(scenes[sc], method_named("restir-pt"), RUNS, sets, 2, 1);
        }
    /* Motion blur: pt integrates the same blurred image (the camera moves from the previous frame's
     * pose during the shutter); backprojection keeps each path's time, splatting re-times it. */
    const char *blur_bp[] = {"camera.shutter=1"};
    check("pillars", method_named("restir-pt"), RUNS, blur_bp, 1, 1);
    const char *blur_splat[] = {"temporal.reuse=splat", "camera.shutter=1"};
    check("pillars", method_named("restir-pt"), RUNS, blur_splat, 2, 1);
    const char *blur_both[] = {"temporal.reuse=both", "camera.shutter=0.5", "temporal.splat_steps=3"};
    check("foliage", method_named("restir-pt"), RUNS, blur_both, 3, 1);
    /* Depth of field: the lens sample is kept by every shift. Cornell's glossy box makes the
     * heaviest tails of these cases: at 2048 runs one pixel reached |t| = 4.27 (limit 4.10) with a
     * pooled z of 1.7; at 4096 runs the worst |t| is 3.36 and z 0.34, so this case takes 4096. */
    const char *lens[] = {"temporal.reuse=splat", "camera.aperture=0.08"};
    check("cornell", method_named("restir-pt"), 2 * RUNS, lens, 2, 1);
    /* area-restir: the primal pass of grad-after-restir and grestir-pt */
    const char *area[] = {"temporal.reuse=both"};
    check("pillars", method_named("area-restir"), RUNS, area, 1, 1);
    /* The test has power: 1/M weights over the splatted candidates are caught. */
    const char *uniform[] = {"temporal.reuse=splat", "mis=1/M"};
    EXPECT(check("cornell", method_named("restir-pt"), RUNS, uniform, 2, 0) > 0, "1/M weights were not detected as biased");
    return test_finish();
}
