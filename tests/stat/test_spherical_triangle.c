/* test_spherical_triangle.c: the solid-angle sampler of emitting triangles (shading/
 * spherical_triangle.h). For triangles near, far, oblique and wide as seen from a point, and close to
 * its plane (the sampler's double path):
 *  1. spherical_triangle_init's solid angle against a quadrature of cos / d^2 over the triangle's area;
 *  2. the sampled directions follow 1 / omega: the triangle cut into K^2 sub-triangles, each with
 *     probability omega_cell / omega (its exact solid angle), chi-square over the cells
 *     (Sidak-corrected over the configurations), and the cells' solid angles summing to omega
 *     (the density integrates to 1). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "chi2_util.h"
#include "core/rng.h"
#include "shading/spherical_triangle.h"
#include "test_util.h"

#define K 12 /* sub-triangles per edge: K^2 cells */

struct config {
    const char *name;
    vec3 x, a, b, c;
};

/* Van Oosterom and Strackee 1983 in double: the solid angle of triangle a, b, c from x, for the
 * cells' probabilities (independent of the sampler's own float or double solid angle). */
static double solid_angle_d(vec3 x, vec3 a, vec3 b, vec3 c)
{
    const double A[3] = {a.x - x.x, a.y - x.y, a.z - x.z}, B[3] = {b.x - x.x, b.y - x.y, b.z - x.z},
                 C[3] = {c.x - x.x, c.y - x.y, c.z - x.z};
    const double la = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]), lb = sqrt(B[0] * B[0] + B[1] * B[1] + B[2] * B[2]),
                 lc = sqrt(C[0] * C[0] + C[1] * C[1] + C[2] * C[2]);
    const double triple = A[0] * (B[1] * C[2] - B[2] * C[1]) - A[1] * (B[0] * C[2] - B[2] * C[0]) +
                          A[2] * (B[0] * C[1] - B[1] * C[0]);
    const double ab = A[0] * B[0] + A[1] * B[1] + A[2] * B[2], ac = A[0] * C[0] + A[1] * C[1] + A[2] * C[2],
                 bc = B[0] * C[0] + B[1] * C[1] + B[2] * C[2];
    return 2.0 * atan2(fabs(triple), la * lb * lc + ab * lc + ac * lb + bc * la);
}

/* omega by quadrature: the midpoint rule over n^2 sub-triangles of cos_l / d^2 dA. */
static double quadrature(vec3 x, vec3 a, vec3 b, vec3 c, int n)
{
    const vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a), nrm = v3_cross(e1, e2);
    const double area2 = v3_length(nrm); /* twice the area */
    const vec3 nu = v3_scale(nrm, (float)(1.0 / area2));
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n - i; j++)
            for (int up = 0; up < (i + j < n - 1 ? 2 : 1); up++) {
                /* centroid of the sub-triangle (barycentric grid cell) */
                double b1 = up ? (i + 2.0 / 3.0) / n : (i + 1.0 / 3.0) / n;
                double b2 = up ? (j + 2.0 / 3.0) / n : (j + 1.0 / 3.0) / n;
                vec3 p = v3_add(a, v3_add(v3_scale(e1, (float)b1), v3_scale(e2, (float)b2)));
                vec3 d = v3_sub(p, x);
                double d2 = v3_length2(d), cos_l = fabs(v3_dot(nu, d)) / sqrt(d2);
                sum += cos_l / d2 * (area2 / 2.0) / ((double)n * n);
            }
    return sum;
}

/* The barycentric cell (of K^2) the ray x + t dir hits, or -1. */
static int cell_of(vec3 x, vec3 dir, vec3 a, vec3 b, vec3 c)
{
    const vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a), pv = v3_cross(dir, e2);
    const double det = v3_dot(e1, pv);
    if (fabs(det) < 1e-30)
        return -1;
    const vec3 tv = v3_sub(x, a), qv = v3_cross(tv, e1);
    const double b1 = v3_dot(tv, pv) / det, b2 = v3_dot(dir, qv) / det;
    if (b1 < -1e-4 || b2 < -1e-4 || b1 + b2 > 1.0 + 1e-4)
        return -1;
    int i = (int)floor(b1 * K), j = (int)floor(b2 * K);
    i = i < 0 ? 0 : (i >= K ? K - 1 : i);
    j = j < 0 ? 0 : (j >= K ? K - 1 : j);
    if (i + j > K - 1)
        j = K - 1 - i;
    const int up = (b1 * K - i) + (b2 * K - j) > 1.0 && i + j < K - 1;
    return (i * K + j) * 2 + up;
}

