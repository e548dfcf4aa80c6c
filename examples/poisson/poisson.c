/* poisson.c: screened Poisson reconstruction with librestir (restir/poisson.h), the last step of
 * gradient-domain rendering: given a noisy image (the "primal") and estimates of its forward
 * differences, find the image that agrees best with both. Here the gradients are exact, so the
 * reconstruction should remove most of the primal's noise.
 *
 * The program builds a synthetic RGB image I (smooth shading plus a rectangle and a disk with
 * sharp edges), its exact forward differences dx, dy (the convention of restir/poisson.h:
 * dx[p] = I(x+1, y) - I(x, y), dy[p] = I(x, y+1) - I(x, y)), and a primal P = I + Gaussian noise
 * + a few bright outliers ("fireflies"). It reconstructs with
 *   restir_poisson_l2 and RESTIR_POISSON_CG (conjugate gradients, always available),
 *   restir_poisson_l2 and RESTIR_POISSON_DCT (a direct solve; only in a librestir built with
 *     FFTW: otherwise it returns -1, and the program says so and skips it),
 *   restir_poisson_l1 (robust to the outliers; it starts from the DCT solution, so it needs FFTW
 *     as well),
 * and checks with restir_metrics_compute that every reconstruction's relMSE against I is far below
 * the primal's, that CG and DCT agree, and that the L1 solve lowers the L1 energy it minimizes and
 * beats L2 on this primal with outliers.
 * Exits 0 on success, 1 with a message on failure. Built against the installed package by
 * scripts/check_core.sh, through CMake's find_package(restir) and through pkg-config. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "restir/metrics.h"
#include "restir/poisson.h"
#include "restir/threads.h"
#include "restir/version.h"

enum { W = 128, H = 96, N = W * H };
#define NOISE_SIGMA 0.1f   /* Gaussian noise of the primal */
#define FIREFLY_RATE 0.002 /* fraction of primal pixels with an outlier */
#define FIREFLY_VALUE 8.0f /* added to every channel of such a pixel */
#define GAIN_MIN 10.0      /* a reconstruction's relMSE must be at least 10x below the primal's */
#define CG_DCT_MAX 1e-4    /* largest allowed |CG - DCT| of one pixel channel */

