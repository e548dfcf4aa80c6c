/* test_regir.c: ReGIR's light grid (methods/restir_di/regir.h) and its light cuts (light_cut.h: the
 * probabilities sum to 1 and match the draws, chi-square). Every valid shading point of a frame
 * lies in an occupied cell; and each slot's contribution weight is unbiased: for f the indicator of
 * a set of emitters, E[f(Y) W] over a cell's slots is the summed area of the set's emitters that the
 * cell's target covers (GRIS, 004 Eq. 7 with f = 1 on those emitters), checked for groups of the
 * many-lights emitters and for all of them, from both sources, with and without an environment
 * (tests/data/scenes/leaves_sky.json: a slot is then a sky direction with probability env_prob),
 * by a t-test per group (Sidak-corrected) over independently seeded frames. Not vacuous: a weight
 * off by the 1/K of the slot's RIS, or by the emitters' share, fails every group by far. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/rng.h"
#include "methods/restir_di/di_sample.h"
#include "methods/restir_di/regir.h"
#include "frame_fixture.h"
#include "test_util.h"

#define WIDTH 32
#define HEIGHT 18
#define FRAMES 400
#define GROUPS 8
/* |t| limit: the two-sided normal quantile at family-wise 0.001 over the GROUPS + 1 tests (Sidak:
 * 1 - 0.999^(1/9) = 1.11e-4 per test) */
#define T_LIMIT 3.86

/* One cell's slots over FRAMES fills: per group g, the mean and variance of W 1{Y in group g}
 * (group of emitter e: e mod GROUPS; group GROUPS: every emitter), against the areas of the
 * emitters the cell covers. Returns the number of failed groups. */
static int check_cell(const char *scene_name, enum regir_source src)
{
    struct scene s;
    struct render_params p;
    struct gbuffer g;
    struct camera_view view;
    if (frame_fixture(scene_name, WIDTH, HEIGHT, 1, 3, &s, &p, &g, &view) != 0)
        return 1;
    struct di_settings *ds = di_settings_of_mut(&p);
    ds->initial = DI_INITIAL_REGIR;
    ds->regir_source = src;
    ds->regir_grid = 2; /* few cells: the fills are the test's cost */
    struct regir_grid r;
    regir_init(&r, &s, ds);
    regir_build(&r, &g, ds);
    int outside = 0;
    for (int i = 0; i < WIDTH * HEIGHT; i++) {
        const struct shading_point *sp = gbuffer_shading(&g, i);
        outside += sp->valid && regir_block_of(&r, sp->p) < 0;
    }
    EXPECT(r.n_blocks > 0 && outside == 0, "%s: %d cells, %d valid points outside them", scene_name, r.n_blocks,
           outside);
    const int b = regir_block_of(&r, gbuffer_shading(&g, (HEIGHT / 2) * WIDTH + WIDTH / 2)->p);
    double expect[GROUPS + 1] = {0}, sum[GROUPS + 1] = {0}, sum2[GROUPS + 1] = {0};
    for (int e = 0; e < s.num_emitters; e++)
        if (regir_cell_weight(&r, &s, b, e) > 0.0f) {
            expect[e % GROUPS] += s.tri_area[s.emitters[e].tri];
            expect[GROUPS] += s.tri_area[s.emitters[e].tri];
        }
    long n = 0, env = 0;
    for (int f = 0; f < FRAMES; f++) {
        regir_fill(&r, &s, ds, 1000 + (uint64_t)f, f);
        for (int k = 0; k < r.block_slots[b]; k++, n++) {
            const int i = r.block_first[b] + k, tri = r.store.tri[i];
            const int e = tri >= 0 && tri != DI_ENV_TRI ? s.tri_emitter[tri] : -1;
            env += tri == DI_ENV_TRI;
            double x[GROUPS + 1] = {0};
            if (e >= 0)
                x[e % GROUPS] = x[GROUPS] = r.store.W[i];
            for (int q = 0; q <= GROUPS; q++)
                sum[q] += x[q], sum2[q] += x[q] * x[q];
        }
    }
    /* slots are independent given the cell, frames independent: n i.i.d. values per group */
    const double limit = T_LIMIT;
    int failed = 0;
    for (int q = 0; q <= GROUPS; q++) {
        const double mean = sum[q] / (double)n, var = (sum2[q] / (double)n - mean * mean) * n / (n - 1.0);
        const double t = var > 0.0 ? (mean - expect[q]) / sqrt(var / (double)n) : (mean == expect[q] ? 0.0 : 1e9);
        printf("%s %s group %d: E[W 1] %.6g, covered area %.6g, t %.2f\n", scene_name,
               src == REGIR_SOURCE_BVH ? "bvh" : "power", q, mean, expect[q], t);
        failed += fabs(t) > limit;
    }
    EXPECT(failed == 0, "%s: %d of %d groups' E[W 1] differ from their covered area (|t| > %.2f)", scene_name,
           failed, GROUPS + 1, limit);
    /* the test's power: a W without RIS's 1/K (one candidate of K too many) would be caught */
    const double mean = sum[GROUPS] / (double)n, var = (sum2[GROUPS] / (double)n - mean * mean) * n / (n - 1.0);
    const double K = ds->regir_candidates, t_wrong = (mean * (K + 1.0) / K - expect[GROUPS]) / sqrt(var / n);
    EXPECT(fabs(t_wrong) > limit, "%s: too few slots to see a weight off by 1/K (|t| %.2f)", scene_name, t_wrong);
    if (s.env)
        EXPECT(env > 0 && env < n, "%s: %ld of %ld slots hold the sky", scene_name, env, n);
    regir_fini(&r);
    gbuffer_fini(&g);
    scene_destroy(&s);
    return failed;
}

