/* bench_poisson.c: the `poisson` section of restir_bench: wall time of the screened Poisson
 * reconstruction (restir/poisson.h), L2 by DCT, L2 by CG to 1e-6 and L1 (20 x 50 Jacobi, 20 x 4
 * multigrid), at 640x360 and 1920x1080 (or the sizes of --res) on a synthetic noisy image; median
 * of N runs (5 by default). Also the relative RMS error of each result against the clean image.
 * --lib-threads N sets librestir's thread count (restir_threads_set; 0: OpenMP's). Must never be
 * run by the tests. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "restir/poisson.h"
#include "restir/threads.h"

static uint64_t bp_state = 0x2545f4914f6cdd1dull;

static double bp_rnd(void) /* uniform [0, 1) */
{
    bp_state ^= bp_state << 13;
    bp_state ^= bp_state >> 7;
    bp_state ^= bp_state << 17;
    return (double)(bp_state >> 11) / 9007199254740992.0;
}

static float *bp_alloc(size_t n)
{
    float *p = malloc(n * sizeof(float));
    if (!p) {
        fprintf(stderr, "bench_poisson: out of memory\n");
        exit(1);
    }
    return p;
}

/* Clean image: smooth shading, a vertical step and a disc. Noisy estimates: primal with
 * uniform noise of amplitude 0.5, gradients of the clean image with amplitude 0.1, and one
 * firefly gradient in 2000. */
static void bp_scene(int w, int h, float *clean, float *P, float *dx, float *dy)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                double v = 0.5 + 0.3 * sin(12.0 * x / w + c) * cos(9.0 * y / h);
                v += x > w / 3 ? 0.4 : 0.0;
                double rx = x - 0.6 * w, ry = y - 0.5 * h;
                v += rx * rx + ry * ry < 0.06 * w * h ? 0.3 * (c + 1) : 0.0;
                clean[3 * ((size_t)y * w + x) + c] = (float)v;
            }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                size_t p = 3 * ((size_t)y * w + x) + c;
                P[p] = clean[p] + (float)(0.5 * (bp_rnd() - 0.5));
                dx[p] = (x + 1 < w ? clean[p + 3] - clean[p] : 0.0f) + (float)(0.1 * (bp_rnd() - 0.5));
                dy[p] = (y + 1 < h ? clean[p + 3 * (size_t)w] - clean[p] : 0.0f) + (float)(0.1 * (bp_rnd() - 0.5));
                if (bp_rnd() < 5e-4)
                    dx[p] += 10.0f;
            }
}

static double bp_rel_rms(const float *a, const float *ref, size_t m)
{
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < m; i++) {
        num += ((double)a[i] - ref[i]) * ((double)a[i] - ref[i]);
        den += (double)ref[i] * ref[i];
    }
    return sqrt(num / den);
}

static int bp_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Parses "WxH[,WxH...]" into res (at most max sizes, each side 2..8192): the count, or -1. */
static int bp_parse_sizes(const char *text, int (*res)[2], int max)
{
    int n = 0;
    for (const char *p = text; p; p = strchr(p, ',') ? strchr(p, ',') + 1 : NULL) {
        if (n == max || sscanf(p, "%dx%d", &res[n][0], &res[n][1]) != 2 || res[n][0] < 2 || res[n][1] < 2 ||
            res[n][0] > 8192 || res[n][1] > 8192)
            return -1;
        n++;
    }
    return n;
}

int bench_poisson(int argc, char **argv)
{
    int runs = 5, lib_threads = 0, n_res = 2;
    int res[8][2] = {{640, 360}, {1920, 1080}};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--runs") && i + 1 < argc && sscanf(argv[i + 1], "%d", &runs) == 1 && runs > 0) {
            i++;
        } else if (!strcmp(argv[i], "--lib-threads") && i + 1 < argc &&
                   sscanf(argv[i + 1], "%d", &lib_threads) == 1 && restir_threads_set(lib_threads) == 0) {
            i++;
        } else if (!strcmp(argv[i], "--res") && i + 1 < argc) {
            n_res = bp_parse_sizes(argv[++i], res, 8);
            if (n_res < 1) {
                fprintf(stderr, "restir_bench poisson: --res wants WxH[,WxH...] (2..8192 each, up to 8 sizes)\n");
                return 2;
            }
        } else {
            fprintf(stderr, "usage: restir_bench poisson [--runs N] [--res WxH[,WxH...]] [--lib-threads N]\n");
            return 2;
        }
    }
    static const char *const names[4] = {"L2 DCT", "L2 CG (tol 1e-6)", "L1 IRLS (20 x 50 Jacobi CG)",
                                         "L1 IRLS (20 x 4 multigrid CG)"};
    printf("\n### Poisson reconstruction, synthetic noisy image, median of %d runs (librestir: %d threads, "
           "restir_threads_set(%d))\n\n",
           runs, restir_threads_get(), lib_threads);
    printf("| resolution | solver | median ms | min ms | iterations | residual | rel. RMS error vs clean |\n"
           "|---|---|---|---|---|---|---|\n");
    double *ms = malloc((size_t)runs * sizeof(double));
    if (!ms)
        return 1;
    for (int r = 0; r < n_res; r++) {
        const int w = res[r][0], h = res[r][1];
        const size_t m = (size_t)w * h * 3;
        float *clean = bp_alloc(m), *P = bp_alloc(m), *dx = bp_alloc(m), *dy = bp_alloc(m), *out = bp_alloc(m);
        bp_scene(w, h, clean, P, dx, dy);
        printf("| %dx%d | primal (noisy input) | | | | | %.4f |\n", w, h, bp_rel_rms(P, clean, m));
        for (int s = 0; s < 4; s++) {
            struct restir_poisson_stats st = {0, 0.0, 0.0};
            for (int k = 0; k < runs; k++) {
                int rc;
                if (s >= 2)
                    rc = restir_poisson_l1(w, h, P, dx, dy, RESTIR_POISSON_ALPHA, RESTIR_POISSON_L1_ITERATIONS,
                                           s == 2 ? RESTIR_POISSON_PRECOND_JACOBI : RESTIR_POISSON_PRECOND_MULTIGRID,
                                           s == 2 ? RESTIR_POISSON_L1_CG_STEPS : RESTIR_POISSON_L1_MG_STEPS, out, &st);
                else
                    rc = restir_poisson_l2(w, h, P, dx, dy, RESTIR_POISSON_ALPHA,
                                           s ? RESTIR_POISSON_CG : RESTIR_POISSON_DCT, RESTIR_POISSON_TOL, 10000,
                                           out, &st);
                if (rc != 0) {
                    fprintf(stderr, "bench_poisson: %s failed at %dx%d\n", names[s], w, h);
                    return 1;
                }
                ms[k] = st.ms;
            }
            qsort(ms, (size_t)runs, sizeof(double), bp_cmp);
            printf("| %dx%d | %s | %.1f | %.1f | %d | %.2e | %.4f |\n", w, h, names[s], ms[runs / 2], ms[0],
                   st.iterations, st.residual, bp_rel_rms(out, clean, m));
            fflush(stdout);
        }
        free(clean), free(P), free(dx), free(dy), free(out);
    }
    free(ms);
    return 0;
}
