/* test_spherical_rect.c: the solid-angle sampler of rectangular emitters (shading/spherical_rect.h).
 * For rectangles near, far, oblique, seen from behind, close to their plane and thin:
 *  1. spherical_rect_init's solid angle against the two triangles' Van Oosterom-Strackee solid
 *     angles in double (an independent formula);
 *  2. the sampled points follow 1 / omega: the rectangle cut into K x K cells, each with probability
 *     omega_cell / omega (its exact solid angle, the same double formula), chi-square over the cells
 *     (Sidak-corrected over the configurations);
 *  3. bad input: x in the rectangle's plane (inside and outside it), a degenerate rectangle and
 *     extreme uniforms give 0 or points inside the rectangle, never a NaN. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "chi2_util.h"
#include "core/rng.h"
#include "shading/spherical_rect.h"
#include "test_util.h"

#define K 10 /* cells per edge */

struct config {
    const char *name;
    vec3 x, corner, ux, uy;
    float lx, ly;
};

/* Van Oosterom and Strackee 1983 in double: the solid angle of triangle a, b, c from x. */
static double tri_solid_angle(vec3 x, vec3 a, vec3 b, vec3 c)
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

/* The solid angle of the sub-rectangle [a0, a1] x [b0, b1] (fractions of the edges) from x. */
static double cell_solid_angle(const struct config *g, double a0, double a1, double b0, double b1)
{
    vec3 p[4];
    const double a[4] = {a0, a1, a1, a0}, b[4] = {b0, b0, b1, b1};
    for (int k = 0; k < 4; k++)
        p[k] = v3_add(g->corner,
                      v3_add(v3_scale(g->ux, (float)(a[k] * g->lx)), v3_scale(g->uy, (float)(b[k] * g->ly))));
    return tri_solid_angle(g->x, p[0], p[1], p[2]) + tri_solid_angle(g->x, p[0], p[2], p[3]);
}

static void bad_input(void)
{
    struct spherical_rect r;
    const vec3 o = v3(0, 0, 0), ux = v3(1, 0, 0), uy = v3(0, 1, 0);
    EXPECT(spherical_rect_init(&r, v3(0.5f, 0.5f, 0), o, ux, uy, 1, 1) == 0.0f, "x inside the rectangle, in its plane");
    EXPECT(spherical_rect_init(&r, v3(3, 0.5f, 0), o, ux, uy, 1, 1) == 0.0f, "x beside the rectangle, in its plane");
    EXPECT(spherical_rect_init(&r, v3(3, 0.5f, 1e-6f), o, ux, uy, 1, 1) == 0.0f, "x 1e-6 off its plane");
    EXPECT(spherical_rect_init(&r, v3(0, 0, 1), o, ux, uy, 0, 1) == 0.0f, "zero width");
    EXPECT(spherical_rect_init(&r, v3(0, 0, 1e30f), o, ux, uy, 1, 1) == 0.0f, "far beyond float's reach");
    /* far and tiny: a finite solid angle or 0, and any sample inside */
    const float far = spherical_rect_init(&r, v3(0.5f, 0.5f, 1e4f), o, ux, uy, 1, 1);
    EXPECT(far >= 0.0f && isfinite(far), "far rectangle: omega %g", (double)far);
    /* extreme uniforms on a wide and a grazing configuration */
    const vec3 xs[3] = {v3(0.5f, 0.5f, 0.01f), v3(-2, 0.5f, 0.002f), v3(0.5f, 0.5f, -0.3f)};
    const float us[5] = {0.0f, 1e-7f, 0.5f, 0.99999994f, 1.0f};
    int bad = 0;
    for (int k = 0; k < 3; k++) {
        if (!(spherical_rect_init(&r, xs[k], o, ux, uy, 1, 1) > 0.0f)) {
            bad++;
            continue;
        }
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 5; j++) {
                float s, t;
                spherical_rect_sample(&r, us[i], us[j], &s, &t);
                if (!(s >= 0.0f && s <= 1.0f && t >= 0.0f && t <= 1.0f))
                    bad++;
            }
    }
    EXPECT(bad == 0, "%d points outside the rectangle or NaN for extreme uniforms", bad);
}

