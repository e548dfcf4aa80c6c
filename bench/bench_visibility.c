/* bench_visibility.c: the `visibility` section of restir_bench: restir-di variants run over the
 * same frames, with time, rays and error at the last frame, for the static camera and the camera
 * path: visibility reuse with ray-traced visibility in the MIS targets (the default), without
 * visibility reuse, and with the biased di.visibility_mis=none; then the defaults (candidate
 * counts, spatial neighbors, selection) with relMSE x time, the work-normalized error that says
 * which setting pays at equal time. Not a test. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "methods/settings.h"
#include "restir/metrics.h"
#include "methods/restir_di/di_settings.h"

struct di_variant {
    const char *label;
    const char *sets; /* "key=value:key=value", or NULL for the defaults */
};

static void variants_table(const struct scene *s, const char *title, const struct di_variant *v, int nv, int width,
                           int height, int frames, int ref_spp, int use_path)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = width;
    p.height = height;
    const size_t npix = (size_t)width * height;
    float *ref = bench_reference(s, method_named("restir-di"), &p, (float)(frames - 1), use_path, ref_spp);
    printf("\n### %s, restir-di, %s %dx%d, %s, error at frame %d (reference: %d spp; %d threads)\n\n", title, s->name,
           width, height, use_path ? "camera path" : "static camera", frames - 1, ref_spp, omp_get_max_threads());
    printf("| setting | ms/frame | rays/px | relMSE | MAPE | SMAPE | relMSE x ms |\n|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < nv; k++) {
        struct render_params q = p;
        char msg[256];
        if (v[k].sets && render_params_set_list(&q, v[k].sets, msg) != 0) {
            fprintf(stderr, "%s\n", msg);
            exit(1);
        }
        struct renderer r;
        renderer_init(&r, s, method_named("restir-di"), &q);
        struct frame_stats st;
        double ms = 0.0, rays = 0.0;
        for (int f = 0; f < frames; f++) {
            struct camera cam = scene_camera_at(s, use_path, (float)f);
            renderer_render(&r, f, &cam, &st);
            if (f > 0) {
                ms += st.ms_total;
                rays += (double)st.rays;
            }
        }
        struct restir_metrics_error e;
        restir_metrics_compute(r.image, ref, npix, NULL, &e);
        ms /= frames - 1;
        printf("| %s | %.1f | %.2f | %.5g | %.4f | %.2f | %.1f |\n", v[k].label, ms, rays / (frames - 1) / (double)npix,
               e.relmse, e.mape, e.smape, e.relmse * ms);
        renderer_fini(&r);
    }
    free(ref);
}

void bench_di_visibility(const char *scene, int width, int height, int frames, int ref_spp)
{
    static const struct di_variant visibility[] = {
        {"visibility reuse, MIS rays (default)", NULL},
        {"no visibility reuse", "di.visibility_reuse=off"},
        {"visibility reuse, MIS none (BIASED)", "di.visibility_mis=none"},
    };
    static const struct di_variant defaults[] = {
        {"32 light + 1 BSDF candidates, 1 neighbor, bitterli (default)", NULL},
        {"16 light candidates", "di.light_candidates=16"},
        {"64 light candidates", "di.light_candidates=64"},
        {"no BSDF candidate", "di.bsdf_candidates=0"},
        {"2 spatial neighbors", "spatial.neighbors=2"},
        {"3 spatial neighbors", "spatial.neighbors=3"},
        {"compat selection", "spatial.select=compat"},
    };
    struct scene s = bench_load_scene(scene);
    for (int use_path = 0; use_path < 2; use_path++)
        variants_table(&s, "Visibility reuse", visibility, 3, width, height, frames, ref_spp, use_path);
    variants_table(&s, "Defaults", defaults, (int)(sizeof(defaults) / sizeof(defaults[0])), width, height, frames,
                   ref_spp, 0);
    scene_destroy(&s);
}
