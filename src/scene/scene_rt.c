/* scene_rt.c: the Embree 3 back end: the BVH over the scene's triangles, closest-hit and occlusion
 * queries. The only file that includes embree3/rtcore.h; must never expose its types. */
#include "scene/scene_rt.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_surface.h"

/* Per-thread append-only ray log (benchmarks only). */
struct ray_log {
    struct ray_record *rays;
    size_t count, cap;
};

#define RAY_LOG_MAX_THREADS 256

/* What an alpha filter needs: a shallow copy of the finished scene (its arrays do not move after
 * the build, while the struct itself may be copied by its owner) and, per primitive, what the
 * alpha test reads of its triangle (one cache line: the test runs for every candidate hit on a
 * masked triangle, several per ray through a tree's crown). */
struct alpha_filter {
    struct scene s;
    struct alpha_tri *tris;
};

struct scene_rt {
    int logging;
    int streams; /* scene_ray_streams */
    struct alpha_filter alpha_masked, alpha_emitters;
    /* The main scene holds the opaque triangles as geometry 0 and, where some material is
     * alpha-masked, the masked ones as geometry 1, so that only hits on those call the filter.
     * geom_tris[g][primID] is the triangle (NULL: primID is the triangle). */
    int *geom_tris[2];
    struct ray_log logs[RAY_LOG_MAX_THREADS];
    RTCDevice device;
    RTCScene scene;
    RTCScene emitters; /* emissive triangles only (NULL without lights); primID = emitter index */
};

static void embree_error(void *user, enum RTCError code, const char *str)
{
    (void)user;
    fprintf(stderr, "embree error %d: %s\n", (int)code, str ? str : "");
}

/* Embree filter (intersection and occlusion): a candidate hit on a cut-out texel of an
 * alpha-masked material is rejected, so every ray (camera, BSDF, NEE, shadow, every shift's
 * replay and reconnection) passes through it as if it were not there (glTF alphaMode MASK). */
static void alpha_filter(const struct RTCFilterFunctionNArguments *args)
{
    const struct alpha_filter *f = args->geometryUserPtr;
    /* RTCHitN is N-wide structure of arrays: Ng x, y, z, u, v, primID, ... (rtcore_ray.h; its
     * accessors are C++ only) */
    const unsigned n = args->N;
    const float *hf = (const float *)args->hit;
    const unsigned *hu = (const unsigned *)args->hit;
    for (unsigned i = 0; i < n; i++) {
        if (args->valid[i] != -1)
            continue;
        if (scene_alpha_cut_tri(&f->s, &f->tris[hu[5 * n + i]], hf[3 * n + i], hf[4 * n + i]))
            args->valid[i] = 0;
    }
}

/* Attaches triangles tris[0 .. count-1] of s (NULL: all, in order) to scene as geometry id, with
 * the alpha filter when filter is not NULL. Returns 0, or -1 when Embree cannot allocate. */
static int attach_triangles(RTCDevice device, RTCScene scene, unsigned id, const struct scene *s, const int *tris,
                            int count, struct alpha_filter *filter)
{
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                        3 * (size_t)count);
    unsigned *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)count);
    if (!vb || !ib) {
        rtcReleaseGeometry(geom);
        return -1;
    }
    /* Un-indexed copy: three vertices per triangle, in the order of tris[] (or all triangles). */
    for (int i = 0; i < count; i++) {
        int t = tris ? tris[i] : i;
        for (int k = 0; k < 3; k++) {
            vec3 v = s->verts[s->indices[3 * t + k]];
            vb[9 * i + 3 * k + 0] = v.x;
            vb[9 * i + 3 * k + 1] = v.y;
            vb[9 * i + 3 * k + 2] = v.z;
            ib[3 * i + k] = (unsigned)(3 * i + k);
        }
    }
    if (filter) {
        filter->s = *s;
        filter->tris = aligned_alloc(32, sizeof(struct alpha_tri) * (size_t)count);
        if (!filter->tris) {
            rtcReleaseGeometry(geom);
            return -1;
        }
        for (int i = 0; i < count; i++)
            scene_alpha_tri(s, tris ? tris[i] : i, &filter->tris[i]);
        rtcSetGeometryUserData(geom, filter);
        rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
        rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, id);
    rtcReleaseGeometry(geom);
    return 0;
}

