/* test_scenes_animated.c: the built-in scenes with animated emitters (scene/scenes_animated.h).
 * switch-room is tests/data/scenes/switch_room.json built in code, bit for bit (vertices,
 * triangles, materials, emitters, keys, camera, and the emitters at a frame with the lamp off), so
 * the numbers docs/BENCHMARKS.md measured on the file hold for the built-in; its lamp is off from
 * frame 16 to 32. moving-lamp's lamp stands until frame 16, has moved by the keys' offset at 24-32
 * (its centre, the pivot, carried by the translation alone) and is back by 40. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_animation.h"
#include "scene/scene_file.h"
#include "scene/scene_motion.h"
#include "scene/scenes_builtin.h"
#include "scene_compare.h"
#include "test_util.h"

/* The strength of material m's first emitter triangle at frame t. */
static float lamp_strength(const struct scene *s, int m, float t)
{
    for (int i = 0; i < s->num_tris; i++)
        if (s->tri_material[i] == m)
            return scene_emission_strength(s, i, t);
    return -1.0f;
}

static void check_switch_room(const char *data)
{
    struct scene a, b;
    char path[1024], msg[512];
    if (scene_create_builtin("switch-room", &a, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    snprintf(path, sizeof path, "%s/scenes/switch_room.json", data);
    if (scene_load(path, &b, msg) == 0) {
        compare_scenes("switch-room", &a, &b); /* with its keys and the lamp off at frame 20 */
        scene_destroy(&b);
    } else {
        EXPECT(0, "%s", msg);
    }
    const int lamp = 3;
    const float at[4] = {15.0f, 16.0f, 31.0f, 32.0f}, want[4] = {1.0f, 0.0f, 0.0f, 1.0f};
    for (int k = 0; k < 4; k++)
        EXPECT(lamp_strength(&a, lamp, at[k]) == want[k], "switch-room: lamp strength %g at frame %g, want %g",
               (double)lamp_strength(&a, lamp, at[k]), (double)at[k], (double)want[k]);
    int changes[8];
    const int n = scene_animation_changes(&a, changes, 8);
    EXPECT(n == 2 && changes[0] == 16 && changes[1] == 32, "switch-room: %d changes (want frames 16, 32)", n);
    EXPECT(!scene_has_moving_emitters(&a), "switch-room: nothing moves");
    scene_destroy(&a);
}

/* The mean of the moving triangles' corners at frame t. */
static vec3 lamp_centre(const struct scene *s, float t)
{
    const int *tris;
    const int n = scene_motion_tris(s, &tris);
    scene_set_frame(s, t);
    vec3 c = v3s(0.0f);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            c = v3_add(c, s->verts[s->indices[3 * tris[i] + k]]);
    return v3_scale(c, 1.0f / (float)(3 * (n > 0 ? n : 1)));
}

static void check_moving_lamp(void)
{
    struct scene s;
    char msg[512];
    if (scene_create_builtin("moving-lamp", &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    const int *tris;
    EXPECT(scene_has_moving_emitters(&s) && scene_motion_tris(&s, &tris) == 2,
           "moving-lamp: one quad of moving triangles");
    int changes[8];
    const int n = scene_animation_changes(&s, changes, 8);
    EXPECT(n == 2 && changes[0] == 24 && changes[1] == 40, "moving-lamp: %d changes (want frames 24, 40)", n);
    EXPECT(!scene_lights_moved(&s, 0.0f, 16.0f) && scene_lights_moved(&s, 16.0f, 17.0f) &&
               !scene_lights_moved(&s, 24.0f, 32.0f) && !scene_lights_moved(&s, 40.0f, 64.0f),
           "moving-lamp: moves over 16-24 and 32-40 only");
    const vec3 rest = lamp_centre(&s, 0.0f), there = lamp_centre(&s, 28.0f), back = lamp_centre(&s, 48.0f);
    const vec3 d = v3_sub(there, rest), e = v3_sub(back, rest);
    EXPECT(fabsf(d.x + 1.2f) < 1e-5f && fabsf(d.y - 0.1f) < 1e-5f && fabsf(d.z - 0.3f) < 1e-5f,
           "moving-lamp: centre moved by (%g %g %g) at frame 28, want (-1.2 0.1 0.3)", d.x, d.y, d.z);
    EXPECT(fabsf(e.x) < 1e-6f && fabsf(e.y) < 1e-6f && fabsf(e.z) < 1e-6f,
           "moving-lamp: centre off by (%g %g %g) at frame 48, want back where it started", e.x, e.y, e.z);
    scene_destroy(&s);
}

int main(void)
{
    const char *data = getenv("RESTIR_TEST_DATA");
    if (!data)
        return test_skip("RESTIR_TEST_DATA is not set (run through ctest)");
    check_switch_room(data);
    check_moving_lamp();
    return test_finish();
}
