/* test_sampling.c: unit tests of the square-to-domain warps and the alias table.
 * Must never depend on scene, shading or render code. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "test_util.h"

static void test_disk_round_trip(void)
{
    pcg32 r = pcg32_make(1u, 2u);
    double max_err = 0.0;
    int outside = 0;
    for (int i = 0; i < 200000; i++) {
        float u1 = pcg32_float(&r), u2 = pcg32_float(&r);
        float x, y, v1, v2;
        warp_concentric_disk(u1, u2, &x, &y);
        if (x * x + y * y > 1.0f + 1e-6f)
            outside++;
        warp_concentric_disk_inverse(x, y, &v1, &v2);
        double e = fmax(fabs((double)v1 - u1), fabs((double)v2 - u2));
        if (e > max_err)
            max_err = e;
    }
    EXPECT(outside == 0, "%d disk points outside the unit disk", outside);
    EXPECT(max_err < 1e-5, "concentric disk inverse round trip max error %g", max_err);

    /* The branch boundaries (diagonals and axes) and the center. */
    const float pts[][2] = {{0.5f, 0.5f}, {0.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}, {1.0f, 0.0f},
                            {0.5f, 1.0f}, {1.0f, 0.5f}, {0.5f, 0.0f}, {0.0f, 0.5f}, {0.25f, 0.75f}};
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
        float x, y, v1, v2;
        warp_concentric_disk(pts[i][0], pts[i][1], &x, &y);
        warp_concentric_disk_inverse(x, y, &v1, &v2);
        EXPECT(fabsf(v1 - pts[i][0]) < 1e-5f && fabsf(v2 - pts[i][1]) < 1e-5f,
               "round trip of (%g, %g) gave (%g, %g)", pts[i][0], pts[i][1], v1, v2);
    }

    /* Area preservation: the four quadrants of the square land in equal-area disk regions;
     * a quarter of a disk of radius 1/2 (the image of the square of side 1/2) has area pi/16. */
    int inner = 0;
    const int n = 100000;
    for (int i = 0; i < n; i++) {
        float x, y;
        warp_concentric_disk(0.25f + 0.5f * pcg32_float(&r), 0.25f + 0.5f * pcg32_float(&r), &x, &y);
        if (x * x + y * y <= 0.25f + 1e-6f)
            inner++;
    }
    EXPECT(inner == n, "inner square must map inside radius 1/2 (%d of %d)", inner, n);
}

static void test_warp_domains(void)
{
    pcg32 r = pcg32_make(3u, 4u);
    int bad_hemi = 0, bad_sphere = 0, bad_tri = 0;
    double mean_z_hemi = 0.0, mean_z_sphere = 0.0, mean_b1 = 0.0, mean_b2 = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; i++) {
        float u1 = pcg32_float(&r), u2 = pcg32_float(&r);
        vec3 h = warp_cosine_hemisphere(u1, u2);
        if (h.z < 0.0f || fabsf(v3_length(h) - 1.0f) > 1e-5f)
            bad_hemi++;
        mean_z_hemi += h.z;
        vec3 s = warp_uniform_sphere(u1, u2);
        if (fabsf(v3_length(s) - 1.0f) > 1e-5f)
            bad_sphere++;
        mean_z_sphere += s.z;
        float b1, b2;
        warp_uniform_triangle(u1, u2, &b1, &b2);
        if (b1 < 0.0f || b2 < 0.0f || b1 + b2 > 1.0f + 1e-6f)
            bad_tri++;
        mean_b1 += b1;
        mean_b2 += b2;
    }
    EXPECT(bad_hemi == 0, "%d hemisphere samples off the unit upper hemisphere", bad_hemi);
    EXPECT(bad_sphere == 0, "%d sphere samples off the unit sphere", bad_sphere);
    EXPECT(bad_tri == 0, "%d triangle samples outside the triangle", bad_tri);
    /* Moments: E[cos] under cos/pi is 2/3; sphere mean z is 0; triangle centroid is 1/3. */
    EXPECT_NEAR(mean_z_hemi / n, 2.0 / 3.0, 5e-3, "cosine hemisphere E[z]");
    EXPECT_NEAR(mean_z_sphere / n, 0.0, 5e-3, "uniform sphere E[z]");
    EXPECT_NEAR(mean_b1 / n, 1.0 / 3.0, 3e-3, "triangle E[b1]");
    EXPECT_NEAR(mean_b2 / n, 1.0 / 3.0, 3e-3, "triangle E[b2]");

    EXPECT_NEAR(warp_cosine_hemisphere_pdf(v3(0.0f, 0.0f, 1.0f)), (double)RESTIR_INV_PI, 1e-6, "pdf at pole");
    EXPECT(warp_cosine_hemisphere_pdf(v3(0.0f, 0.6f, -0.8f)) == 0.0f, "pdf below the horizon must be 0");

    /* Extreme uniforms stay in the domain and finite. */
    const float ext[] = {0.0f, 0x1.fffffep-1f};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            vec3 h = warp_cosine_hemisphere(ext[i], ext[j]);
            vec3 s = warp_uniform_sphere(ext[i], ext[j]);
            float b1, b2;
            warp_uniform_triangle(ext[i], ext[j], &b1, &b2);
            EXPECT(v3_is_finite(h) && h.z >= 0.0f, "hemisphere at corner %d,%d", i, j);
            EXPECT(v3_is_finite(s), "sphere at corner %d,%d", i, j);
            EXPECT(b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f, "triangle at corner %d,%d", i, j);
        }
}

