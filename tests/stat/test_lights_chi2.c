/* test_lights_chi2.c: statistical tests of emitter sampling: chi-square fit of lights_sample
 * over (emitter, barycentric cell), density consistency, and the solid-angle conversion checked
 * against the Van Oosterom-Strackee subtended angle. Must never depend on render passes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chi2_util.h"
#include "emitter_material.h"
#include "core/check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "scene/scene.h"
#include "shading/lights.h"
#include "test_util.h"

#define GRID 4 /* barycentric cells per axis */
#define N_SAMPLES 1000000
#define FAMILY_ALPHA 0.01

/* Emitters of different power and size (and one facing away from the probe point), plus
 * non-emissive geometry so that triangle and emitter indices differ. */
static int build_scene(struct scene *s)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "lights_test");
    int grey = scene_add_material(&b, emitter_material(v3s(0.0f)));
    int hot = scene_add_material(&b, emitter_material(v3(20.0f, 18.0f, 15.0f)));
    int warm = scene_add_material(&b, emitter_material(v3(1.0f, 0.5f, 0.2f)));
    int blue = scene_add_material(&b, emitter_material(v3(0.2f, 0.3f, 5.0f)));
    int obj = scene_new_object(&b);
    /* Floor (not emissive), normal +y. */
    scene_add_quad(&b, v3(-5, 0, -5), v3(-5, 0, 5), v3(5, 0, 5), v3(5, 0, -5), grey, obj);
    /* Small, very bright triangle facing down (-y). */
    scene_add_triangle(&b, v3(-0.2f, 3, -0.1f), v3(0.2f, 3, -0.1f), v3(0.0f, 3, 0.25f), hot, obj);
    /* Large dim quad on the ceiling facing down. */
    scene_add_quad(&b, v3(-2, 4, -2), v3(2, 4, -2), v3(2, 4, 2), v3(-2, 4, 2), warm, obj);
    /* Tilted blue triangle on a wall, facing +x (toward the probe point). */
    scene_add_triangle(&b, v3(-3, 0.5f, -1), v3(-3, 2.5f, 1.5f), v3(-2.6f, 0.5f, 1.2f), blue, obj);
    /* Bright triangle at y = 5 facing up, away from the probe point below it. */
    scene_add_triangle(&b, v3(1, 5, 1), v3(1, 5, 1.8f), v3(1.5f, 5, 1), hot, obj);
    if (scene_builder_end(&b, msg) != 0) {
        printf("scene build failed: %s\n", msg);
        return -1;
    }
    return 0;
}

/* Van Oosterom & Strackee 1983, "The Solid Angle of a Plane Triangle": with R_i the vectors
 * from x to the vertices, tan(Omega / 2) = |R1 . (R2 x R3)| /
 * (r1 r2 r3 + (R1.R2) r3 + (R1.R3) r2 + (R2.R3) r1); atan2 picks the right branch. */
static double solid_angle(vec3 x, vec3 a, vec3 b, vec3 c)
{
    double r[3][3] = {{a.x - x.x, a.y - x.y, a.z - x.z}, {b.x - x.x, b.y - x.y, b.z - x.z},
                      {c.x - x.x, c.y - x.y, c.z - x.z}};
    double len[3], dot01, dot02, dot12;
    for (int i = 0; i < 3; i++)
        len[i] = sqrt(r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2]);
    dot01 = r[0][0] * r[1][0] + r[0][1] * r[1][1] + r[0][2] * r[1][2];
    dot02 = r[0][0] * r[2][0] + r[0][1] * r[2][1] + r[0][2] * r[2][2];
    dot12 = r[1][0] * r[2][0] + r[1][1] * r[2][1] + r[1][2] * r[2][2];
    double triple = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                    r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                    r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    double den = len[0] * len[1] * len[2] + dot01 * len[2] + dot02 * len[1] + dot12 * len[0];
    return 2.0 * atan2(fabs(triple), den);
}

/* Fraction of the barycentric triangle {b1, b2 >= 0, b1 + b2 <= 1} inside cell (i, j) of the
 * GRID x GRID square: whole cells below the diagonal, half cells on it, none above. */
static double cell_fraction(int i, int j)
{
    double cell = 1.0 / (GRID * GRID);
    if (i + j <= GRID - 2)
        return cell / 0.5;
    if (i + j == GRID - 1)
        return 0.5 * cell / 0.5;
    return 0.0;
}

static vec3 vert(const struct scene *s, int tri, int k) { return s->verts[s->indices[3 * tri + k]]; }

/* Chi-square p-value of the (emitter, cell) histogram against pmf[e] * cell fraction. */
static double chi2_emitters(const double *observed, const float *pmf, int n_emit)
{
    int n = n_emit * GRID * GRID;
    double *expected = xmalloc(sizeof(double) * (size_t)n);
    for (int e = 0; e < n_emit; e++)
        for (int i = 0; i < GRID; i++)
            for (int j = 0; j < GRID; j++)
                expected[(e * GRID + i) * GRID + j] = N_SAMPLES * (double)pmf[e] * cell_fraction(i, j);
    int dof;
    double stat = chi2_pooled(observed, expected, n, &dof);
    free(expected);
    return chi2_pvalue(stat, dof);
}

