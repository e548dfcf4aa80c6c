/* scenes_animated.c: the built-in scenes with animated emitters (scenes_animated.h). Both share the
 * room of tests/data/scenes/switch_room.json: a floor, a back wall, a box, a steady lamp above the
 * left side, and a brighter blue lamp beside the box, which is the one that changes. */
#include "scene/scenes_animated.h"

#include <string.h>

#include "core/check.h"
#include "scene/builtin_shapes.h"

/* Materials of the room, in the order the file lists them. */
struct room {
    int floor, wall, steady, lamp;
};

/* An emitter as a scene file's material with "emission" e times "emissive_strength" k and
 * nothing else (its base colour the file's default, 0.8). */
static struct material file_emitter(vec3 e, float k)
{
    return (struct material){.base_color = v3s(0.8f), .roughness = 1.0f, .emission = v3_scale(e, k)};
}

/* The room without the changing lamp; lamp is its material, emission (0.5, 0.7, 1) times 6. */
static struct room build_room(struct scene_builder *b)
{
    struct room r;
    r.floor = scene_add_material(b, builtin_surface(v3(0.7f, 0.7f, 0.7f), 0.0f, 0.5f));
    r.wall = scene_add_material(b, builtin_diffuse(0.6f, 0.62f, 0.65f));
    r.steady = scene_add_material(b, file_emitter(v3(1.0f, 0.9f, 0.8f), 1.5f));
    r.lamp = scene_add_material(b, file_emitter(v3(0.5f, 0.7f, 1.0f), 6.0f));
    scene_add_quad(b, v3(-2, 0, 2), v3(2, 0, 2), v3(2, 0, -2), v3(-2, 0, -2), r.floor, scene_new_object(b));
    scene_add_quad(b, v3(-2, 0, -1), v3(2, 0, -1), v3(2, 2, -1), v3(-2, 2, -1), r.wall, scene_new_object(b));
    scene_add_box(b, v3(-0.25f, 0, -0.2f), v3(0.25f, 0.5f, 0.2f), r.wall, scene_new_object(b));
    scene_add_quad(b, v3(-1.6f, 1.6f, 0.4f), v3(-1.6f, 1.6f, -0.4f), v3(-0.9f, 1.6f, -0.4f), v3(-0.9f, 1.6f, 0.4f),
                   r.steady, scene_new_object(b));
    b->s->camera = (struct camera){v3(0, 0.9f, 2.6f), v3(0, 0.4f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(-0.4f, 0.9f, 2.6f), v3(0, 0.4f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}},
                                 {64, {v3(0.4f, 1.0f, 2.4f), v3(0, 0.4f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
    return r;
}

/* Gives material m the n keys (copied; translate and rotate NULL: no such channel). The keys are
 * the code's own, so a refusal is a bug. */
static void animate(struct scene_builder *b, int m, int n, int step, const float *frame, const float *strength,
                    const vec3 *translate, const vec3 *rotate)
{
    struct emission_animation a = {.n = n, .step = step};
    a.frame = xmalloc(sizeof(float) * (size_t)n);
    a.strength = xmalloc(sizeof(float) * (size_t)n);
    memcpy(a.frame, frame, sizeof(float) * (size_t)n);
    for (int k = 0; k < n; k++)
        a.strength[k] = strength ? strength[k] : 1.0f;
    if (translate) {
        a.translate = xmalloc(sizeof(vec3) * (size_t)n);
        memcpy(a.translate, translate, sizeof(vec3) * (size_t)n);
    }
    if (rotate) {
        a.rotate = xmalloc(sizeof(vec3) * (size_t)n);
        memcpy(a.rotate, rotate, sizeof(vec3) * (size_t)n);
    }
    char msg[RESTIR_MSG_LEN];
    const int rc = scene_animate_material(b, m, &a, msg);
    RESTIR_CHECK(rc == 0);
}

void scene_build_switch_room(struct scene_builder *b)
{
    const struct room r = build_room(b);
    scene_add_quad(b, v3(0.7f, 0.9f, 0.2f), v3(0.7f, 0.9f, -0.2f), v3(1.1f, 0.9f, -0.2f), v3(1.1f, 0.9f, 0.2f), r.lamp,
                   scene_new_object(b));
    const int dimmed = scene_add_material(b, file_emitter(v3(1.0f, 0.4f, 0.3f), 3.0f));
    scene_add_triangle(b, v3(-0.9f, 0.5f, 0.6f), v3(-0.6f, 0.5f, 0.5f), v3(-0.5f, 0.5f, 0.9f), dimmed,
                       scene_new_object(b));
    const float frame[3] = {0, 16, 32}, strength[3] = {1, 0, 1};
    animate(b, r.lamp, 3, 1, frame, strength, NULL, NULL);
}

void scene_build_moving_lamp(struct scene_builder *b)
{
    const struct room r = build_room(b);
    scene_add_quad(b, v3(0.5f, 0.9f, 0.2f), v3(0.5f, 0.9f, -0.2f), v3(0.9f, 0.9f, -0.2f), v3(0.9f, 0.9f, 0.2f), r.lamp,
                   scene_new_object(b));
    /* rotations about the lamp's centre (the default pivot): tipped towards the room's left */
    const float frame[5] = {0, 16, 24, 32, 40};
    const vec3 there = v3(-1.2f, 0.1f, 0.3f), tilt = v3(0, 40, -35);
    const vec3 translate[5] = {v3s(0.0f), v3s(0.0f), there, there, v3s(0.0f)};
    const vec3 rotate[5] = {v3s(0.0f), v3s(0.0f), tilt, tilt, v3s(0.0f)};
    animate(b, r.lamp, 5, 0, frame, NULL, translate, rotate);
}
