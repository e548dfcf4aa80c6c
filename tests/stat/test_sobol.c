/* test_sobol.c: the properties pt's `sampler=sobol` rests on (core/sobol.h).
 *  1. Stratification: for every seed tried, m <= 12 and every aligned block of 2^m sample indices
 *     (the first block and later ones, as consecutive frames use), a padded pair is a (0,m,2)-net:
 *     every elementary interval of area 2^-m, of every shape 2^-a x 2^-(m-a), holds exactly one
 *     point; a padded single dimension holds one point in each interval [j, j+1) / 2^m.
 *  2. Randomization: across seeds, a fixed sample index gives points uniform in [0,1)^2 (the
 *     scramble makes every point uniform, hence unbiased estimates), two different pairs of one
 *     sample are independent of each other, and the shuffle leaves index 0 uniform over the
 *     sequence (chi-square tests, Sidak-corrected). */
#include <stdint.h>
#include <stdlib.h>

#include "chi2_util.h"
#include "core/sobol.h"
#include "test_util.h"

/* The splitmix64 finalizer: how pt derives a dimension's key (rng_mix64). */
static uint64_t mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* 1 when the 2^m points pts[2k], pts[2k+1] form a (0,m,2)-net in base 2. */
static int is_net(const float *pts, int m)
{
    const int n = 1 << m;
    static unsigned char seen[1 << 12];
    for (int a = 0; a <= m; a++) {
        for (int k = 0; k < n; k++)
            seen[k] = 0;
        for (int k = 0; k < n; k++) {
            const int ix = (int)(pts[2 * k] * (float)(1 << a)), iy = (int)(pts[2 * k + 1] * (float)(1 << (m - a)));
            const int cell = (ix << (m - a)) | iy;
            if (cell < 0 || cell >= n || seen[cell]++)
                return 0;
        }
    }
    return 1;
}

static int is_stratified_1d(const float *u, int m)
{
    const int n = 1 << m;
    static unsigned char seen[1 << 12];
    for (int k = 0; k < n; k++)
        seen[k] = 0;
    for (int k = 0; k < n; k++) {
        const int cell = (int)(u[k] * (float)n);
        if (cell < 0 || cell >= n || seen[cell]++)
            return 0;
    }
    return 1;
}

static void test_stratification(void)
{
    static float pts[2 << 12], line[1 << 12];
    int nets = 0, bad = 0;
    for (uint64_t key = 1; key <= 24; key++) {
        const uint64_t k = mix64(key);
        for (int m = 0; m <= 12; m++) {
            for (uint32_t block = 0; block < 3; block++) {
                const uint32_t base = block << m;
                for (int i = 0; i < (1 << m); i++) {
                    sobol_sample_2d(base + (uint32_t)i, k, &pts[2 * i]);
                    line[i] = sobol_sample_1d(base + (uint32_t)i, mix64(k));
                }
                nets++;
                if (!is_net(pts, m) || !is_stratified_1d(line, m))
                    bad++;
            }
        }
    }
    EXPECT(bad == 0, "%d of %d point sets are not (0,m,2)-nets / stratified", bad, nets);
    /* Dimension 1 against its definition by direction numbers, v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1). */
    int wrong = 0;
    for (uint64_t k = 0; k < 8192u; k++) {
        const uint32_t i = k < 4096u ? (uint32_t)k : (uint32_t)(k * 0x9e3779b97f4a7c15ull >> 32);
        uint32_t x = 0u, v = 0x80000000u;
        for (uint32_t bits = i; bits; bits >>= 1, v ^= v >> 1)
            if (bits & 1u)
                x ^= v;
        wrong += sobol_dim1(i) != x;
    }
    EXPECT(wrong == 0, "sobol_dim1 differs from the direction numbers at %d indices", wrong);
    /* The unscrambled sequence as well: Sobol' dimensions 0 and 1 themselves. */
    for (int m = 0; m <= 12; m++) {
        for (int i = 0; i < (1 << m); i++) {
            pts[2 * i] = sobol_to_float(sobol_dim0((uint32_t)i));
            pts[2 * i + 1] = sobol_to_float(sobol_dim1((uint32_t)i));
        }
        EXPECT(is_net(pts, m), "the first 2^%d Sobol' points are not a (0,%d,2)-net", m, m);
    }
}

/* Chi-square p-value of n points in a bins x bins grid against the uniform distribution. */
static double uniform_p(const float *xy, int n, int bins)
{
    static double count[256], prob[256];
    const int cells = bins * bins;
    for (int c = 0; c < cells; c++) {
        count[c] = 0.0;
        prob[c] = 1.0 / cells;
    }
    for (int k = 0; k < n; k++) {
        int ix = (int)(xy[2 * k] * bins), iy = (int)(xy[2 * k + 1] * bins);
        count[ix * bins + iy] += 1.0;
    }
    int dof;
    return chi2_counts(count, prob, cells, (double)n, &dof);
}

static void test_randomization(void)
{
    enum { SEEDS = 200000, TESTS = 4 };
    const double alpha = chi2_sidak(0.01, TESTS);
    float *a = malloc(sizeof(float) * 2 * SEEDS), *b = malloc(sizeof(float) * 2 * SEEDS);
    float *c = malloc(sizeof(float) * 2 * SEEDS), *d = malloc(sizeof(float) * 2 * SEEDS);
    for (int s = 0; s < SEEDS; s++) {
        const uint64_t key = mix64((uint64_t)s); /* keys are well-mixed hashes, as pt's are */
        float p0[2], p1[2], q[2];
        sobol_sample_2d(0u, key, a + 2 * s);   /* index 0 of a pair */
        sobol_sample_2d(5u, key, p0);          /* index 5 of the same pair ... */
        sobol_sample_2d(5u, mix64(key), p1);   /* ... and of another pair of the same sample */
        b[2 * s] = p0[0], b[2 * s + 1] = p1[1];
        sobol_sample_2d(1000u, key, c + 2 * s);
        q[0] = sobol_sample_1d(3u, key), q[1] = sobol_sample_1d(3u, mix64(key + 1u)); /* two singles */
        d[2 * s] = q[0], d[2 * s + 1] = q[1];
    }
    const double p_a = uniform_p(a, SEEDS, 16), p_b = uniform_p(b, SEEDS, 16);
    const double p_c = uniform_p(c, SEEDS, 16), p_d = uniform_p(d, SEEDS, 16);
    EXPECT(p_a > alpha, "index 0 of a pair is not uniform over seeds: p = %.3g", p_a);
    EXPECT(p_b > alpha, "two pairs of one sample are not independent: p = %.3g", p_b);
    EXPECT(p_c > alpha, "index 1000 of a pair is not uniform over seeds: p = %.3g", p_c);
    EXPECT(p_d > alpha, "two single dimensions are not independent: p = %.3g", p_d);
    printf("uniformity over %d seeds: p = %.3f %.3f %.3f %.3f (alpha %.4f each)\n", SEEDS, p_a, p_b, p_c, p_d,
           alpha);
    free(a), free(b), free(c), free(d);
}

int main(void)
{
    test_stratification();
    test_randomization();
    return test_finish();
}
