/* cmd_reference.c: `restir reference`, a converged image of what a method estimates, with resumable checkpoints.
 * Must never implement a method; its sharded form (reference_shards.c) never calls back into it. */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "commands.h"
#include "core/check.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "methods/reference.h"
#include "reference_run.h"
#include "reference_shards.h"

/* Checkpoints let the same command continue after Ctrl-C, SIGTERM or a kill and still give the
 * bytes of an uninterrupted run (issue 13). */

/* FILE.exr -> FILE.checkpoint.exr; any other name gets ".checkpoint.exr" appended. */
static void checkpoint_path(const char *out, char *path, size_t len)
{
    size_t n = strlen(out);
    if (n >= 4 && strcmp(out + n - 4, ".exr") == 0)
        snprintf(path, len, "%.*s.checkpoint.exr", (int)(n - 4), out);
    else
        snprintf(path, len, "%s.checkpoint.exr", out);
}

/* The first "key=value" field where two run descriptions differ, as "key: A (checkpoint) vs B". */
static void first_difference(const char *theirs, const char *ours, char *out, size_t len)
{
    while (*theirs || *ours) {
        size_t a = strcspn(theirs, ";"), b = strcspn(ours, ";");
        if (a != b || strncmp(theirs, ours, a) != 0) {
            size_t key = strcspn(ours, "=");
            const char *ta = memchr(theirs, '=', a), *ob = memchr(ours, '=', b);
            snprintf(out, len, "%.*s: %.*s in the checkpoint, %.*s now", (int)(key < b ? key : b), ours,
                     ta ? (int)(a - (size_t)(ta + 1 - theirs)) : (int)a, ta ? ta + 1 : theirs,
                     ob ? (int)(b - (size_t)(ob + 1 - ours)) : (int)b, ob ? ob + 1 : ours);
            return;
        }
        theirs += a + (theirs[a] == ';');
        ours += b + (ours[b] == ';');
        theirs += *theirs == ' ';
        ours += *ours == ' ';
    }
    snprintf(out, len, "(no difference found)");
}

/* Writes the running mean and its attributes to path (atomically: io/atomic_file.h). */
static int write_state(const char *path, const struct reference_accum *a, const char *run, const char *method,
                       const char *scene, char *msg)
{
    return reference_write_image(path, a->mean, a->params.width, a->params.height, a->done, a->spp, run, method,
                                 scene, NULL, NULL, msg);
}

/* Continues a from the checkpoint at path when it is this run's. Returns 0 (resumed, or no
 * checkpoint: *resumed says which), or -1 with msg saying why the checkpoint cannot be used. */
