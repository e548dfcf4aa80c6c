/* test_pt_unbiased.c: restir-pt with temporal and spatial reuse on is unbiased for every shift
 * mapping: the mean of K independently seeded runs matches K runs of the path tracer per pixel
 * (Welch t-test, Sidak-corrected) and over the whole image (pooled z). Runs follow the camera
 * path, so temporal reuse shifts paths between frames along fractional motion vectors.
 * Usage for experiments: render_test_pt_unbiased [SCENE RUNS key=value...]. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unbiased_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 200

#define RUNS 2048

/* Returns the number of pixels that fail the per-pixel test (unbiased_check_path). */
static int check(const char *scene_name, int runs, const char *const *sets, int nsets, int expect_unbiased)
{
    return unbiased_check_path(scene_name, method_named("restir-pt"), runs, sets, nsets, expect_unbiased);
}

int main(int argc, char **argv)
{
    if (argc >= 3) {
        check(argv[1], atoi(argv[2]), (const char *const *)argv + 3, argc - 3, 1);
        return test_finish();
    }
    const char *scenes[] = {"cornell", "ajar"};
    const char *shifts[] = {"shift=hybrid", "shift=reconnection", "shift=replay"};
    for (int sc = 0; sc < 2; sc++) {
        for (int k = 0; k < 3; k++) {
            const char *sets[] = {shifts[k], "mis=pairwise"};
            check(scenes[sc], RUNS, sets, 2, 1);
        }
    }
    const char *balance[] = {"shift=hybrid", "mis=balance"};
    check("cornell", RUNS, balance, 2, 1);
    /* temporal.permutation: the history of a neighbouring previous pixel, its own domain.
     * ajar too at 8192 runs (0 pixels fail, pooled z 0.76; at 2048 one dark pixel's heavy tail gives
     * |t| 4.60, gone at 8192): too long for here. */
    const char *permutation[] = {"shift=hybrid", "mis=pairwise", "temporal.permutation=on"};
    check("cornell", RUNS, permutation, 3, 1);
    /* pt.boiling_filter (BIASED): at the default strength no reservoir of these small images exceeds 41x
     * its group's mean (cornell and ajar at 2048 runs measure as without it); at strength 1 everything
     * above the group's mean goes, and the test must see the lost energy (-29% of the image mean) */
    const char *boil[] = {"shift=hybrid", "mis=pairwise", "pt.boiling_filter=on", "pt.boiling_strength=1"};
    EXPECT(check("cornell", RUNS, boil, 4, 0) > 0, "pt.boiling_filter at strength 1 drops no energy");
    /* Compatibility-guided selection reads only the G-buffer, so reuse stays unbiased (000 Sec. 4.3). */
    const char *compat[] = {"shift=hybrid", "spatial.select=compat", "spatial.radius=8"};
    for (int sc = 0; sc < 2; sc++)
        check(scenes[sc], RUNS, compat, 3, 1);
    /* A real asset nobody here wrote (assimp-testmodels' BoxTextured glTF with its base colour
     * texture, through a JSON scene that adds a ground, a wall and a lamp). */
    char real[1024];
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (data) {
        const char *sets[] = {"shift=hybrid", "mis=pairwise"};
        snprintf(real, sizeof real, "%s/scenes/box_textured.json", data);
        check(real, RUNS, sets, 2, 1);
        /* base colour, metallic-roughness and emission maps (shading varies inside triangles) */
        snprintf(real, sizeof real, "%s/scenes/textured.json", data);
        check(real, RUNS, sets, 2, 1);
        /* shading normals (smooth.json): at every vertex, and at the reconnection vertex x_k,
         * whose normal the shift rebuilds for its new outgoing direction */
        snprintf(real, sizeof real, "%s/scenes/smooth.json", data);
        check(real, RUNS, sets, 2, 1);
        const char *rc_sets[] = {"shift=reconnection", "mis=pairwise"};
        check(real, RUNS, rc_sets, 2, 1);
        /* alpha cutouts (leaves.json): alpha-masked leaf cards and lamp */
        snprintf(real, sizeof real, "%s/scenes/leaves.json", data);
        check(real, RUNS, sets, 2, 1);
        /* Environment light: paths ending in a direction, reconnected to it with no
         * distance term, under every shift (sky_only.json: a sky map with a sun, no emitter), and
         * next to an emitter with temporal splatting (leaves_sky.json). Treating the direction as
         * a point one unit away fails the sky-only case (8 pixels, pooled z -5.5; checked). */
        snprintf(real, sizeof real, "%s/scenes/sky_only.json", data);
        for (int k = 0; k < 3; k++) {
            const char *env_sets[] = {shifts[k], "mis=pairwise"};
            check(real, RUNS, env_sets, 2, 1);
        }
        /* A real asset's smooth vertex normals and its own normal maps (tangents computed from
         * its UVs), lit by a sky: assimp-testmodels' ClearCoatTest.gltf (clearcoat_sky.json). */
        snprintf(real, sizeof real, "%s/scenes/clearcoat_sky.json", data);
        check(real, RUNS, sets, 2, 1);
        snprintf(real, sizeof real, "%s/scenes/leaves_sky.json", data);
        const char *splat[] = {"shift=reconnection", "temporal.reuse=both"};
        check(real, RUNS, splat, 2, 1);
    }
    /* The built-in forest: alpha-masked leaf cards, normal-mapped trunks and a sky with
     * a sun as the only light, along its walk. */
    const char *forest[] = {"shift=hybrid", "mis=pairwise"};
    /* at 16 x 10: 48 CPU-s at 20 x 12 made it the test's longest case by three */
    unbiased_check_path_at("forest", method_named("restir-pt"), 16, 10, RUNS, forest, 2, 1);
    /* The hybrid rule's length relative to each domain's camera distance, along the camera path
     * (temporal shifts cross cameras, each domain judging by its own), and in scene units. */
    const char *relative[] = {"shift=hybrid", "mis=pairwise", "shift.distance_mode=relative", "shift.distance=0.1"};
    check("ajar", RUNS, relative, 4, 1);
    const char *absolute[] = {"shift=hybrid", "mis=pairwise", "shift.distance_mode=absolute", "shift.distance=0.5"};
    check("cornell", RUNS, absolute, 4, 1);
    /* Backprojection searching the 2x2 previous pixels with clipped shifts (temporal.subpixel=search)
     * along both camera paths: pairwise MIS over tiling domains, and the balance heuristic. */
    const char *search[] = {"shift=hybrid", "mis=pairwise", "temporal.subpixel=search"};
    for (int sc = 0; sc < 2; sc++)
        check(scenes[sc], RUNS, search, 3, 1);
    const char *search_balance[] = {"shift=hybrid", "mis=balance", "temporal.subpixel=search"};
    check("ajar", RUNS, search_balance, 3, 1);
    /* The test has power: the BIASED 1/M weights are caught on the same setup. */
    const char *uniform[] = {"shift=hybrid", "mis=1/M"};
    EXPECT(check("cornell", RUNS, uniform, 2, 0) > 0, "1/M weights were not detected as biased");
    return test_finish();
}