/* light_cut.h: the probabilities of a cut sum to 1 and are the frequencies of its draws (chi-square
 * over the emitters expected at least 20 times, the rest pooled into one bin). */
static void check_cut(const char *scene_name, vec3 c)
{
    struct scene s;
    char msg[512];
    if (scene_load(scene_name, &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    struct light_cut_order o;
    EXPECT(light_cut_order_init(&o, &s.light_bvh, s.num_emitters) == 0, "%s: no light tree", scene_name);
    struct light_cut cut;
    light_cut_build(&cut, &s.light_bvh, &o, c);
    double total = 0.0;
    for (int e = 0; e < s.num_emitters; e++)
        total += light_cut_pmf(&cut, &o, e);
    EXPECT(cut.nodes > 1 && fabs(total - 1.0) < 1e-4, "%s: %d cut nodes, probabilities sum to %.7f", scene_name,
           cut.nodes, total);
    const long draws = 400000;
    long *count = calloc((size_t)s.num_emitters, sizeof(long)), nulls = 0;
    pcg32 rng = rng_for(7, 0, 0, 1);
    for (long k = 0; k < draws; k++) {
        const int e = light_cut_sample(&cut, &o, (double)pcg32_next(&rng) * 0x1.0p-32, pcg32_float(&rng));
        if (e < 0)
            nulls++;
        else
            count[e]++;
    }
    double chi2 = 0.0, pooled_obs = 0.0, pooled_exp = 0.0;
    int bins = 0;
    for (int e = 0; e < s.num_emitters; e++) {
        const double expected = draws * (double)light_cut_pmf(&cut, &o, e);
        if (expected >= 20.0) {
            chi2 += (count[e] - expected) * (count[e] - expected) / expected;
            bins++;
        } else {
            pooled_obs += count[e];
            pooled_exp += expected;
        }
    }
    if (pooled_exp > 0.0)
        chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp, bins++;
    /* chi-square with bins - 1 degrees of freedom: mean bins - 1, sd sqrt(2 (bins - 1)); 5 sd */
    const double dof = bins - 1.0, limit = dof + 5.0 * sqrt(2.0 * dof);
    printf("%s cut: %d nodes, %d bins, chi2 %.1f (limit %.1f), %ld null draws\n", scene_name, cut.nodes, bins, chi2,
           limit, nulls);
    EXPECT(bins > 10 && chi2 < limit && nulls == 0, "%s: the cut's draws do not follow its pmf (chi2 %.1f, %d bins)",
           scene_name, chi2, bins);
    free(count);
    light_cut_order_fini(&o);
    scene_destroy(&s);
}

int main(void)
{
    check_cut("many-lights", v3(0.0f, 0.5f, 0.0f));
    check_cell("many-lights", REGIR_SOURCE_POWER);
    check_cell("many-lights", REGIR_SOURCE_BVH);
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (data) {
        char path[1024];
        snprintf(path, sizeof path, "%s/scenes/leaves_sky.json", data);
        check_cell(path, REGIR_SOURCE_BVH);
    }
    return test_finish();
}
