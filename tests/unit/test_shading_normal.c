/* test_shading_normal.c: shading normals. scene_shading_normal interpolates the
 * corners' normals by barycentrics, turns them to the side of the geometric normal it is given and
 * falls back to it where a corner has none; bsdf_shading_normal leaves a normal alone where wo is
 * above it, bends it in the plane of ns and ng where wo is below (so ns'.wo > 0), and never touches
 * flat shading; with the geometric side test every path vertex applies, an albedo-1 Lambertian and
 * white GGX lobes reflect at most the energy they receive (quadrature over the sphere); normals
 * follow non-uniform transforms (mat4d_normal); the JSON reader takes "normals" and "smooth"; a
 * normal map tilts the normal toward dp/du for red and dp/dv for green, scaled by normal_scale,
 * with UV-derived or the file's tangents (whose handedness flips the bitangent). */
#include <math.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "scene/mat4d.h"
#include "scene/scene.h"
#include "scene/scene_json.h"
#include "shading/bsdf.h"
#include "test_util.h"

static vec3 random_dir(pcg32 *rng) { return warp_uniform_sphere(pcg32_float(rng), pcg32_float(rng)); }

/* One triangle in the z = 0 plane, front +z, with the given corner normals (NULL: none). */
static int one_triangle(struct scene *s, const vec3 *normals)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "tri");
    int m = scene_add_material(&b, (struct material){.base_color = v3s(0.5f), .roughness = 1.0f});
    int l = scene_add_material(&b, (struct material){.emission = v3s(1.0f), .roughness = 1.0f});
    scene_add_triangle(&b, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), m, scene_new_object(&b));
    if (normals)
        scene_set_normals(&b, 0, normals);
    scene_add_triangle(&b, v3(0, 0, 2), v3(0, 1, 2), v3(1, 0, 2), l, scene_new_object(&b)); /* a lamp */
    int rc = scene_builder_end(&b, msg);
    EXPECT(rc == 0, "builder: %s", msg);
    return rc;
}

static void test_interpolation(void)
{
    struct scene s;
    const vec3 n[3] = {v3(0, 0, 2), v3(1, 0, 1), v3(0, -3, 3)}; /* lengths differ: normalized on input */
    if (one_triangle(&s, n) != 0)
        return;
    const float b1 = 0.2f, b2 = 0.3f, b0 = 0.5f;
    const float r = 0.70710678f;
    vec3 want = v3(b1 * r, -b2 * r, b0 + b1 * r + b2 * r); /* by hand: unit corners, then normalize */
    want = v3_scale(want, 1.0f / v3_length(want));
    vec3 got = scene_shading_normal(&s, 0, b1, b2, v3(0, 0, 1));
    EXPECT(v3_length(v3_sub(got, want)) < 1e-6f, "interpolated (%g %g %g), want (%g %g %g)", got.x, got.y, got.z,
           want.x, want.y, want.z);
    vec3 back = scene_shading_normal(&s, 0, b1, b2, v3(0, 0, -1)); /* hit from behind */
    EXPECT(v3_length(v3_add(back, want)) < 1e-6f, "a back hit turns the normal to its side");
    vec3 corner = scene_shading_normal(&s, 0, 1.0f, 0.0f, v3(0, 0, 1));
    EXPECT(v3_length(v3_sub(corner, v3(r, 0, r))) < 1e-6f, "corner 1 reproduces its normal");
    vec3 lamp = scene_shading_normal(&s, 1, 0.3f, 0.3f, v3(0, 0, -1));
    EXPECT(lamp.x == 0.0f && lamp.y == 0.0f && lamp.z == -1.0f, "a triangle without normals shades flat");
    scene_destroy(&s);

    const vec3 bad[3] = {v3(0, 0, 1), v3(0, 0, 0), v3(NAN, 0, 1)};
    if (one_triangle(&s, bad) != 0)
        return;
    vec3 flat = scene_shading_normal(&s, 0, 0.3f, 0.3f, v3(0, 0, 1));
    EXPECT(flat.x == 0.0f && flat.y == 0.0f && flat.z == 1.0f, "zero or NaN corner normals shade flat");
    scene_destroy(&s);
    if (one_triangle(&s, NULL) != 0)
        return;
    EXPECT(s.normals == NULL, "a scene without normals stores none");
    scene_destroy(&s);
}

