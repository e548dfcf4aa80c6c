/* test_pt_unbiased.c: restir-pt with temporal and spatial reuse on is unbiased for every shift
 * mapping: the mean of K independently seeded runs matches K runs of the path tracer per pixel
 * (Welch t-test, Sidak-corrected) and over the whole image (pooled z). Runs follow the camera
 * path, so temporal reuse shifts paths between frames along fractional motion vectors.
 * Usage for experiments: render_test_pt_unbiased [SCENE RUNS key=value...]. */
#include <stdlib.h>
#include <string.h>

#include "test_util.h"
#include "unbiased_runs.h"

#define RUNS 2048
#define FRAMES 4
#define FRAME_STEP 6
#define REF_SPP 8

/* Pass rate: family-wise alpha = 0.01 over all pixels per case, and pooled |z| < 4.5 (~1e-5);
 * the seeds are fixed, so the outcome is deterministic. */
#define ALPHA 0.01
#define POOLED_Z_MAX 4.5

/* Returns the number of pixels that fail the per-pixel test. */
static int check(const char *scene_name, int runs, const char *const *sets, int nsets, int expect_unbiased)
{
    const int w = 20, h = 12;
    struct scene s;
    char msg[512];
    EXPECT(scene_create_builtin(scene_name, &s, msg) == 0, "%s", msg);
    struct render_params p;
    render_params_defaults(&p);
    p.width = w;
    p.height = h;
    p.max_bounces = 4;
    for (int k = 0; k < nsets; k++)
        EXPECT(render_params_set(&p, sets[k], msg) == 0, "%s", msg);
    struct pixel_stats ref, pt;
    pixel_stats_init(&ref, w * h);
    pixel_stats_init(&pt, w * h);
    unbiased_run_reference(&s, METHOD_RESTIR_PT, &p, runs, REF_SPP, (float)((FRAMES - 1) * FRAME_STEP), &ref);
    unbiased_run_method(&s, METHOD_RESTIR_PT, &p, 1000, runs, FRAMES, FRAME_STEP, &pt);
    printf("%s %dx%d restir-pt, %d runs of %d frames", scene_name, w, h, runs, FRAMES);
    for (int k = 0; k < nsets; k++)
        printf(" %s", sets[k]);
    printf(":\n");
    struct unbiased_report rep = unbiased_compare(&pt, &ref, ALPHA);
    if (expect_unbiased) {
        EXPECT(rep.pixels_failed == 0, "%s: %d pixels fail the Sidak-corrected Welch test", scene_name,
               rep.pixels_failed);
        EXPECT(fabs(rep.pooled_z) < POOLED_Z_MAX, "%s: pooled z = %.2f", scene_name, rep.pooled_z);
    }
    pixel_stats_free(&ref);
    pixel_stats_free(&pt);
    scene_destroy(&s);
    return rep.pixels_failed;
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
    /* Compatibility-guided selection reads only the G-buffer, so reuse stays unbiased (000 Sec. 4.3). */
    const char *compat[] = {"shift=hybrid", "spatial.select=compat", "spatial.radius=8"};
    for (int sc = 0; sc < 2; sc++)
        check(scenes[sc], RUNS, compat, 3, 1);
    /* The test has power: the BIASED 1/M weights are caught on the same setup. */
    const char *uniform[] = {"shift=hybrid", "mis=1/M"};
    EXPECT(check("cornell", RUNS, uniform, 2, 0) > 0, "1/M weights were not detected as biased");
    return test_finish();
}
