/* scene_rt.h: ray queries against the scene and the Embree BVH build behind them.
 * Must never expose embree types (only scene_rt.c and the benchmarks' ray replay, scene_ray_log.c,
 * include embree3/rtcore.h, the latter through scene_rt_embree.h). */
#ifndef RESTIR_SCENE_SCENE_RT_H
#define RESTIR_SCENE_SCENE_RT_H

#include <math.h>
#include <stddef.h>

#include "core/vec3.h"
#include "scene/scene_types.h"

/* Builds the acceleration structure over s's triangles (scene_builder_end), the moving emitters'
 * triangles moving_tris[0 .. moving-1] (ascending; scene_motion.h) apart, to be refitted by
 * scene_rt_update_moving. Returns 0, or -1 with msg. */
int scene_rt_build(struct scene *s, const int *moving_tris, int moving, char *msg);
void scene_rt_destroy(struct scene *s);
/* Moves the moving emitters' triangles (scene_motion.h) to where s->verts has them now, in the main
 * BVH and the emitters' (a refit). Nothing for a scene whose emitters stand still. Not thread-safe
 * with any query. */
void scene_rt_update_moving(struct scene *s);
/* Poses the moving emitters' triangles of the previous-frame queries (scene_occluded_previous_batch):
 * corners holds 3 per moving triangle, in the ascending order of scene_motion_tris. Nothing where
 * scene_can_trace_previous is 0. Not thread-safe with any query; scene_motion_pose_previous calls it. */
void scene_rt_update_previous(const struct scene *s, const vec3 *corners);
/* 1 when s can answer occlusion queries in an earlier frame's geometry (its emitters move, and
 * Embree has ray masks). */
int scene_can_trace_previous(const struct scene *s);

/* Surface point reconstructed from a triangle hit. */
struct surface_hit {
    vec3 p;
    vec3 ng;   /* geometric normal, unit, facing the incoming ray */
    vec3 ns;   /* shading normal on ng's side (scene_surface.h), before bsdf_shading_normal */
    float t;
    int tri;
    float b1, b2; /* barycentrics of p: p = (1-b1-b2) v0 + b1 v1 + b2 v2 */
    int material;
    int object;
    int front; /* 1 when the ray hit the front (emitting) side */
};

/* The surface point p on triangle tri (barycentrics b1, b2) as a ray of direction d would hit it
 * (t = 0): what scene_intersect reports there, without tracing. */
void scene_surface_at(const struct scene *s, int tri, float b1, float b2, vec3 p, vec3 d, struct surface_hit *hit);

/* Ray queries. tmax may be INFINITY. */
int scene_intersect(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax, struct surface_hit *hit);
/* Closest hit among the emissive triangles only, ignoring every other surface. */
int scene_intersect_emitters(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax,
                             struct surface_hit *hit);
int scene_occluded(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax);

/* Offset scale for self-intersection: relative to the coordinates' magnitude, so it tracks float
 * precision whatever the scene's size. */
static inline float scene_ray_epsilon(vec3 p)
{
    return 1e-4f * (1.0f + max_f(fabsf(p.x), max_f(fabsf(p.y), fabsf(p.z)))); /* not fmaxf: a libm call */
}

/* p moved off its surface (normal n) to the side that direction `toward` leaves from. */
static inline vec3 scene_offset_point(vec3 p, vec3 n, vec3 toward)
{
    float e = scene_ray_epsilon(p);
    return v3_madd(p, n, v3_dot(n, toward) >= 0.0f ? e : -e);
}

/* A ray of the batched queries: origin, unit direction, interval. */
struct ray_query {
    vec3 o, d;
    float tmin, tmax;
};
/* The shadow ray scene_visible traces between p0 and p1; 0 when the points coincide (visible,
 * nothing to trace). Inline, as scene_visible and scene_offset_point: out of line, GCC passed
 * their vec3 arguments through the stack in pieces it read back at other widths, and the
 * store-forwarding stalls were most of scene_visible's self time (3.9% of a restir-pt run). */
static inline int scene_visibility_query(vec3 p0, vec3 n0, vec3 p1, vec3 n1, struct ray_query *q)
{
    vec3 d = v3_sub(p1, p0);
    vec3 o = scene_offset_point(p0, n0, d);
    vec3 e = scene_offset_point(p1, n1, v3_neg(d));
    vec3 od = v3_sub(e, o);
    float dist = v3_length(od);
    if (!(dist > 0.0f))
        return 0;
    *q = (struct ray_query){o, v3_scale(od, 1.0f / dist), 0.0f, dist * (1.0f - 1e-4f)};
    return 1;
}

/* Visibility between two surface points with normals, offsetting both ends. */
static inline int scene_visible(const struct scene *s, vec3 p0, vec3 n0, vec3 p1, vec3 n1)
{
    struct ray_query q;
    if (!scene_visibility_query(p0, n0, p1, n1, &q))
        return 1;
    return !scene_occluded(s, q.o, q.d, q.tmin, q.tmax);
}
/* Batched queries: the same answers as scene_intersect / scene_occluded ray by ray (Embree's
 * stream traversal: hit distances and barycentrics may differ from single rays' in the last
 * bits), at lower cost per ray where many are traced together: primary rays of a tile
 * (coherent = 1: they share the camera's origin) and shadow rays of a tile (measured in
 * docs/BENCHMARKS.md, the section on ray streams). hit[k] / occluded[k] are 0 or 1. */
void scene_intersect_batch(const struct scene *s, const struct ray_query *q, int n, int coherent,
                           struct surface_hit *hits, unsigned char *hit);
void scene_occluded_batch(const struct scene *s, const struct ray_query *q, int n, unsigned char *occluded);
/* scene_occluded_batch in the geometry of the frame scene_motion_pose_previous last posed: every
 * still triangle, and the moving emitters where that frame had them (not where they are now). The
 * same as scene_occluded_batch for a scene whose emitters stand still. Thread-safe, as the other
 * queries. */
void scene_occluded_previous_batch(const struct scene *s, const struct ray_query *q, int n,
                                   unsigned char *occluded);
/* on = 0: the batched queries trace ray by ray; on = 1 (the default): as Embree streams. The
 * scene's owner's setting, not a renderer's: loading sets it (scene_load_desc.ray_streams_off,
 * from rays.streams), and an owner may change it while no query runs (the benchmark of streams
 * toggles it per run). The same answers either way. */
void scene_set_ray_streams(struct scene *s, int on);

/* Which query traced a ray: scene_intersect (and the batched closest hits), scene_occluded (and
 * the batched occlusion), scene_intersect_emitters. The benchmarks' ray log records it
 * (scene_ray_log.h). */
enum ray_kind { RAY_CLOSEST = 0, RAY_OCCLUDED, RAY_EMITTERS };

#endif
