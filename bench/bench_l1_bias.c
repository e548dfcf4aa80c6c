/* bench_l1_bias.c: `restir_bench l1-bias FRAME.exr REF.exr`: where L1 reconstruction's dark bias
 * comes from. Reads the primal, dx and dy layers of one gradient-method frame (restir
 * render --method grestir-pt|gpt|grad-after-restir writes them) and a converged reference, then
 * solves the same inputs with the L2 DCT solve and with IRLS L1 (recon/poisson_l1.c) over a grid
 * of reweightings, CG steps per reweighting and alpha, printing each result's image mean as a
 * share of the reference's and its relMSE. If the mean moved toward the reference's as the IRLS
 * solve converges, the bias would be the settings'; if it stays or falls, it is the L1 energy's. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "io/exr.h"
#include "restir/metrics.h"
#include "restir/poisson.h"

static double image_mean(const float *v, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < 3 * n; i++)
        s += v[i];
    return s / (3.0 * (double)n);
}

struct l1_case {
    const char *solve; /* "L2" or "L1" */
    int iterations, cg_steps;
    float alpha;
    enum restir_poisson_precond precond;
};

static void print_case(const struct l1_case *c, int w, int h, const float *p, const float *dx, const float *dy,
                       const float *ref, float *out)
{
    struct restir_poisson_stats st;
    const size_t n = (size_t)w * (size_t)h;
    int rc = c->solve[1] == '2'
                 ? restir_poisson_l2(w, h, p, dx, dy, c->alpha, RESTIR_POISSON_DCT, 0.0, 0, out, &st)
                 : restir_poisson_l1(w, h, p, dx, dy, c->alpha, c->iterations, c->precond, c->cg_steps, out, &st);
    if (rc != 0) {
        printf("| %s | | %d | %d | %g | (solve failed) | | | | | |\n", c->solve, c->iterations, c->cg_steps,
               (double)c->alpha);
        return;
    }
    struct restir_metrics_error e;
    restir_metrics_compute(out, ref, n, NULL, &e);
    const char *pre = c->solve[1] == '2'                            ? ""
                      : c->precond == RESTIR_POISSON_PRECOND_JACOBI ? "Jacobi"
                                                                    : "multigrid";
    printf("| %s | %s | %d | %d | %g | %.3f | %.4f | %.4f | %.6e | %.2e | %.0f |\n", c->solve, pre, c->iterations,
           c->cg_steps, (double)c->alpha, image_mean(out, n) / image_mean(ref, n), e.relmse, e.mape,
           restir_poisson_l1_energy(w, h, p, dx, dy, c->alpha, out), st.residual, st.ms);
}

int bench_l1_bias(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: restir_bench l1-bias FRAME.exr REF.exr (FRAME: a gradient method's frame, with its "
                        "primal, dx and dy layers)\n");
        return 2;
    }
    float *p = NULL, *dx = NULL, *dy = NULL, *ref = NULL;
    int w, h, rw, rh, status = 2;
    char msg[512];
    if (exr_read_layer(argv[1], "primal", &p, &w, &h, msg) != 0 ||
        exr_read_layer(argv[1], "dx", &dx, &w, &h, msg) != 0 ||
        exr_read_layer(argv[1], "dy", &dy, &w, &h, msg) != 0 || exr_read_rgb(argv[2], &ref, &rw, &rh, msg) != 0) {
        fprintf(stderr, "restir_bench l1-bias: %s\n", msg);
        goto done;
    }
    if (rw != w || rh != h) {
        fprintf(stderr, "restir_bench l1-bias: %s is %dx%d, %s is %dx%d\n", argv[1], w, h, argv[2], rw, rh);
        goto done;
    }
    float *out = malloc(3 * (size_t)w * (size_t)h * sizeof(float));
    if (!out) {
        fprintf(stderr, "restir_bench l1-bias: out of memory\n");
        goto done;
    }
    const enum restir_poisson_precond J = RESTIR_POISSON_PRECOND_JACOBI, M = RESTIR_POISSON_PRECOND_MULTIGRID;
    const struct l1_case cases[] = {
        {"L2", 0, 0, 0.2f, J},     {"L1", 1, 50, 0.2f, J},   {"L1", 2, 50, 0.2f, J},   {"L1", 5, 50, 0.2f, J},
        {"L1", 10, 50, 0.2f, J},   {"L1", 20, 10, 0.2f, J},  {"L1", 20, 50, 0.2f, J},  {"L1", 20, 200, 0.2f, J},
        {"L1", 20, 1000, 0.2f, J}, {"L1", 40, 200, 0.2f, J}, {"L1", 20, 50, 0.05f, J}, {"L1", 20, 50, 1.0f, J},
        {"L1", 20, 50, 5.0f, J},   {"L1", 20, 1, 0.2f, M},   {"L1", 20, 2, 0.2f, M},   {"L1", 20, 4, 0.2f, M},
        {"L1", 20, 8, 0.2f, M},    {"L1", 20, 16, 0.2f, M},  {"L1", 40, 16, 0.2f, M},
    };
    printf("\n### L1 bias on %s (%dx%d) against %s\n\n", argv[1], w, h, argv[2]);
    printf("| solve | preconditioner | reweightings | CG steps each | alpha | mean / reference mean | relMSE | MAPE | "
           "L1 energy | residual | ms |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); k++)
        print_case(&cases[k], w, h, p, dx, dy, ref, out);
    printf("\nprimal mean / reference mean: %.3f\n",
           image_mean(p, (size_t)w * (size_t)h) / image_mean(ref, (size_t)w * (size_t)h));
    free(out);
    status = 0;
done:
    free(p), free(dx), free(dy), free(ref);
    return status;
}
