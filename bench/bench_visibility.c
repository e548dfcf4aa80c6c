/* bench_visibility.c: the `visibility` section of restir_bench: restir-di with visibility reuse and
 * ray-traced visibility in the MIS targets (the default), without visibility reuse, and with the
 * biased di.visibility_mis=none, at the same frames: time, rays and error at the last frame, for
 * the static camera and the camera path. Not a test. */
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "restir/metrics.h"

void bench_di_visibility(const char *scene, int width, int height, int frames, int ref_spp)
{
    static const char *const variants[][2] = {
        {"on, rays (default)", NULL},
        {"off", "di.visibility_reuse=off"},
        {"on, none (BIASED)", "di.visibility_mis=none"},
    };
    const int nv = (int)(sizeof(variants) / sizeof(variants[0]));
    struct scene s = bench_load_scene(scene);
    const size_t npix = (size_t)width * height;
    for (int use_path = 0; use_path < 2; use_path++) {
        struct render_params p;
        render_params_defaults(&p);
        p.width = width;
        p.height = height;
        float *ref = bench_reference(&s, METHOD_RESTIR_DI, &p, (float)(frames - 1), use_path, ref_spp);
        printf("\n### Visibility reuse, restir-di, %s %dx%d, %s, error at frame %d (reference: %d spp)\n\n", scene,
               width, height, use_path ? "camera path" : "static camera", frames - 1, ref_spp);
        printf("| visibility | ms/frame | rays/px | relMSE | MAPE | SMAPE |\n|---|---|---|---|---|---|\n");
        for (int v = 0; v < nv; v++) {
            struct render_params q = p;
            char msg[256];
            if (variants[v][1] && render_params_set(&q, variants[v][1], msg) != 0) {
                fprintf(stderr, "%s\n", msg);
                exit(1);
            }
            struct renderer r;
            renderer_init(&r, &s, METHOD_RESTIR_DI, &q);
            struct frame_stats st;
            double ms = 0.0, rays = 0.0;
            for (int f = 0; f < frames; f++) {
                struct camera cam = scene_camera_at(&s, use_path, (float)f);
                renderer_render(&r, f, &cam, &st);
                if (f > 0) {
                    ms += st.ms_total;
                    rays += (double)st.rays;
                }
            }
            struct restir_error e;
            restir_error_compute(r.image, ref, npix, NULL, &e);
            printf("| %s | %.1f | %.2f | %.5g | %.4f | %.2f |\n", variants[v][0], ms / (frames - 1),
                   rays / (frames - 1) / (double)npix, e.relmse, e.mape, e.smape);
            renderer_fini(&r);
        }
        free(ref);
    }
    scene_destroy(&s);
}
