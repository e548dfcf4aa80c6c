/* scene_ray_log.c: ray logging and replay for the benchmarks (scene_ray_log.h): the log behind
 * scene_rt.c's hook, and the replay through Embree alone (scene_rt_embree.h), ray by ray, in
 * packets or in streams. Only the benchmarks use it. */
#include "scene/scene_ray_log.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_rt_embree.h"

#define RAY_LOG_MAX_THREADS 256

/* One thread's append-only part of the log. */
struct thread_log {
    struct ray_record *rays;
    size_t count, cap;
};

/* An active log: the hook's user pointer (scene_rt_set_ray_hook), allocated by
 * scene_ray_log_begin and freed by scene_ray_log_end. */
struct ray_log {
    struct thread_log thread[RAY_LOG_MAX_THREADS];
};

/* The hook: appends q[0 .. n-1] to the calling thread's log. */
static void record_rays(void *user, const struct ray_query *q, int n, int kind)
{
    int t = omp_get_thread_num();
    if (t >= RAY_LOG_MAX_THREADS)
        return;
    struct thread_log *lg = &((struct ray_log *)user)->thread[t];
    for (int k = 0; k < n; k++) {
        if (lg->count == lg->cap) {
            lg->cap = lg->cap ? 2 * lg->cap : 4096;
            struct ray_record *grown = realloc(lg->rays, lg->cap * sizeof(*lg->rays));
            RESTIR_CHECK(grown != NULL);
            lg->rays = grown;
        }
        lg->rays[lg->count++] = (struct ray_record){q[k].o, q[k].d, q[k].tmin, q[k].tmax, kind};
    }
}

void scene_ray_log_begin(const struct scene *s)
{
    struct ray_log *log = scene_rt_set_ray_hook(s, NULL, NULL);
    if (log) /* already active: start over, keeping the buffers */
        for (int t = 0; t < RAY_LOG_MAX_THREADS; t++)
            log->thread[t].count = 0;
    else
        log = xcalloc(1, sizeof(*log));
    scene_rt_set_ray_hook(s, record_rays, log);
}

struct ray_record *scene_ray_log_end(const struct scene *s, size_t *count)
{
    struct ray_log *log = scene_rt_set_ray_hook(s, NULL, NULL);
    size_t n = 0;
    for (int t = 0; log && t < RAY_LOG_MAX_THREADS; t++)
        n += log->thread[t].count;
    struct ray_record *all = xmalloc(sizeof(*all) * (n ? n : 1));
    size_t k = 0;
    for (int t = 0; log && t < RAY_LOG_MAX_THREADS; t++) {
        struct thread_log *lg = &log->thread[t];
        if (lg->count)
            memcpy(all + k, lg->rays, lg->count * sizeof(*all));
        k += lg->count;
        free(lg->rays);
    }
    free(log);
    *count = n;
    return all;
}

/* The Embree scene and triangle map that answer each kind of ray (enum ray_kind). */
struct targets {
    RTCScene scene[3];
    int *const *geom_tris[3];
};

static struct targets targets_of(const struct scene *s)
{
    struct targets tg;
    for (int kind = 0; kind < 3; kind++)
        tg.scene[kind] = scene_rt_embree(s, kind, &tg.geom_tris[kind]);
    return tg;
}

double scene_ray_replay(const struct scene *s, const struct ray_record *rays, size_t count)
{
    const struct targets tg = targets_of(s);
    long long hits = 0;
    double t0 = omp_get_wtime();
#pragma omp parallel for schedule(dynamic, 4096) reduction(+ : hits)
    for (long long i = 0; i < (long long)count; i++) {
        const struct ray_record *r = &rays[i];
        float t, u, v;
        if (r->kind == RAY_OCCLUDED)
            hits += scene_rt_occluded(tg.scene[r->kind], r->o, r->d, r->tmin, r->tmax);
        else
            hits += scene_rt_closest(tg.scene[r->kind], tg.geom_tris[r->kind], r->o, r->d, r->tmin, r->tmax, &t, &u,
                                     &v) >= 0;
    }
    (void)hits;
    return 1e3 * (omp_get_wtime() - t0);
}

/* One group of same-kind rays (at most 16 for packets, 64 for streams) traced through Embree in one
 * call; returns the number of hits / occluded rays. */