static int resume_from(const char *path, const char *run, struct reference_accum *a, int *resumed, char *msg)
{
    *resumed = 0;
    struct stat st;
    if (stat(path, &st) != 0)
        return 0;
    char theirs[RUN_TEXT_MAX], text[64], why[RESTIR_MSG_LEN];
    int rc = exr_read_attribute(path, "restir.run", theirs, sizeof theirs, why);
    if (rc != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s exists but is not a reference checkpoint (%.150s); move it away",
                 path, rc > 0 ? "no restir.run attribute" : why);
        return -1;
    }
    if (strcmp(theirs, run) != 0) {
        first_difference(theirs, run, why, sizeof why);
        snprintf(msg, RESTIR_MSG_LEN,
                 "%.200s is a checkpoint of another run (%.150s); remove it to start over or choose another --out",
                 path, why);
        return -1;
    }
    char *end = NULL;
    errno = 0;
    long done = exr_read_attribute(path, "restir.samples", text, sizeof text, why) == 0 ? strtol(text, &end, 10) : -1;
    if (!end || end == text || *end != '\0' || errno != 0 || done < 1 || done > (1L << 20)) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: restir.samples is missing or not a sample count", path);
        return -1;
    }
    if (!reference_accum_can_resume((int)done, a->spp)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 done > a->spp ? "%.300s holds %ld samples, more than --spp %d"
                               : "%.300s holds %ld samples, which is not a multiple of %d: it cannot continue exactly",
                 path, done, done > a->spp ? a->spp : REFERENCE_CHUNK_SPP);
        return -1;
    }
    float *mean = NULL;
    int w = 0, h = 0;
    if (exr_read_rgb(path, &mean, &w, &h, why) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "cannot resume: %.400s", why);
        return -1;
    }
    if (w != a->params.width || h != a->params.height) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: its image is %dx%d, not the %dx%d its restir.run names; remove it",
                 path, w, h, a->params.width, a->params.height);
        free(mean);
        return -1;
    }
    for (size_t i = 0; i < 3 * (size_t)w * (size_t)h; i++)
        if (!isfinite(mean[i])) {
            snprintf(msg, RESTIR_MSG_LEN, "%.300s: pixel (%zu, %zu) is %f; remove the checkpoint to start over", path,
                     i / 3 % (size_t)w, i / 3 / (size_t)w, (double)mean[i]);
            free(mean);
            return -1;
        }
    reference_accum_resume(a, mean, (int)done);
    free(mean);
    *resumed = 1;
    return 0;
}

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
    const enum method_id method = st.method;
    struct camera cam = st.cam, open = st.cam_open;
    struct reference_accum a;
    reference_accum_init(&a, &s, method, &o.params, &cam, &open, spp);
    char run[RUN_TEXT_MAX], ckpt[4200];
    reference_describe(&a, run, sizeof run);
    checkpoint_path(o.out, ckpt, sizeof ckpt);
    /* a kill during an earlier run's write leaves its temporary behind */
    io_remove_stale_temporaries(ckpt);
    io_remove_stale_temporaries(o.out);
    int resumed = 0;
    if (resume_from(ckpt, run, &a, &resumed, msg) != 0) {
        cli_error("%s", msg);
        reference_accum_fini(&a);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    if (resumed)
        printf("resuming %s from %d of %d samples\n", ckpt, a.done, spp);
    const int checkpoints = o.checkpoint_every >= 0.0;
    cli_catch_stop_signals();
    struct progress pg;
    progress_begin(&pg, "reference", spp);
    double last = omp_get_wtime(), t_render = 0.0, t_checkpoints = 0.0;
    int saved = 0, first = a.done;
    while (a.done < spp && !cli_stop_signal) {
        double t0 = omp_get_wtime();
        reference_accum_step(&a);
        t_render += omp_get_wtime() - t0;
        progress_update(&pg, a.done);
        if (checkpoints && a.done < spp && !cli_stop_signal && omp_get_wtime() - last >= o.checkpoint_every) {
            t0 = omp_get_wtime();
            if (write_state(ckpt, &a, run, o.method, o.scene, msg) != 0) {
                rc = EXIT_RUNTIME;
                break;
            }
            last = omp_get_wtime();
            t_checkpoints += last - t0;
            saved++;
        }
    }
    progress_end(&pg);
    if (rc == 0 && a.done < spp) { /* stopped by a signal */
        const char *sig = cli_stop_signal_name();
        if (!checkpoints) {
            cli_error("interrupted by %s at %d of %d samples; nothing written (--checkpoint-every makes a reference "
                      "resumable)", sig, a.done, spp);
        } else if (write_state(ckpt, &a, run, o.method, o.scene, msg) != 0) {
            cli_error("interrupted by %s at %d of %d samples, and the checkpoint failed: %s", sig, a.done, spp, msg);
        } else {
            cli_error("interrupted by %s at %d of %d samples; checkpoint %s (the same command continues)", sig,
                      a.done, spp, ckpt);
        }
        rc = 128 + (int)cli_stop_signal;
    } else if (rc == 0 && write_state(o.out, &a, run, o.method, o.scene, msg) != 0) {
        rc = EXIT_RUNTIME;
    } else if (rc == 0) {
        if (remove(ckpt) != 0 && errno != ENOENT)
            cli_error("warning: cannot remove %s: %s", ckpt, strerror(errno));
        printf("reference of %s on %s (%dx%d, %d spp) written to %s\n", o.method, o.scene, o.params.width,
               o.params.height, spp, o.out);
        if (saved > 0)
            printf("%d checkpoints, %.1f ms each; %.1f ms per chunk of %d samples rendered\n", saved,
                   1e3 * t_checkpoints / saved, 1e3 * t_render * REFERENCE_CHUNK_SPP / (spp - first),
                   REFERENCE_CHUNK_SPP);
    }
    if (rc == EXIT_RUNTIME)
        cli_error("%s", msg);
    reference_accum_fini(&a);
    scene_destroy(&s);
    return rc;
}

