/* test_furnace.c: the analytic furnace: inside a closed sphere of a Lambertian of albedo a = 0.5
 * emitting Le = 0.5, L = Le / (1 - a) = 1, and with one bounce L = Le (1 + a) = 0.75. pt and
 * restir-pt (all bounces), pt and restir-di (one bounce) must match per pixel and over the image. Must never use pt
 * internals: a bsdf_eval quadrature checks the material independently. */
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "methods/settings.h"
#include "scene/scenes_builtin.h"
#include "shading/bsdf.h"
#include "test_util.h"
#include "unbiased_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 45

#define W 32
#define H 32
#define RUNS 8   /* independent seeds: their spread gives each pixel's standard error */
#define SPP 128  /* paths per pixel per run */
#define RESTIR_RUNS 256 /* ReSTIR: independent sequences ... */
#define RESTIR_FRAMES 4 /* ... of this many frames, the last one measured */

/* Family-wise level of the per-pixel test (Sidak over W*H pixels) and the |z| bound of the image
 * mean: an unbiased renderer fails either with probability ~1e-3 (seeds are fixed, so the
 * outcome is deterministic). */
#define ALPHA 1e-3
#define IMAGE_Z_MAX 4.5

/* For a Lambertian the answer does not depend on the sphere's shape (every surface point sees
 * only the sphere), so facets change nothing; the allowance covers float rounding only. */
#define GEOMETRY_ALLOWANCE 1e-4

/* Quadrature nodes: midpoint rule in mu = cos(theta) and in phi. The value of L(1) changes by
 * < 1e-5 from 100 to 800 nodes. */
#define NMU 128
#define NPHI 64

/* Inside a sphere, a chord leaves x at angle theta to the inward normal and arrives at y at the
 * same angle; with uniform emission and one material the radiance therefore depends only on the
 * cosine mu between the outgoing direction and the normal: L(mu) = Le + int f(mu, wi) L(mu_i) mu_i
 * dwi. K[j][k] holds the weight of L(mu_k) in that integral for wo at mu_j. Returns the
 * directional albedo at normal incidence A(1) (the one-bounce answer is Le (1 + A(1))) and
 * writes L(1), the radiance seen by a camera at the centre, to *l_center. */
static double furnace_solution(const struct material *m, double le, double *l_center)
{
    static double K[NMU][NMU];
    double mu[NMU], L[NMU], Ln[NMU], k1[NMU];
    struct bsdf b;
    bsdf_from_material(m, &b);
    const vec3 n = v3(0.0f, 0.0f, 1.0f);
    for (int j = 0; j < NMU; j++)
        mu[j] = (j + 0.5) / NMU;
    /* Row NMU is wo = n exactly (the centre camera). */
    for (int j = 0; j <= NMU; j++) {
        double mo = j < NMU ? mu[j] : 1.0;
        vec3 wo = v3((float)sqrt(1.0 - mo * mo), 0.0f, (float)mo);
        for (int k = 0; k < NMU; k++) {
            double si = sqrt(1.0 - mu[k] * mu[k]), acc = 0.0;
            for (int q = 0; q < NPHI; q++) {
                double phi = 2.0 * RESTIR_PI * (q + 0.5) / NPHI;
                vec3 wi = v3((float)(si * cos(phi)), (float)(si * sin(phi)), (float)mu[k]);
                acc += v3_luminance(bsdf_eval(&b, n, wo, wi));
            }
            double w = acc * (2.0 * RESTIR_PI / NPHI) * mu[k] / NMU; /* dw = dmu dphi */
            if (j < NMU)
                K[j][k] = w;
            else
                k1[k] = w;
        }
    }
    for (int j = 0; j < NMU; j++)
        L[j] = le;
    for (int it = 0; it < 300; it++) { /* Neumann series; the albedo < 1 makes it contract */
        for (int j = 0; j < NMU; j++) {
            double s = le;
            for (int k = 0; k < NMU; k++)
                s += K[j][k] * L[k];
            Ln[j] = s;
        }
        memcpy(L, Ln, sizeof(L));
    }
    double albedo = 0.0, l1 = le;
    for (int k = 0; k < NMU; k++) {
        albedo += k1[k];
        l1 += k1[k] * L[k];
    }
    *l_center = l1;
    return albedo;
}

struct furnace_result {
    double image_mean, image_se;
    int pixels_failed;
    double worst_z;
};

