/* test_light_tree.c: emitter selection by the emitter BVH (shading/light_tree.h,
 * scene/scene_light_bvh.h). On a scene of many emitters of random size, power and orientation,
 * at probe points inside and outside the emitters' bounds:
 *  1. light_tree_pmf sums to at most 1 over the emitters; the rest is the probability that the
 *     descent reaches a node none of whose children can light the point (then NEE draws nothing,
 *     as pbrt-v4's BVHLightSampler: such a draw would have found no light anyway);
 *  2. it matches a brute-force evaluation: every leaf's probability from a top-down recursion over
 *     the whole tree in double precision (importance of a child over the sum of both children's);
 *  3. light_tree_sample's choices follow it: chi-square over the emitters and "none" (Sidak-corrected
 *     over the probes), and the pmf it returns equals light_tree_pmf bit for bit;
 *  4. every emitter that can light a probe point (some of its area in front of it) has a positive
 *     probability there: the bounds are conservative;
 *  5. the union of two direction cones holds both (light_cone_union).
 * Must never depend on render passes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chi2_util.h"
#include "emitter_material.h"
#include "core/check.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "scene/scene_light_bvh.h"
#include "shading/light_tree.h"
#include "test_util.h"

#define NUM_EMITTERS 300
#define N_SAMPLES 400000
#define FAMILY_ALPHA 0.01

static vec3 random_unit(pcg32 *r)
{
    const float z = 2.0f * pcg32_float(r) - 1.0f, phi = 6.2831853f * pcg32_float(r), s = sqrtf(1.0f - z * z);
    return v3(s * cosf(phi), s * sinf(phi), z);
}

/* NUM_EMITTERS triangles of random size (0.05 to 1), orientation and one of three emissions in
 * [-10, 10]^3, clustered in two groups so that the tree has structure, plus a grey floor. */
static int build_scene(struct scene *s)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "light_tree_test");
    const int grey = scene_add_material(&b, emitter_material(v3s(0.0f)));
    const int mats[3] = {scene_add_material(&b, emitter_material(v3(20.0f, 18.0f, 15.0f))),
                         scene_add_material(&b, emitter_material(v3(1.0f, 0.5f, 0.2f))),
                         scene_add_material(&b, emitter_material(v3(0.2f, 0.3f, 5.0f)))};
    const int obj = scene_new_object(&b);
    scene_add_quad(&b, v3(-20, -12, -20), v3(-20, -12, 20), v3(20, -12, 20), v3(20, -12, -20), grey, obj);
    pcg32 r = pcg32_make(41u, 7u);
    for (int i = 0; i < NUM_EMITTERS; i++) {
        const vec3 center = i % 3 == 0 ? v3(6.0f, 2.0f, 0.0f) : v3(-4.0f, 0.0f, 3.0f);
        const vec3 c = v3_add(center, v3_scale(v3(pcg32_float(&r) - 0.5f, pcg32_float(&r) - 0.5f,
                                                  pcg32_float(&r) - 0.5f), i % 3 == 0 ? 8.0f : 12.0f));
        const float size = 0.05f + 0.95f * pcg32_float(&r) * pcg32_float(&r);
        const vec3 a = v3_add(c, v3_scale(random_unit(&r), size)), bb = v3_add(c, v3_scale(random_unit(&r), size));
        const vec3 cc = v3_add(c, v3_scale(random_unit(&r), size));
        scene_add_triangle(&b, a, bb, cc, mats[i % 3], obj);
    }
    if (scene_builder_end(&b, msg) != 0) {
        printf("scene build failed: %s\n", msg);
        return -1;
    }
    return 0;
}

/* Brute force: the probability of every leaf below node k, given that k is reached with prob. */
static void brute_force(const struct light_bvh *t, int k, double prob, vec3 p, vec3 n, double *out)
{
    const struct light_bvh_node *nd = &t->nodes[k];
    if (nd->second < 0) {
        out[nd->emitter] = prob;
        return;
    }
    const double c0 = light_tree_importance(&t->nodes[k + 1], p, n);
    const double c1 = light_tree_importance(&t->nodes[nd->second], p, n);
    if (!(c0 + c1 > 0.0))
        return; /* the sampler stops here: nothing below is chosen */
    brute_force(t, k + 1, prob * c0 / (c0 + c1), p, n, out);
    brute_force(t, nd->second, prob * c1 / (c0 + c1), p, n, out);
}

