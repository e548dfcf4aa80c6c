/* reference_run.h: what `restir reference` (cmd_reference.c) and its sharded form (reference_shards.c) share.
 * Must never implement a method or call into cmd_reference.c or reference_shards.c. */
#ifndef RESTIR_EXPERIMENTS_REFERENCE_RUN_H
#define RESTIR_EXPERIMENTS_REFERENCE_RUN_H

#include "experiments/options.h"
#include "io/exr.h"
#include "methods/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"

#define RUN_TEXT_MAX 1024 /* a run description (reference_describe): restir.run */

/* The most samples a reference with --target-relmse and no --spp renders. */
#define REFERENCE_TARGET_MAX_SPP 65536

struct reference_setup {
    struct cli_options o;
    const struct method *method;
    struct scene s;
    int spp;
    struct camera cam, cam_open; /* the frame's camera and where its shutter opens */
};

/* A reference from its description (struct cli_options as the option table parsed it): method,
 * scene (st->s, to destroy), camera and samples; need_out: --out (or --plan) is required. Returns 0,
 * or an exit code having said why. */
int reference_setup(const struct cli_options *desc, int need_out, struct reference_setup *st);
/* reference_setup of a plan's stored arguments (need_out 0). */
int reference_setup_args(int argc, char **argv, struct reference_setup *st);
/* A reference image (the running mean of `samples` of `spp` samples) with its attributes
 * restir.samples, restir.spp, restir.run, restir.method, restir.scene and the n_extra (at most 8)
 * in extra; when m2 is not NULL (a checkpoint of a run with a relMSE target: reference.h's variance
 * state) also the layer "m2"; atomically. Returns 0, or -1 with msg. */
int reference_write_image(const char *path, const float *mean, int w, int h, int samples, int spp, const char *run,
                          const char *method, const char *scene, const float *m2, const struct exr_attribute *extra,
                          int n_extra, char *msg);

#endif