/* The application's own random numbers: splitmix64, and Gaussians by Box-Muller. */
static uint64_t splitmix64(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double uniform01(uint64_t *s) /* in (0, 1): safe for log */
{
    return ((double)(splitmix64(s) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double gaussian(uint64_t *s)
{
    return sqrt(-2.0 * log(uniform01(s))) * cos(6.283185307179586 * uniform01(s));
}

/* The synthetic image, channel c at pixel (x, y): smooth shading with different phases per
 * channel, plus a brighter rectangle and a darker disk with sharp edges. Values stay in
 * [0.1, 1.3]. */
static float synthetic(int x, int y, int c)
{
    const double pi = 3.141592653589793;
    double u = (x + 0.5) / W, v = (y + 0.5) / H;
    double value = 0.5 + 0.2 * sin(2.0 * pi * u + 1.7 * c) * cos(pi * v) + 0.1 * v;
    if (x >= 20 && x < 60 && y >= 15 && y < 45)
        value += c == 0 ? 0.5 : 0.3; /* rectangle */
    double dxd = x - 90.5, dyd = y - 60.5;
    if (dxd * dxd + dyd * dyd < 22.0 * 22.0)
        value -= c == 2 ? 0.1 : 0.35; /* disk */
    return (float)value;
}

static int fail(const char *what)
{
    printf("poisson: FAIL: %s\n", what);
    return 1;
}

static double relmse(const float *image, const float *reference)
{
    struct restir_metrics_error e;
    if (restir_metrics_compute(image, reference, N, NULL, &e) != 0)
        return NAN;
    return e.relmse;
}

int main(void)
{
    /* librestir's whole-image functions (these solves) run OpenMP loops on their own threads by
     * default. An engine with its own job system calls them from its workers instead and wants
     * them on the calling thread only: */
    restir_threads_set(1);

    static float image[N * 3], dx[N * 3], dy[N * 3], primal[N * 3];
    static float cg[N * 3], dct[N * 3], l1[N * 3];
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                image[(y * W + x) * 3 + c] = synthetic(x, y, c);

    /* Exact forward differences; the last column of dx and the last row of dy are ignored by the
     * solver (set to 0 here). */
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                int p = (y * W + x) * 3 + c;
                dx[p] = x + 1 < W ? image[p + 3] - image[p] : 0.0f;
                dy[p] = y + 1 < H ? image[p + 3 * W] - image[p] : 0.0f;
            }

    /* The noisy primal. */
    uint64_t seed = 2024u;
    for (int p = 0; p < N; p++) {
        int firefly = uniform01(&seed) < FIREFLY_RATE;
        for (int c = 0; c < 3; c++)
            primal[3 * p + c] =
                image[3 * p + c] + NOISE_SIGMA * (float)gaussian(&seed) + (firefly ? FIREFLY_VALUE : 0.0f);
    }

    const float alpha = RESTIR_POISSON_ALPHA; /* the weight of the primal against the gradients */
    struct restir_poisson_stats st_cg, st_dct, st_l1;
    double e_primal = relmse(primal, image);
    printf("librestir %s: screened Poisson reconstruction of a %d x %d RGB image from a noisy primal and\n"
           "exact gradients (alpha = %.2f, %d thread(s))\n",
           RESTIR_VERSION_STRING, W, H, alpha, restir_threads_get());
    printf("  relMSE vs the true image: primal          %.3e\n", e_primal);

    int ok = 1;
    if (restir_poisson_l2(W, H, primal, dx, dy, alpha, RESTIR_POISSON_CG, RESTIR_POISSON_TOL, 1000, cg, &st_cg) != 0)
        return fail("restir_poisson_l2 with RESTIR_POISSON_CG returned -1");
    double e_cg = relmse(cg, image);
    printf("                            L2, CG          %.3e  (%.0fx lower; %d iterations, residual %.1e, %.1f ms)\n",
           e_cg, e_primal / e_cg, st_cg.iterations, st_cg.residual, st_cg.ms);
    if (!(e_cg * GAIN_MIN < e_primal))
        ok = !fail("the CG reconstruction is not 10x better than the primal");

    if (!restir_poisson_has_dct()) {
        /* restir/poisson.h: a librestir built without FFTW has no DCT solve, and restir_poisson_l1
         * starts from it: use RESTIR_POISSON_CG. */
        printf("  RESTIR_POISSON_DCT is not available (librestir built without FFTW): skipping the DCT and\n"
               "  L1 reconstructions\n");
    } else if (restir_poisson_l2(W, H, primal, dx, dy, alpha, RESTIR_POISSON_DCT, 0.0, 0, dct, &st_dct) != 0) {
        return fail("restir_poisson_l2 with RESTIR_POISSON_DCT returned -1 although the library has it");
    } else {
        double e_dct = relmse(dct, image), diff = 0.0;
        for (int i = 0; i < N * 3; i++)
            diff = fmax(diff, fabs((double)cg[i] - dct[i]));
        printf("                            L2, DCT         %.3e  (%.0fx lower; %.1f ms); max |CG - DCT| = %.1e\n",
               e_dct, e_primal / e_dct, st_dct.ms, diff);
        if (!(e_dct * GAIN_MIN < e_primal))
            ok = !fail("the DCT reconstruction is not 10x better than the primal");
        if (!(diff < CG_DCT_MAX))
            ok = !fail("the CG and DCT solutions differ");

        if (restir_poisson_l1(W, H, primal, dx, dy, alpha, RESTIR_POISSON_L1_ITERATIONS,
                              RESTIR_POISSON_PRECOND_MULTIGRID, RESTIR_POISSON_L1_MG_STEPS, l1, &st_l1) != 0)
            return fail("restir_poisson_l1 returned -1 although the DCT solve works");
        double e_l1 = relmse(l1, image);
        double energy_l2 = restir_poisson_l1_energy(W, H, primal, dx, dy, alpha, dct);
        double energy_l1 = restir_poisson_l1_energy(W, H, primal, dx, dy, alpha, l1);
        printf("                            L1 (IRLS)       %.3e  (%.0fx lower; %d CG steps, %.1f ms)\n", e_l1,
               e_primal / e_l1, st_l1.iterations, st_l1.ms);
        printf("  L1 energy: of the L2 solution %.2f, of the L1 solution %.2f\n", energy_l2, energy_l1);
        if (!(e_l1 * GAIN_MIN < e_primal))
            ok = !fail("the L1 reconstruction is not 10x better than the primal");
        if (!(e_l1 < e_cg))
            ok = !fail("the L1 reconstruction is not better than the L2 one despite the outliers");
        if (!(energy_l1 < energy_l2))
            ok = !fail("the L1 solve did not lower the L1 energy below the L2 solution's");
    }
    restir_poisson_release_plans(); /* e.g. before unloading librestir; a no-op without FFTW */
    if (ok)
        printf("poisson: PASS\n");
    return ok ? 0 : 1;
}