/* Vertices of cell (i, j, up) in world space. */
static void cell_vertices(vec3 a, vec3 b, vec3 c, int i, int j, int up, vec3 v[3])
{
    const vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a);
    const float s = 1.0f / K;
    const float bi[2][3][2] = {{{0, 0}, {1, 0}, {0, 1}}, {{1, 0}, {1, 1}, {0, 1}}};
    for (int k = 0; k < 3; k++) {
        float u = (i + bi[up][k][0]) * s, w = (j + bi[up][k][1]) * s;
        v[k] = v3_add(a, v3_add(v3_scale(e1, u), v3_scale(e2, w)));
    }
}

int main(void)
{
    const struct config cfg[] = {
        {"near, facing", v3(0, 0, 0), v3(-1, -1, 1), v3(1, -1, 1), v3(0, 1, 1)},
        {"far", v3(0, 0, 0), v3(-1, -1, 40), v3(1, -1, 40), v3(0, 1, 40)},
        {"oblique", v3(0.3f, 0.2f, 0), v3(2, -1, 0.3f), v3(3, 1, 0.5f), v3(1.5f, 0.5f, 2)},
        {"wide (close to its plane)", v3(0, 0, 0.05f), v3(-3, -3, 0), v3(3, -3, 0), v3(0, 4, 0)},
        {"thin sliver", v3(0, 0, 0), v3(-2, 0, 1), v3(2, 0.02f, 1), v3(0, 0.05f, 1.2f)},
        {"close to its plane (double)", v3(0.1f, 0.2f, 0.03f), v3(-3, -3, 0), v3(3, -3, 0), v3(0, 4, 0)},
        {"beside it, grazing (double)", v3(2.5f, 2.5f, 0.02f), v3(-1, -1, 0), v3(2, -1, 0), v3(0, 2, 0)},
    };
    const int ncfg = (int)(sizeof cfg / sizeof cfg[0]);
    const double alpha = chi2_sidak(0.01, ncfg);
    enum { N = 400000 };
    for (int t = 0; t < ncfg; t++) {
        const struct config *g = &cfg[t];
        struct spherical_triangle tri;
        const double omega = spherical_triangle_init(&tri, g->x, g->a, v3_sub(g->b, g->a), v3_sub(g->c, g->a));
        const double quad = quadrature(g->x, g->a, g->b, g->c, 600);
        const double exact = solid_angle_d(g->x, g->a, g->b, g->c);
        EXPECT(fabs(omega - quad) <= 2e-3 * quad && fabs(omega - exact) <= 2e-5 * exact,
               "%s: solid angle %.9g, quadrature %.9g, in double %.9g", g->name, omega, quad, exact);
        static double count[2 * K * K], prob[2 * K * K];
        double sum_cells = 0.0;
        for (int i = 0; i < K; i++)
            for (int j = 0; j < K; j++)
                for (int up = 0; up < 2; up++) {
                    const int k = (i * K + j) * 2 + up;
                    count[k] = 0.0;
                    prob[k] = 0.0;
                    if (i + j > K - 1 || (up && i + j == K - 1))
                        continue;
                    vec3 v[3];
                    cell_vertices(g->a, g->b, g->c, i, j, up, v);
                    prob[k] = solid_angle_d(g->x, v[0], v[1], v[2]) / exact;
                    sum_cells += prob[k];
                }
        EXPECT(fabs(sum_cells - 1.0) < 1e-6, "%s: cells' solid angles sum to %.9g of omega", g->name, sum_cells);
        pcg32 rng = pcg32_make(1234u + (uint64_t)t, 77u);
        int missed = 0;
        for (int n = 0; n < N; n++) {
            vec3 dir;
            const float u1 = pcg32_float(&rng), u2 = pcg32_float(&rng);
            int cell = spherical_triangle_sample(&tri, u1, u2, &dir)
                           ? cell_of(g->x, dir, g->a, g->b, g->c)
                           : -1;
            if (cell < 0)
                missed++;
            else
                count[cell] += 1.0;
        }
        int dof;
        const double p = chi2_counts(count, prob, 2 * K * K, (double)(N - missed), &dof);
        EXPECT(missed <= N / 100000, "%s: %d of %d directions missed the triangle", g->name, missed, N);
        EXPECT(p > alpha, "%s: chi-square p = %.3g (dof %d)", g->name, p, dof);
        printf("%-30s omega %.6g (quadrature %.6g), %s, chi-square p = %.3f, %d missed\n", g->name, omega, quad,
               tri.precise ? "double" : "float", p, missed);
    }
    return test_finish();
}