/* 1 when some part of emitter e's front side faces p (it can light p). */
static int can_light(const struct emitter *em, vec3 p)
{
    const vec3 v[3] = {em->v0, v3_add(em->v0, em->e1), v3_add(em->v0, em->e2)};
    for (int k = 0; k < 3; k++)
        if (v3_dot(em->n, v3_sub(p, v[k])) > 1e-4f)
            return 1;
    return 0;
}

static void check_probe(const struct scene *s, vec3 p, vec3 n, double alpha, const char *what)
{
    const struct light_bvh *t = &s->light_bvh;
    const int ne = s->num_emitters;
    double *pmf = xcalloc((size_t)ne, sizeof(double)), *brute = xcalloc((size_t)ne, sizeof(double));
    double *count = xcalloc((size_t)ne + 1, sizeof(double));
    double sum = 0.0, worst = 0.0;
    int uncovered = 0;
    for (int e = 0; e < ne; e++) {
        pmf[e] = light_tree_pmf(t, p, n, e);
        sum += pmf[e];
        if (can_light(&s->emitters[e], p) && !(pmf[e] > 0.0))
            uncovered++;
    }
    brute_force(t, 0, 1.0, p, n, brute);
    for (int e = 0; e < ne; e++)
        worst = fmax(worst, fabs(pmf[e] - brute[e]) / fmax(brute[e], 1e-30) * (pmf[e] > 0.0 || brute[e] > 0.0));
    EXPECT(sum <= 1.0 + 1e-5 && sum > 0.5, "%s: the emitters' probabilities sum to %.7f", what, sum);
    /* float products over ~20 levels against double: a few ulp per level */
    EXPECT(worst < 1e-5, "%s: pmf and the brute-force evaluation differ by %.3g (relative)", what, worst);
    EXPECT(uncovered == 0, "%s: %d emitters that can light the point have probability 0", what, uncovered);

    pcg32 r = pcg32_make(99u, (uint64_t)(1000.0f * p.x));
    int mismatched = 0;
    for (int i = 0; i < N_SAMPLES; i++) {
        float prob;
        const int e = light_tree_sample(t, p, n, pcg32_float(&r), &prob);
        count[e < 0 ? ne : e] += 1.0; /* cell ne: nothing chosen */
        if (e >= 0 && prob != (float)pmf[e])
            mismatched++;
        if (e < 0 && prob != 0.0f)
            mismatched++;
    }
    EXPECT(mismatched == 0, "%s: %d draws' pmf differ from light_tree_pmf", what, mismatched);
    int dof;
    double expected[NUM_EMITTERS + 1];
    for (int e = 0; e < ne; e++)
        expected[e] = pmf[e] * N_SAMPLES;
    expected[ne] = fmax(0.0, 1.0 - sum) * N_SAMPLES;
    const double stat = chi2_pooled(count, expected, ne + 1, &dof), pv = chi2_pvalue(stat, dof);
    printf("%-26s sum %.7f (none %.4f drawn %.4f)  pmf vs brute %.2g  chi2 %.1f dof %d p %.3g\n", what, sum, 1.0 - sum,
           count[ne] / N_SAMPLES, worst, stat, dof, pv);
    EXPECT(pv > alpha, "%s: chi-square p = %.3g (alpha %.3g)", what, pv, alpha);
    free(pmf);
    free(brute);
    free(count);
}

