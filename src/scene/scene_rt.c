/* scene_rt.c: the Embree 3 back end: the BVH over the scene's triangles, closest-hit and occlusion
 * queries. With the benchmarks' ray replay (scene_ray_log.c, through scene_rt_embree.h) the only
 * file that includes embree3/rtcore.h; must never expose its types. */
#include "scene/scene_rt.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "scene/scene_rt_embree.h"
#include "scene/scene_surface.h"

/* What an alpha filter needs: a shallow copy of the finished scene (its arrays do not move after
 * the build, while the struct itself may be copied by its owner) and, per primitive, what the
 * alpha test reads of its triangle (one cache line: the test runs for every candidate hit on a
 * masked triangle, several per ray through a tree's crown). */
struct alpha_filter {
    struct scene s;
    struct alpha_tri *tris;
};

struct scene_rt {
    scene_ray_hook hook; /* the ray log's (scene_rt_embree.h), NULL unless a benchmark logs */
    void *hook_user;
    int streams; /* scene_set_ray_streams; set at load from scene_load_desc.ray_streams_off */
    struct alpha_filter alpha_masked, alpha_emitters, alpha_moving, alpha_previous;
    /* The main scene holds the opaque triangles as geometry 0 and, where some material is
     * alpha-masked, the masked ones as geometry 1, so that only hits on those call the filter, and
     * the moving emitters' as geometry 2 (build_main). geom_tris[g][primID] is the triangle (NULL:
     * primID is the triangle). */
    int *geom_tris[3];
    int num_moving; /* triangles in geometry 2 */
    RTCDevice device;
    RTCScene scene;
    RTCScene emitters; /* emissive triangles only (NULL without lights); primID = emitter index */
    /* The moving emitters' triangles alone where an earlier frame had them (scene_rt_update_previous),
     * for scene_occluded_previous_batch; NULL where nothing moves or Embree has no ray masks. */
    RTCScene previous;
};

/* The main scene's geometry masks where emitters move: a ray whose mask is MASK_STILL sees every
 * triangle but the moving ones (scene_occluded_previous_batch), the others' (all bits) see all. */
#define MASK_STILL 1u
#define MASK_MOVING 2u

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

/* The un-indexed vertex buffer of triangles tris[0 .. count-1] of s (NULL: all, in order) where s->verts
 * has them now: three vertices per triangle. */