#define RAY_GROUP_MAX RAY_STREAM_MAX
static long long trace_group(const struct targets *tg, const struct ray_record *r, int n, enum ray_batch batch)
{
    RTCScene sc = tg->scene[r[0].kind];
    const int occ = r[0].kind == RAY_OCCLUDED;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    long long hits = 0;
    if (batch == RAY_BATCH_PACKET8 || batch == RAY_BATCH_PACKET16) {
        /* RTCRayHit16's and RTCRay16's leading members are the ray's SoA arrays, 16 wide; the 8-wide
         * structs have the same layout at width 8: fill both through one SoA float view. */
        RTC_ALIGN(64) struct RTCRayHit16 rh;
        RTC_ALIGN(64) int valid[16];
        const int w = batch == RAY_BATCH_PACKET8 ? 8 : 16;
        float *f = (float *)&rh;
        unsigned *u = (unsigned *)&rh;
        for (int i = 0; i < w; i++) {
            const struct ray_record *q = &r[i < n ? i : 0];
            valid[i] = i < n ? -1 : 0;
            f[0 * w + i] = q->o.x, f[1 * w + i] = q->o.y, f[2 * w + i] = q->o.z, f[3 * w + i] = q->tmin;
            f[4 * w + i] = q->d.x, f[5 * w + i] = q->d.y, f[6 * w + i] = q->d.z, f[7 * w + i] = 0.0f;
            f[8 * w + i] = q->tmax;
            u[9 * w + i] = 0xffffffffu, u[10 * w + i] = 0, u[11 * w + i] = 0;
            u[18 * w + i] = RTC_INVALID_GEOMETRY_ID; /* hit.geomID: after 12 ray arrays, Ng xyz, u, v, primID */
        }
        if (w == 8) {
            if (occ)
                rtcOccluded8(valid, sc, &ctx, (struct RTCRay8 *)&rh);
            else
                rtcIntersect8(valid, sc, &ctx, (struct RTCRayHit8 *)&rh);
        } else {
            if (occ)
                rtcOccluded16(valid, sc, &ctx, &rh.ray);
            else
                rtcIntersect16(valid, sc, &ctx, &rh);
        }
        for (int i = 0; i < n; i++)
            hits += occ ? f[8 * w + i] == -INFINITY : u[18 * w + i] != RTC_INVALID_GEOMETRY_ID;
        return hits;
    }
    const int coherent = batch == RAY_BATCH_STREAM_COHERENT;
    struct ray_query rq[RAY_STREAM_MAX];
    for (int i = 0; i < n; i++)
        rq[i] = (struct ray_query){r[i].o, r[i].d, r[i].tmin, r[i].tmax};
    if (occ) {
        unsigned char o[RAY_STREAM_MAX];
        scene_rt_occluded_stream(sc, rq, n, coherent, o);
        for (int i = 0; i < n; i++)
            hits += o[i];
    } else {
        int tri[RAY_STREAM_MAX];
        float t[RAY_STREAM_MAX], u[RAY_STREAM_MAX], v[RAY_STREAM_MAX];
        scene_rt_closest_stream(sc, tg->geom_tris[r[0].kind], rq, n, coherent, tri, t, u, v);
        for (int i = 0; i < n; i++)
            hits += tri[i] >= 0;
    }
    return hits;
}

double scene_ray_replay_batched(const struct scene *s, const struct ray_record *rays, size_t count,
                                enum ray_batch batch)
{
    if (batch == RAY_BATCH_SINGLE)
        return scene_ray_replay(s, rays, count);
    const struct targets tg = targets_of(s);
    const int w = batch == RAY_BATCH_PACKET8 ? 8 : batch == RAY_BATCH_PACKET16 ? 16 : RAY_GROUP_MAX;
    const long long chunk = 4096, nchunks = ((long long)count + chunk - 1) / chunk;
    long long hits = 0;
    double t0 = omp_get_wtime();
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : hits)
    for (long long c = 0; c < nchunks; c++) {
        const long long end = (c + 1) * chunk < (long long)count ? (c + 1) * chunk : (long long)count;
        for (long long i = c * chunk; i < end;) {
            int n = 1;
            while (n < w && i + n < end && rays[i + n].kind == rays[i].kind)
                n++;
            hits += trace_group(&tg, &rays[i], n, batch);
            i += n;
        }
    }
    (void)hits;
    return 1e3 * (omp_get_wtime() - t0);
}