/* Directions on the boundary and the axis of each cone lie in the union. */
static void check_cone_union(void)
{
    pcg32 r = pcg32_make(5u, 3u);
    int outside = 0;
    for (int i = 0; i < 2000; i++) {
        const vec3 wa = random_unit(&r), wb = random_unit(&r);
        const float ca = 2.0f * pcg32_float(&r) - 1.0f, cb = i % 4 == 0 ? 1.0f : 2.0f * pcg32_float(&r) - 1.0f;
        vec3 w;
        float co;
        light_cone_union(wa, ca, wb, cb, &w, &co);
        for (int side = 0; side < 2; side++) {
            const vec3 axis = side ? wb : wa;
            const float c = side ? cb : ca, sn = sqrtf(fmaxf(0.0f, 1.0f - c * c));
            const frame f = frame_from_normal(axis);
            for (int k = 0; k < 16; k++) {
                const float phi = 6.2831853f * k / 16;
                const vec3 d = frame_to_world(&f, v3(sn * cosf(phi), sn * sinf(phi), c));
                if (v3_dot(d, w) < co - 1e-5f)
                    outside++;
            }
        }
    }
    EXPECT(outside == 0, "cone union: %d boundary directions of the inputs fall outside", outside);
}

int main(void)
{
    check_cone_union();
    struct scene s;
    if (build_scene(&s) != 0)
        return 1;
    EXPECT(s.num_emitters == NUM_EMITTERS, "emitters %d", s.num_emitters);
    EXPECT(s.light_bvh.num_nodes == 2 * NUM_EMITTERS - 1, "nodes %d", s.light_bvh.num_nodes);
    const struct {
        const char *what;
        vec3 p, n;
    } probes[] = {
        {"floor, below both groups", v3(0, -12, 0), v3(0, 1, 0)},
        {"inside group A", v3(6, 2, 0.3f), v3(0.6f, 0.8f, 0)},
        {"inside group B", v3(-4, 0.5f, 2), v3(0, 0, 1)},
        {"far away", v3(80, 40, -60), v3(-0.57735f, -0.57735f, 0.57735f)},
        {"between, grazing normal", v3(1, 1, 1.5f), v3(1, 0, 0)},
    };
    const int np = (int)(sizeof probes / sizeof probes[0]);
    const double alpha = chi2_sidak(FAMILY_ALPHA, np);
    for (int i = 0; i < np; i++)
        check_probe(&s, probes[i].p, probes[i].n, alpha, probes[i].what);
    EXPECT(light_tree_pmf(&s.light_bvh, v3(0, 0, 0), v3(0, 1, 0), -1) == 0.0f, "pmf of emitter -1");
    EXPECT(light_tree_pmf(&s.light_bvh, v3(0, 0, 0), v3(0, 1, 0), NUM_EMITTERS) == 0.0f, "pmf past the last");
    scene_destroy(&s);

    /* one emitter: chosen with probability 1 in front of it, never behind it */
    struct scene one;
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, &one, "one_light");
    const int m = scene_add_material(&b, emitter_material(v3s(3.0f)));
    scene_add_triangle(&b, v3(0, 2, 0), v3(1, 2, 0), v3(0, 2, 1), m, scene_new_object(&b));
    EXPECT(scene_builder_end(&b, msg) == 0, "%s", msg);
    const vec3 nrm = one.emitters[0].n;
    float prob;
    const vec3 front = v3_add(v3(0.3f, 2, 0.3f), nrm), back = v3_sub(v3(0.3f, 2, 0.3f), nrm);
    EXPECT(light_tree_sample(&one.light_bvh, front, v3(0, 1, 0), 0.5f, &prob) == 0 && prob == 1.0f, "one light, front");
    EXPECT(light_tree_pmf(&one.light_bvh, front, v3(0, 1, 0), 0) == 1.0f, "one light, front pmf");
    EXPECT(light_tree_sample(&one.light_bvh, back, v3(0, 1, 0), 0.5f, &prob) == -1 && prob == 0.0f, "one light, back");
    EXPECT(light_tree_pmf(&one.light_bvh, back, v3(0, 1, 0), 0) == 0.0f, "one light, back pmf");
    scene_destroy(&one);

    struct light_bvh empty = {0, NULL, NULL};
    EXPECT(light_tree_sample(&empty, v3(0, 0, 0), v3(0, 1, 0), 0.5f, &prob) == -1, "empty tree");
    EXPECT(light_tree_pmf(&empty, v3(0, 0, 0), v3(0, 1, 0), 0) == 0.0f, "empty tree pmf");
    return test_finish();
}