static void copy_vertices(float *vb, const struct scene *s, const int *tris, int count)
{
    for (int i = 0; i < count; i++) {
        const int t = tris ? tris[i] : i;
        for (int k = 0; k < 3; k++) {
            const vec3 v = s->verts[s->indices[3 * t + k]];
            vb[9 * i + 3 * k + 0] = v.x;
            vb[9 * i + 3 * k + 1] = v.y;
            vb[9 * i + 3 * k + 2] = v.z;
        }
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
    copy_vertices(vb, s, tris, count);
    for (int i = 0; i < 3 * count; i++)
        ib[i] = (unsigned)i;
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

/* Geometry id of scene gets a BVH of its own built at `quality` (RTC_BUILD_QUALITY_REFIT: refitted when
 * its vertices move). Embree reads a geometry's quality only in a scene of low build quality, whose
 * commit builds a two-level BVH: each geometry's own, rebuilt only when it changed, under a quickly
 * built top level (Embree 3's rtcSetGeometryBuildQuality). */
static void set_quality(RTCScene scene, unsigned id, enum RTCBuildQuality quality, unsigned mask)
{
    RTCGeometry geom = rtcGetGeometry(scene, id);
    rtcSetGeometryBuildQuality(geom, quality);
    rtcSetGeometryMask(geom, mask);
    rtcCommitGeometry(geom);
}

/* A scene whose geometries keep their own BVHs (set_quality), for one that holds moving emitters. */
static void make_two_level(RTCScene scene)
{
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_LOW);
}

/* The main scene's geometries (struct scene_rt's geom_tris). */
enum { GEOM_OPAQUE, GEOM_MASKED, GEOM_MOVING, GEOM_COUNT };

static int tri_masked(const struct scene *s, int t) { return s->materials[s->tri_material[t]].alpha_mask != 0; }

/* The main scene: all triangles as one geometry when nothing is masked or moves, else the opaque
 * ones (geometry 0) apart from the masked ones (geometry 1, filtered) and the moving emitters'
 * (geometry 2, filtered where one of them is masked); with moving emitters a two-level scene whose
 * commit keeps the still geometries' BVHs and refits the moving one's (scene_rt_update_moving). */
static RTCScene build_main(struct scene_rt *rt, const struct scene *s, const int *moving_tris, int moving)
{
    int n[GEOM_COUNT] = {0, 0, 0}, moving_masked = 0;
    for (int t = 0, i = 0; t < s->num_tris; t++) {
        if (i < moving && moving_tris[i] == t) {
            n[GEOM_MOVING]++, i++;
            moving_masked |= tri_masked(s, t);
        } else {
            n[tri_masked(s, t) ? GEOM_MASKED : GEOM_OPAQUE]++;
        }
    }
    RTCScene scene = new_scene(rt->device);
    int rc = 0;
    if (n[GEOM_MASKED] == 0 && moving == 0) {
        rc = attach_triangles(rt->device, scene, 0, s, NULL, s->num_tris, NULL);
    } else {
        if (moving > 0)
            make_two_level(scene);
        for (int g = 0; g < GEOM_COUNT; g++)
            rt->geom_tris[g] = xmalloc(sizeof(int) * (size_t)(n[g] > 0 ? n[g] : 1));
        int at[GEOM_COUNT] = {0, 0, 0};
        for (int t = 0, i = 0; t < s->num_tris; t++) {
            const int g = i < moving && moving_tris[i] == t ? (i++, GEOM_MOVING) : tri_masked(s, t);
            rt->geom_tris[g][at[g]++] = t;
        }
        struct alpha_filter *filter[GEOM_COUNT] = {NULL, &rt->alpha_masked,
                                                   moving_masked ? &rt->alpha_moving : NULL};
        for (int g = 0; g < GEOM_COUNT && rc == 0; g++)
            if (n[g] > 0)
                rc = attach_triangles(rt->device, scene, (unsigned)g, s, rt->geom_tris[g], n[g], filter[g]);
        for (int g = 0; g < GEOM_COUNT && rc == 0 && moving > 0; g++)
            if (n[g] > 0)
                set_quality(scene, (unsigned)g, g == GEOM_MOVING ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_HIGH,
                            g == GEOM_MOVING ? MASK_MOVING : MASK_STILL);
        rt->num_moving = moving;
    }
    if (rc != 0) {
        rtcReleaseScene(scene);
        return NULL;
    }
    rtcCommitScene(scene);
    return scene;
}

/* Writes triangles tris[0 .. count-1] of s (NULL: all) where they are now into geometry id of scene
 * and commits the geometry (the scene's commit is the caller's). */
static void update_vertices(RTCScene scene, unsigned id, const struct scene *s, const int *tris, int count)
{
    RTCGeometry geom = rtcGetGeometry(scene, id);
    copy_vertices(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0), s, tris, count);
    rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geom);
}

void scene_rt_update_moving(struct scene *s)
{
    struct scene_rt *rt = s->rt;
    if (!rt || rt->num_moving == 0)
        return;
    update_vertices(rt->scene, GEOM_MOVING, s, rt->geom_tris[GEOM_MOVING], rt->num_moving);
    rtcCommitScene(rt->scene);
    if (rt->emitters) { /* none where every emitter's emission is 0 (an environment lights the scene) */
        update_vertices(rt->emitters, 0, s, s->emitter_tri, s->num_emitters);
        rtcCommitScene(rt->emitters);
    }
}

/* The emissive triangles alone (primID = emitter index), filtered when any material is masked; refitted
 * when some of them move. */
static RTCScene build_emitters(struct scene_rt *rt, const struct scene *s, int masked)
{
    RTCScene scene = new_scene(rt->device);
    if (rt->num_moving > 0)
        make_two_level(scene);
    if (attach_triangles(rt->device, scene, 0, s, s->emitter_tri, s->num_emitters,
                         masked ? &rt->alpha_emitters : NULL) != 0) {
        rtcReleaseScene(scene);
        return NULL;
    }
    if (rt->num_moving > 0)
        set_quality(scene, 0, RTC_BUILD_QUALITY_REFIT, ~0u);
    rtcCommitScene(scene);
    return scene;
}

