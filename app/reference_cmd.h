/* reference_cmd.h: what `restir reference` (cmd_reference.c) and its sharded form
 * (reference_shards.c: --shards N --plan DIR, restir job, --merge DIR) share. */
#ifndef RESTIR_APP_REFERENCE_CMD_H
#define RESTIR_APP_REFERENCE_CMD_H

#include "options.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"

#define RUN_TEXT_MAX 1024

struct reference_setup {
    struct cli_options o;
    enum method_id method;
    struct scene s;
    int spp;
    struct camera cam;
};

/* Parses and checks the options, loads the scene (st->s, to destroy) and checks memory; need_out:
 * --out (or --plan) is required. Returns 0, -1 after printing --help, or an exit code having
 * said why. */
int reference_setup(int argc, char **argv, int need_out, struct reference_setup *st);
/* A reference image (the running mean of `samples` of `spp` samples) with its attributes
 * restir.samples, restir.spp, restir.run, restir.method, restir.scene and, when extra_name is not
 * NULL, one more; atomically. Returns 0, or -1 with msg. */
int reference_write_image(const char *path, const float *mean, int w, int h, int samples, int spp, const char *run,
                          const char *method, const char *scene, const char *extra_name, const char *extra_value,
                          char *msg);
/* --shards N --plan DIR: writes the plan. Returns an exit code. */
int reference_plan(const struct reference_setup *st, int argc, char **argv);
/* --merge DIR --out FILE.exr. Returns an exit code. */
int reference_merge(int argc, char **argv);

#endif
