/* test_lights_quad.c: solid-angle sampling of rectangular emitters through lights_sample_at and
 * lights_pdf_at (shading/lights.h), which draw a quad's two triangles as one spherical rectangle:
 *  1. the scene pairs rectangles' triangles, and not a parallelogram's nor two materials';
 *  2. lights_pdf_at is the density of lights_sample_at's points: for points on a quad, the mean of
 *     1{point in cell} / lights_pdf_at over the samples is the cell's solid angle, for a 4 x 4 grid
 *     of cells, from receivers near, beside (grazing), far, behind and in the quad's plane, emitters
 *     chosen by power and by the BVH (also where the BVH keeps a quad's halves under different
 *     parents, in the pillars scene), with lights.sample=solid-angle and auto; and each sample's own
 *     density agrees with lights_pdf_at;
 *  3. no NaN: receivers in the light's plane and a hair-thin quad fall back to area sampling. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "core/check.h"
#include "core/rng.h"
#include "emitter_material.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "shading/lights.h"
#include "test_util.h"

#define CELLS 4
#define SAMPLES 200000

static const vec3 LAMP = {-0.3f, 2.0f, -0.2f}; /* corner of the lamp quad, 0.6 x 0.4, facing down */

static int build_scene(struct scene *s)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "lights_quad_test");
    const int grey = scene_add_material(&b, emitter_material(v3s(0.0f)));
    const int lamp = scene_add_material(&b, emitter_material(v3(10, 9, 8)));
    const int blue = scene_add_material(&b, emitter_material(v3(0.5f, 0.5f, 4)));
    const int red = scene_add_material(&b, emitter_material(v3(3, 0.2f, 0.2f)));
    const int obj = scene_new_object(&b);
    scene_add_quad(&b, v3(-3, 0, -3), v3(-3, 0, 3), v3(3, 0, 3), v3(3, 0, -3), grey, obj);
    /* the lamp: emitters 0 and 1 */
    const vec3 l = LAMP;
    scene_add_quad(&b, l, v3(l.x + 0.6f, l.y, l.z), v3(l.x + 0.6f, l.y, l.z + 0.4f), v3(l.x, l.y, l.z + 0.4f), lamp,
                   obj);
    /* a tilted rectangle on a wall (emitters 2, 3) */
    const vec3 o = v3(2.5f, 0.5f, -1), ex = v3(0, 0.6f, 0.8f), ey = v3(-0.3f, 0, 0);
    scene_add_quad(&b, o, v3_add(o, ey), v3_add(o, v3_add(ex, ey)), v3_add(o, ex), blue, obj);
    /* a parallelogram (emitters 4, 5): no rectangle */
    scene_add_quad(&b, v3(-2, 1, 2), v3(-1, 1, 2), v3(-0.5f, 2, 2), v3(-1.5f, 2, 2), red, obj);
    /* two materials on one rectangle (emitters 6, 7): no pair */
    scene_add_triangle(&b, v3(1, 2.5f, 1), v3(1.5f, 2.5f, 1), v3(1.5f, 2.5f, 1.5f), red, obj);
    scene_add_triangle(&b, v3(1, 2.5f, 1), v3(1.5f, 2.5f, 1.5f), v3(1, 2.5f, 1.5f), blue, obj);
    /* a hair-thin rectangle (emitters 8, 9), 1e-5 wide */
    scene_add_quad(&b, v3(-1, 1.5f, -2), v3(1, 1.5f, -2), v3(1, 1.5f, -2 + 1e-5f), v3(-1, 1.5f, -2 + 1e-5f), lamp, obj);
    /* a strip (emitters 10, 11) */
    scene_add_quad(&b, v3(-2, 2.4f, 1), v3(2, 2.4f, 1), v3(2, 2.4f, 1.1f), v3(-2, 2.4f, 1.1f), lamp, obj);
    if (scene_builder_end(&b, msg) != 0) {
        printf("scene build failed: %s\n", msg);
        return -1;
    }
    return 0;
}

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

/* Rectangle q's point at fractions (a, b) of its edges. */
static vec3 quad_point(const struct emitter_quad *q, double a, double b)
{
    return v3_add(q->corner, v3_add(v3_scale(q->ux, (float)(a * q->lx)), v3_scale(q->uy, (float)(b * q->ly))));
}

static double cell_solid_angle(const struct emitter_quad *q, vec3 x, int i, int j)
{
    const double a0 = (double)i / CELLS, a1 = (i + 1.0) / CELLS, b0 = (double)j / CELLS, b1 = (j + 1.0) / CELLS;
    const vec3 p00 = quad_point(q, a0, b0), p10 = quad_point(q, a1, b0), p11 = quad_point(q, a1, b1);
    const vec3 p01 = quad_point(q, a0, b1);
    return tri_solid_angle(x, p00, p10, p11) + tri_solid_angle(x, p00, p11, p01);
}

