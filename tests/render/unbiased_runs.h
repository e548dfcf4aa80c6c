/* unbiased_runs.h: the two sides of a render unbiasedness test: K independently seeded runs of a
 * method over a short moving-camera sequence, and K runs of the path-traced reference seen from
 * the sequence's last camera, each accumulated per pixel into pixel_stats. */
#ifndef RESTIR_TEST_UNBIASED_RUNS_H
#define RESTIR_TEST_UNBIASED_RUNS_H

#include "render/renderer.h"
#include "unbiased_util.h"

/* Frame f of a run is seen from camera-path frame f * frame_step. */
static inline void unbiased_run_method(const struct scene *s, enum method_id m, const struct render_params *base,
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

/* The reference of method m (pt over the same integrand) with spp paths per run. */
static inline void unbiased_run_reference(const struct scene *s, enum method_id m, const struct render_params *base,
                                          int runs, int spp, float camera_frame, struct pixel_stats *st)
{
    struct render_params rp = *base;
    renderer_reference_params(m, &rp);
    rp.spp = spp;
    for (int k = 0; k < runs; k++) {
        struct render_params q = rp;
        q.seed = 900000 + (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, METHOD_PT, &q);
        struct frame_stats fs;
        struct camera cam = scene_camera_at(s, 1, camera_frame);
        renderer_render(&r, 0, &cam, &fs);
        pixel_stats_add(st, r.image);
        renderer_fini(&r);
    }
}

#endif