int main(void)
{
    struct scene s;
    if (build_scene(&s) != 0) {
        EXPECT(0, "scene must build");
        return test_finish();
    }
    const int ne = s.num_emitters;
    EXPECT(ne == 5, "expected 5 emissive triangles, got %d", ne);

    /* Selection is proportional to power = luminance * area * pi. */
    double total_power = 0.0;
    for (int e = 0; e < ne; e++)
        total_power += lights_emitter_power(&s, s.emitter_tri[e]);
    for (int e = 0; e < ne; e++) {
        int t = s.emitter_tri[e];
        double pw = v3_luminance(s.materials[s.tri_material[t]].emission) * s.tri_area[t] * RESTIR_PI;
        EXPECT(fabs(lights_emitter_power(&s, t) - pw) <= 1e-5 * pw, "emitter %d power", e);
        EXPECT_NEAR(s.emitter_table.pmf[e], pw / total_power, 1e-6, "pmf proportional to power");
        EXPECT(fabs(lights_pdf_area(&s, t) - s.emitter_table.pmf[e] / s.tri_area[t]) <=
                   1e-6 * lights_pdf_area(&s, t),
               "pdf_area of emitter %d", e);
    }
    EXPECT(lights_pdf_area(&s, 0) == 0.0f && lights_pdf_area(&s, 1) == 0.0f, "floor is not a light");

    /* One-sided emission. */
    {
        int t = s.emitter_tri[0];
        vec3 n = s.tri_normal[t];
        vec3 le = lights_radiance(&s, t, 0.25f, 0.25f, n);
        vec3 back = lights_radiance(&s, t, 0.25f, 0.25f, v3_neg(n));
        EXPECT(le.x == s.materials[s.tri_material[t]].emission.x, "front side emits");
        EXPECT(v3_max_component(back) == 0.0f, "back side is dark");
        EXPECT(v3_max_component(lights_radiance(&s, 0, 0.25f, 0.25f, v3(0, 1, 0))) == 0.0f, "floor does not emit");
    }

    /* Chi-square over (emitter, barycentric cell), plus per-sample consistency. */
    double *observed = xcalloc((size_t)ne * GRID * GRID, sizeof(double));
    long bad_pdf = 0, bad_point = 0, outside = 0;
    pcg32 r = pcg32_make(2024u, 11u);
    for (int k = 0; k < N_SAMPLES; k++) {
        struct light_sample ls;
        float u0 = pcg32_float(&r), u1 = pcg32_float(&r), u2 = pcg32_float(&r);
        if (!lights_sample(&s, u0, u1, u2, &ls)) {
            bad_pdf++;
            continue;
        }
        int e = s.tri_emitter[ls.tri];
        if (e < 0) {
            bad_point++;
            continue;
        }
        if (ls.pdf_area != lights_pdf_area(&s, ls.tri) || !(ls.pdf_area > 0.0f))
            bad_pdf++;
        if (ls.b1 < 0.0f || ls.b2 < 0.0f || ls.b1 + ls.b2 > 1.0f + 1e-6f)
            outside++;
        vec3 p = v3_add(v3_add(v3_scale(vert(&s, ls.tri, 0), 1.0f - ls.b1 - ls.b2), v3_scale(vert(&s, ls.tri, 1), ls.b1)),
                        v3_scale(vert(&s, ls.tri, 2), ls.b2));
        vec3 le = s.materials[s.tri_material[ls.tri]].emission;
        if (v3_length(v3_sub(p, ls.p)) > 1e-5f || v3_dot(ls.n, s.tri_normal[ls.tri]) < 0.99999f ||
            le.x != ls.Le.x || le.y != ls.Le.y || le.z != ls.Le.z)
            bad_point++;
        int i = (int)(ls.b1 * GRID), j = (int)(ls.b2 * GRID);
        i = i < 0 ? 0 : (i >= GRID ? GRID - 1 : i);
        j = j < 0 ? 0 : (j >= GRID ? GRID - 1 : j);
        observed[(e * GRID + i) * GRID + j] += 1.0;
    }
    EXPECT(bad_pdf == 0, "%ld samples with pdf_area != lights_pdf_area", bad_pdf);
    EXPECT(bad_point == 0, "%ld samples with inconsistent point/normal/Le", bad_point);
    EXPECT(outside == 0, "%ld samples outside their triangle", outside);

    const double alpha_i = chi2_sidak(FAMILY_ALPHA, 1);
    double p = chi2_emitters(observed, s.emitter_table.pmf, ne);
    printf("chi-square (emitter x %dx%d barycentric cells, %d samples): p = %.4f (alpha %.3g)\n", GRID, GRID,
           N_SAMPLES, p, alpha_i);
    EXPECT(p >= alpha_i, "lights chi-square p %g < %g", p, alpha_i);

    /* Power self-check: the same histogram must reject selection by area instead of power. */
    {
        float *wrong = xmalloc(sizeof(float) * (size_t)ne);
        double area_sum = 0.0;
        for (int e = 0; e < ne; e++)
            area_sum += s.tri_area[s.emitter_tri[e]];
        for (int e = 0; e < ne; e++)
            wrong[e] = (float)(s.tri_area[s.emitter_tri[e]] / area_sum);
        double pw = chi2_emitters(observed, wrong, ne);
        printf("power check (area-proportional pmf): p = %.3g\n", pw);
        EXPECT(pw < 1e-6, "chi-square must reject an area-proportional pmf (p = %g)", pw);
        /* And a subtle one: 2% of the most likely emitter's probability moved to another. */
        int top = 0;
        for (int e = 0; e < ne; e++) {
            wrong[e] = s.emitter_table.pmf[e];
            if (wrong[e] > wrong[top])
                top = e;
        }
        int other = top == 0 ? 1 : 0;
        wrong[other] += 0.02f * wrong[top];
        wrong[top] *= 0.98f;
        pw = chi2_emitters(observed, wrong, ne);
        printf("power check (2%% of the top pmf moved): p = %.3g\n", pw);
        EXPECT(pw < 1e-6, "chi-square must reject a 2%% pmf shift (p = %g)", pw);
        free(wrong);
    }
    free(observed);

    /* Solid-angle density: for points uniform on one light, E[1 / p_w] with
     * p_w = lights_pdf_solid_angle(1 / area) is the solid angle the light subtends from x. */
    const vec3 x = v3(0.3f, 0.2f, 0.4f);
    double omega_sum = 0.0;
    for (int e = 0; e < ne; e++) {
        int t = s.emitter_tri[e];
        vec3 a = vert(&s, t, 0), b = vert(&s, t, 1), c = vert(&s, t, 2);
        int faces_x = v3_dot(s.tri_normal[t], v3_sub(x, a)) > 0.0f;
        double omega = faces_x ? solid_angle(x, a, b, c) : 0.0;
        omega_sum += omega;
        double acc = 0.0;
        const int m = 200000;
        pcg32 rr = pcg32_make(99u, (uint64_t)e);
        for (int k = 0; k < m; k++) {
            struct light_sample ls;
            float b1, b2;
            warp_uniform_triangle(pcg32_float(&rr), pcg32_float(&rr), &b1, &b2);
            lights_point(&s, t, b1, b2, &ls);
            float pw = lights_pdf_solid_angle(1.0f / s.tri_area[t], x, ls.p, ls.n);
            if (pw > 0.0f)
                acc += 1.0 / pw;
        }
        acc /= m;
        printf("  emitter %d: E[1/p_w] = %.6f, Van Oosterom-Strackee %.6f%s\n", e, acc, omega,
               faces_x ? "" : " (faces away)");
        if (faces_x)
            EXPECT(fabs(acc - omega) <= 0.01 * omega, "emitter %d: E[1/p_w] %g vs solid angle %g", e, acc, omega);
        else
            EXPECT(acc == 0.0, "emitter %d faces away but has nonzero solid-angle density", e);
    }
    /* The same through lights_sample: E[1/p_w] over the mixture is the total solid angle. */
    {
        double acc = 0.0;
        pcg32 rr = pcg32_make(1234u, 5u);
        for (int k = 0; k < N_SAMPLES; k++) {
            struct light_sample ls;
            if (!lights_sample(&s, pcg32_float(&rr), pcg32_float(&rr), pcg32_float(&rr), &ls))
                continue;
            float pw = lights_pdf_solid_angle(ls.pdf_area, x, ls.p, ls.n);
            if (pw > 0.0f)
                acc += 1.0 / pw;
        }
        acc /= N_SAMPLES;
        printf("  all emitters: E[1/p_w] = %.6f, sum of solid angles %.6f\n", acc, omega_sum);
        EXPECT(fabs(acc - omega_sum) <= 0.01 * omega_sum, "mixture E[1/p_w] %g vs %g", acc, omega_sum);
    }
    /* Degenerate geometry: x on the light's plane or behind it has density 0. */
    EXPECT(lights_pdf_solid_angle(1.0f, v3(0, 0, 0), v3(0, 1, 0), v3(0, 1, 0)) == 0.0f, "behind the light");
    EXPECT(lights_pdf_solid_angle(1.0f, v3(1, 1, 0), v3(0, 1, 0), v3(0, 1, 0)) == 0.0f, "in the light's plane");
    EXPECT(lights_pdf_solid_angle(1.0f, v3(0, 1, 0), v3(0, 1, 0), v3(0, 1, 0)) == 0.0f, "at the light point");
    EXPECT_NEAR(lights_pdf_solid_angle(0.5f, v3(0, 0, 0), v3(0, 2, 0), v3(0, -1, 0)), 2.0, 1e-6, "head-on");

    scene_destroy(&s);
    return test_finish();
}
