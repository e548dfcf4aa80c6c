/* reference_run.c: what `restir reference` and its sharded form share (reference_run.h): options, the image.
 * Must never implement a method or call into cmd_reference.c or reference_shards.c. */
#include "experiments/options.h"
#include "experiments/reference_run.h"

#include <omp.h>
#include <stdio.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "io/exr.h"
#include "methods/reference.h"
#include "scene/scene_file.h"

static void reference_usage(FILE *out)
{
    fprintf(out,
            "usage: restir reference --scene NAME --method NAME [--res WxH] [--spp N] [--camera static|path]\n"
            "                        [--frame F] [--seed N] [--threads N] [--checkpoint-every SECONDS]\n"
            "                        [--max-memory MB] --out FILE.exr | --shards N --plan DIR\n"
            "       restir reference --merge DIR --out FILE.exr\n"
            "Renders the converged image of what METHOD estimates (pt over the same integrand: direct\n"
            "lighting only for DI methods) from the camera of frame F. Default --spp 1024. The samples come\n"
            "in chunks of %d, chunk c always from the same random numbers, so the image does not depend on\n"
            "--threads or on interruptions.\n"
            "--checkpoint-every S saves the running mean and its sample count (EXR attributes restir.samples\n"
            "and restir.run) to FILE.checkpoint.exr every S seconds (0: after every chunk) and when SIGINT or\n"
            "SIGTERM arrives, each time through a temporary file and a rename. The same command then\n"
            "continues from the checkpoint, after a kill too, and writes byte for byte the image an\n"
            "uninterrupted run gives; a larger --spp extends it. A checkpoint of another run (scene content,\n"
            "camera, resolution, seed or pt parameters) is refused, not overwritten. The finished reference\n"
            "carries the same attributes, and the checkpoint is removed.\n"
            "SIGINT / SIGTERM stop after the current chunk (a second one stops at once); without\n"
            "--checkpoint-every nothing is written. Exit status 128 + the signal.\n"
            "--shards N --plan DIR splits the chunks into N jobs (DIR/jobs.txt, plan.json, slurm.sh; see\n"
            "restir study --help and docs/CLUSTER.md); `restir reference --merge DIR --out FILE.exr` then\n"
            "averages the shards, weighted by samples: the same samples as the unsplit reference, equal to\n"
            "it up to the order of the floating-point sums (relative difference at most (2C+1) 2^-24 for C\n"
            "chunks).\n",
            REFERENCE_CHUNK_SPP);
    cli_options_help(out, "reference");
}

int reference_write_image(const char *path, const float *mean, int w, int h, int samples, int spp, const char *run,
                          const char *method, const char *scene, const char *extra_name, const char *extra_value,
                          char *msg)
{
    char samples_text[32], spp_text[32];
    snprintf(samples_text, sizeof samples_text, "%d", samples);
    snprintf(spp_text, sizeof spp_text, "%d", spp);
    const struct exr_attribute attrs[6] = {{"restir.samples", samples_text}, {"restir.spp", spp_text},
                                           {"restir.run", run},           {"restir.method", method},
                                           {"restir.scene", scene},       {extra_name, extra_value}};
    const struct exr_layer layer = {NULL, mean};
    return exr_write_layers_attrs(path, &layer, 1, attrs, extra_name ? 6 : 5, w, h, msg);
}

int reference_setup(int argc, char **argv, int need_out, struct reference_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    struct cli_options *o = &st->o;
    if (cli_parse_options("reference", argc, argv, o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o->help) {
        reference_usage(stdout);
        return -1;
    }
    if (need_out && !o->out && !o->plan) {
        cli_error("--out FILE.exr (or --shards N --plan DIR) is required");
        return EXIT_USAGE;
    }
    if (!method_find(o->method)) {
        cli_error(o->method ? "unknown method '%s' (see restir list)" : "--method is required (see restir list)%s",
                  o->method ? o->method : "");
        return EXIT_USAGE;
    }
    st->method = method_find(o->method);
    if (cli_scene_load(&o->params, o->env, o->scene, &st->s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (method_check_settings(st->method, &o->params, &st->s, msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&st->s);
        return EXIT_USAGE;
    }
    /* the mean, the chunk and, while resuming or merging, one image read: three RGB float images */
    const double per_pixel = 3.0 * 3.0 * sizeof(float);
    if (cli_check_bytes("reference", o->params.width, o->params.height,
                        per_pixel * o->params.width * (double)o->params.height, per_pixel, o->max_memory_mb, msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&st->s);
        return EXIT_RUNTIME;
    }
    st->spp = o->spp_given ? o->params.spp : 1024;
    if (o->params.threads > 0)
        omp_set_num_threads(o->params.threads);
    cli_frame_cameras(&st->s, o->params.camera_path, o->frame, &st->cam, &st->cam_open);
    return 0;
}
