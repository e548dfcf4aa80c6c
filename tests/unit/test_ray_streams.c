/* test_ray_streams.c: the batched ray queries (scene_intersect_batch, scene_occluded_batch: Embree
 * streams) answer as the single-ray queries do, on every built-in scene: camera rays (coherent),
 * rays leaving camera hits in random directions (incoherent) and shadow rays between hits. Hit or
 * miss, the triangle and occlusion must agree exactly; distances and barycentrics bit for bit
 * (Embree's stream and single-ray triangle tests compute the same expressions; checked here so
 * that a library whose kernels differ is caught, not assumed). With streams off the batched calls
 * are the single-ray path itself. */
#include <math.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "scene/scene_file.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

#define W 64
#define H 36
#define N (W * H)

static int same_hit(const struct surface_hit *a, const struct surface_hit *b)
{
    return a->tri == b->tri && a->t == b->t && a->b1 == b->b1 && a->b2 == b->b2 && a->front == b->front &&
           !memcmp(&a->p, &b->p, sizeof(a->p));
}

/* Batched closest hits of q against single-ray ones (hit[k]: ray k hit); returns the hits. */
static int compare_intersect(const struct scene *s, const char *name, const char *what, const struct ray_query *q,
                             int n, int coherent, struct surface_hit *hits, unsigned char *hit)
{
    int mismatch = 0, found = 0;
    scene_intersect_batch(s, q, n, coherent, hits, hit);
    for (int k = 0; k < n; k++) {
        struct surface_hit h;
        const int single = scene_intersect(s, q[k].o, q[k].d, q[k].tmin, q[k].tmax, &h);
        found += single;
        if (single != hit[k] || (single && !same_hit(&h, &hits[k]))) {
            if (mismatch++ == 0)
                printf("%s %s ray %d: single %d tri %d t %.9g, batch %d tri %d t %.9g\n", name, what, k, single,
                       single ? h.tri : -1, single ? h.t : 0.0f, hit[k], hit[k] ? hits[k].tri : -1,
                       hit[k] ? hits[k].t : 0.0f);
        }
    }
    EXPECT(mismatch == 0, "%s: %d of %d %s differ between streams and single rays", name, mismatch, n, what);
    return found;
}

static void check_scene(const char *name)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_load(name, &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return;
    }
    struct camera cam = scene_camera_at(&s, 0, 0.0f);
    struct camera_view view;
    camera_view_init(&view, &cam, W, H);
    static struct ray_query q[N];
    static struct surface_hit cam_hits[N], hits[N];
    static unsigned char cam_hit[N], hit[N];
    pcg32 rng = rng_for(7, 0, 0, 0);
    for (int i = 0; i < N; i++)
        q[i] = (struct ray_query){
            view.position,
            camera_view_ray(&view, (float)(i % W) + pcg32_float(&rng), (float)(i / W) + pcg32_float(&rng)), 0.0f,
            INFINITY};
    const int seen = compare_intersect(&s, name, "camera rays", q, N, 1, cam_hits, cam_hit);
    EXPECT(seen > N / 4, "%s: only %d of %d camera rays hit", name, seen, N);
    /* From each camera hit: a random direction (incoherent), and a shadow ray to another hit. */
    int n = 0;
    for (int i = 0; i < N; i++) {
        if (!cam_hit[i])
            continue;
        const vec3 d =
            v3_normalize(v3(pcg32_float(&rng) - 0.5f, pcg32_float(&rng) - 0.5f, pcg32_float(&rng) - 0.5f));
        q[n++] = (struct ray_query){scene_offset_point(cam_hits[i].p, cam_hits[i].ng, d), d, 0.0f, INFINITY};
    }
    compare_intersect(&s, name, "random rays", q, n, 0, hits, hit);
    n = 0;
    for (int i = 0; i < N; i++) {
        const int j = (int)(pcg32_float(&rng) * N) % N;
        if (cam_hit[i] && cam_hit[j] &&
            scene_visibility_query(cam_hits[i].p, cam_hits[i].ng, cam_hits[j].p, cam_hits[j].ng, &q[n]))
            n++;
    }
    static unsigned char occ[N];
    scene_occluded_batch(&s, q, n, occ);
    int mismatch = 0, blocked = 0;
    for (int k = 0; k < n; k++) {
        const int single = scene_occluded(&s, q[k].o, q[k].d, q[k].tmin, q[k].tmax);
        blocked += single;
        mismatch += single != occ[k];
    }
    EXPECT(mismatch == 0, "%s: %d of %d shadow rays differ between streams and single rays", name, mismatch, n);
    printf("%s: %d camera hits, %d shadow rays (%d occluded): streams = single rays\n", name, seen, n, blocked);
    scene_destroy(&s);
}

int main(void)
{
    for (int k = 0; scene_builtins[k].name; k++)
        check_scene(scene_builtins[k].name);
    return test_finish();
}
