/* scene_rt_embree.h: the Embree level of scene_rt.c, for the one other file that traces through
 * Embree itself: the benchmarks' ray replay (scene_ray_log.c). The scene's Embree scenes, the
 * single-ray and stream queries without the surface reconstruction, and the hook through which
 * every query reports its rays to the ray log.
 * Must never be included by a header or outside src/scene: it exposes embree types. */
#ifndef RESTIR_SCENE_SCENE_RT_EMBREE_H
#define RESTIR_SCENE_SCENE_RT_EMBREE_H

#include <embree3/rtcore.h>
#include <math.h>
#include <stddef.h>

#include "core/vec3.h"
#include "scene/scene_types.h"

struct ray_query; /* scene_rt.h, which cannot be included here: scene_rt.c includes this */

/* Embree's stream calls take at most this many rays per call here (stack arrays). */
#define RAY_STREAM_MAX 64

/* The Embree scene that answers s's queries of kind (enum ray_kind, scene_rt.h): the emitters'
 * for RAY_EMITTERS (NULL without emitters), else the main one; *geom_tris (when not NULL) is the
 * map scene_rt_closest takes for it. */
RTCScene scene_rt_embree(const struct scene *s, int kind, int *const **geom_tris);

/* The single-ray queries, inline so that the replay's loop, like scene_rt.c's queries, traces
 * without a call between it and Embree. */

/* Closest hit in sc; returns the triangle (geom_tris[geomID][primID], or primID where geom_tris
 * or its entry is NULL) or -1, with the distance and barycentrics. */
static inline int scene_rt_closest(RTCScene sc, int *const *geom_tris, vec3 o, vec3 d, float tmin, float tmax,
                                   float *t, float *u, float *v)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tmin;
    rh.ray.tfar = tmax;
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(sc, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return -1;
    *t = rh.ray.tfar;
    *u = rh.hit.u;
    *v = rh.hit.v;
    const int *map = geom_tris ? geom_tris[rh.hit.geomID] : NULL;
    return map ? map[rh.hit.primID] : (int)rh.hit.primID;
}

/* 1 when something in sc blocks the ray between tmin and tmax. */
static inline int scene_rt_occluded(RTCScene sc, vec3 o, vec3 d, float tmin, float tmax)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray;
    ray.org_x = o.x;
    ray.org_y = o.y;
    ray.org_z = o.z;
    ray.dir_x = d.x;
    ray.dir_y = d.y;
    ray.dir_z = d.z;
    ray.tnear = tmin;
    ray.tfar = tmax;
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(sc, &ctx, &ray);
    return ray.tfar == -INFINITY;
}

/* Closest hits of q[0 .. n-1] (n <= RAY_STREAM_MAX) in sc through one rtcIntersect1M call:
 * tri[k] as scene_rt_closest returns it, with t, u, v. */
void scene_rt_closest_stream(RTCScene sc, int *const *geom_tris, const struct ray_query *q, int n, int coherent,
                             int *tri, float *t, float *u, float *v);
/* Occlusion of q[0 .. n-1] (n <= RAY_STREAM_MAX) through one rtcOccluded1M call. */
void scene_rt_occluded_stream(RTCScene sc, const struct ray_query *q, int n, int coherent, unsigned char *occ);

/* While set, every query of scene_rt.h calls hook with the rays it is about to trace, q[0 .. n-1],
 * all of one kind (enum ray_kind), from the tracing thread. */
typedef void (*scene_ray_hook)(void *user, const struct ray_query *q, int n, int kind);
/* Sets s's hook (NULL: none) and its user pointer; returns the user pointer it replaces. */
void *scene_rt_set_ray_hook(const struct scene *s, scene_ray_hook hook, void *user);

#endif
