/* test_alpha.c: alpha cutouts (glTF alphaMode MASK). A texture's alpha channel is kept
 * only when some texel is not opaque; scene_alpha_cut rejects exactly the points whose coverage
 * (base_alpha times the map's bilinear alpha) is below the cutoff; every ray query (closest hit,
 * occlusion, the emitters-only BVH) passes through cut-out points and stops at the others; a cut
 * part of an emitter emits nothing; the ray tracer's per-primitive records (struct alpha_tri) give
 * scene_alpha_cut's answer at every point, through either UV set and a texture transform; the
 * JSON reader refuses a bad alpha_mode or cutoff by key. */
#include <math.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene.h"
#include "scene/scene_json.h"
#include "scene/scene_surface.h"
#include "shading/lights.h"
#include "test_util.h"

/* A 2x2 alpha texture: opaque texels at the top-left and bottom-right of the image. */
static struct texture checker(void)
{
    struct texture t = {2, 2, NULL, NULL};
    t.rgb = xmalloc(12 * sizeof(float));
    t.alpha = xmalloc(4 * sizeof(float));
    for (int i = 0; i < 12; i++)
        t.rgb[i] = 0.5f;
    const float a[4] = {1, 0, 0, 1}; /* row 0 is the image's top row */
    memcpy(t.alpha, a, sizeof a);
    return t;
}

/* Quad [0,1]^2 at z = 0 facing +z with UVs = (x, y), emissive and alpha-masked; a lamp elsewhere
 * is not needed: the quad is the emitter. */
static int masked_quad_lookup(struct scene *s, float base_alpha, int use_map, struct texture_lookup lookup)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "masked");
    int map = use_map ? scene_add_texture(&b, checker(), "checker-alpha", 1) : 0;
    int m = scene_add_material(&b, (struct material){.base_color = v3s(0.5f),
                                                     .roughness = 1.0f,
                                                     .emission = v3s(2.0f),
                                                     .base_color_map = map,
                                                     .alpha_mask = 1,
                                                     .alpha_cutoff = 0.5f,
                                                     .base_alpha = base_alpha,
                                                     .base_color_lookup = lookup});
    scene_add_quad(&b, v3(0, 0, 0), v3(1, 0, 0), v3(1, 1, 0), v3(0, 1, 0), m, scene_new_object(&b));
    const float uv0[6] = {0, 0, 1, 0, 1, 1}, uv1[6] = {0, 0, 1, 1, 0, 1};
    scene_set_uvs(&b, 0, uv0);
    scene_set_uvs(&b, 1, uv1);
    const float swapped0[6] = {0, 0, 0, 1, 1, 1}, swapped1[6] = {0, 0, 1, 1, 1, 0}; /* set 1: (v, u) */
    scene_set_uv_set(&b, 0, 1, swapped0);
    scene_set_uv_set(&b, 1, 1, swapped1);
    int rc = scene_builder_end(&b, msg);
    EXPECT(rc == 0, "builder: %s", msg);
    return rc;
}

static int masked_quad(struct scene *s, float base_alpha, int use_map)
{
    return masked_quad_lookup(s, base_alpha, use_map, (struct texture_lookup){0});
}

/* scene_alpha_cut_tri of scene_alpha_tri's record equals scene_alpha_cut at random points, many of
 * them near the checker's cutoff lines, for UV set 0, set 1 and set 1 through a transform. */
static void test_records(void)
{
    const struct texture_lookup lookups[3] = {
        {0}, {.uv_set = 1}, {.uv_set = 1, .has_xform = 1, .xform = {0.7f, 0.2f, 0.13f, -0.3f, 1.1f, 0.4f}}};
    for (int k = 0; k < 3; k++) {
        struct scene s;
        if (masked_quad_lookup(&s, 1.0f, 1, lookups[k]) != 0)
            return;
        uint32_t state = 12345u + (uint32_t)k;
        int differ = 0, cut = 0;
        const int n = 20000;
        for (int i = 0; i < n; i++) {
            state = state * 1664525u + 1013904223u;
            float b1 = (float)(state >> 8) / 16777216.0f;
            state = state * 1664525u + 1013904223u;
            float b2 = (float)(state >> 8) / 16777216.0f * (1.0f - b1);
            const int tri = i & 1;
            struct alpha_tri r;
            scene_alpha_tri(&s, tri, &r);
            const int want = scene_alpha_cut(&s, tri, b1, b2);
            differ += scene_alpha_cut_tri(&s, &r, b1, b2) != want;
            cut += want;
        }
        EXPECT(differ == 0, "lookup %d: the record's alpha test differs at %d of %d points", k, differ, n);
        EXPECT(cut > n / 5 && cut < 4 * n / 5, "lookup %d: %d of %d points cut: the test sees one side only", k,
               cut, n);
        scene_destroy(&s);
    }
}

/* The opaque quarters are (x < 0.5, y > 0.5) and (x > 0.5, y < 0.5); points near the centres. */
static int opaque_at(float x, float y) { return (x < 0.5f) == (y > 0.5f); }