/* `runs` independently seeded renders of `frames` frames (the last one is measured); each pixel's
 * mean over runs is tested against `expect` with the standard error from the pooled per-pixel
 * variance across runs (every pixel sees the same radiance distribution, so pooling over pixels
 * is exact up to facet effects). pt's pixels are independent, so its image mean's standard error
 * follows from that variance; ReSTIR's pixels share samples, so theirs comes from the spread of
 * the per-run image means. */
static struct furnace_result render_furnace(const struct scene *s, const struct method *method, int runs, int frames,
                                            int max_bounces, double expect)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = W;
    p.height = H;
    p.spp = SPP;
    p.max_bounces = max_bounces; /* Russian roulette: default (pt.rr_bounces = 3) */
    struct pixel_stats st;
    pixel_stats_init(&st, W * H);
    double run_sum = 0.0, run_sum2 = 0.0;
    for (int k = 0; k < runs; k++) {
        p.seed = 4242 + 17 * (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, method, &p);
        struct frame_stats fs;
        struct camera cam = scene_camera_at(s, 0, 0.0f);
        for (int f = 0; f < frames; f++)
            renderer_render(&r, f, &cam, &fs);
        pixel_stats_add(&st, r.image);
        double m = 0.0;
        for (int i = 0; i < W * H; i++)
            m += v3_luminance(v3(r.image[3 * i], r.image[3 * i + 1], r.image[3 * i + 2])) / (W * H);
        run_sum += m;
        run_sum2 += m * m;
        renderer_fini(&r);
    }
    double sum = 0.0, var_sum = 0.0;
    for (int i = 0; i < W * H; i++) {
        sum += st.mean[i];
        var_sum += st.m2[i] / (runs - 1);
    }
    double var_run = var_sum / (W * H); /* variance of one run's pixel value */
    struct furnace_result res;
    res.image_mean = sum / (W * H);
    if (method == method_named("pt")) {
        res.image_se = sqrt(var_run / ((double)runs * W * H));
    } else {
        double mu = run_sum / runs, var_means = (run_sum2 / runs - mu * mu) * runs / (runs - 1);
        res.image_se = sqrt(fmax(var_means, 0.0) / runs);
    }
    double se_pixel = sqrt(var_run / runs);
    double z_crit = normal_two_sided_quantile(1.0 - pow(1.0 - ALPHA, 1.0 / (W * H)));
    res.pixels_failed = 0;
    res.worst_z = 0.0;
    for (int i = 0; i < W * H; i++) {
        /* ReSTIR pixels differ in variance (less spatial reuse near the image border): each pixel
         * gets its own standard error from its spread over the independent runs. */
        double se = method == method_named("pt") ? se_pixel : sqrt(st.m2[i] / (runs - 1) / runs);
        double z = se > 0.0 ? fabs(st.mean[i] - expect) / se : INFINITY;
        if (z > res.worst_z)
            res.worst_z = z;
        if (z > z_crit)
            res.pixels_failed++;
    }
    printf("%s, max_bounces %d: image mean %.5f (se %.5f), expected %.5f, pixel se %.4f, worst |z| %.2f "
           "(crit %.2f), %d pixels fail\n",
           method->name, max_bounces, res.image_mean, res.image_se, expect, se_pixel, res.worst_z, z_crit,
           res.pixels_failed);
    EXPECT(var_run > 0.0, "%s with jitter and random bounces must show noise", method->name);
    pixel_stats_free(&st);
    return res;
}

/* Shading normals: the same furnace as a coarse 12-segment sphere with its exact normals
 * as shading normals (up to 15 degrees off its facets). The BSDF's support is the intersection of
 * the shading and geometric hemispheres, so a bounce reflects at most the albedo (the quadrature
 * of tests/unit/test_shading_normal.c) and L <= Le / (1 - a) = 1: no energy gain. It loses a
 * little where ns and ng disagree; a black-facet bug would lose much more, hence the floor 0.9.
 * restir-pt must agree with pt on this integral (two-sample z of the image means). */
