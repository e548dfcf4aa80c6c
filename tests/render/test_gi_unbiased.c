/* test_gi_unbiased.c: restir-gi with temporal and spatial reuse (gi.radiance=reevaluate, the
 * default) is unbiased: the mean of K independently seeded runs along the camera path matches K
 * runs of the path tracer per pixel (Welch t-test, Sidak-corrected) and over the whole image
 * (pooled z), with pairwise and balance MIS, with compat selection, and on real assets.
 * gi.radiance=stored (Ouyang et al. 2021's form) is BIASED; its failing pixels and pooled z are
 * printed as its measured bias, not asserted; gi.boiling_filter (BIASED) at strength 1 must show the
 * energy it drops. This file is the template of
 * docs/ADDING_A_METHOD.md. Usage for experiments: render_test_gi_unbiased [SCENE RUNS key=value...]. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unbiased_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 75

#define RUNS 2048

/* Returns the number of pixels that fail the per-pixel test (unbiased_check_path). */
static int check(const char *scene_name, int runs, const char *const *sets, int nsets, int expect_unbiased)
{
    return unbiased_check_path(scene_name, method_named("restir-gi"), runs, sets, nsets, expect_unbiased);
}

int main(int argc, char **argv)
{
    if (argc >= 3) {
        check(argv[1], atoi(argv[2]), (const char *const *)argv + 3, argc - 3, 1);
        return test_finish();
    }
    const char *scenes[] = {"cornell", "ajar"};
    const char *pairwise[] = {"mis=pairwise"};
    for (int sc = 0; sc < 2; sc++)
        check(scenes[sc], RUNS, pairwise, 1, 1);
    const char *balance[] = {"mis=balance"};
    check("cornell", RUNS, balance, 1, 1);
    /* Compatibility-guided selection reads only the G-buffer (000 Sec. 4.3). */
    const char *compat[] = {"spatial.select=compat", "spatial.radius=8"};
    check("cornell", RUNS, compat, 2, 1);
    /* Real assets: base colour, metallic-roughness and emission maps, shading normals. */
    char real[1024];
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (data) {
        snprintf(real, sizeof real, "%s/scenes/textured.json", data);
        /* Heavy tails in its dark pixels: with the light BVH in the walk one pixel reached |t| 4.18
         * at 2048 runs (limit 4.10); the same runs doubled put the worst pixel at 2.68. */
        check(real, 2 * RUNS, pairwise, 1, 1);
        snprintf(real, sizeof real, "%s/scenes/smooth.json", data);
        check(real, RUNS, pairwise, 1, 1);
    }
    /* gi.boiling_filter (BIASED): at the default strength cornell at 2048 runs measures as without it
     * (pooled z 0.10, +0.10% of the image mean; without: z 0.19, +0.20%); at strength 1 everything above the
     * group's mean goes, and the test must see the lost energy (-13.5%) */
    const char *boil[] = {"gi.boiling_filter=on", "gi.boiling_strength=1"};
    EXPECT(check("cornell", RUNS, boil, 2, 0) > 0, "gi.boiling_filter at strength 1 drops no energy");
    /* The paper's stored radiance: printed, not asserted (BIASED where the sample point is glossy). */
    const char *stored[] = {"gi.radiance=stored"};
    for (int sc = 0; sc < 2; sc++) {
        int failed = check(scenes[sc], RUNS, stored, 1, 0);
        printf("gi.radiance=stored on %s: %d pixels fail (measured bias, not asserted)\n", scenes[sc], failed);
    }
    return test_finish();
}
