/* reference_run.c: what `restir reference` and its sharded form share (reference_run.h): options, the image.
 * Must never implement a method or call into cmd_reference.c or reference_shards.c. */
#include "experiments/options.h"
#include "experiments/reference_run.h"

#include <omp.h>
#include <stdio.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/run_prepare.h"
#include "io/exr.h"
#include "methods/pt/reference.h"
#include "scene/scene_file.h"

int reference_write_image(const char *path, const float *mean, int w, int h, int samples, int spp, const char *run,
                          const char *method, const char *scene, const float *m2, const struct exr_attribute *extra,
                          int n_extra, char *msg)
{
    char samples_text[32], spp_text[32];
    snprintf(samples_text, sizeof samples_text, "%d", samples);
    snprintf(spp_text, sizeof spp_text, "%d", spp);
    struct exr_attribute attrs[5 + 8] = {{"restir.samples", samples_text}, {"restir.spp", spp_text},
                                         {"restir.run", run},           {"restir.method", method},
                                         {"restir.scene", scene}};
    RESTIR_CHECK(n_extra >= 0 && n_extra <= 8);
    for (int k = 0; k < n_extra; k++)
        attrs[5 + k] = extra[k];
    const struct exr_layer layers[2] = {{NULL, mean}, {"m2", m2}};
    return exr_write_layers_attrs(path, layers, m2 ? 2 : 1, attrs, 5 + n_extra, w, h, msg);
}

int reference_setup(const struct cli_options *desc, int need_out, struct reference_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    st->o = *desc;
    struct cli_options *o = &st->o;
    if (need_out && !o->out && !o->plan) {
        cli_error("--out FILE.exr (or --shards N --plan DIR) is required");
        return EXIT_USAGE;
    }
    if (!(st->method = run_find_method(o->method)))
        return EXIT_USAGE;
    /* the reference renders pt over the method's integrand, not the method: its memory is checked below */
    int rc = run_prepare(o, st->method, 0, &st->s);
    if (rc != 0)
        return rc;
    /* the mean, the chunk and, while resuming or merging, one image read: three RGB float images;
     * with a relMSE target the variance state and its read too */
    const double per_pixel = (o->target_relmse > 0.0 ? 5.0 : 3.0) * 3.0 * sizeof(float);
    if (cli_check_bytes("reference", o->params.width, o->params.height,
                        per_pixel * o->params.width * (double)o->params.height, per_pixel, o->max_memory_mb,
                        msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&st->s);
        return EXIT_RUNTIME;
    }
    st->spp = o->spp_given ? o->params.spp : o->target_relmse > 0.0 ? REFERENCE_TARGET_MAX_SPP : 1024;
    if (o->params.threads > 0)
        omp_set_num_threads(o->params.threads);
    cli_frame_cameras(&st->s, o->params.camera_path, o->frame, &st->cam, &st->cam_open);
    return 0;
}

int reference_setup_args(int argc, char **argv, struct reference_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("reference", argc, argv, &desc, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    return reference_setup(&desc, 0, st);
}
