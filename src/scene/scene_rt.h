/* scene_rt.h: ray queries against the scene and the Embree BVH build behind them.
 * Must never expose embree types (only scene_rt.c includes embree3/rtcore.h). */
#ifndef RESTIR_SCENE_SCENE_RT_H
#define RESTIR_SCENE_SCENE_RT_H

#include <stddef.h>

#include "core/vec3.h"
#include "scene/scene_types.h"

/* Builds the acceleration structure over s's triangles (scene_builder_end). Returns 0, or -1 with
 * msg. */
int scene_rt_build(struct scene *s, char *msg);
void scene_rt_destroy(struct scene *s);

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
/* p moved off its surface (normal n) to the side that direction `toward` leaves from. */
vec3 scene_offset_point(vec3 p, vec3 n, vec3 toward);
/* Visibility between two surface points with normals, offsetting both ends. */
int scene_visible(const struct scene *s, vec3 p0, vec3 n0, vec3 p1, vec3 n1);

/* Ray logging for benchmarks: while a log is active every query is recorded (per thread, no
 * locks), so a frame's rays can be replayed through Embree alone to separate ray-tracing time
 * from shading time. */
enum ray_kind { RAY_CLOSEST = 0, RAY_OCCLUDED, RAY_EMITTERS };
struct ray_record {
    vec3 o, d;
    float tmin, tmax;
    int kind;
};
void scene_ray_log_begin(const struct scene *s);
/* Stops logging and returns all recorded rays (malloc'ed, caller frees) and their count. */
struct ray_record *scene_ray_log_end(const struct scene *s, size_t *count);
/* Traces the recorded rays again in parallel; returns the elapsed milliseconds. */
double scene_ray_replay(const struct scene *s, const struct ray_record *rays, size_t count);

#endif
