/* test_env_pt.c: pt, restir-di and restir-pt under an environment light against answers
 * known in closed form. A
 * Lambertian floor of albedo a, open to the sky, seen from above, has radiance a E / pi with E the
 * irradiance of the sky; for the nearest-texel map of environment.h, E is a finite sum over texels
 * of L * dphi * (sin^2 theta1 - sin^2 theta0) / 2 over the part of each texel row above the
 * horizon. Cases: a constant sky of 1 over albedo 1 (the white furnace: exactly 1, no gain); a map
 * with a bright sun, a gradient and black texels over albedo 0.5, rotated; the same with an emitter
 * under the floor that no floor point sees, so that half of the light samples go to it (env_prob
 * 1/2) and contribute nothing; and shading normals on the floor, which may only lose energy. Each
 * pixel's mean over independent runs is tested (Sidak-corrected) and the image mean by its z (at
 * most 4.5 away, or only below +4.5 where the answer is a bound: rounding alone cannot move a mean
 * of 64 x 192 samples by 4.5 standard errors, so a failure means energy is gained). */
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "methods/settings.h"
#include "scene/environment.h"
#include "scene/scene.h"
#include "scene/scene_env.h"
#include "test_util.h"
#include "unbiased_util.h"

#define W 16
#define H 12
#define RUNS 64
#define SPP 32
#define RESTIR_FRAMES 4
#define ALPHA 1e-3
#define IMAGE_Z_MAX 4.5

/* A 16 x 8 map: a dim sky gradient, a black band below the horizon's first rows, and a sun. */
static float map[8][16][3];

static void make_map(void)
{
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 16; x++)
            for (int c = 0; c < 3; c++)
                map[y][x][c] = y == 2 ? 0.0f : 0.2f + 0.05f * (float)x + 0.1f * (float)c;
    map[1][5][0] = 40.0f, map[1][5][1] = 35.0f, map[1][5][2] = 30.0f; /* the sun */
}

/* Irradiance on a surface facing +y: the texel sum of the header comment. */
static double irradiance(const struct environment *e)
{
    if (!e->rgb)
        return RESTIR_PI * v3_luminance(e->constant) * e->intensity;
    double sum = 0.0;
    for (int y = 0; y < e->height; y++) {
        double t0 = RESTIR_PI * y / e->height, t1 = fmin(RESTIR_PI * (y + 1) / e->height, 0.5 * RESTIR_PI);
        if (t0 >= 0.5 * RESTIR_PI)
            break;
        double band = 0.5 * (sin(t1) * sin(t1) - sin(t0) * sin(t0)) * 2.0 * RESTIR_PI / e->width;
        for (int x = 0; x < e->width; x++) {
            const float *p = &e->rgb[3 * ((size_t)y * e->width + x)];
            sum += band * (0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
        }
    }
    return sum * e->intensity;
}

/* The floor (y = 0, +-1000, facing up) of albedo a, smooth-shaded with tilted normals when tilt,
 * a downward lamp under it when lamp, and the environment env (taken over). */
static int floor_scene(struct scene *s, float a, int tilt, int lamp, struct environment *env)
{
    struct scene_builder b;
    char msg[RESTIR_MSG_LEN];
    scene_builder_begin(&b, s, "env-floor");
    int m = scene_add_material(&b, (struct material){.base_color = v3s(a), .roughness = 1.0f, .lambert_only = 1});
    scene_add_quad(&b, v3(-1000, 0, 1000), v3(1000, 0, 1000), v3(1000, 0, -1000), v3(-1000, 0, -1000), m,
                   scene_new_object(&b));
    if (tilt) { /* corner normals leaning up to 30 degrees in different directions */
        const vec3 n0[3] = {v3(0.5f, 1, 0), v3(0, 1, 0.5f), v3(-0.3f, 1, -0.3f)};
        scene_set_normals(&b, 0, n0);
        scene_set_normals(&b, 1, n0);
    }
    if (lamp) {
        int l = scene_add_material(&b, (struct material){.emission = v3s(5.0f), .roughness = 1.0f});
        scene_add_quad(&b, v3(-1, -1, -1), v3(1, -1, -1), v3(1, -1, 1), v3(-1, -1, 1), l, scene_new_object(&b));
    }
    s->camera = (struct camera){v3(0, 1, 0), v3(0, 0, 0), v3(0, 0, 1), 50.0f, 0.0f, 0.0f};
    if (scene_builder_end(&b, msg) != 0 || scene_set_environment(s, env, msg) != 0) {
        EXPECT(0, "%s", msg);
        return -1;
    }
    return 0;
}

/* RUNS seeded images of method m (pt: SPP paths; the ReSTIR methods: the last of RESTIR_FRAMES
 * frames from the same camera, temporal and spatial reuse on): each pixel against `expect`
 * (per-pixel standard error from the runs), the image mean by its z. at_most: only a one-sided
 * bound (the image may be darker, never brighter). */
static void check_method(const char *what, const struct scene *s, double expect, int at_most, const struct method *m)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = W;
    p.height = H;
    p.spp = m == method_named("pt") ? SPP : 1;
    const int frames = m == method_named("pt") ? 1 : RESTIR_FRAMES;
    struct pixel_stats st;
    pixel_stats_init(&st, W * H);
    const struct camera cam = s->camera;
    for (int k = 0; k < RUNS; k++) {
        p.seed = 77 + 13 * (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, m, &p);
        struct frame_stats fs;
        for (int f = 0; f < frames; f++)
            renderer_render(&r, f, &cam, &fs);
        pixel_stats_add(&st, r.image);
        renderer_fini(&r);
    }
    const double z_crit = normal_two_sided_quantile(1.0 - pow(1.0 - ALPHA, 1.0 / (W * H)));
    double sum = 0.0, var = 0.0, worst = 0.0;
    int failed = 0;
    for (int i = 0; i < W * H; i++) {
        double v = st.m2[i] / (RUNS - 1) / RUNS, z = (st.mean[i] - expect) / sqrt(v);
        sum += st.mean[i];
        var += v;
        worst = fmax(worst, fabs(z));
        failed += at_most ? z > z_crit : fabs(z) > z_crit;
    }
    const double mean = sum / (W * H), z = (sum - expect * W * H) / sqrt(var);
    printf("%s, %s: image mean %.5f, expected %s%.5f, z %.2f, worst pixel |z| %.2f (limit %.2f), %d pixels off\n",
           m->name, what, mean, at_most ? "<= " : "", expect, z, worst, z_crit, failed);
    EXPECT(failed == 0, "%s, %s: %d pixels off", m->name, what, failed);
    EXPECT(at_most ? z < IMAGE_Z_MAX : fabs(z) < IMAGE_Z_MAX, "%s, %s: image mean %.5f vs %.5f (z %.2f)", m->name, what,
           mean, expect, z);
    pixel_stats_free(&st);
}