/* The moving emitters' triangles alone (primID = their index in geom_tris[GEOM_MOVING]), filtered
 * where one of them is alpha-masked, refitted when scene_rt_update_previous poses them. */
static RTCScene build_previous(struct scene_rt *rt, const struct scene *s)
{
    RTCScene scene = new_scene(rt->device);
    make_two_level(scene);
    if (attach_triangles(rt->device, scene, 0, s, rt->geom_tris[GEOM_MOVING], rt->num_moving,
                         rt->alpha_moving.tris ? &rt->alpha_previous : NULL) != 0) {
        rtcReleaseScene(scene);
        return NULL;
    }
    set_quality(scene, 0, RTC_BUILD_QUALITY_REFIT, ~0u);
    rtcCommitScene(scene);
    return scene;
}

void scene_rt_update_previous(const struct scene *s, const vec3 *corners)
{
    const struct scene_rt *rt = s->rt;
    if (!rt || !rt->previous)
        return;
    RTCGeometry geom = rtcGetGeometry(rt->previous, 0);
    float *vb = rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0);
    for (int i = 0; i < 3 * rt->num_moving; i++) {
        vb[3 * i + 0] = corners[i].x;
        vb[3 * i + 1] = corners[i].y;
        vb[3 * i + 2] = corners[i].z;
    }
    rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geom);
    rtcCommitScene(rt->previous);
}

int scene_can_trace_previous(const struct scene *s) { return s->rt && s->rt->previous != NULL; }

static void rt_free(struct scene_rt *rt)
{
    for (int g = 0; g < GEOM_COUNT; g++)
        free(rt->geom_tris[g]);
    free(rt->alpha_masked.tris);
    free(rt->alpha_emitters.tris);
    free(rt->alpha_moving.tris);
    free(rt->alpha_previous.tris);
    free(rt);
}

int scene_rt_build(struct scene *s, const int *moving_tris, int moving, char *msg)
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
    rt->scene = build_main(rt, s, moving_tris, moving);
    rt->emitters = s->num_emitters > 0 ? build_emitters(rt, s, masked) : NULL;
    /* without ray masks (an Embree built without them) the previous frame's geometry cannot be
     * traced, and the methods that would need it go without (scene_can_trace_previous) */
    const int masks = rtcGetDeviceProperty(rt->device, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 0;
    rt->previous = rt->scene && rt->num_moving > 0 && masks ? build_previous(rt, s) : NULL;
    if (!rt->scene || (s->num_emitters > 0 && !rt->emitters) || (rt->num_moving > 0 && masks && !rt->previous)) {
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': Embree BVH construction failed", s->name);
        if (rt->scene)
            rtcReleaseScene(rt->scene);
        if (rt->emitters)
            rtcReleaseScene(rt->emitters);
        if (rt->previous)
            rtcReleaseScene(rt->previous);
        rtcReleaseDevice(rt->device);
        rt_free(rt);
        return -1;
    }
    s->rt = rt;
    return 0;
}

void scene_rt_destroy(struct scene *s)
{
    if (!s->rt)
        return;
    rtcReleaseScene(s->rt->scene);
    if (s->rt->emitters)
        rtcReleaseScene(s->rt->emitters);
    if (s->rt->previous)
        rtcReleaseScene(s->rt->previous);
    rtcReleaseDevice(s->rt->device);
    rt_free(s->rt);
    s->rt = NULL;
}

void *scene_rt_set_ray_hook(const struct scene *s, scene_ray_hook hook, void *user)
{
    void *old = s->rt->hook_user;
    s->rt->hook = hook;
    s->rt->hook_user = user;
    return old;
}

/* Hands the rays q[0 .. n-1] a query is about to trace to the ray log, while one is active. */
static inline void log_rays(const struct scene *s, const struct ray_query *q, int n, enum ray_kind kind)
{
    if (s->rt->hook)
        s->rt->hook(s->rt->hook_user, q, n, (int)kind);
}

