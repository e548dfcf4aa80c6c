/* test_gradient_unbiased.c: the gradient-domain methods of 002 (gpt, grad-after-restir, grestir-pt)
 * estimate the forward-difference gradients of the image without bias on cornell, with temporal
 * and spatial reuse on and a moving camera (gradient_runs.h: dx, dy, the primal and the L2
 * reconstruction against K path-traced references), with 002's ablations; L1's bias is measured;
 * BIASED 1/M weights are caught. The other scenes: test_gradient_unbiased_scenes.c.
 * Usage for experiments: render_test_gradient_unbiased [SCENE METHOD RUNS key=value...]. */
#include <stdlib.h>

#include "gradient_runs.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 80

int main(int argc, char **argv)
{
    if (argc >= 4) {
        gradient_check(argv[1], argv[2], atoi(argv[3]), (const char *const *)argv + 4, argc - 4, 1);
        return test_finish();
    }
    const char *none[] = {"recon=l2"};
    gradient_check("cornell", "gpt", 4096, none, 1, 1);
    gradient_check("cornell", "grad-after-restir", 4096, none, 1, 1);
    gradient_check("cornell", "grestir-pt", 4096, none, 1, 1);
    /* The ablations of 002 Fig. 9-10 and Sec. 4.4 are unbiased too. */
    const char *variants[][2] = {{"recon=l2", "grad.positivize=off"},
                                 {"recon=l2", "grad.cross_sign=on"},
                                 {"recon=l2", "grad.spatial=dense"},
                                 {"recon=l2", "history=temporal"},
                                 {"recon=l2", "grad.base=shared"},
                                 /* the 2x2 previous pairs with clipped shifts (Area ReSTIR Sec. 4.3.1) */
                                 {"recon=l2", "temporal.subpixel=search"}};
    for (int k = 0; k < 6; k++)
        gradient_check("cornell", "grestir-pt", 2048, variants[k], 2, 1);
    /* L1's bias, measured (printed) with the L2 checks of the same runs: 512 of them, as L1's iterative
     * solve is most of the test's time at 2048 (95 CPU-s of 115; the L2 checks of recon=l2 above have 4096) */
    const char *both[] = {"recon=both"};
    gradient_check("cornell", "grestir-pt", 512, both, 1, 1);
    /* The test has power: BIASED 1/M resampling weights in the paired-pixel merges are caught. */
    const char *uniform[] = {"recon=l2", "mis=1/M"};
    EXPECT(gradient_check("cornell", "grestir-pt", 2048, uniform, 2, 0) > 0, "1/M weights were not detected as biased");
    return test_finish();
}