int main(void)
{
    const vec3 ux = v3(1, 0, 0), uy = v3(0, 0, 1);
    /* a rotated frame: ux, uy orthonormal, not axis-aligned */
    const vec3 rx = v3_normalize(v3(1, 0.3f, -0.2f));
    const vec3 ry = v3_normalize(v3_cross(v3(0.1f, 0.2f, 1.0f), rx));
    const struct config cfg[] = {
        {"near, above the middle", v3(0.3f, 0.4f, 0.3f), v3(0, 1, 0), ux, uy, 0.6f, 0.6f},
        {"far", v3(0, 0, 0), v3(-0.5f, 30, -0.3f), ux, uy, 1.0f, 0.6f},
        {"oblique, off to one side", v3(2, 0, -1), v3(-1, 1.5f, 0), rx, ry, 1.2f, 0.8f},
        {"from behind", v3(0.2f, 2.5f, 0.1f), v3(0, 2, 0), ux, uy, 0.6f, 0.6f},
        {"close to its plane", v3(-0.3f, 1.96f, 0.25f), v3(0, 2, 0), ux, uy, 0.6f, 0.6f},
        {"most of a hemisphere", v3(0.5f, 1.8f, 0.2f), v3(-2.5f, 2, -2.5f), ux, uy, 6.0f, 6.0f},
        {"grazing, beside it", v3(-0.1f, 2.01f, 0.3f), v3(0, 2, 0), ux, uy, 0.6f, 0.6f},
        {"thin strip", v3(0.1f, 0, 0.2f), v3(-2, 1, 0), ux, uy, 4.0f, 0.02f},
    };
    const int ncfg = (int)(sizeof cfg / sizeof cfg[0]);
    const double alpha = chi2_sidak(0.01, ncfg);
    enum { N = 400000 };
    for (int c = 0; c < ncfg; c++) {
        const struct config *g = &cfg[c];
        struct spherical_rect r;
        const double omega = spherical_rect_init(&r, g->x, g->corner, g->ux, g->uy, g->lx, g->ly);
        const double exact = cell_solid_angle(g, 0, 1, 0, 1);
        EXPECT(fabs(omega - exact) <= 2e-5 * exact + 1e-6, "%s: solid angle %.9g, two triangles %.9g", g->name, omega,
               exact);
        static double count[K * K], prob[K * K];
        double sum_cells = 0.0;
        for (int i = 0; i < K; i++)
            for (int j = 0; j < K; j++) {
                count[i * K + j] = 0.0;
                const double cell = cell_solid_angle(g, (double)i / K, (i + 1.0) / K, (double)j / K, (j + 1.0) / K);
                prob[i * K + j] = cell / exact;
                sum_cells += prob[i * K + j];
            }
        EXPECT(fabs(sum_cells - 1.0) < 1e-6, "%s: cells' solid angles sum to %.9g of omega", g->name, sum_cells);
        pcg32 rng = pcg32_make(4321u + (uint64_t)c, 99u);
        int outside = 0;
        for (int n = 0; n < N; n++) {
            float s, t;
            spherical_rect_sample(&r, pcg32_float(&rng), pcg32_float(&rng), &s, &t);
            if (!(s >= 0.0f && s <= g->lx && t >= 0.0f && t <= g->ly)) {
                outside++;
                continue;
            }
            int i = (int)(s / g->lx * K), j = (int)(t / g->ly * K);
            i = i >= K ? K - 1 : i;
            j = j >= K ? K - 1 : j;
            count[i * K + j] += 1.0;
        }
        int dof;
        const double p = chi2_counts(count, prob, K * K, (double)(N - outside), &dof);
        EXPECT(outside == 0, "%s: %d of %d points outside the rectangle", g->name, outside, N);
        EXPECT(p > alpha, "%s: chi-square p = %.3g (dof %d)", g->name, p, dof);
        printf("%-26s omega %.6g (two triangles %.6g), chi-square p = %.3f (dof %d)\n", g->name, omega, exact, p, dof);
    }
    bad_input();
    return test_finish();
}
