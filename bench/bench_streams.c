/* bench_streams.c: `restir_bench streams [--res WxH] [--rounds N]`: the batched passes with
 * rays.streams on (Embree streams per tile) against off (one Embree call per ray), per pass, in
 * alternating rounds of one run (this machine's speed drifts), so that the faster way is kept per
 * pass on measurement. The images are the same either way (rays.streams). The setting is the
 * scene's (scene_set_ray_streams): this benchmark owns its scene and sets it before each run. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "methods/settings.h"

#define STREAMS_FRAMES 9

/* Mean per-pass ms over frames 1 .. STREAMS_FRAMES-1 of one renderer into ms[], the frame's in
 * ms[PASS_COUNT]; streams on or off as s is set. */
static void timed_run(const struct scene *s, const struct method *method, int width, int height, double *ms)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = width;
    p.height = height;
    struct renderer r;
    renderer_init(&r, s, method, &p);
    struct camera cam = scene_camera_at(s, 0, 0.0f);
    struct frame_stats st;
    memset(ms, 0, sizeof(double) * (PASS_COUNT + 1));
    for (int f = 0; f < STREAMS_FRAMES; f++) {
        renderer_render(&r, f, &cam, &st);
        if (f == 0)
            continue;
        for (int q = 0; q < PASS_COUNT; q++)
            ms[q] += st.ms[q] / (STREAMS_FRAMES - 1);
        ms[PASS_COUNT] += st.ms_total / (STREAMS_FRAMES - 1);
    }
    renderer_fini(&r);
}

static void streams_case(const char *scene, const struct method *method, int width, int height, int rounds)
{
    struct scene s = bench_load_scene(scene);
    double best[2][PASS_COUNT + 1];
    for (int m = 0; m < 2; m++)
        for (int q = 0; q <= PASS_COUNT; q++)
            best[m][q] = INFINITY;
    for (int round = 0; round < rounds; round++)
        for (int m = 0; m < 2; m++) {
            const int streams = (round + m) % 2; /* alternate which goes first */
            double ms[PASS_COUNT + 1];
            scene_set_ray_streams(&s, streams);
            timed_run(&s, method, width, height, ms);
            for (int q = 0; q <= PASS_COUNT; q++)
                best[streams][q] = ms[q] < best[streams][q] ? ms[q] : best[streams][q];
        }
    printf("\n### rays.streams, %s %s %dx%d, static camera, best of %d rounds of frames 1-%d (%d threads)\n\n"
           "| pass | off (ms) | on (ms) | on / off |\n|---|---|---|---|\n",
           method->name, scene, width, height, rounds, STREAMS_FRAMES - 1, omp_get_max_threads());
    for (int q = 0; q <= PASS_COUNT; q++) {
        if (!(best[0][q] > 0.0))
            continue;
        printf("| %s | %.2f | %.2f | %.3f |\n", q < PASS_COUNT ? pass_name(q) : "frame", best[0][q], best[1][q],
               best[1][q] / best[0][q]);
    }
    scene_destroy(&s);
}

int bench_streams(int argc, char **argv)
{
    int width = 640, height = 360, rounds = 3;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--res") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &width, &height) == 2 &&
            width > 0 && height > 0)
            i++;
        else if (!strcmp(argv[i], "--rounds") && i + 1 < argc && (rounds = atoi(argv[i + 1])) > 0)
            i++;
        else {
            fprintf(stderr, "usage: restir_bench streams [--res WxH] [--rounds N]\n");
            return 2;
        }
    }
    streams_case("many-lights", method_named("restir-di"), width, height, rounds);
    streams_case("many-lights", method_named("ris-di"), width, height, rounds);
    streams_case("ajar", method_named("restir-pt"), width, height, rounds);
    streams_case("foliage", method_named("grestir-pt"), width, height, rounds);
    return 0;
}
