/* test_light_pool.c: the per-frame light pool of ReSTIR DI's initial RIS (light_pool.h) draws
 * lights_sample's distribution: chi-square over (emitter, barycentric cell) on many-lights' 1200
 * emitters; every entry is consistent with lights_point; a window never wraps (the tail repeats
 * the head); pools are reproducible per (seed, frame) at any thread count and differ between
 * frames; a pixel's window offset is uniform. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chi2_util.h"
#include "core/check.h"
#include "core/rng.h"
#include "methods/restir_di/light_pool.h"
#include "scene/scenes_builtin.h"
#include "shading/lights.h"
#include "test_util.h"

#define GRID 2    /* barycentric cells per axis: 3 non-empty cells per emitter */
#define FRAMES 96 /* pools drawn: 96 x 16384 = 1.6M samples, ~440 per emitter */

static double cell_fraction(int i, int j)
{
    double cell = 1.0 / (GRID * GRID);
    return i + j <= GRID - 2 ? cell / 0.5 : (i + j == GRID - 1 ? 0.5 * cell / 0.5 : 0.0);
}

static int pools_equal(const struct light_pool *a, const struct light_pool *b)
{
    size_t n = (size_t)a->size;
    return !memcmp(a->tri, b->tri, n * sizeof(int)) && !memcmp(a->b1, b->b1, n * sizeof(float)) &&
           !memcmp(a->b2, b->b2, n * sizeof(float)) && !memcmp(a->px, b->px, n * sizeof(float));
}

int main(void)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    EXPECT(scene_create_builtin("many-lights", &s, msg) == 0, "%s", msg);
    const int ne = s.num_emitters, window = 32;
    struct light_pool lp;
    light_pool_init(&lp, window);
    double *observed = xcalloc((size_t)ne * GRID * GRID, sizeof(double));
    long inconsistent = 0, tail_wrong = 0;
    for (int f = 0; f < FRAMES; f++) {
        light_pool_fill(&lp, &s, 7, f);
        for (int i = 0; i < lp.size; i++) {
            int e = s.tri_emitter[lp.tri[i]];
            struct light_sample ls;
            lights_point(&s, lp.tri[i], lp.b1[i], lp.b2[i], &ls);
            if (e < 0 || ls.p.x != lp.px[i] || ls.p.y != lp.py[i] || ls.p.z != lp.pz[i] || ls.n.x != lp.nx[i] ||
                ls.Le.y != lp.Lg[i] || ls.pdf_area != lp.pdf[i] || !(lp.b1[i] >= 0.0f && lp.b2[i] >= 0.0f &&
                                                                     lp.b1[i] + lp.b2[i] <= 1.0f + 1e-6f))
                inconsistent++;
            if (i >= LIGHT_POOL_SIZE) {
                int h = i - LIGHT_POOL_SIZE;
                tail_wrong += lp.tri[i] != lp.tri[h] || lp.b1[i] != lp.b1[h] || lp.px[i] != lp.px[h];
                continue; /* copies: not new draws */
            }
            int ci = (int)(lp.b1[i] * GRID), cj = (int)(lp.b2[i] * GRID);
            ci = ci >= GRID ? GRID - 1 : ci;
            cj = cj >= GRID ? GRID - 1 : cj;
            observed[(e * GRID + ci) * GRID + cj] += 1.0;
        }
    }
    EXPECT(inconsistent == 0, "%ld pool entries disagree with lights_point", inconsistent);
    EXPECT(tail_wrong == 0, "%ld tail entries differ from the head they repeat", tail_wrong);
    const double n_samples = (double)FRAMES * LIGHT_POOL_SIZE;
    double *expected = xmalloc(sizeof(double) * (size_t)ne * GRID * GRID);
    for (int e = 0; e < ne; e++)
        for (int i = 0; i < GRID; i++)
            for (int j = 0; j < GRID; j++)
                expected[(e * GRID + i) * GRID + j] = n_samples * (double)s.emitter_table.pmf[e] * cell_fraction(i, j);
    int dof;
    double stat = chi2_pooled(observed, expected, ne * GRID * GRID, &dof);
    double p = chi2_pvalue(stat, dof);
    printf("pool chi-square (%d emitters x %dx%d cells, %.0f samples): p = %.4f, dof %d\n", ne, GRID, GRID,
           n_samples, p, dof);
    EXPECT(p >= 0.01, "pool chi-square p %g < 0.01", p);
    /* The same test must reject a pool that draws emitters by area instead of power. */
    double area_sum = 0.0;
    for (int e = 0; e < ne; e++)
        area_sum += s.tri_area[s.emitter_tri[e]];
    for (int e = 0; e < ne; e++)
        for (int c = 0; c < GRID * GRID; c++)
            expected[e * GRID * GRID + c] *= (s.tri_area[s.emitter_tri[e]] / area_sum) / s.emitter_table.pmf[e];
    stat = chi2_pooled(observed, expected, ne * GRID * GRID, &dof);
    double p_wrong = chi2_pvalue(stat, dof);
    printf("area-proportional pmf: p = %.3g\n", p_wrong);
    EXPECT(p_wrong < 1e-6, "the chi-square must reject an area-proportional pmf (p = %g)", p_wrong);

    /* Reproducible per (seed, frame) whatever the thread count; frames differ. */
    struct light_pool a, b;
    light_pool_init(&a, window);
    light_pool_init(&b, window);
    omp_set_num_threads(1);
    light_pool_fill(&a, &s, 3, 5);
    omp_set_num_threads(2);
    light_pool_fill(&b, &s, 3, 5);
    EXPECT(pools_equal(&a, &b), "pool of (seed 3, frame 5) depends on the thread count");
    light_pool_fill(&b, &s, 3, 6);
    EXPECT(!pools_equal(&a, &b), "frames 5 and 6 drew the same pool");

    /* Window offsets: uniform over the pool (chi-square over 64 bins) and inside it. */
    double bins[64] = {0}, prob[64];
    pcg32 r = pcg32_make(99u, 1u);
    int out_of_range = 0;
    for (int k = 0; k < 640000; k++) {
        int o = light_pool_offset(pcg32_float(&r));
        out_of_range += o < 0 || o >= LIGHT_POOL_SIZE;
        bins[(o * 64) / LIGHT_POOL_SIZE] += 1.0;
    }
    EXPECT(light_pool_offset(0.99999994f) == LIGHT_POOL_SIZE - 1 && light_pool_offset(0.0f) == 0, "offset range");
    for (int k = 0; k < 64; k++)
        prob[k] = 1.0 / 64.0;
    double p_off = chi2_counts(bins, prob, 64, 640000.0, &dof);
    printf("window offsets chi-square: p = %.4f\n", p_off);
    EXPECT(out_of_range == 0 && p_off >= 0.01, "window offsets not uniform (p = %g, %d outside)", p_off, out_of_range);

    free(observed);
    free(expected);
    light_pool_fini(&lp);
    light_pool_fini(&a);
    light_pool_fini(&b);
    scene_destroy(&s);
    return test_finish();
}
