/* scene_motion.h: moving emitters: an emissive material whose "animation" keys translate or rotate
 * its triangles (scene_animation.h). The motion is rigid, so every area, power, pdf and the order of
 * the emitters stay what the load made them; what a frame changes is where the triangles are: the
 * vertices, shading normals and tangents, the triangles' normals, the emitters' records and
 * rectangles, the emitter BVH's bounds (refitted: its tree and leaf order stay, which ReGIR's cut
 * order relies on) and the ray-tracing BVH (scene_rt_update_moving: the moving triangles are their
 * own Embree geometry, refitted, in a two-level scene). The scene keeps the triangles' rest pose,
 * where the file put them, and poses every frame from it, so no rounding accumulates. */
#ifndef RESTIR_SCENE_SCENE_MOTION_H
#define RESTIR_SCENE_SCENE_MOTION_H

#include <stddef.h>

#include "scene/scene_types.h"

/* x -> r x + t, r a rotation (row-major 3x3). */
struct rigid_motion {
    float r[9];
    vec3 t;
};

static inline vec3 rigid_dir(const struct rigid_motion *m, vec3 d)
{
    return v3(m->r[0] * d.x + m->r[1] * d.y + m->r[2] * d.z, m->r[3] * d.x + m->r[4] * d.y + m->r[5] * d.z,
              m->r[6] * d.x + m->r[7] * d.y + m->r[8] * d.z);
}

static inline vec3 rigid_point(const struct rigid_motion *m, vec3 p) { return v3_add(rigid_dir(m, p), m->t); }

/* The motion of animation a at frame t: rotate by its angles about x, then y, then z around the
 * pivot, then translate (identity for a channel it has no keys of). */
void emission_animation_motion(const struct emission_animation *a, float t, struct rigid_motion *m);

/* 1 when some emitter of s moves (its rest pose is kept in s->motion). */
static inline int scene_has_moving_emitters(const struct scene *s) { return s->motion != NULL; }

/* Called by scene_builder_end after the emitter table is built and before the ray-tracing BVH:
 * keeps the rest pose of every triangle whose material has translation or rotation keys. Nothing
 * to do (0) without s->emission_anim. Returns 0, or -1 with msg when a moving triangle shares a
 * vertex with any other triangle (each corner is posed on its own; the scene builder gives every
 * triangle its own three). */
int scene_motion_prepare(struct scene *s, char *msg);

/* The moving triangles, ascending; returns how many (0 for a scene whose emitters stand still). */
int scene_motion_tris(const struct scene *s, const int **tris);

/* Poses the moving emitters at frame t (scene_set_frame; nothing when they are already there). Not
 * thread-safe with anything that reads the scene. */
void scene_motion_apply(const struct scene *s, float t);

/* Poses the moving emitters of the previous-frame queries (scene_occluded_previous_batch,
 * scene_rt.h) at frame t, rigidly from their rest pose as scene_motion_apply does (nothing when
 * they are there already, or where the scene cannot trace them: scene_can_trace_previous). Not
 * thread-safe with any query; a method calls it before the pass that traces in frame t. */
void scene_motion_pose_previous(const struct scene *s, float t);

/* scene_motion_point_at at the frame scene_motion_pose_previous last posed, from its poses (no
 * trigonometry per call: the temporal pass asks it for every pixel); before any, frame 0's. */
void scene_motion_point_previous(const struct scene *s, int tri, float b1, float b2, vec3 *p, vec3 *n);

/* The point at barycentrics (b1, b2) of triangle tri, and its geometric normal, at frame t (where
 * the scene holds it now for a triangle that stays). */
void scene_motion_point_at(const struct scene *s, int tri, float b1, float b2, float t, vec3 *p, vec3 *n);

/* Sets every animated material's emission, and the Le of its emitters, to frame t's (the loaded
 * scene's frame 0 otherwise), and puts the moving emitters where frame t has them
 * (scene_motion_apply). The one change a loaded scene takes: its arrays are written through the
 * const scene. Not thread-safe with anything that reads the scene;
 * renderer_render calls it before a frame's passes, the references before their first path. Does
 * nothing for a still scene. */
void scene_set_frame(const struct scene *s, float t);

void scene_motion_free(struct scene *s);

#endif