/* Part 2 for rectangle k, receiver x (normal n) and one emitter choice, over `samples` light samples. */
static void check_density(const struct scene *s, int k, const char *name, vec3 x, vec3 n, enum light_selection select,
                          enum light_sampling point, int samples)
{
    const struct emitter_quad *q = &s->emitter_quads[k];
    const struct light_choice choice = {select, point, LIGHT_ENV_MAP};
    double sum[CELLS * CELLS] = {0}, sum2[CELLS * CELLS] = {0};
    long mismatched = 0, nonfinite = 0, on_lamp = 0;
    pcg32 rng = pcg32_make(77u, (uint64_t)select);
    for (int m = 0; m < samples; m++) {
        struct light_sample ls;
        const float u0 = pcg32_float(&rng), u1 = pcg32_float(&rng), u2 = pcg32_float(&rng);
        if (!lights_sample_at(s, choice, x, n, u0, u1, u2, &ls))
            continue;
        if (!v3_is_finite(ls.p) || !isfinite(ls.pdf_area)) {
            nonfinite++;
            continue;
        }
        const int e = s->tri_emitter[ls.tri];
        if (e != q->e[0] && e != q->e[1])
            continue;
        on_lamp++;
        const vec3 d = v3_sub(ls.p, x);
        const float dist = v3_length(d), cos_l = fabsf(v3_dot(ls.n, d)) / dist;
        const float pdf = lights_pdf_at(s, choice, x, n, ls.tri, dist, cos_l);
        const float own = ls.pdf_area * dist * dist / cos_l;
        if (cos_l > 1e-6f && !(fabsf(own - pdf) <= 1e-4f * pdf)) /* in the plane both are infinite */
            mismatched++;
        const vec3 rel = v3_sub(ls.p, q->corner);
        int i = (int)(v3_dot(rel, q->ux) / q->lx * CELLS), j = (int)(v3_dot(rel, q->uy) / q->ly * CELLS);
        i = i < 0 ? 0 : (i >= CELLS ? CELLS - 1 : i);
        j = j < 0 ? 0 : (j >= CELLS ? CELLS - 1 : j);
        const double w = 1.0 / pdf;
        sum[i * CELLS + j] += w;
        sum2[i * CELLS + j] += w * w;
    }
    EXPECT(nonfinite == 0, "%s: %ld samples with a NaN point or density", name, nonfinite);
    EXPECT(mismatched == 0, "%s: %ld of %ld samples' densities differ from lights_pdf_at", name, mismatched, on_lamp);
    /* a lamp the BVH cannot choose from x (x behind it): no samples, and its density 0 */
    const float pdf_mid =
        lights_pdf_at(s, choice, x, n, s->emitter_tri[q->e[0]], v3_length(v3_sub(q->centre, x)), 1.0f);
    double worst = 0.0, total = 0.0, expected_total = 0.0;
    for (int c = 0; c < CELLS * CELLS; c++) {
        const double expected = pdf_mid > 0.0f ? cell_solid_angle(q, x, c / CELLS, c % CELLS) : 0.0;
        const double mean = sum[c] / samples, var = sum2[c] / samples - mean * mean;
        const double se = sqrt((var > 0.0 ? var : 0.0) / samples);
        const double z = fabs(mean - expected) / (se + 1e-5 * expected + 1e-12);
        worst = z > worst ? z : worst;
        total += mean;
        expected_total += expected;
    }
    EXPECT(worst < 5.0, "%s: a cell's mean of 1/pdf is %.2f standard errors off its solid angle", name, worst);
    const struct light_bvh *t = &s->light_bvh;
    const int siblings = t->nodes[t->emitter_leaf[q->e[0]]].parent == t->nodes[t->emitter_leaf[q->e[1]]].parent;
    printf("%-28s %-5s %-11s%s %6ld on it, sum over cells %.6f (solid angle %.6f), worst |z| %.2f\n", name,
           select == LIGHT_SELECT_BVH ? "bvh" : "power", point == LIGHT_SAMPLING_AUTO ? "auto" : "solid-angle",
           select == LIGHT_SELECT_BVH && !siblings ? " (halves apart)" : "", on_lamp, total, expected_total, worst);
}