static void test_bend(void)
{
    pcg32 rng = pcg32_make(3, 9);
    int bent = 0;
    float worst_plane = 0.0f;
    for (int k = 0; k < 100000; k++) {
        vec3 ng = random_dir(&rng), ns = random_dir(&rng), wo = random_dir(&rng);
        if (v3_dot(ns, ng) < 0.0f)
            ns = v3_neg(ns);
        if (v3_dot(wo, ng) <= 1e-3f)
            wo = v3_neg(wo);
        if (!(v3_dot(wo, ng) > 1e-3f))
            continue;
        vec3 n = bsdf_shading_normal(ns, ng, wo);
        if (v3_dot(ns, wo) >= BSDF_SHADING_COS_MIN) {
            EXPECT(n.x == ns.x && n.y == ns.y && n.z == ns.z, "a normal wo is above must stay unchanged");
            continue;
        }
        bent++;
        EXPECT(fabsf(v3_length(n) - 1.0f) < 1e-5f, "bent normal is unit: %g", v3_length(n));
        EXPECT(v3_dot(n, wo) > 0.0f, "wo must be above the bent normal: %g", v3_dot(n, wo));
        float plane = fabsf(v3_dot(n, v3_cross(ns, ng))) / fmaxf(v3_length(v3_cross(ns, ng)), 1e-6f);
        worst_plane = fmaxf(worst_plane, plane);
        /* flat shading is never touched, even at grazing wo */
        vec3 f = bsdf_shading_normal(ng, ng, wo);
        EXPECT(f.x == ng.x && f.y == ng.y && f.z == ng.z, "flat shading changed");
    }
    EXPECT(bent > 10000 && worst_plane < 1e-5f, "%d bent, worst distance from the ns-ng plane %g", bent,
           worst_plane);
}

/* Reflected fraction of light from wo: the integral over directions above the geometric surface
 * of f(wo, wi) (ns'.wi)+ with ns' = bsdf_shading_normal, by the midpoint rule in (cos, phi) around
 * ng: what every path vertex integrates (path_walk rejects wi.ng <= 0; bsdf_eval is zero below
 * ns'). */
static double reflected(const struct bsdf *b, vec3 ns, vec3 ng, vec3 wo)
{
    enum { NMU = 200, NPHI = 400 };
    const vec3 n = bsdf_shading_normal(ns, ng, wo);
    frame fr = frame_from_normal(ng);
    double sum = 0.0;
    for (int i = 0; i < NMU; i++) {
        float mu = ((float)i + 0.5f) / NMU, st = sqrtf(1.0f - mu * mu);
        for (int j = 0; j < NPHI; j++) {
            float phi = 2.0f * RESTIR_PI * ((float)j + 0.5f) / NPHI;
            vec3 wi = frame_to_world(&fr, v3(st * cosf(phi), st * sinf(phi), mu));
            float c = v3_dot(n, wi);
            if (c > 0.0f)
                sum += v3_luminance(bsdf_eval(b, n, wo, wi)) * c;
        }
    }
    return sum * (2.0 * RESTIR_PI / NPHI) / NMU;
}

static void test_no_energy_gain(void)
{
    pcg32 rng = pcg32_make(11, 5);
    const struct material mats[3] = {
        {.base_color = v3s(1.0f), .roughness = 1.0f, .lambert_only = 1},
        {.base_color = v3s(1.0f), .metallic = 1.0f, .roughness = 0.5f},
        {.base_color = v3s(1.0f), .metallic = 0.0f, .roughness = 0.7f},
    };
    const char *names[3] = {"albedo-1 Lambertian", "white GGX metal (roughness 0.5)", "white dielectric (0.7)"};
    for (int m = 0; m < 3; m++) {
        struct bsdf b;
        bsdf_from_material(&mats[m], &b);
        double worst = 0.0, flat_worst = 0.0;
        for (int k = 0; k < 16; k++) {
            vec3 ng = random_dir(&rng);
            frame fr = frame_from_normal(ng);
            /* shading normals up to 60 degrees off, views down to grazing, half of them below ns */
            float tilt = 1.047f * pcg32_float(&rng), az = 2.0f * RESTIR_PI * pcg32_float(&rng);
            vec3 ns = frame_to_world(&fr, v3(sinf(tilt) * cosf(az), sinf(tilt) * sinf(az), cosf(tilt)));
            float c = 0.02f + 0.98f * pcg32_float(&rng), a2 = 2.0f * RESTIR_PI * pcg32_float(&rng);
            vec3 wo = frame_to_world(&fr, v3(sqrtf(1 - c * c) * cosf(a2), sqrtf(1 - c * c) * sinf(a2), c));
            worst = fmax(worst, reflected(&b, ns, ng, wo));
            flat_worst = fmax(flat_worst, reflected(&b, ng, ng, wo));
        }
        printf("%s: largest reflected fraction %.4f with shading normals, %.4f flat\n", names[m], worst, flat_worst);
        /* 2e-3: the midpoint rule's error on these integrands (the flat Lambertian integrates to
         * 1 within 1e-5); a gain would show as several percent at 60 degrees of tilt */
        EXPECT(worst <= 1.0 + 2e-3, "%s gains energy with shading normals: %.4f", names[m], worst);
    }
}