static RTCScene new_scene(RTCDevice device)
{
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    return scene;
}

/* The main scene: all triangles as one geometry when nothing is masked, else the opaque ones
 * (geometry 0) apart from the masked ones (geometry 1, filtered). */
static RTCScene build_main(struct scene_rt *rt, const struct scene *s)
{
    int masked = 0;
    for (int t = 0; t < s->num_tris; t++)
        masked += s->materials[s->tri_material[t]].alpha_mask != 0;
    RTCScene scene = new_scene(rt->device);
    int rc = 0;
    if (masked == 0) {
        rc = attach_triangles(rt->device, scene, 0, s, NULL, s->num_tris, NULL);
    } else {
        const int opaque = s->num_tris - masked;
        rt->geom_tris[0] = xmalloc(sizeof(int) * (size_t)(opaque > 0 ? opaque : 1));
        rt->geom_tris[1] = xmalloc(sizeof(int) * (size_t)masked);
        int n[2] = {0, 0};
        for (int t = 0; t < s->num_tris; t++) {
            const int g = s->materials[s->tri_material[t]].alpha_mask != 0;
            rt->geom_tris[g][n[g]++] = t;
        }
        if (opaque > 0)
            rc = attach_triangles(rt->device, scene, 0, s, rt->geom_tris[0], opaque, NULL);
        if (rc == 0)
            rc = attach_triangles(rt->device, scene, 1, s, rt->geom_tris[1], masked, &rt->alpha_masked);
    }
    if (rc != 0) {
        rtcReleaseScene(scene);
        return NULL;
    }
    rtcCommitScene(scene);
    return scene;
}

/* The emissive triangles alone (primID = emitter index), filtered when any material is masked. */
static RTCScene build_emitters(struct scene_rt *rt, const struct scene *s, int masked)
{
    RTCScene scene = new_scene(rt->device);
    if (attach_triangles(rt->device, scene, 0, s, s->emitter_tri, s->num_emitters,
                         masked ? &rt->alpha_emitters : NULL) != 0) {
        rtcReleaseScene(scene);
        return NULL;
    }
    rtcCommitScene(scene);
    return scene;
}

int scene_rt_build(struct scene *s, char *msg)
{
    struct scene_rt *rt = xcalloc(1, sizeof(*rt));
    rt->device = rtcNewDevice(NULL);
    if (!rt->device) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': Embree device creation failed (error %d)", s->name,
                 (int)rtcGetDeviceError(NULL));
        free(rt);
        return -1;
    }
    rtcSetDeviceErrorFunction(rt->device, embree_error, NULL);
    rt->streams = 1;
    int masked = 0; /* filters only where some material is alpha-masked: they cost every hit a call */
    for (int m = 0; m < s->num_materials; m++)
        masked |= s->materials[m].alpha_mask;
    rt->scene = build_main(rt, s);
    rt->emitters = s->num_emitters > 0 ? build_emitters(rt, s, masked) : NULL;
    if (!rt->scene || (s->num_emitters > 0 && !rt->emitters)) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': Embree BVH construction failed", s->name);
        if (rt->scene)
            rtcReleaseScene(rt->scene);
        rtcReleaseDevice(rt->device);
        free(rt->geom_tris[0]);
        free(rt->geom_tris[1]);
        free(rt->alpha_masked.tris);
        free(rt->alpha_emitters.tris);
        free(rt);
        return -1;
    }
    s->rt = rt;
    return 0;
}

void scene_rt_destroy(struct scene *s)
{
    if (!s->rt)
        return;
    for (int t = 0; t < RAY_LOG_MAX_THREADS; t++)
        free(s->rt->logs[t].rays);
    rtcReleaseScene(s->rt->scene);
    if (s->rt->emitters)
        rtcReleaseScene(s->rt->emitters);
    rtcReleaseDevice(s->rt->device);
    free(s->rt->geom_tris[0]);
    free(s->rt->geom_tris[1]);
    free(s->rt->alpha_masked.tris);
    free(s->rt->alpha_emitters.tris);
    free(s->rt);
    s->rt = NULL;
}