static void test_queries(void)
{
    struct scene s;
    if (masked_quad(&s, 1.0f, 1) != 0)
        return;
    const float xs[4] = {0.2f, 0.8f, 0.2f, 0.8f}, ys[4] = {0.2f, 0.2f, 0.8f, 0.8f};
    for (int k = 0; k < 4; k++) {
        const vec3 o = v3(xs[k], ys[k], 1.0f), d = v3(0, 0, -1);
        const int want = opaque_at(xs[k], ys[k]);
        struct surface_hit h;
        EXPECT(scene_intersect(&s, o, d, 0.0f, INFINITY, &h) == want, "closest hit at (%g, %g): want %d", xs[k], ys[k],
               want);
        EXPECT(scene_occluded(&s, o, d, 0.0f, 2.0f) == want, "occlusion at (%g, %g): want %d", xs[k], ys[k], want);
        EXPECT(scene_intersect_emitters(&s, o, d, 0.0f, INFINITY, &h) == want, "emitters BVH at (%g, %g): want %d",
               xs[k], ys[k], want);
        /* the point on the quad: tri 0 holds (x > y) with b1 = x - y, b2 = y (p = b1 (1,0) + b2 (1,1)) */
        int tri = xs[k] > ys[k] ? 0 : 1;
        float b1 = tri == 0 ? xs[k] - ys[k] : xs[k], b2 = tri == 0 ? ys[k] : ys[k] - xs[k];
        EXPECT(scene_alpha_cut(&s, tri, b1, b2) == !want, "scene_alpha_cut at (%g, %g)", xs[k], ys[k]);
        struct light_sample ls;
        lights_point(&s, tri, b1, b2, &ls);
        EXPECT((ls.Le.x > 0.0f) == want, "emission at (%g, %g): %g, want %s", xs[k], ys[k], ls.Le.x,
               want ? "2" : "none (cut out)");
    }
    scene_destroy(&s);
    /* base_alpha alone: 0.3 < 0.5 hides the whole quad, 0.7 shows it */
    for (int k = 0; k < 2; k++) {
        if (masked_quad(&s, k ? 0.7f : 0.3f, 0) != 0)
            return;
        struct surface_hit h;
        EXPECT(scene_intersect(&s, v3(0.3f, 0.6f, 1), v3(0, 0, -1), 0.0f, INFINITY, &h) == k,
               "base_alpha %g with cutoff 0.5", k ? 0.7 : 0.3);
        scene_destroy(&s);
    }
}

static void test_texture_alpha(const char *data)
{
    char path[1024], msg[RESTIR_MSG_LEN];
    struct texture t;
    snprintf(path, sizeof path, "%s/textures/leaf_rgba.png", data);
    EXPECT(texture_load_file(path, 1, &t, msg) == 0, "%s", msg);
    if (!t.alpha) {
        EXPECT(0, "leaf_rgba.png has an alpha channel");
        texture_fini(&t);
        return;
    }
    /* the leaf covers the middle, the corners are transparent (exact texels, bilinear at centres) */
    EXPECT(texture_sample_alpha(&t, 0.5f, 0.5f) == 1.0f, "leaf centre opaque");
    EXPECT(texture_sample_alpha(&t, 0.5f / 32.0f, 0.5f / 32.0f) == 0.0f, "leaf corner cut out");
    texture_fini(&t);
    snprintf(path, sizeof path, "%s/textures/checker.png", data);
    EXPECT(texture_load_file(path, 1, &t, msg) == 0 && t.alpha == NULL, "an image without alpha keeps none");
    EXPECT(texture_sample_alpha(&t, 0.3f, 0.3f) == 1.0f, "no alpha reads as opaque");
    texture_fini(&t);
}

static void expect_refused(const char *material_keys, const char *key)
{
    char text[1024], msg[RESTIR_MSG_LEN];
    snprintf(text, sizeof text,
             "{\"format\": \"restir-scene 1\", \"camera\": {\"position\": [0, 0, 3], \"look_at\": [0, 0, 0]},"
             " \"materials\": [{\"name\": \"lamp\", \"emission\": [1, 1, 1], %s}],"
             " \"shapes\": [{\"type\": \"quads\", \"material\": \"lamp\", \"quads\": [[[0, 0, 0], [1, 0, 0], [1, 1, 0],"
             " [0, 1, 0]]]}]}",
             material_keys);
    struct scene s;
    int rc = scene_json_parse(text, strlen(text), "alpha.json", NULL, &s, msg);
    EXPECT(rc != 0 && strstr(msg, key) && strstr(msg, "alpha.json"), "%s must be refused naming %s: %s",
           material_keys, key, msg);
    if (rc == 0)
        scene_destroy(&s);
}

int main(void)
{
    test_queries();
    test_records();
    const char *data = getenv("RESTIR_TEST_DATA");
    EXPECT(data != NULL, "RESTIR_TEST_DATA is not set (run through ctest)");
    if (data)
        test_texture_alpha(data);
    expect_refused("\"alpha_mode\": \"cutout\"", "materials[0].alpha_mode");
    expect_refused("\"alpha_mode\": \"mask\", \"alpha_cutoff\": 1.5", "materials[0].alpha_cutoff");
    expect_refused("\"alpha\": -0.1", "materials[0].alpha");
    return test_finish();
}