static void test_transform(void)
{
    pcg32 rng = pcg32_make(5, 1);
    float worst = 0.0f;
    for (int k = 0; k < 1000; k++) {
        mat4d t = mat4d_identity();
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                t.m[4 * i + j] = (i == j ? 1.0 : 0.0) + 2.0 * (pcg32_float(&rng) - 0.5) * (i == j ? 1.5 : 0.8);
        vec3 e1 = random_dir(&rng), e2 = random_dir(&rng), n = v3_normalize(v3_cross(e1, e2));
        vec3 te1 = mat4d_dir(&t, e1.x, e1.y, e1.z), te2 = mat4d_dir(&t, e2.x, e2.y, e2.z);
        vec3 tn = v3_normalize(mat4d_normal(&t, n.x, n.y, n.z));
        worst = fmaxf(worst, fmaxf(fabsf(v3_dot(tn, v3_normalize(te1))), fabsf(v3_dot(tn, v3_normalize(te2)))));
        /* orientation: the side the surface faced stays its side (mirrors included) */
        vec3 wind = v3_cross(te1, te2);
        float side = v3_dot(tn, wind) * (float)(mat4d_det3(&t) < 0.0 ? -1.0 : 1.0);
        EXPECT(side > 0.0f || v3_length(wind) < 1e-4f, "transformed normal flipped sides (k %d)", k);
    }
    EXPECT(worst < 1e-4f, "transformed normals must stay perpendicular to transformed edges: %g", worst);
}

/* A lamp triangle whose "normals" are `normals` must be refused with a message naming the file, the
 * key and `why`. */
static void expect_normals_refused(const char *normals, const char *why)
{
    char text[1024], msg[RESTIR_MSG_LEN];
    snprintf(text, sizeof text,
             "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0]},"
             " \"materials\": [{\"name\": \"lamp\", \"emission\": [1, 1, 1]}],"
             " \"shapes\": [{\"type\": \"triangles\", \"material\": \"lamp\", \"vertices\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],"
             " \"normals\": %s}]}",
             normals);
    struct scene s;
    int rc = scene_json_parse(text, strlen(text), "bad-normals.json", NULL, &s, msg);
    EXPECT(rc != 0 && strstr(msg, "normals") && strstr(msg, "bad-normals.json") && strstr(msg, why),
           "normals %s must be refused (%s): %s", normals, why, msg);
    if (rc == 0)
        scene_destroy(&s);
}

static void test_json(void)
{
    const char *text =
        "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0]},"
        " \"materials\": [{\"name\": \"m\", \"base_color\": [0.5, 0.5, 0.5]},"
        " {\"name\": \"lamp\", \"emission\": [1, 1, 1]}],"
        " \"shapes\": [{\"type\": \"triangles\", \"material\": \"m\", \"vertices\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],"
        " \"normals\": [[0, 0, 1], [1, 0, 1], [0, 0, 5]]},"
        " {\"type\": \"sphere\", \"material\": \"lamp\", \"radius\": 0.2, \"center\": [0, 0, 2], \"segments\": 6,"
        " \"smooth\": true}]}";
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    int rc = scene_json_parse(text, strlen(text), "normals.json", NULL, &s, msg);
    EXPECT(rc == 0, "normals.json: %s", msg);
    if (rc != 0)
        return;
    vec3 n1 = s.normals[s.indices[1]], n2 = s.normals[s.indices[2]];
    EXPECT(fabsf(n1.x - 0.70710678f) < 1e-6f && n2.z == 1.0f, "normals read and normalized");
    /* the sphere's corners carry its exact normals: outward, |p - c| / r */
    float worst = 0.0f;
    for (int t = 1; t < s.num_tris; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t i = s.indices[3 * t + k];
            vec3 radial = v3_scale(v3_sub(s.verts[i], v3(0, 0, 2)), 1.0f / 0.2f);
            worst = fmaxf(worst, v3_length(v3_sub(s.normals[i], radial)));
        }
    EXPECT(worst < 1e-5f, "smooth sphere normals off the radial direction by %g", worst);
    scene_destroy(&s);
    expect_normals_refused("[[0, 0, 1], [0, 0, 0], [0, 0, 1]]", "non-zero");
    expect_normals_refused("[[0, 0, 1]]", "per vertex");
}

