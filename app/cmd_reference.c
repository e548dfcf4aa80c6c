/* cmd_reference.c: `restir reference`, a converged image of what a method estimates, with resumable checkpoints.
 * Must never implement a method; its sharded form (reference_shards.c) never calls back into it. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "experiments/reference_checkpoint.h"
#include "experiments/reference_run.h"
#include "experiments/reference_shards.h"
#include "methods/pt/reference.h"

static void reference_usage(FILE *out)
{
    fprintf(out,
            "usage: restir reference --scene NAME --method NAME [--res WxH] [--spp N] [--target-relmse X]\n"
            "                        [--camera static|path]\n"
            "                        [--frame F] [--seed N] [--threads N] [--checkpoint-every SECONDS]\n"
            "                        [--max-memory MB] [--force | --resume] --out FILE.exr | --shards N --plan DIR\n"
            "       restir reference --merge DIR --out FILE.exr [--force]\n"
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
            "carries the same attributes, and the checkpoint is removed. --resume insists on continuing (exit 2\n"
            "when there is no checkpoint). An existing FILE.exr is refused (exit 2, nothing touched) unless\n"
            "--force, which replaces it once the new one is written and starts over from a checkpoint that\n"
            "cannot be continued. A --plan DIR must be new, empty or hold this very plan (planned again, its\n"
            "finished jobs kept); --force empties one that holds anything else (restir's outputs only).\n"
            "SIGINT / SIGTERM stop after the current chunk (a second one stops at once); without\n"
            "--checkpoint-every nothing is written. Exit status 128 + the signal.\n"
            "--shards N --plan DIR splits the chunks into N jobs (DIR/jobs.txt, plan.json, slurm.sh; see\n"
            "restir study --help and docs/CLUSTER.md); `restir reference --merge DIR --out FILE.exr` then\n"
            "averages the shards, weighted by samples: the same samples as the unsplit reference, equal to\n"
            "it up to the order of the floating-point sums (relative difference at most (2C+1) 2^-24 for C\n"
            "chunks).\n"
            "--target-relmse X stops once the estimated relMSE of the image against the converged one is at\n"
            "most X (checked after every chunk from the 8th on): per pixel and channel, the variance of the\n"
            "mean from the spread of the chunks' means, over (mean^2 + 1e-3), averaged. --spp is then the\n"
            "most samples it renders (default %d); the image records restir.relmse_estimate. With\n"
            "sampler=sobol the chunks continue one sequence, whose mean usually converges faster. Checkpoints\n"
            "keep the variance (layer m2); with --shards N each shard stops at N X. The estimate runs low\n"
            "where rare bright paths dominate and few samples are in (docs/BENCHMARKS.md: the actual relMSE\n"
            "was 1.3x the estimate at 320 samples, 1.1x at 1100 on cornell).\n",
            REFERENCE_CHUNK_SPP, REFERENCE_TARGET_MAX_SPP);
    cli_options_help(out, "reference");
}

/* The finished image, with its estimated relMSE when it ran to a target. */
static int write_reference(const struct cli_options *o, const struct reference_accum *a,
                           const struct reference_checkpoint *c, char *msg)
{
    char text[64];
    snprintf(text, sizeof text, "%.6g", reference_accum_relmse_estimate(a));
    const struct exr_attribute est = {"restir.relmse_estimate", text};
    return reference_write_image(o->out, a->mean, a->params.width, a->params.height, a->done, a->spp, c->run,
                                  o->method, o->scene, NULL, &est, c->target > 0.0 ? 1 : 0, msg);
}

