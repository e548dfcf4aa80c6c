/* scenes_builtin.c: the scenes made in code (cornell, ajar, many-lights, foliage, pillars, furnace;
 * forest in scenes_forest.c, night-forest in scenes_night_forest.c, the animated ones in
 * scenes_animated.c), each with a default static camera and camera path, and their table. Must
 * never read files. */
#include "scene/scenes_builtin.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/builtin_shapes.h"
#include "scene/scenes_animated.h"
#include "scene/scenes_forest.h"
#include "scene/scenes_night_forest.h"

static vec3 hue_color(float h)
{
    /* Saturated colour from a hue in [0,1): piecewise-linear RGB wheel, mixed with white. */
    float r = fabsf(h * 6.0f - 3.0f) - 1.0f, g = 2.0f - fabsf(h * 6.0f - 2.0f), b = 2.0f - fabsf(h * 6.0f - 4.0f);
    vec3 c = v3(fminf(fmaxf(r, 0.0f), 1.0f), fminf(fmaxf(g, 0.0f), 1.0f), fminf(fmaxf(b, 0.0f), 1.0f));
    return v3_lerp(c, v3s(1.0f), 0.25f);
}

static void build_cornell(struct scene_builder *b)
{
    int white = scene_add_material(b, builtin_diffuse(0.73f, 0.73f, 0.73f));
    int red = scene_add_material(b, builtin_diffuse(0.65f, 0.05f, 0.05f));
    int green = scene_add_material(b, builtin_diffuse(0.12f, 0.45f, 0.15f));
    int glossy = scene_add_material(b, builtin_surface(v3(0.95f, 0.64f, 0.54f), 1.0f, 0.25f));
    int light = scene_add_material(b, builtin_emitter(v3(17.0f, 12.0f, 4.0f)));
    int room = scene_new_object(b);
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), 1, 1, white, room);    /* floor */
    builtin_rect(b, v3(0, 2, 0), v3(0, -1, 0), v3(1, 0, 0), 1, 1, white, room);   /* ceiling */
    builtin_rect(b, v3(0, 1, -1), v3(0, 0, 1), v3(1, 0, 0), 1, 1, white, room);   /* back */
    builtin_rect(b, v3(-1, 1, 0), v3(1, 0, 0), v3(0, 0, 1), 1, 1, red, room);     /* left */
    builtin_rect(b, v3(1, 1, 0), v3(-1, 0, 0), v3(0, 0, 1), 1, 1, green, room);   /* right */
    builtin_rect(b, v3(0, 1.995f, 0), v3(0, -1, 0), v3(1, 0, 0), 0.25f, 0.2f, light, scene_new_object(b));
    scene_add_box_rotated_y(b, v3(-0.65f, 0, -0.55f), v3(-0.05f, 1.2f, 0.05f), 0.3f, white, scene_new_object(b));
    scene_add_box_rotated_y(b, v3(0.05f, 0, -0.05f), v3(0.65f, 0.6f, 0.55f), -0.3f, glossy, scene_new_object(b));
    b->s->camera = (struct camera){v3(0, 1, 3.4f), v3(0, 1, 0), v3(0, 1, 0), 40.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(-0.3f, 1.0f, 3.4f), v3(0, 1, 0), v3(0, 1, 0), 40.0f, 0.0f, 0.0f}},
                                 {64, {v3(0.3f, 1.1f, 3.2f), v3(0, 1, 0), v3(0, 1, 0), 40.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
}

/* A closed room lit only through a door left ajar. The room spans x in [-2.5, 2.5], y in [0, 2.6],
 * z in [-3, 3]; its +x wall (0.15 thick) has a 0.9 x 2.1 opening, z in [-1.5, -0.6], whose door
 * panel is hinged at z = -1.5 and swung 18 degrees into the room, leaving a narrow slit at the
 * z = -0.6 jamb. Behind it a closed vestibule (x in [2.65, 4.65]) has an emissive panel on its far
 * wall aimed at the slit: only a thin wedge of direct light enters, so most of the room is lit by
 * two or more bounces. The emitter sits on the side of the vestibule the camera cannot see
 * through the slit. Glossy floor, two rough metal objects, two diffuse boxes. */
static void build_ajar(struct scene_builder *b)
{
    const float rx = 2.5f, rz = 3.0f, h = 2.6f, wt = 0.15f; /* room half widths, height; wall thickness */
    const float dz0 = -1.5f, dz1 = -0.6f, dh = 2.1f;        /* door opening */
    const float vx1 = 4.65f, vz0 = -2.5f, vz1 = 0.5f;       /* vestibule far wall and sides */
    const float ox = rx + wt, dcz = 0.5f * (dz0 + dz1), dhw = 0.5f * (dz1 - dz0);
    int wall_warm = scene_add_material(b, builtin_diffuse(0.72f, 0.67f, 0.6f));
    int wall_cool = scene_add_material(b, builtin_diffuse(0.62f, 0.66f, 0.72f));
    int ceiling = scene_add_material(b, builtin_diffuse(0.74f, 0.74f, 0.72f));
    int floor_mat = scene_add_material(b, builtin_surface(v3(0.62f, 0.56f, 0.5f), 0.0f, 0.2f));
    int outside = scene_add_material(b, builtin_diffuse(0.75f, 0.75f, 0.75f));
    int door_mat = scene_add_material(b, builtin_diffuse(0.6f, 0.45f, 0.32f));
    int steel = scene_add_material(b, builtin_surface(v3(0.86f, 0.87f, 0.9f), 1.0f, 0.35f));
    int gold = scene_add_material(b, builtin_surface(v3(0.95f, 0.78f, 0.45f), 1.0f, 0.4f));
    int red = scene_add_material(b, builtin_diffuse(0.65f, 0.2f, 0.15f));
    int blue = scene_add_material(b, builtin_diffuse(0.2f, 0.35f, 0.6f));
    int light = scene_add_material(b, builtin_emitter(v3(120.0f, 110.0f, 95.0f)));
    /* Room, all faces inward. */
    int room = scene_new_object(b);
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), rx, rz, floor_mat, room);
    builtin_rect(b, v3(0, h, 0), v3(0, -1, 0), v3(1, 0, 0), rx, rz, ceiling, room);
    builtin_rect(b, v3(0, h / 2, -rz), v3(0, 0, 1), v3(1, 0, 0), rx, h / 2, wall_warm, room);  /* back */
    builtin_rect(b, v3(0, h / 2, rz), v3(0, 0, -1), v3(1, 0, 0), rx, h / 2, wall_warm, room);  /* front */
    builtin_rect(b, v3(-rx, h / 2, 0), v3(1, 0, 0), v3(0, 0, 1), rz, h / 2, wall_cool, room); /* left */
    /* Door wall: inner face (x = rx, facing -x) and outer face (x = ox, facing +x) around the
     * opening, the jambs, the lintel's underside and the threshold. */
    for (int side = 0; side < 2; side++) {
        float x = side ? ox : rx, z0 = side ? vz0 : -rz, z1 = side ? vz1 : rz;
        vec3 n = v3(side ? 1.0f : -1.0f, 0, 0);
        int m = side ? outside : wall_warm;
        builtin_rect(b, v3(x, h / 2, 0.5f * (z0 + dz0)), n, v3(0, 0, 1), 0.5f * (dz0 - z0), h / 2, m, room);
        builtin_rect(b, v3(x, h / 2, 0.5f * (dz1 + z1)), n, v3(0, 0, 1), 0.5f * (z1 - dz1), h / 2, m, room);
        builtin_rect(b, v3(x, 0.5f * (dh + h), dcz), n, v3(0, 0, 1), dhw, 0.5f * (h - dh), m, room);
    }
    builtin_rect(b, v3(rx + wt / 2, dh / 2, dz0), v3(0, 0, 1), v3(1, 0, 0), wt / 2, dh / 2, wall_warm, room);
    builtin_rect(b, v3(rx + wt / 2, dh / 2, dz1), v3(0, 0, -1), v3(1, 0, 0), wt / 2, dh / 2, wall_warm, room);
    builtin_rect(b, v3(rx + wt / 2, dh, dcz), v3(0, -1, 0), v3(1, 0, 0), wt / 2, dhw, wall_warm, room);
    builtin_rect(b, v3(rx + wt / 2, 0, dcz), v3(0, 1, 0), v3(1, 0, 0), wt / 2, dhw, floor_mat, room);
    /* Vestibule beyond the door, faces inward, with the emitter just in front of its far wall. */
    int vest = scene_new_object(b);
    float vcx = 0.5f * (ox + vx1), vhx = 0.5f * (vx1 - ox), vcz = 0.5f * (vz0 + vz1), vhz = 0.5f * (vz1 - vz0);
    builtin_rect(b, v3(vcx, 0, vcz), v3(0, 1, 0), v3(1, 0, 0), vhx, vhz, outside, vest);
    builtin_rect(b, v3(vcx, h, vcz), v3(0, -1, 0), v3(1, 0, 0), vhx, vhz, outside, vest);
    builtin_rect(b, v3(vcx, h / 2, vz0), v3(0, 0, 1), v3(1, 0, 0), vhx, h / 2, outside, vest);
    builtin_rect(b, v3(vcx, h / 2, vz1), v3(0, 0, -1), v3(1, 0, 0), vhx, h / 2, outside, vest);
    builtin_rect(b, v3(vx1, h / 2, vcz), v3(-1, 0, 0), v3(0, 0, 1), vhz, h / 2, outside, vest);
    /* Emitter z in [-1.3, 0]: its light reaches the slit at shallow angles, while the camera's view
     * through the slit lands on the plain wall further toward -z. */
    builtin_rect(b, v3(vx1 - 0.01f, 1.3f, -0.65f), v3(-1, 0, 0), v3(0, 0, 1), 0.65f, 1.0f, light,
             scene_new_object(b));
    /* Door panel: closed it would fill x in [rx - dt, rx]; rotated about its center so that the
     * hinge corner (rx, dz0) stays put while the free edge swings 18 degrees into the room. */
    const float dt = 0.04f, dw = 0.88f, open = -18.0f * RESTIR_PI / 180.0f;
    float cs = cosf(open), sn = sinf(open);
    vec3 hinge_local = v3(dt / 2, 0, -dw / 2); /* hinge corner relative to the panel's center */
    vec3 hinge_rot = v3(cs * hinge_local.x + sn * hinge_local.z, 0, -sn * hinge_local.x + cs * hinge_local.z);
    vec3 dc = v3(rx - hinge_rot.x, 0, dz0 + 0.01f - hinge_rot.z);
    scene_add_box_rotated_y(b, v3(dc.x - dt / 2, 0.005f, dc.z - dw / 2), v3(dc.x + dt / 2, dh - 0.01f, dc.z + dw / 2),
                            open, door_mat, scene_new_object(b));
    /* Furniture: the steel box stands in the wedge of direct light, the gold sphere just beside it. */
    scene_add_sphere(b, v3(0.9f, 0.4f, -1.35f), 0.4f, 32, 0, gold, scene_new_object(b));
    scene_add_box_rotated_y(b, v3(-1.6f, 0, -0.8f), v3(-1.0f, 0.6f, -0.2f), 0.3f, steel, scene_new_object(b));
    scene_add_box_rotated_y(b, v3(1.5f, 0, -2.9f), v3(2.2f, 1.2f, -2.3f), -0.2f, blue, scene_new_object(b));
    scene_add_box_rotated_y(b, v3(-0.8f, 0, -2.4f), v3(-0.2f, 0.7f, -1.8f), 0.5f, red, scene_new_object(b));
    /* The camera looks at the slit from the side the wedge of light does not reach, so the emitter
     * stays hidden; the path is a slow dolly of about 0.25 m over 120 frames. */
    b->s->camera = (struct camera){v3(-1.8f, 1.5f, 2.4f), v3(1.2f, 0.6f, -1.2f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f};
    struct camera_key keys[3] = {{0, {v3(-1.85f, 1.5f, 2.45f), v3(1.2f, 0.6f, -1.25f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}},
                                 {60, {v3(-1.75f, 1.47f, 2.37f), v3(1.2f, 0.6f, -1.2f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}},
                                 {120, {v3(-1.65f, 1.45f, 2.3f), v3(1.2f, 0.6f, -1.15f), v3(0, 1, 0), 55.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 3, keys);
}

static void build_many_lights(struct scene_builder *b)
{
    pcg32 r = pcg32_make(7, 11);
    int floor_mat = scene_add_material(b, builtin_diffuse(0.6f, 0.6f, 0.6f));
    int box_mat = scene_add_material(b, builtin_diffuse(0.7f, 0.68f, 0.62f));
    int metal = scene_add_material(b, builtin_surface(v3(0.9f, 0.9f, 0.92f), 1.0f, 0.3f));
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), 12, 12, floor_mat, scene_new_object(b));
    for (int i = 0; i < 5; i++) {
        for (int j = 0; j < 5; j++) {
            float x = -8.0f + 4.0f * (float)i + builtin_rnd(&r, -0.6f, 0.6f);
            float z = -8.0f + 4.0f * (float)j + builtin_rnd(&r, -0.6f, 0.6f);
            float h = builtin_rnd(&r, 0.4f, 2.5f), w = builtin_rnd(&r, 0.3f, 0.9f);
            scene_add_box_rotated_y(b, v3(x - w, 0, z - w), v3(x + w, h, z + w), builtin_rnd(&r, 0, 1.5f),
                                    (i + j) % 3 == 0 ? metal : box_mat, scene_new_object(b));
        }
    }
    /* 1200 small one-sided emitters facing mostly downward, power spread over two decades. */
    int light_obj = scene_new_object(b);
    for (int i = 0; i < 1200; i++) {
        vec3 c = v3(builtin_rnd(&r, -11, 11), builtin_rnd(&r, 0.4f, 4.0f), builtin_rnd(&r, -11, 11));
        vec3 n = builtin_random_unit(&r);
        n.y = -fabsf(n.y) - 0.5f;
        n = v3_normalize(n);
        frame f = frame_from_normal(n);
        float size = builtin_rnd(&r, 0.08f, 0.25f);
        float power = expf(builtin_rnd(&r, logf(0.5f), logf(40.0f)));
        int m = scene_add_material(b, builtin_emitter(v3_scale(hue_color(pcg32_float(&r)), power)));
        vec3 p0 = v3_madd(c, f.t, size), p1 = v3_madd(c, v3_add(v3_scale(f.t, -0.5f), v3_scale(f.b, 0.866f)), size);
        vec3 p2 = v3_madd(c, v3_add(v3_scale(f.t, -0.5f), v3_scale(f.b, -0.866f)), size);
        /* counter-clockwise around n: t -> b */
        scene_add_triangle(b, p0, p1, p2, m, light_obj);
    }
    b->s->camera = (struct camera){v3(0, 7, 15), v3(0, 0.5f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(-3, 7, 15), v3(-1, 0.5f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}},
                                 {64, {v3(3, 6, 13), v3(1, 0.5f, 0), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
}

static void build_foliage(struct scene_builder *b)
{
    pcg32 r = pcg32_make(3, 5);
    int ground = scene_add_material(b, builtin_diffuse(0.35f, 0.28f, 0.2f));
    int bark = scene_add_material(b, builtin_diffuse(0.3f, 0.2f, 0.12f));
    int leaf[3] = {scene_add_material(b, builtin_diffuse(0.25f, 0.5f, 0.12f)),
                   scene_add_material(b, builtin_diffuse(0.35f, 0.55f, 0.1f)),
                   scene_add_material(b, builtin_surface(v3(0.2f, 0.45f, 0.1f), 0.0f, 0.35f))};
    int sky = scene_add_material(b, builtin_emitter(v3(6.0f, 6.0f, 5.5f)));
    int sun = scene_add_material(b, builtin_emitter(v3(40.0f, 34.0f, 26.0f)));
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), 8, 8, ground, scene_new_object(b));
    const vec3 stems[3] = {v3(-1.3f, 0, -0.5f), v3(0.2f, 0, -1.2f), v3(1.4f, 0, -0.2f)};
    for (int s = 0; s < 3; s++) {
        float h = 2.2f + 0.3f * (float)s;
        vec3 base = stems[s];
        scene_add_box(b, v3(base.x - 0.05f, 0, base.z - 0.05f), v3(base.x + 0.05f, h, base.z + 0.05f), bark,
                      scene_new_object(b));
        int obj = scene_new_object(b);
        for (int i = 0; i < 1500; i++) {
            /* Leaves fill an ellipsoidal crown around the top of the stem. */
            vec3 d = builtin_random_unit(&r);
            float rad = cbrtf(pcg32_float(&r));
            vec3 c = v3(base.x + 0.9f * rad * d.x, h - 0.5f + 0.8f * rad * d.y, base.z + 0.9f * rad * d.z);
            vec3 n = builtin_random_unit(&r);
            frame f = frame_from_normal(n);
            float len = builtin_rnd(&r, 0.06f, 0.12f), wid = builtin_rnd(&r, 0.025f, 0.05f);
            builtin_rect(b, c, n, f.t, len, wid, leaf[i % 3], obj);
        }
    }
    builtin_rect(b, v3(0, 6, 0), v3(0, -1, 0), v3(1, 0, 0), 3, 3, sky, scene_new_object(b));
    vec3 sun_n = v3_normalize(v3(-1, -1.2f, -0.6f));
    builtin_rect(b, v3(5, 5, 3), sun_n, frame_from_normal(sun_n).t, 0.5f, 0.5f, sun, scene_new_object(b));
    b->s->camera = (struct camera){v3(0, 1.7f, 5.0f), v3(0, 1.6f, -0.5f), v3(0, 1, 0), 45.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(-0.6f, 1.7f, 5.0f), v3(0, 1.6f, -0.5f), v3(0, 1, 0), 45.0f, 0.0f, 0.0f}},
                                 {64, {v3(0.6f, 1.8f, 4.6f), v3(0, 1.6f, -0.5f), v3(0, 1, 0), 45.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
}

static void build_pillars(struct scene_builder *b)
{
    int white = scene_add_material(b, builtin_diffuse(0.75f, 0.75f, 0.72f));
    int floor_mat = scene_add_material(b, builtin_surface(v3(0.5f, 0.5f, 0.55f), 0.0f, 0.3f));
    int stone = scene_add_material(b, builtin_diffuse(0.55f, 0.45f, 0.35f));
    int warm = scene_add_material(b, builtin_emitter(v3(30.0f, 20.0f, 10.0f)));
    int cool = scene_add_material(b, builtin_emitter(v3(8.0f, 14.0f, 30.0f)));
    builtin_rect(b, v3(0, 0, 0), v3(0, 1, 0), v3(1, 0, 0), 10, 6, floor_mat, scene_new_object(b));
    builtin_rect(b, v3(0, 2.5f, -2.5f), v3(0, 0, 1), v3(1, 0, 0), 10, 2.5f, white, scene_new_object(b));
    for (int i = 0; i < 7; i++) {
        float x = -6.0f + 2.0f * (float)i;
        scene_add_box(b, v3(x - 0.25f, 0, -0.25f), v3(x + 0.25f, 3.5f, 0.25f), stone, scene_new_object(b));
    }
    /* Light strips hidden above, between pillars and wall, washing the wall. */
    vec3 down_back = v3_normalize(v3(0, -1, -0.6f));
    for (int i = 0; i < 4; i++) {
        float x = -6.0f + 4.0f * (float)i;
        builtin_rect(b, v3(x, 4.6f, -1.2f), down_back, v3(1, 0, 0), 0.9f, 0.1f, i % 2 ? cool : warm,
                 scene_new_object(b));
    }
    b->s->camera = (struct camera){v3(-1, 1.6f, 6), v3(-1, 1.6f, -2.5f), v3(0, 1, 0), 50.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(-4, 1.6f, 6), v3(-4, 1.6f, -2.5f), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}},
                                 {64, {v3(4, 1.6f, 6), v3(4, 1.6f, -2.5f), v3(0, 1, 0), 50.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
}

static void build_furnace(struct scene_builder *b)
{
    /* A pure Lambertian (no specular layer) so that L = Le / (1 - albedo) = 1 exactly. */
    int m = scene_add_material(
        b, (struct material){.base_color = v3s(0.5f), .roughness = 1.0f, .emission = v3s(0.5f), .lambert_only = 1});
    scene_add_sphere(b, v3(0, 0, 0), 1.0f, 48, 1, m, scene_new_object(b));
    b->s->camera = (struct camera){v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), 60.0f, 0.0f, 0.0f};
    struct camera_key keys[2] = {{0, {v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), 60.0f, 0.0f, 0.0f}},
                                 {64, {v3(0.2f, 0, 0), v3(1, 0, 1), v3(0, 1, 0), 60.0f, 0.0f, 0.0f}}};
    builtin_set_path(b->s, 2, keys);
}

const struct scene_builtin scene_builtins[] = {
    {"many-lights", "floor and occluders lit by 1200 small emissive triangles of varied colour and power (default)",
     build_many_lights, NULL},
    {"cornell", "Cornell box with a ceiling light, a diffuse block and a glossy metal block", build_cornell, NULL},
    {"ajar", "closed room lit only through the narrow gap of a door left ajar: glossy floor, rough metal, indirect "
             "light",
     build_ajar, NULL},
    {"foliage", "thousands of thin leaf quads on a few stems over a ground, lit by two area lights (hard pixels)",
     build_foliage, NULL},
    {"pillars", "a row of pillars before a lit wall; the camera path strafes sideways (disocclusion)", build_pillars,
     NULL},
    {"furnace", "closed sphere of albedo 0.5 and emission 0.5 seen from inside: radiance is exactly 1 (test)",
     build_furnace, NULL},
    {"forest", "25 trees with 75000 alpha-masked leaf cards and normal-mapped trunks under a sky with a sun (walk)",
     scene_build_forest, scene_light_forest},
    {"night-forest",
     "the forest at night, no sky, lit only by strings of fairy lights: over 100,000 small emissive triangles (walk)",
     scene_build_night_forest, NULL},
    {"switch-room", "a room whose blue lamp switches off at frame 16 and on at 32 (lag and ghosting)",
     scene_build_switch_room, NULL},
    {"moving-lamp", "the same room, its blue lamp carried across it over frames 16-24 and back over 32-40",
     scene_build_moving_lamp, NULL},
    {NULL, NULL, NULL, NULL}};

static const struct scene_builtin *find_builtin(const char *name)
{
    for (const struct scene_builtin *e = scene_builtins; e->name; e++)
        if (strcmp(name, e->name) == 0)
            return e;
    return NULL;
}

int scene_is_builtin(const char *name) { return find_builtin(name) != NULL; }

static int create_builtin(const char *name, const struct scene_load_desc *d, struct scene *s,
                          struct scene_shape_record **records, int *num_records, char *msg)
{
    const struct scene_builtin *e = find_builtin(name);
    if (!e) {
        int n = snprintf(msg, RESTIR_MSG_LEN, "unknown scene '%s' (built-in scenes:", name);
        for (int k = 0; scene_builtins[k].name && n < RESTIR_MSG_LEN; k++)
            n += snprintf(msg + n, (size_t)(RESTIR_MSG_LEN - n), " %s", scene_builtins[k].name);
        if (n < RESTIR_MSG_LEN)
            snprintf(msg + n, (size_t)(RESTIR_MSG_LEN - n), "; or a scene file: .json, .gltf, .glb, .obj, .ply)");
        return -1;
    }
    struct scene_builder b;
    scene_builder_begin_with(&b, s, name, d);
    b.record = records != NULL;
    e->build(&b);
    if (scene_builder_end(&b, msg) != 0 || (e->light && e->light(s, msg) != 0)) {
        free(b.records);
        scene_destroy(s);
        return -1;
    }
    if (records) {
        *records = b.records;
        *num_records = b.num_records;
    }
    return 0;
}

int scene_create_builtin(const char *name, struct scene *s, char *msg)
{
    return create_builtin(name, NULL, s, NULL, NULL, msg);
}

int scene_create_builtin_with(const char *name, const struct scene_load_desc *d, struct scene *s, char *msg)
{
    return create_builtin(name, d, s, NULL, NULL, msg);
}

int scene_create_builtin_recorded(const char *name, struct scene *s, struct scene_shape_record **records,
                                  int *num_records, char *msg)
{
    return create_builtin(name, NULL, s, records, num_records, msg);
}