static void log_ray(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax, int kind)
{
    int t = omp_get_thread_num();
    if (t >= RAY_LOG_MAX_THREADS)
        return;
    struct ray_log *lg = &s->rt->logs[t];
    if (lg->count == lg->cap) {
        lg->cap = lg->cap ? 2 * lg->cap : 4096;
        struct ray_record *grown = realloc(lg->rays, lg->cap * sizeof(*lg->rays));
        RESTIR_CHECK(grown != NULL);
        lg->rays = grown;
    }
    lg->rays[lg->count++] = (struct ray_record){o, d, tmin, tmax, kind};
}

/* Closest hit in rtc_scene; returns the triangle (geom_tris[geomID][primID], or primID where
 * geom_tris or its entry is NULL) or -1, with the distance and barycentrics. */
static int intersect_closest(RTCScene rtc_scene, int *const *geom_tris, vec3 o, vec3 d, float tmin, float tmax,
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
    rtcIntersect1(rtc_scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return -1;
    *t = rh.ray.tfar;
    *u = rh.hit.u;
    *v = rh.hit.v;
    const int *map = geom_tris ? geom_tris[rh.hit.geomID] : NULL;
    return map ? map[rh.hit.primID] : (int)rh.hit.primID;
}

void scene_surface_at(const struct scene *s, int tri, float b1, float b2, vec3 p, vec3 d, struct surface_hit *hit)
{
    vec3 n = s->tri_normal[tri];
    hit->t = 0.0f;
    hit->p = p;
    hit->front = v3_dot(n, d) < 0.0f;
    hit->ng = hit->front ? n : v3_neg(n);
    hit->ns = scene_shading_normal(s, tri, b1, b2, hit->ng);
    hit->tri = tri;
    hit->b1 = b1;
    hit->b2 = b2;
    hit->material = s->tri_material[tri];
    hit->object = s->tri_object[tri];
}

static void fill_hit(const struct scene *s, int tri, vec3 o, vec3 d, float t, float u, float v,
                     struct surface_hit *hit)
{
    scene_surface_at(s, tri, u, v, v3_madd(o, d, t), d, hit);
    hit->t = t;
}

int scene_intersect(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax, struct surface_hit *hit)
{
    float t, u, v;
    if (s->rt->logging)
        log_ray(s, o, d, tmin, tmax, RAY_CLOSEST);
    int tri = intersect_closest(s->rt->scene, s->rt->geom_tris, o, d, tmin, tmax, &t, &u, &v);
    if (tri < 0)
        return 0;
    fill_hit(s, tri, o, d, t, u, v, hit);
    return 1;
}

int scene_intersect_emitters(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax,
                             struct surface_hit *hit)
{
    if (!s->rt->emitters)
        return 0;
    float t, u, v;
    if (s->rt->logging)
        log_ray(s, o, d, tmin, tmax, RAY_EMITTERS);
    int e = intersect_closest(s->rt->emitters, NULL, o, d, tmin, tmax, &t, &u, &v);
    if (e < 0)
        return 0;
    fill_hit(s, s->emitter_tri[e], o, d, t, u, v, hit);
    return 1;
}

static int occluded(RTCScene rtc_scene, vec3 o, vec3 d, float tmin, float tmax)
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
    rtcOccluded1(rtc_scene, &ctx, &ray);
    return ray.tfar == -INFINITY;
}

int scene_occluded(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax)
{
    if (s->rt->logging)
        log_ray(s, o, d, tmin, tmax, RAY_OCCLUDED);
    return occluded(s->rt->scene, o, d, tmin, tmax);
}

void scene_ray_log_begin(const struct scene *s)
{
    for (int t = 0; t < RAY_LOG_MAX_THREADS; t++)
        s->rt->logs[t].count = 0;
    s->rt->logging = 1;
}