static void smooth_furnace(double le)
{
    struct scene s;
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, &s, "smooth-furnace");
    int m = scene_add_material(
        &b,
        (struct material){.base_color = v3s(0.5f), .roughness = 1.0f, .emission = v3s((float)le), .lambert_only = 1});
    scene_add_sphere(&b, v3(0, 0, 0), 1.0f, 12, SPHERE_INWARD | SPHERE_SMOOTH, m, scene_new_object(&b));
    s.camera = (struct camera){v3(0.3f, 0.1f, 0), v3(1, 0, 1), v3(0, 1, 0), 60.0f, 0.0f, 0.0f};
    if (scene_builder_end(&b, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    struct furnace_result pt = render_furnace(&s, method_named("pt"), RUNS, 1, 64, 1.0);
    struct furnace_result rpt = render_furnace(&s, method_named("restir-pt"), RESTIR_RUNS, RESTIR_FRAMES, 64, 1.0);
    printf("smooth furnace: pt %.5f (se %.5f), restir-pt %.5f (se %.5f); flat answer 1\n", pt.image_mean, pt.image_se,
           rpt.image_mean, rpt.image_se);
    EXPECT(pt.image_mean <= 1.0 + IMAGE_Z_MAX * pt.image_se, "shading normals gain energy: pt mean %.5f (se %.5f)",
           pt.image_mean, pt.image_se);
    EXPECT(pt.image_mean >= 0.9, "shading normals lose too much: pt mean %.5f", pt.image_mean);
    const double z = (rpt.image_mean - pt.image_mean) / sqrt(pt.image_se * pt.image_se + rpt.image_se * rpt.image_se);
    EXPECT(fabs(z) <= IMAGE_Z_MAX, "restir-pt %.5f vs pt %.5f on the smooth furnace: z %.2f", rpt.image_mean,
           pt.image_mean, z);
    scene_destroy(&s);
}

int main(void)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_create_builtin("furnace", &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return test_finish();
    }
    EXPECT(s.num_materials == 1, "furnace has %d materials", s.num_materials);
    const struct material *m = &s.materials[0];
    EXPECT(m->base_color.x == 0.5f && m->emission.x == 0.5f && m->lambert_only == 1,
           "furnace material changed: base %g emission %g lambert_only %d", m->base_color.x, m->emission.x,
           m->lambert_only);
    const double le = m->emission.x;
    /* The emission is one-sided (front = geometric normal): every facet must face the camera at
     * the centre, or the camera sees the unlit back of the sphere. */
    int facing_out = 0;
    for (int t = 0; t < s.num_tris; t++) {
        const uint32_t *ix = &s.indices[3 * t];
        vec3 c = v3_add(v3_add(s.verts[ix[0]], s.verts[ix[1]]), s.verts[ix[2]]);
        if (v3_dot(c, s.tri_normal[t]) >= 0.0f)
            facing_out++;
    }
    EXPECT(facing_out == 0, "%d of %d furnace triangles face away from the centre (inward_facing winding)",
           facing_out, s.num_tris);

    /* Independent check of the material: quadrature of bsdf_eval gives albedo 0.5 and the
     * integral equation's solution L = 1 (midpoint-rule error ~1e-5). */
    double l_center;
    double albedo = furnace_solution(m, le, &l_center);
    printf("quadrature: directional albedo A(1) = %.5f, L(1) = %.5f\n", albedo, l_center);
    EXPECT_NEAR(albedo, 0.5, 1e-3, "directional albedo of the furnace material");
    EXPECT_NEAR(l_center, 1.0, 1e-3, "quadrature solution of the furnace");
    l_center = 1.0;                          /* analytic: Le / (1 - a) */
    const double l_one_bounce = le * (1.0 + 0.5); /* analytic: Le + a Le */

    /* All bounces: pt and restir-pt (path reuse through every shift) solve the same equation;
     * one bounce: Le seen directly plus one scattering of Le = 0.75, for pt and restir-di. */
    const struct {
        const struct method *method;
        int runs, frames, max_bounces;
        double expect;
    } cases[] = {
        {method_named("pt"), RUNS, 1, 64, l_center},
        {method_named("pt"), RUNS, 1, 1, l_one_bounce},
        {method_named("restir-pt"), RESTIR_RUNS, RESTIR_FRAMES, 64, l_center},
        {method_named("restir-di"), RESTIR_RUNS, RESTIR_FRAMES, 1, l_one_bounce},
    };
    for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
        struct furnace_result r = render_furnace(&s, cases[k].method, cases[k].runs, cases[k].frames,
                                                 cases[k].max_bounces, cases[k].expect);
        EXPECT(fabs(r.image_mean - cases[k].expect) <= IMAGE_Z_MAX * r.image_se + GEOMETRY_ALLOWANCE,
               "%s: image mean %.5f vs %.5f (se %.5f)", cases[k].method->name, r.image_mean,
               cases[k].expect, r.image_se);
        EXPECT(r.pixels_failed == 0, "%s: %d pixels off (worst |z| %.2f)", cases[k].method->name,
               r.pixels_failed, r.worst_z);
    }

    scene_destroy(&s);
    smooth_furnace(le);
    return test_finish();
}