RTCScene scene_rt_embree(const struct scene *s, int kind, int *const **geom_tris)
{
    if (geom_tris)
        *geom_tris = kind == RAY_EMITTERS ? NULL : s->rt->geom_tris;
    return kind == RAY_EMITTERS ? s->rt->emitters : s->rt->scene;
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
    log_rays(s, &(struct ray_query){o, d, tmin, tmax}, 1, RAY_CLOSEST);
    int tri = scene_rt_closest(s->rt->scene, s->rt->geom_tris, o, d, tmin, tmax, &t, &u, &v);
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
    log_rays(s, &(struct ray_query){o, d, tmin, tmax}, 1, RAY_EMITTERS);
    int e = scene_rt_closest(s->rt->emitters, NULL, o, d, tmin, tmax, &t, &u, &v);
    if (e < 0)
        return 0;
    fill_hit(s, s->emitter_tri[e], o, d, t, u, v, hit);
    return 1;
}

int scene_occluded(const struct scene *s, vec3 o, vec3 d, float tmin, float tmax)
{
    log_rays(s, &(struct ray_query){o, d, tmin, tmax}, 1, RAY_OCCLUDED);
    return scene_rt_occluded(s->rt->scene, o, d, tmin, tmax);
}

static void fill_ray(struct RTCRay *ray, const struct ray_query *q, unsigned mask)
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
    ray->mask = mask;
    ray->id = 0;
    ray->flags = 0;
}

void scene_rt_closest_stream(RTCScene sc, int *const *geom_tris, const struct ray_query *q, int n, int coherent,
                             int *tri, float *t, float *u, float *v)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRayHit rh[RAY_STREAM_MAX];
    for (int k = 0; k < n; k++) {
        fill_ray(&rh[k].ray, &q[k], ~0u);
        rh[k].hit.geomID = rh[k].hit.primID = rh[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(sc, &ctx, rh, (unsigned)n, sizeof(rh[0]));
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

/* scene_rt_occluded_stream for rays of the given mask (n <= RAY_STREAM_MAX). */
static void occluded_stream_masked(RTCScene sc, const struct ray_query *q, int n, int coherent, unsigned mask,
                                   unsigned char *occ)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRay ray[RAY_STREAM_MAX];
    for (int k = 0; k < n; k++)
        fill_ray(&ray[k], &q[k], mask);
    rtcOccluded1M(sc, &ctx, ray, (unsigned)n, sizeof(ray[0]));
    for (int k = 0; k < n; k++)
        occ[k] = ray[k].tfar == -INFINITY;
}

void scene_rt_occluded_stream(RTCScene sc, const struct ray_query *q, int n, int coherent, unsigned char *occ)
{
    occluded_stream_masked(sc, q, n, coherent, ~0u, occ);
}

void scene_set_ray_streams(struct scene *s, int on)
{
    s->rt->streams = on != 0;
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
        log_rays(s, q + first, m, RAY_CLOSEST);
        scene_rt_closest_stream(s->rt->scene, s->rt->geom_tris, q + first, m, coherent, tri, t, u, v);
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
        log_rays(s, q + first, m, RAY_OCCLUDED);
        scene_rt_occluded_stream(s->rt->scene, q + first, m, 0, occluded + first);
    }
}

void scene_occluded_previous_batch(const struct scene *s, const struct ray_query *q, int n, unsigned char *occluded)
{
    const struct scene_rt *rt = s->rt;
    if (!rt->previous) {
        scene_occluded_batch(s, q, n, occluded);
        return;
    }
    for (int first = 0; first < n; first += RAY_STREAM_MAX) {
        const int m = n - first < RAY_STREAM_MAX ? n - first : RAY_STREAM_MAX;
        log_rays(s, q + first, m, RAY_OCCLUDED);
        occluded_stream_masked(rt->scene, q + first, m, 0, MASK_STILL, occluded + first); /* all but the movers */
        struct ray_query open[RAY_STREAM_MAX];
        int at[RAY_STREAM_MAX], k = 0;
        for (int i = 0; i < m; i++)
            if (!occluded[first + i]) {
                open[k] = q[first + i];
                at[k++] = first + i;
            }
        unsigned char occ[RAY_STREAM_MAX];
        if (k > 0)
            occluded_stream_masked(rt->previous, open, k, 0, ~0u, occ); /* the movers where they were */
        for (int i = 0; i < k; i++)
            occluded[at[i]] = occ[i];
    }
}