struct ray_record *scene_ray_log_end(const struct scene *s, size_t *count)
{
    s->rt->logging = 0;
    size_t n = 0;
    for (int t = 0; t < RAY_LOG_MAX_THREADS; t++)
        n += s->rt->logs[t].count;
    struct ray_record *all = xmalloc(sizeof(*all) * (n ? n : 1));
    size_t k = 0;
    for (int t = 0; t < RAY_LOG_MAX_THREADS; t++) {
        struct ray_log *lg = &s->rt->logs[t];
        if (lg->count)
            memcpy(all + k, lg->rays, lg->count * sizeof(*all));
        k += lg->count;
    }
    *count = n;
    return all;
}

double scene_ray_replay(const struct scene *s, const struct ray_record *rays, size_t count)
{
    long long hits = 0;
    double t0 = omp_get_wtime();
#pragma omp parallel for schedule(dynamic, 4096) reduction(+ : hits)
    for (long long i = 0; i < (long long)count; i++) {
        const struct ray_record *r = &rays[i];
        float t, u, v;
        if (r->kind == RAY_OCCLUDED)
            hits += occluded(s->rt->scene, r->o, r->d, r->tmin, r->tmax);
        else
            hits += intersect_closest(r->kind == RAY_EMITTERS ? s->rt->emitters : s->rt->scene,
                                      r->kind == RAY_EMITTERS ? NULL : s->rt->geom_tris, r->o, r->d, r->tmin, r->tmax,
                                      &t, &u, &v) >= 0;
    }
    (void)hits;
    return 1e3 * (omp_get_wtime() - t0);
}

/* Embree's stream calls take at most this many rays per call here (stack arrays). */
#define RAY_STREAM_MAX 64

static void fill_ray(struct RTCRay *ray, const struct ray_query *q)
{
    ray->org_x = q->o.x;
    ray->org_y = q->o.y;
    ray->org_z = q->o.z;
    ray->tnear = q->tmin;
    ray->dir_x = q->d.x;
    ray->dir_y = q->d.y;
    ray->dir_z = q->d.z;
    ray->time = 0.0f;
    ray->tfar = q->tmax;
    ray->mask = 0xffffffffu;
    ray->id = 0;
    ray->flags = 0;
}

/* Closest hits of q[0 .. n-1] (n <= RAY_STREAM_MAX) in rtc_scene through one rtcIntersect1M call:
 * tri[k] as intersect_closest returns it, with t, u, v. */
static void intersect_stream(RTCScene rtc_scene, int *const *geom_tris, const struct ray_query *q, int n, int coherent,
                             int *tri, float *t, float *u, float *v)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRayHit rh[RAY_STREAM_MAX];
    for (int k = 0; k < n; k++) {
        fill_ray(&rh[k].ray, &q[k]);
        rh[k].hit.geomID = rh[k].hit.primID = rh[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(rtc_scene, &ctx, rh, (unsigned)n, sizeof(rh[0]));
    for (int k = 0; k < n; k++) {
        tri[k] = -1;
        if (rh[k].hit.geomID == RTC_INVALID_GEOMETRY_ID)
            continue;
        const int *map = geom_tris ? geom_tris[rh[k].hit.geomID] : NULL;
        tri[k] = map ? map[rh[k].hit.primID] : (int)rh[k].hit.primID;
        t[k] = rh[k].ray.tfar;
        u[k] = rh[k].hit.u;
        v[k] = rh[k].hit.v;
    }
}

/* Occlusion of q[0 .. n-1] (n <= RAY_STREAM_MAX) through one rtcOccluded1M call. */
static void occluded_stream(RTCScene rtc_scene, const struct ray_query *q, int n, int coherent, unsigned char *occ)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRay ray[RAY_STREAM_MAX];
    for (int k = 0; k < n; k++)
        fill_ray(&ray[k], &q[k]);
    rtcOccluded1M(rtc_scene, &ctx, ray, (unsigned)n, sizeof(ray[0]));
    for (int k = 0; k < n; k++)
        occ[k] = ray[k].tfar == -INFINITY;
}

void scene_ray_streams(const struct scene *s, int on)
{
    s->rt->streams = on;
}

