/* cmd_reference.c: `restir reference`, a converged image of what a method estimates, with resumable checkpoints.
 * Must never implement a method; its sharded form (reference_shards.c) never calls back into it. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/reference_checkpoint.h"
#include "experiments/reference_run.h"
#include "experiments/reference_shards.h"
#include "methods/reference.h"

int cmd_reference(int argc, char **argv)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge"))
            return reference_merge(argc, argv);
    struct reference_setup st;
    int rc = reference_setup(argc, argv, 1, &st);
    if (rc != 0)
        return rc < 0 ? 0 : rc;
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
    int resumed = 0;
    if (reference_checkpoint_resume(&c, &a, &resumed, msg) != 0) {
        cli_error("%s", msg);
        reference_accum_fini(&a);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    if (resumed)
        printf("resuming %s from %d of %d samples\n", c.path, a.done, spp);
    cli_catch_stop_signals();
    const int first = a.done;
    if (reference_checkpoint_render(&c, &a, msg) != 0) { /* a save failed; msg says which */
        rc = cli_stop_signal ? 128 + (int)cli_stop_signal : EXIT_RUNTIME;
        if (cli_stop_signal)
            cli_error("%s", msg);
    } else if (a.done < spp) { /* stopped by a signal */
        const char *sig = cli_stop_signal_name();
        if (c.every < 0.0)
            cli_error("interrupted by %s at %d of %d samples; nothing written (--checkpoint-every makes a reference "
                      "resumable)", sig, a.done, spp);
        else
            cli_error("interrupted by %s at %d of %d samples; checkpoint %s (the same command continues)", sig,
                      a.done, spp, c.path);
        rc = 128 + (int)cli_stop_signal;
    } else if (reference_write_image(o.out, a.mean, a.params.width, a.params.height, a.done, a.spp, c.run, o.method,
                                     o.scene, NULL, NULL, msg) != 0) {
        rc = EXIT_RUNTIME;
    } else {
        reference_checkpoint_remove(&c);
        printf("reference of %s on %s (%dx%d, %d spp) written to %s\n", o.method, o.scene, o.params.width,
               o.params.height, spp, o.out);
        if (c.saved > 0)
            printf("%d checkpoints, %.1f ms each; %.1f ms per chunk of %d samples rendered\n", c.saved,
                   1e3 * c.t_saves / c.saved, 1e3 * c.t_render * REFERENCE_CHUNK_SPP / (spp - first),
                   REFERENCE_CHUNK_SPP);
    }
    if (rc == EXIT_RUNTIME)
        cli_error("%s", msg);
    reference_accum_fini(&a);
    scene_destroy(&s);
    return rc;
}

