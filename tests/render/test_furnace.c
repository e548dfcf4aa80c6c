/* test_furnace.c: the analytic furnace: inside a closed sphere of a Lambertian of albedo a = 0.5
 * emitting Le = 0.5, L = Le / (1 - a) = 1, and with one bounce L = Le (1 + a) = 0.75. pt must
 * match per pixel and over the image. Must never use pt internals: a bsdf_eval quadrature checks
 * the material independently. */
#include <string.h>

#include "core/check.h"
#include "render/renderer.h"
#include "shading/bsdf.h"
#include "test_util.h"
#include "unbiased_util.h"

#define W 32
#define H 32
#define RUNS 8   /* independent seeds: their spread gives each pixel's standard error */
#define SPP 128  /* paths per pixel per run */

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

/* RUNS independently seeded renders; each pixel's mean over runs is tested against `expect`
 * with the standard error from the pooled per-pixel variance across runs (every pixel sees the
 * same radiance distribution, so pooling over pixels is exact up to facet effects). */
static struct furnace_result render_furnace(const struct scene *s, int max_bounces, double expect)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = W;
    p.height = H;
    p.spp = SPP;
    p.max_bounces = max_bounces; /* Russian roulette: default (pt.rr_bounces = 3) */
    struct pixel_stats st;
    pixel_stats_init(&st, W * H);
    for (int k = 0; k < RUNS; k++) {
        p.seed = 4242 + 17 * (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, METHOD_PT, &p);
        struct frame_stats fs;
        struct camera cam = scene_camera_at(s, 0, 0.0f);
        renderer_render(&r, 0, &cam, &fs);
        pixel_stats_add(&st, r.image);
        renderer_fini(&r);
    }
    double sum = 0.0, var_sum = 0.0;
    for (int i = 0; i < W * H; i++) {
        sum += st.mean[i];
        var_sum += st.m2[i] / (RUNS - 1);
    }
    double var_run = var_sum / (W * H); /* variance of one run's pixel value */
    struct furnace_result res;
    res.image_mean = sum / (W * H);
    res.image_se = sqrt(var_run / ((double)RUNS * W * H));
    double se_pixel = sqrt(var_run / RUNS);
    double z_crit = normal_two_sided_quantile(1.0 - pow(1.0 - ALPHA, 1.0 / (W * H)));
    res.pixels_failed = 0;
    res.worst_z = 0.0;
    for (int i = 0; i < W * H; i++) {
        double z = fabs(st.mean[i] - expect) / se_pixel;
        if (z > res.worst_z)
            res.worst_z = z;
        if (z > z_crit)
            res.pixels_failed++;
    }
    printf("max_bounces %d: image mean %.5f (se %.5f), expected %.5f, pixel se %.4f, worst |z| %.2f "
           "(crit %.2f), %d pixels fail\n",
           max_bounces, res.image_mean, res.image_se, expect, se_pixel, res.worst_z, z_crit, res.pixels_failed);
    EXPECT(var_run > 0.0, "a path tracer with jitter and random bounces must show noise");
    pixel_stats_free(&st);
    return res;
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

    /* All bounces: the path tracer solves the same equation. */
    struct furnace_result all = render_furnace(&s, 64, l_center);
    EXPECT(fabs(all.image_mean - l_center) <= IMAGE_Z_MAX * all.image_se + GEOMETRY_ALLOWANCE,
           "image mean %.5f vs %.5f (se %.5f)", all.image_mean, l_center, all.image_se);
    EXPECT(all.pixels_failed == 0, "%d pixels off (worst |z| %.2f)", all.pixels_failed, all.worst_z);
    /* One bounce: Le seen directly plus one scattering of Le: 0.75. */
    struct furnace_result one = render_furnace(&s, 1, l_one_bounce);
    EXPECT(fabs(one.image_mean - l_one_bounce) <= IMAGE_Z_MAX * one.image_se + GEOMETRY_ALLOWANCE,
           "image mean %.5f vs %.5f (se %.5f)", one.image_mean, l_one_bounce, one.image_se);
    EXPECT(one.pixels_failed == 0, "%d pixels off (worst |z| %.2f)", one.pixels_failed, one.worst_z);

    scene_destroy(&s);
    return test_finish();
}
