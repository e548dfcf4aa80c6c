/* unbiased_runs.h: the two sides of a render unbiasedness test: K independently seeded runs of a
 * method over a short moving-camera sequence, and K runs of the path-traced reference seen from
 * the sequence's last camera, each accumulated per pixel into pixel_stats. */
#ifndef RESTIR_TEST_UNBIASED_RUNS_H
#define RESTIR_TEST_UNBIASED_RUNS_H

#include <string.h>
#include <time.h>

#include "methods/settings.h"
#include "reference_cache.h"
#include "reference_pt.h"
#include "methods/renderer.h"
#include "scene/scene_file.h"
#include "test_util.h"
#include "unbiased_util.h"

/* Frame f of a run is seen from camera-path frame f * frame_step. */
static inline void unbiased_run_method(const struct scene *s, const struct method *m, const struct render_params *base,
                                       uint64_t seed0, int runs, int frames, int frame_step, struct pixel_stats *st)
{
    for (int k = 0; k < runs; k++) {
        struct render_params p = *base;
        p.seed = seed0 + (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, m, &p);
        for (int f = 0; f < frames; f++) {
            struct frame_stats fs;
            struct camera cam = scene_camera_at(s, 1, (float)(f * frame_step));
            renderer_render(&r, f, &cam, &fs);
        }
        pixel_stats_add(st, r.image);
        renderer_fini(&r);
    }
}

/* The reference of method m (pt over the same integrand) with spp paths per run, seen from
 * camera-path frame camera_frame with the shutter opening at frame open_frame: runs 0 .. runs-1 of
 * the process's reference cache (rendered once however many cases share them). */
static inline void unbiased_run_reference(const struct scene *s, const struct method *m,
                                          const struct render_params *base, int runs, int spp, float camera_frame,
                                          float open_frame, struct pixel_stats *st)
{
    struct render_params rp = *base;
    method_reference_params(m, &rp);
    reference_pt_pin(&rp);
    rp.spp = spp;
    struct camera cam = scene_camera_at(s, 1, camera_frame), open = scene_camera_at(s, 1, open_frame);
    const float *images = reference_cache_runs(s, &rp, &cam, &open, runs);
    const size_t floats = 3 * (size_t)rp.width * (size_t)rp.height;
    for (int k = 0; k < runs; k++)
        pixel_stats_add(st, images + (size_t)k * floats);
}

/* One unbiasedness case: `runs` seeded sequences of `frames` camera-path frames (frame_step apart)
 * against `runs` x ref_spp paths of pt from the last camera. */
struct unbiased_case {
    const char *scene;
    const struct method *method;
    int width, height;
    int runs, frames, frame_step, ref_spp;
    double alpha;        /* family-wise level of the per-pixel Welch tests (Sidak) */
    double pooled_z_max; /* bound on the pooled whole-image z */
};

/* Runs case c with the `--set` assignments sets; when expect_unbiased, expects no pixel to fail
 * and |pooled z| < c->pooled_z_max. Returns the number of pixels that fail. */
static inline int unbiased_check(const struct unbiased_case *c, const char *const *sets, int nsets,
                                 int expect_unbiased)
{
    struct scene s;
    char msg[512];
    EXPECT(scene_load(c->scene, &s, msg) == 0, "%s", msg);
    struct render_params p;
    render_params_defaults(&p);
    p.width = c->width;
    p.height = c->height;
    for (int k = 0; k < nsets; k++)
        EXPECT(render_params_set(&p, sets[k], msg) == 0, "%s", msg);
    struct pixel_stats ref, m;
    pixel_stats_init(&ref, c->width * c->height);
    pixel_stats_init(&m, c->width * c->height);
    const int last = (c->frames - 1) * c->frame_step;
    const clock_t start = clock();
    unbiased_run_reference(&s, c->method, &p, c->runs, c->ref_spp, (float)last,
                           (float)(c->frames > 1 ? last - c->frame_step : last), &ref);
    unbiased_run_method(&s, c->method, &p, 1000, c->runs, c->frames, c->frame_step, &m);
    printf("%s %dx%d %s, %d runs of %d frames (%.1f CPU-s):", c->scene, c->width, c->height, c->method->name,
           c->runs, c->frames, (double)(clock() - start) / CLOCKS_PER_SEC);
    for (int k = 0; k < nsets; k++)
        printf(" %s", sets[k]);
    printf("\n");
    struct unbiased_report rep = unbiased_compare(&m, &ref, c->alpha);
    if (expect_unbiased) {
        EXPECT(rep.pixels_failed == 0, "%s: %d pixels fail the Sidak-corrected Welch test", c->scene,
               rep.pixels_failed);
        EXPECT(fabs(rep.pooled_z) < c->pooled_z_max, "%s: pooled z = %.2f", c->scene, rep.pooled_z);
    }
    pixel_stats_free(&ref);
    pixel_stats_free(&m);
    scene_destroy(&s);
    return rep.pixels_failed;
}

/* The camera-path case of the path-reuse tests (test_pt_unbiased, test_splat_unbiased) at w x h:
 * `runs` sequences of 4 frames 6 path frames apart against runs x 8 spp of pt, family-wise alpha
 * 0.01 per case and pooled |z| < 4.5 (~1e-5), with pt.max_bounces=4 before sets. The seeds are
 * fixed, so the outcome is deterministic. Returns the number of pixels that fail. */
static inline int unbiased_check_path_at(const char *scene_name, const struct method *m, int w, int h, int runs,
                                         const char *const *sets, int nsets, int expect_unbiased)
{
    const struct unbiased_case c = {scene_name, m, w, h, runs, 4, 6, 8, 0.01, 4.5};
    const char *all[16] = {"pt.max_bounces=4"};
    for (int k = 0; k < nsets && k < 15; k++)
        all[k + 1] = sets[k];
    return unbiased_check(&c, all, nsets + 1, expect_unbiased);
}

/* unbiased_check_path_at at 20 x 12. */
static inline int unbiased_check_path(const char *scene_name, const struct method *m, int runs, const char *const *sets,
                                      int nsets, int expect_unbiased)
{
    return unbiased_check_path_at(scene_name, m, 20, 12, runs, sets, nsets, expect_unbiased);
}

#endif