int cmd_reference(int argc, char **argv)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge"))
            return reference_merge(argc, argv);
    char parse_msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("reference", argc, argv, &desc, parse_msg) != 0) {
        cli_error("%s", parse_msg);
        return EXIT_USAGE;
    }
    if (desc.help) {
        reference_usage(stdout);
        return 0;
    }
    if (desc.force && desc.resume) {
        cli_error("give one of --force (start over) and --resume (continue the checkpoint)");
        return EXIT_USAGE;
    }
    /* an earlier run's image is never replaced without --force; its checkpoint is continued */
    if (!desc.plan && !desc.shards && desc.out && out_file_check("--out", desc.out, desc.force, parse_msg) != 0) {
        cli_error("%s", parse_msg);
        return EXIT_USAGE;
    }
    struct reference_setup st;
    int rc = reference_setup(&desc, 1, &st);
    if (rc != 0)
        return rc;
    if (st.o.plan || st.o.shards) {
        rc = reference_plan(&st, argc, argv);
        scene_destroy(&st.s);
        return rc;
    }
    char msg[RESTIR_MSG_LEN];
    const struct cli_options o = st.o;
    const int spp = st.spp;
    struct scene s = st.s;
    const struct method *method = st.method;
    struct camera cam = st.cam, open = st.cam_open;
    struct reference_accum a;
    reference_accum_init(&a, &s, method, &o.params, &cam, &open, spp);
    struct reference_checkpoint c;
    reference_checkpoint_init(&c, &a, o.out, o.checkpoint_every, o.method, o.scene);
    c.target = o.target_relmse;
    int resumed = 0;
    rc = reference_checkpoint_resume(&c, &a, &resumed, msg);
    if (rc != 0 && o.force) { /* a checkpoint that cannot be continued: --force starts over */
        printf("--force: removing %s (%s)\n", c.path, msg);
        reference_checkpoint_remove(&c);
        rc = reference_checkpoint_resume(&c, &a, &resumed, msg);
    }
    if (rc == 0 && o.resume && !resumed) {
        snprintf(msg, RESTIR_MSG_LEN, "--resume: there is no checkpoint %.300s to continue (drop --resume to start)",
                 c.path);
        rc = EXIT_USAGE;
    }
    if (rc != 0) {
        cli_error("%s", msg);
        reference_accum_fini(&a);
        scene_destroy(&s);
        return rc == EXIT_USAGE ? EXIT_USAGE : EXIT_RUNTIME;
    }
    if (resumed)
        printf("resuming %s from %d of %d samples\n", c.path, a.done, spp);
    cli_catch_stop_signals();
    const int first = a.done;
    if (reference_checkpoint_render(&c, &a, msg) != 0) { /* a save failed; msg says which */
        rc = cli_stop_signal ? 128 + (int)cli_stop_signal : EXIT_RUNTIME;
        if (cli_stop_signal)
            cli_error("%s", msg);
    } else if (a.done < a.spp) { /* stopped by a signal */
        const char *sig = cli_stop_signal_name();
        if (c.every < 0.0)
            cli_error("interrupted by %s at %d of %d samples; nothing written (--checkpoint-every makes a reference "
                      "resumable)", sig, a.done, spp);
        else
            cli_error("interrupted by %s at %d of %d samples; checkpoint %s (the same command continues)", sig,
                      a.done, spp, c.path);
        rc = 128 + (int)cli_stop_signal;
    } else if (write_reference(&o, &a, &c, msg) != 0) {
        rc = EXIT_RUNTIME;
    } else {
        reference_checkpoint_remove(&c);
        printf("reference of %s on %s (%dx%d, %d spp) written to %s\n", o.method, o.scene, o.params.width,
               o.params.height, a.done, o.out);
        if (c.target > 0.0)
            printf("estimated relMSE %.4g (target %.4g%s)\n", reference_accum_relmse_estimate(&a), c.target,
                   reference_accum_relmse_estimate(&a) <= c.target ? "" : ": not reached within --spp");
        if (c.saved > 0)
            printf("%d checkpoints, %.1f ms each; %.1f ms per chunk of %d samples rendered\n", c.saved,
                   1e3 * c.t_saves / c.saved, 1e3 * c.t_render * REFERENCE_CHUNK_SPP / (a.done - first),
                   REFERENCE_CHUNK_SPP);
    }
    if (rc == EXIT_RUNTIME)
        cli_error("%s", msg);
    reference_accum_fini(&a);
    scene_destroy(&s);
    return rc;
}