static void test_alias_frequencies(void)
{
    const float w[] = {1.0f, 0.0f, 5.0f, 0.25f, 3.0f, 10.0f, 0.0f, 2.5f, 7.0f, 0.5f};
    const int n = (int)(sizeof w / sizeof w[0]);
    struct alias_table t;
    EXPECT(alias_table_init(&t, w, n) == 0, "valid weights must build");
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        sum += w[i];
    EXPECT_NEAR(t.total, sum, 1e-9, "alias total");
    double pmf_sum = 0.0;
    for (int i = 0; i < n; i++) {
        pmf_sum += t.pmf[i];
        EXPECT_NEAR(t.pmf[i], w[i] / sum, 1e-7, "pmf entry");
    }
    EXPECT_NEAR(pmf_sum, 1.0, 1e-6, "pmf sums to one");

    const int samples = 1000000;
    int counts[10] = {0};
    pcg32 r = pcg32_make(7u, 9u);
    for (int s = 0; s < samples; s++) {
        int i = alias_table_sample(&t, pcg32_float(&r));
        if (i >= 0 && i < n)
            counts[i]++;
    }
    for (int i = 0; i < n; i++) {
        double p = w[i] / sum;
        double f = (double)counts[i] / samples;
        if (p == 0.0) {
            EXPECT(counts[i] == 0, "zero-weight index %d sampled %d times", i, counts[i]);
        } else if (p * samples >= 40000.0) {
            /* 1% relative is > 5 sigma for these p (sigma/p = sqrt((1-p)/(p N)) < 0.5%). */
            EXPECT(fabs(f - p) <= 0.01 * p, "index %d: frequency %g vs p %g", i, f, p);
        } else {
            /* Small p: 5-sigma binomial bound instead of a relative one. */
            double sigma = sqrt(p * (1.0 - p) / samples);
            EXPECT(fabs(f - p) <= 5.0 * sigma, "index %d: frequency %g vs p %g", i, f, p);
        }
    }
    /* The top of the uniform range stays in bounds. */
    int last = alias_table_sample(&t, 0x1.fffffep-1f);
    EXPECT(last >= 0 && last < n && w[last] > 0.0f, "u -> 1 gave index %d", last);
    alias_table_fini(&t);

    /* One entry. */
    float one = 2.0f;
    EXPECT(alias_table_init(&t, &one, 1) == 0, "single weight builds");
    EXPECT(alias_table_sample(&t, 0.3f) == 0 && alias_table_sample(&t, 0.99f) == 0, "single entry");
    EXPECT_NEAR(t.pmf[0], 1.0, 0.0, "single pmf");
    alias_table_fini(&t);
}

static void test_alias_bad_weights(void)
{
    struct alias_table t;
    const float neg[] = {1.0f, -0.5f, 2.0f};
    const float zero[] = {0.0f, 0.0f, 0.0f};
    const float nan_w[] = {1.0f, NAN, 2.0f};
    const float inf_w[] = {1.0f, INFINITY, 2.0f};
    EXPECT(alias_table_init(&t, neg, 3) == -1, "negative weight must be rejected");
    EXPECT(alias_table_init(&t, zero, 3) == -1, "all-zero weights must be rejected");
    EXPECT(alias_table_init(&t, nan_w, 3) == -1, "NaN weight must be rejected");
    EXPECT(alias_table_init(&t, inf_w, 3) == -1, "infinite weight must be rejected");
    EXPECT(alias_table_init(&t, neg, 0) == -1, "n = 0 must be rejected");
    EXPECT(alias_table_init(&t, neg, -3) == -1, "n < 0 must be rejected");
    /* A rejected table owns nothing, so fini on it is harmless. */
    alias_table_fini(&t);
}

int main(void)
{
    test_disk_round_trip();
    test_warp_domains();
    test_alias_frequencies();
    test_alias_bad_weights();
    return test_finish();
}