/* A quad in the z = 0 plane (front +z) with UVs u along +x and v along +y, whose material has a
 * 1x1 normal map of tangent-space normal `local` (encoded as texel 0.5 local + 0.5) and scale. */
static int mapped_quad(struct scene *s, vec3 local, float scale, const float *tangents)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "mapped");
    struct texture t = {1, 1, NULL, NULL};
    t.rgb = xmalloc(3 * sizeof(float));
    t.rgb[0] = 0.5f * local.x + 0.5f;
    t.rgb[1] = 0.5f * local.y + 0.5f;
    t.rgb[2] = 0.5f * local.z + 0.5f;
    int map = scene_add_texture(&b, t, "normal-map", 0);
    int m = scene_add_material(&b, (struct material){.base_color = v3s(0.5f), .roughness = 1.0f, .normal_map = map,
                                                     .normal_scale = scale});
    int l = scene_add_material(&b, (struct material){.emission = v3s(1.0f), .roughness = 1.0f});
    scene_add_triangle(&b, v3(0, 0, 0), v3(2, 0, 0), v3(2, 1, 0), m, scene_new_object(&b));
    const float uv[6] = {0, 0, 1, 0, 1, 1};
    scene_set_uvs(&b, 0, uv);
    if (tangents)
        scene_set_tangents(&b, 0, tangents);
    scene_add_triangle(&b, v3(0, 0, 2), v3(0, 1, 2), v3(1, 0, 2), l, scene_new_object(&b));
    int rc = scene_builder_end(&b, msg);
    EXPECT(rc == 0, "builder: %s", msg);
    return rc;
}

static void expect_mapped(vec3 local, float scale, const float *tangents, vec3 want, const char *what)
{
    struct scene s;
    if (mapped_quad(&s, local, scale, tangents) != 0)
        return;
    want = v3_normalize(want);
    vec3 got = scene_shading_normal(&s, 0, 0.3f, 0.2f, v3(0, 0, 1));
    EXPECT(v3_length(v3_sub(got, want)) < 1e-5f, "%s: (%g %g %g), want (%g %g %g)", what, got.x, got.y, got.z, want.x,
           want.y, want.z);
    vec3 back = scene_shading_normal(&s, 0, 0.3f, 0.2f, v3(0, 0, -1));
    EXPECT(v3_length(v3_add(back, got)) < 1e-6f, "%s: a back hit mirrors the mapped normal", what);
    scene_destroy(&s);
}

static void test_normal_map(void)
{
    const float s45 = 0.70710678f;
    /* the triangle's UV derivatives: dp/du = (2, 0, 0), dp/dv = (0, 1, 0) */
    expect_mapped(v3(s45, 0, s45), 1.0f, NULL, v3(1, 0, 1), "red tilts toward dp/du");
    expect_mapped(v3(0, s45, s45), 1.0f, NULL, v3(0, 1, 1), "green tilts toward dp/dv");
    expect_mapped(v3(0, 0, 1), 1.0f, NULL, v3(0, 0, 1), "a flat map keeps the normal");
    expect_mapped(v3(s45, 0, s45), 0.5f, NULL, v3(0.5f, 0, 1), "normal_scale multiplies x and y");
    expect_mapped(v3(s45, 0, s45), 0.0f, NULL, v3(0, 0, 1), "normal_scale 0 switches the map off");
    /* the file's tangents: +x with handedness +1 gives bitangent n x t = +y; -1 gives -y */
    const float plus[12] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
    const float minus[12] = {1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};
    expect_mapped(v3(0, s45, s45), 1.0f, plus, v3(0, 1, 1), "file tangent, w = +1");
    expect_mapped(v3(0, s45, s45), 1.0f, minus, v3(0, -1, 1), "file tangent, w = -1");
    const float tilted[12] = {1, 0, 1, 1, 1, 0, 1, 1, 1, 0, 1, 1}; /* not orthogonal to n */
    expect_mapped(v3(s45, 0, s45), 1.0f, tilted, v3(1, 0, 1), "the tangent is made orthogonal to the normal");
}

int main(void)
{
    test_normal_map();
    test_interpolation();
    test_bend();
    test_no_energy_gain();
    test_transform();
    test_json();
    return test_finish();
}