void scene_intersect_batch(const struct scene *s, const struct ray_query *q, int n, int coherent,
                           struct surface_hit *hits, unsigned char *hit)
{
    if (!s->rt->streams) {
        for (int k = 0; k < n; k++)
            hit[k] = (unsigned char)scene_intersect(s, q[k].o, q[k].d, q[k].tmin, q[k].tmax, &hits[k]);
        return;
    }
    for (int first = 0; first < n; first += RAY_STREAM_MAX) {
        const int m = n - first < RAY_STREAM_MAX ? n - first : RAY_STREAM_MAX;
        int tri[RAY_STREAM_MAX];
        float t[RAY_STREAM_MAX], u[RAY_STREAM_MAX], v[RAY_STREAM_MAX];
        if (s->rt->logging)
            for (int k = 0; k < m; k++)
                log_ray(s, q[first + k].o, q[first + k].d, q[first + k].tmin, q[first + k].tmax, RAY_CLOSEST);
        intersect_stream(s->rt->scene, s->rt->geom_tris, q + first, m, coherent, tri, t, u, v);
        for (int k = 0; k < m; k++) {
            const struct ray_query *r = &q[first + k];
            hit[first + k] = tri[k] >= 0;
            if (tri[k] >= 0)
                fill_hit(s, tri[k], r->o, r->d, t[k], u[k], v[k], &hits[first + k]);
        }
    }
}

void scene_occluded_batch(const struct scene *s, const struct ray_query *q, int n, unsigned char *occluded)
{
    if (!s->rt->streams) {
        for (int k = 0; k < n; k++)
            occluded[k] = (unsigned char)scene_occluded(s, q[k].o, q[k].d, q[k].tmin, q[k].tmax);
        return;
    }
    for (int first = 0; first < n; first += RAY_STREAM_MAX) {
        const int m = n - first < RAY_STREAM_MAX ? n - first : RAY_STREAM_MAX;
        if (s->rt->logging)
            for (int k = 0; k < m; k++)
                log_ray(s, q[first + k].o, q[first + k].d, q[first + k].tmin, q[first + k].tmax, RAY_OCCLUDED);
        occluded_stream(s->rt->scene, q + first, m, 0, occluded + first);
    }
}

/* One group of same-kind rays (at most 16 for packets, 64 for streams) traced through Embree in one
 * call; returns the number of hits / occluded rays. */
#define RAY_GROUP_MAX RAY_STREAM_MAX
static long long trace_group(const struct scene *s, const struct ray_record *r, int n, enum ray_batch batch)
{
    RTCScene sc = r[0].kind == RAY_EMITTERS ? s->rt->emitters : s->rt->scene;
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
        occluded_stream(sc, rq, n, coherent, o);
        for (int i = 0; i < n; i++)
            hits += o[i];
    } else {
        int tri[RAY_STREAM_MAX];
        float t[RAY_STREAM_MAX], u[RAY_STREAM_MAX], v[RAY_STREAM_MAX];
        intersect_stream(sc, r[0].kind == RAY_EMITTERS ? NULL : s->rt->geom_tris, rq, n, coherent, tri, t, u, v);
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
            hits += trace_group(s, &rays[i], n, batch);
            i += n;
        }
    }
    (void)hits;
    return 1e3 * (omp_get_wtime() - t0);
}

/* Offset scale for self-intersection: relative to the coordinates' magnitude, so it tracks float
 * precision whatever the scene's size. */
static float ray_epsilon(vec3 p)
{
    return 1e-4f * (1.0f + max_f(fabsf(p.x), max_f(fabsf(p.y), fabsf(p.z)))); /* not fmaxf: a libm call */
}

vec3 scene_offset_point(vec3 p, vec3 n, vec3 toward)
{
    float e = ray_epsilon(p);
    return v3_madd(p, n, v3_dot(n, toward) >= 0.0f ? e : -e);
}

int scene_visibility_query(vec3 p0, vec3 n0, vec3 p1, vec3 n1, struct ray_query *q)
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

int scene_visible(const struct scene *s, vec3 p0, vec3 n0, vec3 p1, vec3 n1)
{
    struct ray_query q;
    if (!scene_visibility_query(p0, n0, p1, n1, &q))
        return 1;
    return !scene_occluded(s, q.o, q.d, q.tmin, q.tmax);
}