int main(void)
{
    struct scene s;
    if (build_scene(&s) != 0) {
        EXPECT(0, "scene must build");
        return test_finish();
    }
    /* 1. pairing */
    EXPECT(s.num_emitters == 12, "%d emitters, want 12", s.num_emitters);
    EXPECT(s.num_emitter_quads == 4, "%d rectangles, want 4 (lamp, wall, thin, strip)", s.num_emitter_quads);
    const int want_quad[12] = {0, 0, 1, 1, -1, -1, -1, -1, 2, 2, 3, 3};
    for (int e = 0; e < s.num_emitters && e < 12; e++)
        EXPECT(s.emitters[e].quad == want_quad[e], "emitter %d: quad %d, want %d", e, s.emitters[e].quad, want_quad[e]);

    /* 2. density */
    const struct {
        const char *name;
        vec3 x, n;
    } rx[] = {
        {"below the lamp, near", v3(0.05f, 1.7f, 0.1f), v3(0, 1, 0)},
        {"beside the lamp, grazing", v3(0.45f, 1.99f, -0.1f), v3(0, -1, 0)},
        {"far", v3(2.0f, 0.01f, 2.5f), v3(0, 1, 0)},
        {"behind the lamp", v3(0.1f, 2.3f, 0.0f), v3(0, -1, 0)},
        {"in the lamp's plane", v3(0.6f, 2.0f, 0.0f), v3(0, -1, 0)},
    };
    for (int r = 0; r < (int)(sizeof rx / sizeof rx[0]); r++) {
        check_density(&s, 0, rx[r].name, rx[r].x, rx[r].n, LIGHT_SELECT_POWER, LIGHT_SAMPLING_SOLID_ANGLE, SAMPLES);
        check_density(&s, 0, rx[r].name, rx[r].x, rx[r].n, LIGHT_SELECT_BVH, LIGHT_SAMPLING_SOLID_ANGLE, SAMPLES);
    }
    /* lights.sample=auto: solid angle below the lamp, area far from it and beside it (its rule) */
    for (int r = 0; r < 3; r++)
        check_density(&s, 0, rx[r].name, rx[r].x, rx[r].n, LIGHT_SELECT_BVH, LIGHT_SAMPLING_AUTO, SAMPLES);
    /* the tilted rectangle on the wall, from just in front of it (chosen rarely by power: more samples) */
    const vec3 wall_x = v3(1.9f, 0.9f, -0.5f);
    const enum light_sampling sa = LIGHT_SAMPLING_SOLID_ANGLE;
    check_density(&s, 1, "wall rectangle, in front", wall_x, v3(1, 0, 0), LIGHT_SELECT_POWER, sa, 5 * SAMPLES);
    check_density(&s, 1, "wall rectangle, in front", wall_x, v3(1, 0, 0), LIGHT_SELECT_BVH, sa, SAMPLES);
    check_density(&s, 3, "strip, below", v3(0.5f, 2.0f, 1.0f), v3(0, 1, 0), LIGHT_SELECT_BVH, sa, SAMPLES);

    /* 3. the hair-thin rectangle seen from its own plane and from just above it */
    {
        const struct light_choice choice = {LIGHT_SELECT_POWER, LIGHT_SAMPLING_SOLID_ANGLE, LIGHT_ENV_MAP};
        const vec3 xs[2] = {v3(0, 1.5f, -1.9f), v3(0, 1.4999f, -2.0f)};
        int bad = 0;
        for (int k = 0; k < 2; k++)
            for (int i = 0; i < 64; i++) {
                struct light_sample ls;
                const float u = (i + 0.5f) / 64.0f;
                if (!lights_sample_at(&s, choice, xs[k], v3(0, -1, 0), u, u, 1.0f - u, &ls))
                    continue;
                const vec3 d = v3_sub(ls.p, xs[k]);
                const float dist = v3_length(d);
                const float pdf = lights_pdf_at(&s, choice, xs[k], v3(0, -1, 0), ls.tri, dist, 0.0f);
                bad += !v3_is_finite(ls.p) || !isfinite(ls.pdf_area) || !isfinite(pdf);
            }
        EXPECT(bad == 0, "%d samples with a NaN point or density at the thin rectangle", bad);
    }
    scene_destroy(&s);

    /* The pillars scene's BVH puts the halves of one of its light strips under different parents:
     * the quad's probability is then the sum of two paths' (quad_pmf's other branch). */
    char msg[RESTIR_MSG_LEN];
    EXPECT(scene_load("pillars", &s, msg) == 0, "%s", msg);
    int apart = -1;
    for (int k = 0; k < s.num_emitter_quads; k++) {
        const struct light_bvh *t = &s.light_bvh;
        const struct emitter_quad *q = &s.emitter_quads[k];
        if (t->nodes[t->emitter_leaf[q->e[0]]].parent != t->nodes[t->emitter_leaf[q->e[1]]].parent)
            apart = k;
    }
    EXPECT(apart >= 0, "pillars: no light strip whose halves the BVH keeps apart (the test needs one)");
    if (apart >= 0) {
        const vec3 below = v3_add(s.emitter_quads[apart].centre, v3(0.3f, -0.3f, -0.2f));
        check_density(&s, apart, "pillars strip, below", below, v3(0, 1, 0), LIGHT_SELECT_BVH,
                      LIGHT_SAMPLING_SOLID_ANGLE, SAMPLES);
    }
    scene_destroy(&s);
    return test_finish();
}