/* The same for pt, restir-di (the floor sees only the sky, so direct light is the whole answer)
 * and restir-pt, whose paths end in directions of the sky. */
static void check(const char *what, const struct scene *s, double expect, int at_most)
{
    const struct method *methods[3] = {method_named("pt"), method_named("restir-di"), method_named("restir-pt")};
    for (int k = 0; k < 3; k++)
        check_method(what, s, expect, at_most, methods[k]);
}

static struct environment *env_map(float rotation)
{
    char msg[RESTIR_MSG_LEN];
    struct environment *e = xcalloc(1, sizeof *e);
    EXPECT(environment_from_rgb("test", "map", &map[0][0][0], 16, 8, 1.5f, rotation, e, msg) == 0, "%s", msg);
    return e;
}

int main(void)
{
    make_map();
    char msg[RESTIR_MSG_LEN];
    struct scene s;
    struct environment *sky = xcalloc(1, sizeof *sky);
    EXPECT(environment_constant("test", v3s(1.0f), 1.0f, sky, msg) == 0, "%s", msg);
    if (floor_scene(&s, 1.0f, 0, 0, sky) == 0) {
        check("white furnace: albedo 1 under a constant sky of 1", &s, 1.0, 0);
        scene_destroy(&s);
    }
    struct environment *e = env_map(0.7f);
    const double E = irradiance(e);
    if (floor_scene(&s, 0.5f, 0, 0, e) == 0) {
        check("map with a sun (rotated 0.7 rad), albedo 0.5", &s, 0.5 * E / RESTIR_PI, 0);
        scene_destroy(&s);
    }
    if (floor_scene(&s, 0.5f, 0, 1, env_map(0.7f)) == 0) {
        EXPECT(s.env_prob == 0.5f, "with an emitter the environment gets half of the light samples");
        check("the same with an unseen emitter taking half of the light samples", &s, 0.5 * E / RESTIR_PI, 0);
        scene_destroy(&s);
    }
    sky = xcalloc(1, sizeof *sky);
    EXPECT(environment_constant("test", v3s(1.0f), 1.0f, sky, msg) == 0, "%s", msg);
    if (floor_scene(&s, 1.0f, 1, 0, sky) == 0) {
        check("white furnace with shading normals tilted up to 30 degrees (no gain)", &s, 1.0, 1);
        scene_destroy(&s);
    }
    return test_finish();
}
