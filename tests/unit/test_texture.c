/* test_texture.c: texture decoding (sRGB and linear), bilinear lookup with repeat wrapping and
 * assimp's bottom-left UV origin, and scene_material_at on a JSON scene whose materials have base
 * colour, metallic-roughness and emission maps. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_file.h"
#include "shading/lights.h"
#include "test_util.h"

static int near(float a, float b, float tol) { return fabsf(a - b) <= tol; }

static void test_decode_and_lookup(const char *data)
{
    char path[1024], msg[RESTIR_MSG_LEN];
    struct texture t;
    snprintf(path, sizeof path, "%s/textures/two.png", data);
    EXPECT(texture_load_file(path, 0, &t, msg) == 0, "%s", msg);
    if (!t.rgb)
        return;
    EXPECT(t.width == 2 && t.height == 1, "two.png is %dx%d", t.width, t.height);
    /* texel centres at u = 0.25 and 0.75; halfway between them the mean; repeat wrapping */
    EXPECT(texture_sample(&t, 0.25f, 0.5f).x == 0.0f, "texel 0");
    EXPECT(texture_sample(&t, 0.75f, 0.5f).x == 1.0f, "texel 1");
    EXPECT(near(texture_sample(&t, 0.5f, 0.5f).x, 0.5f, 1e-6f), "bilinear midpoint %g",
           texture_sample(&t, 0.5f, 0.5f).x);
    EXPECT(near(texture_sample(&t, 0.0f, 0.5f).x, 0.5f, 1e-6f), "wraps across u = 0: %g",
           texture_sample(&t, 0.0f, 0.5f).x);
    EXPECT(texture_sample(&t, 1.25f, 0.5f).x == 0.0f && texture_sample(&t, -0.75f, 0.5f).x == 0.0f, "repeat");
    EXPECT(texture_sample(&t, NAN, 0.5f).x == 0.0f, "a NaN UV reads texel 0 instead of spreading");
    texture_fini(&t);

    /* sRGB decoding: 255 -> 1, 0 -> 0 exactly; the checker's 230 -> ((230/255 + 0.055) / 1.055)^2.4 */
    snprintf(path, sizeof path, "%s/textures/checker.png", data);
    EXPECT(texture_load_file(path, 1, &t, msg) == 0, "%s", msg);
    if (t.rgb) {
        float want = powf((230.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
        EXPECT(near(t.rgb[0], want, 1e-6f), "sRGB 230 -> %g, want %g", t.rgb[0], want);
        /* the bottom-left texel (x 0, image row 7) is at UV (1/16, 1/16): row 7 col 0 is dark */
        vec3 c = texture_sample(&t, 1.0f / 16.0f, 1.0f / 16.0f);
        EXPECT(near(c.x, t.rgb[3 * (7 * 8 + 0)], 1e-6f), "UV origin is the bottom-left texel");
        texture_fini(&t);
    }
    snprintf(path, sizeof path, "%s/textures/no-such.png", data);
    EXPECT(texture_load_file(path, 1, &t, msg) != 0 && strstr(msg, "no-such.png"), "missing texture: %s", msg);
    const unsigned char junk[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    EXPECT(texture_load_memory(junk, 8, 1, "junk", &t, msg) != 0 && strstr(msg, "junk"), "junk bytes: %s", msg);
}

static void test_scene_textures(const char *data)
{
    char path[1024], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/scenes/textured.json", data);
    struct scene s;
    EXPECT(scene_load(path, &s, msg) == 0, "%s", msg);
    if (!s.num_tris)
        return;
    EXPECT(s.num_textures == 3 && s.uv != NULL, "3 textures and UVs (%d)", s.num_textures);
    /* ground quad (triangles 0, 1): material factor 1 times the checker at the point's UV */
    struct material tmp;
    const struct texture *checker = &s.textures[s.materials[0].base_color_map - 1];
    for (int k = 0; k < 4; k++) {
        float b1 = 0.1f + 0.2f * (float)k, b2 = 0.05f;
        const struct material *m = scene_material_at(&s, 0, b1, b2, &tmp);
        /* triangle 0 has UVs (0,0) (1,0) (1,1) */
        vec3 want = texture_sample(checker, b1 + b2, b2);
        EXPECT(near(m->base_color.x, want.x, 1e-6f) && near(m->base_color.z, want.z, 1e-6f),
               "ground colour at b1 %g: %g vs %g", b1, m->base_color.x, want.x);
    }
    vec3 a = scene_material_at(&s, 0, 0.05f, 0.02f, &tmp)->base_color;
    vec3 b = scene_material_at(&s, 0, 0.45f, 0.02f, &tmp)->base_color;
    EXPECT(fabsf(a.x - b.x) > 0.05f, "shading varies inside a triangle (%g vs %g)", a.x, b.x);
    /* panel (triangles 2, 3): metallic = 1 * B, roughness = 1 * G of the map */
    const struct texture *mr = &s.textures[s.materials[1].metal_rough_map - 1];
    const struct material *pm = scene_material_at(&s, 2, 0.3f, 0.3f, &tmp);
    vec3 t = texture_sample(mr, 0.6f, 0.3f);
    EXPECT(near(pm->metallic, t.z, 1e-6f) && near(pm->roughness, t.y, 1e-6f), "panel metallic %g roughness %g",
           pm->metallic, pm->roughness);
    /* the lamp (triangles 4, 5): light sampling and BSDF hits see the same textured radiance */
    struct light_sample ls;
    lights_point(&s, 4, 0.1f, 0.1f, &ls);
    vec3 want =
        v3_mul(s.materials[2].emission, texture_sample(&s.textures[s.materials[2].emission_map - 1], 0.2f, 0.1f));
    vec3 hit = lights_radiance(&s, 4, 0.1f, 0.1f, s.tri_normal[4]);
    EXPECT(near(ls.Le.x, want.x, 1e-5f) && near(ls.Le.z, want.z, 1e-5f), "sampled Le %g %g, want %g %g", ls.Le.x,
           ls.Le.z, want.x, want.z);
    EXPECT(ls.Le.x == hit.x && ls.Le.y == hit.y && ls.Le.z == hit.z, "lights_point and lights_radiance agree");
    int e = s.tri_emitter[4];
    struct light_sample le;
    lights_emitter_point(&s, &s.emitters[e], 0.1f, 0.1f, &le);
    EXPECT(le.Le.x == ls.Le.x && le.Le.z == ls.Le.z, "the emitter record gives the same radiance");
    lights_point(&s, 4, 0.7f, 0.1f, &le);
    EXPECT(fabsf(le.Le.x - ls.Le.x) + fabsf(le.Le.z - ls.Le.z) > 0.5f, "emission varies inside the lamp");
    scene_destroy(&s);
}

/* glTF sampler wrap modes on a 4x1 ramp (texel i holds i): repeat, clamp to edge, mirrored repeat
 * at texel centres outside [0, 1], by hand; and clamp along v on a 1x4 column. */
static void test_wrap_modes(void)
{
    struct texture t = {4, 1, NULL, NULL};
    t.rgb = calloc(12, sizeof(float));
    for (int i = 0; i < 4; i++)
        t.rgb[3 * i] = (float)i;
    const float us[3] = {-0.125f, 1.125f, 1.375f}; /* texel centres -1, 4, 5 */
    const float want[3][3] = {{3, 0, 1}, {0, 3, 3}, {0, 3, 2}}; /* [mode][u]: repeat, clamp, mirror */
    for (int mode = 0; mode < 3; mode++)
        for (int k = 0; k < 3; k++) {
            float got = texture_sample_wrap(&t, us[k], 0.5f, mode, mode).x;
            EXPECT(fabsf(got - want[mode][k]) < 1e-6f, "wrap mode %d at u %g: %g, want %g", mode, us[k], got,
                   want[mode][k]);
        }
    EXPECT(texture_sample(&t, 1.125f, 0.5f).x == texture_sample_wrap(&t, 1.125f, 0.5f, 0, 0).x,
           "texture_sample repeats");
    texture_fini(&t);
    struct texture c = {1, 4, NULL, NULL}; /* row 0 (the image's top, v = 1) holds 0, row 3 holds 3 */
    c.rgb = calloc(12, sizeof(float));
    for (int i = 0; i < 4; i++)
        c.rgb[3 * i] = (float)i;
    EXPECT(texture_sample_wrap(&c, 0.5f, 1.125f, 1, 1).x == 0.0f && texture_sample_wrap(&c, 0.5f, -0.125f, 1, 1).x == 3.0f,
           "clamp along v keeps the top and bottom rows");
    texture_fini(&c);
}

int main(void)
{
    test_wrap_modes();
    const char *data = getenv("RESTIR_TEST_DATA");
    if (!data) {
        EXPECT(0, "RESTIR_TEST_DATA is not set (run through ctest)");
        return test_finish();
    }
    test_decode_and_lookup(data);
    test_scene_textures(data);
    return test_finish();
}
