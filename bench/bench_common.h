/* bench_common.h: helpers shared by the benchmark sections of restir_bench.
 * Must never be run by the tests. */
#ifndef RESTIR_BENCH_COMMON_H
#define RESTIR_BENCH_COMMON_H

#include "methods/renderer.h"

/* A built-in scene; exits with a message when the name is unknown. */
struct scene bench_load_scene(const char *name);
/* pt reference of what `method` estimates, seen from camera frame `frame` (camera path when
 * use_path), spp paths per pixel, as a new malloc'ed RGB buffer. */
float *bench_reference(const struct scene *s, const struct method *method, const struct render_params *p, float frame,
                       int use_path, int spp);
/* The `spmis` section (bench_spmis.c). */
struct bench_spmis_options {
    int width, height, runs, ref_spp;
    int scale_radii;    /* scale 004's 30 px radii by height / 1080 */
    int main, ablations, interplay; /* which tables */
};
void bench_spmis(const struct bench_spmis_options *o);
/* The `visibility` section (bench_visibility.c): restir-di's visibility reuse variants. */
void bench_di_visibility(const char *scene, int width, int height, int frames, int ref_spp);
/* The `poisson` section (bench_poisson.c): argv[0] is "poisson", then its options. */
int bench_poisson(int argc, char **argv);
/* The `gradient` section (bench_gradient.c): argv[0] is "gradient", then its options. */
int bench_gradient(int argc, char **argv);
/* The `streams` section (bench_streams.c): argv[0] is "streams", then its options. */
int bench_streams(int argc, char **argv);
/* The `gi-bias` section (bench_gi.c): argv[0] is "gi-bias", then its options. */
int bench_gi_bias(int argc, char **argv);
/* The `l1-bias` section (bench_l1_bias.c): argv[0] is "l1-bias", then FRAME.exr REF.exr. */
int bench_l1_bias(int argc, char **argv);
/* The `denoise` section (bench_denoise.c): argv[0] is "denoise", then its options. */
int bench_denoise(int argc, char **argv);
/* The `error` section (bench_error.c): argv[0] is "error", then IMAGE.exr REF.exr. */
int bench_error(int argc, char **argv);

#endif
