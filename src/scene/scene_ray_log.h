/* scene_ray_log.h: ray logging and replay, used only by the benchmarks (restir_bench's pass
 * timing): while a log is active every ray query of the scene is recorded (per thread, no locks),
 * so that a frame's rays can be traced again through Embree alone, to separate ray-tracing time
 * from shading time, and in packets or streams, to measure what batching could save.
 * Must never be needed by the renderer: scene_rt.c only calls the hook this module sets. */
#ifndef RESTIR_SCENE_SCENE_RAY_LOG_H
#define RESTIR_SCENE_SCENE_RAY_LOG_H

#include <stddef.h>

#include "core/vec3.h"
#include "scene/scene_rt.h"
#include "scene/scene_types.h"

/* One logged ray: the query's origin, direction, interval and enum ray_kind (scene_rt.h). */
struct ray_record {
    vec3 o, d;
    float tmin, tmax;
    int kind;
};
/* Starts recording s's queries (anew, where a log is already active). */
void scene_ray_log_begin(const struct scene *s);
/* Stops logging and returns all recorded rays (malloc'ed, caller frees; thread 0's first, each
 * thread's in the order it traced them) and their count (0 where no log was active). Call it before
 * the scene is destroyed: the log's buffers are freed here. */
struct ray_record *scene_ray_log_end(const struct scene *s, size_t *count);
/* Traces the recorded rays again in parallel; returns the elapsed milliseconds. */
double scene_ray_replay(const struct scene *s, const struct ray_record *rays, size_t count);
/* The same rays traced in groups of consecutive same-kind rays (the order in which one thread
 * traced them): Embree packets of 8 / 16 or streams (rtcIntersect1M / rtcOccluded1M, groups of
 * 64, with the coherent or incoherent hint). Measures what batching a pass's rays could save. */
enum ray_batch {
    RAY_BATCH_SINGLE = 0,
    RAY_BATCH_PACKET8,
    RAY_BATCH_PACKET16,
    RAY_BATCH_STREAM,
    RAY_BATCH_STREAM_COHERENT,
    RAY_BATCH_COUNT
};
double scene_ray_replay_batched(const struct scene *s, const struct ray_record *rays, size_t count,
                                enum ray_batch batch);

#endif
