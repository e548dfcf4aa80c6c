/* test_scene_motion.c: moving emitters (scene/scene_motion.h) on tests/data/scenes/moving_lamp.json,
 * whose lamp translates and rotates about its own centre (the default pivot) between frames 0, 3
 * and 6: at each frame its corners are the rigid motion of where the file put them (computed here
 * from the keys, independently of the scene's code), its normal turns with it, rays find it where
 * it is and no longer where it was, the emitter BVH's root holds it, the point at another frame
 * (scene_motion_point_at) is that frame's, and frame 0 puts everything back bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scene/scene_animation.h"
#include "scene/scene_file.h"
#include "scene/scene_motion.h"
#include "scene/scene_rt.h"
#include "test_util.h"

#define DEG (3.14159265358979323846 / 180.0)

/* p rotated by angles a (degrees; about x, then y, then z) around c, then moved by t, in double */
static vec3 expected_point(vec3 p, vec3 a, vec3 c, vec3 t)
{
    double x = p.x - c.x, y = p.y - c.y, z = p.z - c.z, u;
    u = y * cos(a.x * DEG) - z * sin(a.x * DEG), z = y * sin(a.x * DEG) + z * cos(a.x * DEG), y = u;
    u = x * cos(a.y * DEG) + z * sin(a.y * DEG), z = -x * sin(a.y * DEG) + z * cos(a.y * DEG), x = u;
    u = x * cos(a.z * DEG) - y * sin(a.z * DEG), y = x * sin(a.z * DEG) + y * cos(a.z * DEG), x = u;
    return v3((float)(x + c.x + t.x), (float)(y + c.y + t.y), (float)(z + c.z + t.z));
}

static vec3 tri_corner(const struct scene *s, int tri, int k) { return s->verts[s->indices[3 * tri + k]]; }

