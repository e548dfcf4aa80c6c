/* bench_denoise.c: `restir_bench denoise [--scene S] [--method M] [--res WxH] [--frames N]
 * [--threads T] [--camera static|path] [--isa I] [--set K=V]...`: what denoising costs beside the
 * frame it denoises (the budget it is held to: SVGF at 640x360 in at most 15% of a restir-di frame on 2 threads).
 * Renders N frames of the method without denoising, keeps the last frame's image and G-buffer, then
 * runs each denoiser N times on them (SVGF then reprojects its history by the last frame's motion
 * vectors each time: a static history under a static camera) and prints the medians of the
 * frames' and the denoisers' milliseconds and their ratio, measured in the same run. --isa limits
 * every kernel's instruction set, the frame's too; --set changes any setting (denoise.* ones).
 * Must never be run by the tests. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "core/simd.h"
#include "denoise/denoise.h"
#include "experiments/cli.h"
#include "methods/settings.h"
#include "scene/scene_file.h"

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The instruction set of that name (the best the CPU has up to it runs), or -1. */
static int isa_named(const char *name)
{
    for (int k = SIMD_ISA_BASELINE; k <= SIMD_ISA_AVX512; k++)
        if (!strcmp(name, simd_isa_name((enum simd_isa)k)))
            return k;
    return -1;
}

int bench_denoise(int argc, char **argv)
{
    const char *scene_name = "many-lights", *method_name = "restir-di";
    int width = 640, height = 360, frames = 12, threads = 2, isa = SIMD_ISA_AVX512, path = 0;
    struct render_params p;
    render_params_defaults(&p);
    char msg[RESTIR_MSG_LEN];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--scene") && i + 1 < argc)
            scene_name = argv[++i];
        else if (!strcmp(argv[i], "--method") && i + 1 < argc)
            method_name = argv[++i];
        else if (!strcmp(argv[i], "--res") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &width, &height) == 2)
            i++;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && (frames = atoi(argv[++i])) >= 3)
            ;
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc && (threads = atoi(argv[++i])) >= 1)
            ;
        else if (!strcmp(argv[i], "--camera") && i + 1 < argc &&
                 (!strcmp(argv[i + 1], "path") || !strcmp(argv[i + 1], "static")))
            path = !strcmp(argv[++i], "path");
        else if (!strcmp(argv[i], "--set") && i + 1 < argc) {
            if (render_params_set(&p, argv[++i], msg) != 0) {
                fprintf(stderr, "restir_bench denoise: %s\n", msg);
                return 2;
            }
        } else if (!strcmp(argv[i], "--isa") && i + 1 < argc && (isa = isa_named(argv[i + 1])) >= 0)
            i++;
        else {
            fprintf(stderr, "usage: restir_bench denoise [--scene S] [--method M] [--res WxH] [--frames N>=3] "
                            "[--threads T] [--camera static|path] [--isa baseline|avx2|avx512] [--set key=value]...\n");
            return 2;
        }
    }
    struct scene s = bench_load_scene(scene_name);
    p.width = width;
    p.height = height;
    p.threads = threads;
    struct renderer r;
    p.simd = isa != SIMD_ISA_BASELINE;
    renderer_init(&r, &s, method_named(method_name), &p);
    double *ms = xmalloc(sizeof(double) * (size_t)frames);
    for (int f = 0; f < frames; f++) {
        struct frame_stats st;
        const struct camera cam = scene_camera_at(&s, path, (float)f);
        renderer_render(&r, f, &cam, &st);
        ms[f] = st.ms_total;
    }
    const double frame_ms = median(ms + 2, frames - 2); /* frames 0 and 1 warm up */
    simd_limit((enum simd_isa)isa); /* each frame set the process's limit from p.simd */
    struct renderer_inspect in;
    renderer_inspect(&r, &in);
    struct gbuffer own;
    const struct gbuffer *g = in.gbuffer;
    if (!g) {
        gbuffer_init(&own, width, height, 0);
        struct camera_view view;
        const struct camera cam = scene_camera_at(&s, path, (float)(frames - 1));
        renderer_camera_view(&r.p, &cam, NULL, &view);
        gbuffer_pass(&own, &s, &view, NULL, 0, p.seed, 0);
        g = &own;
    }
    struct denoise_guide guide;
    renderer_denoise_guide(g, &guide);
    float *out = xmalloc(sizeof(float) * 3 * (size_t)width * (size_t)height);
    printf("%s on %s, %dx%d, %s camera, %d threads (%s): frame %.2f ms (median of frames 2..%d)\n", method_name,
           scene_name, width, height, path ? "moving" : "static", threads, simd_isa_name(simd_isa_active()), frame_ms,
           frames - 1);
    for (int k = 1; denoise_names[k]; k++) {
        struct denoise_settings ds = p.denoise;
        ds.method = k;
        struct denoiser *d = denoiser_create(&ds, width, height);
        for (int f = 0; f < frames; f++) {
            const double t0 = omp_get_wtime();
            RESTIR_CHECK(denoiser_run(d, r.image, &guide, out, NULL) == 0);
            ms[f] = 1e3 * (omp_get_wtime() - t0);
        }
        const double dm = median(ms + 2, frames - 2);
        printf("  %-7s %8.2f ms  = %5.1f%% of the frame\n", denoise_names[k], dm, 100.0 * dm / frame_ms);
        denoiser_destroy(d);
    }
    if (g == &own)
        gbuffer_fini(&own);
    free(out);
    free(ms);
    renderer_fini(&r);
    scene_destroy(&s);
    return 0;
}