int main(void)
{
    const char *data = getenv("RESTIR_TEST_DATA");
    if (!data)
        return test_skip("RESTIR_TEST_DATA is not set (run through ctest)");
    char path[1024], msg[512];
    snprintf(path, sizeof path, "%s/scenes/moving_lamp.json", data);
    struct scene s;
    if (scene_load(path, &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return test_finish();
    }
    EXPECT(scene_has_moving_emitters(&s), "moving_lamp.json has a moving emitter");
    const int *tris;
    const int n = scene_motion_tris(&s, &tris);
    EXPECT(n == 2, "the moving lamp is one quad: %d moving triangles", n);
    const int lamp = 3; /* the material of the moving quad */
    const struct emission_animation *a = &s.emission_anim[lamp];
    vec3 rest[2][3], centre = v3(0.7f, 0.9f, 0.0f); /* the quad's centre: the default pivot */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            rest[i][k] = tri_corner(&s, tris[i], k);
    EXPECT(fabsf(a->pivot.x - centre.x) < 1e-6f && fabsf(a->pivot.y - centre.y) < 1e-6f &&
               fabsf(a->pivot.z - centre.z) < 1e-6f,
           "default pivot (%g %g %g): the quad's centre", a->pivot.x, a->pivot.y, a->pivot.z);
    const float frames[] = {1.5f, 3.0f, 4.5f, 7.0f};
    for (int f = 0; f < 4; f++) {
        const float t = frames[f];
        scene_set_frame(&s, t);
        const vec3 ang = emission_animation_vec_at(a, a->rotate, t);
        const vec3 move = emission_animation_vec_at(a, a->translate, t);
        double worst = 0.0;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 3; k++)
                worst = fmax(worst, v3_length(v3_sub(tri_corner(&s, tris[i], k),
                                                     expected_point(rest[i][k], ang, centre, move))));
        EXPECT(worst < 1e-5, "frame %g: corners %.3g from the rigid motion of the keys", t, worst);
        /* the emitter's record and normal move with it */
        const int e = s.tri_emitter[tris[0]];
        const vec3 c0 = tri_corner(&s, tris[0], 0), c1 = tri_corner(&s, tris[0], 1), c2 = tri_corner(&s, tris[0], 2);
        const vec3 nrm = v3_normalize(v3_cross(v3_sub(c1, c0), v3_sub(c2, c0)));
        EXPECT(v3_length(v3_sub(s.emitters[e].v0, c0)) == 0.0f && v3_dot(s.emitters[e].n, nrm) > 0.99999f &&
                   v3_dot(s.tri_normal[tris[0]], nrm) > 0.99999f,
               "frame %g: the emitter record and the triangle's normal follow the corners", t);
        /* a ray from just below the lamp's moved centre finds the lamp; aimed at the rest centre it does
         * not (the lamp left it: at every frame tested it moved by more than its half-diagonal) */
        const vec3 moved = expected_point(centre, ang, centre, move);
        struct surface_hit hit;
        const vec3 o = v3(moved.x, moved.y - 0.3f, moved.z); /* above the box that stands under the path */
        const int found = scene_intersect(&s, o, v3_normalize(v3_sub(moved, o)), 1e-4f, INFINITY, &hit);
        EXPECT(found && s.tri_material[hit.tri] == lamp, "frame %g: a ray at the moved lamp hits material %d", t,
               found ? s.tri_material[hit.tri] : -1);
        EXPECT(scene_intersect_emitters(&s, o, v3_normalize(v3_sub(moved, o)), 1e-4f, INFINITY, &hit) &&
                   s.tri_material[hit.tri] == lamp,
               "frame %g: the emitters' BVH finds it too", t);
        const vec3 o_rest = v3(centre.x, 0.05f, centre.z);
        const int stale =
            scene_intersect(&s, o_rest, v3(0, 1, 0), 1e-4f, 1.5f, &hit) && s.tri_material[hit.tri] == lamp;
        EXPECT(!stale, "frame %g: a ray at the lamp's rest place still hits it", t);
        /* the emitter BVH: every node from the moving lamp's leaves up to the root holds its corners where
         * they are now (inside the node's box, so inside the sphere around it: a refit; the root alone
         * would hold the lamp at any of its poses) */
        int holds = 1;
        for (int i = 0; i < n; i++) {
            int node = s.light_bvh.emitter_leaf[s.tri_emitter[tris[i]]];
            for (; node >= 0; node = s.light_bvh.nodes[node].parent) {
                const struct light_bvh_node *nd = &s.light_bvh.nodes[node];
                for (int k = 0; k < 3; k++)
                    holds &= v3_length2(v3_sub(tri_corner(&s, tris[i], k), nd->center)) <=
                             nd->radius2 * 1.0001f + 1e-9f;
            }
        }
        EXPECT(holds, "frame %g: the emitter BVH's bounds do not hold the moved lamp", t);
        /* the point at another frame is that frame's */
        vec3 p, pn;
        scene_motion_point_at(&s, tris[0], 0.0f, 0.0f, 3.0f, &p, &pn);
        const vec3 at3 = expected_point(rest[0][0], emission_animation_vec_at(a, a->rotate, 3.0f), centre,
                                        emission_animation_vec_at(a, a->translate, 3.0f));
        EXPECT(v3_length(v3_sub(p, at3)) < 1e-5f, "frame %g: scene_motion_point_at(frame 3) is %.3g off", t,
               v3_length(v3_sub(p, at3)));
    }
    EXPECT(scene_lights_moved(&s, 0.0f, 1.0f) && !scene_lights_moved(&s, 6.0f, 9.0f) &&
               scene_lights_differ(&s, 2.0f, 3.0f),
           "moves between frames 0 and 6 only");
    scene_set_frame(&s, 0.0f);
    int same = 1;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            same &= v3_equal(tri_corner(&s, tris[i], k), rest[i][k]);
    EXPECT(same, "frame 0 puts the lamp back where the file has it, bit for bit");
    scene_destroy(&s);
    return test_finish();
}
