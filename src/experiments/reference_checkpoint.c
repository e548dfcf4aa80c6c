/* reference_checkpoint.c: a reference's running mean saved and continued exactly (reference_checkpoint.h).
 * Must never implement a method or call into a command. */
#include "experiments/reference_checkpoint.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "io/atomic_file.h"
#include "io/exr.h"

/* Checkpoints let the same command continue after Ctrl-C, SIGTERM or a kill and still give the
 * bytes of an uninterrupted run. */

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

/* Writes the running mean and its attributes to c's file (atomically: io/atomic_file.h). */
static int save(struct reference_checkpoint *c, const struct reference_accum *a, char *msg)
{
    const double t0 = omp_get_wtime();
    char obs[32];
    snprintf(obs, sizeof obs, "%d", a->var_obs);
    const struct exr_attribute var_obs = {"restir.var_obs", obs};
    const int rc = reference_write_image(c->path, a->mean, a->params.width, a->params.height, a->done, a->spp,
                                         c->run, c->method, c->scene, a->m2, &var_obs, a->m2 ? 1 : 0, msg);
    c->t_saves += omp_get_wtime() - t0;
    c->saved += rc == 0;
    return rc;
}

/* The checkpoint's variance state when it has a usable one, else tracking from here on. */
static void resume_variance(const char *path, struct reference_accum *a)
{
    char text[32], why[RESTIR_MSG_LEN], *end = NULL;
    float *m2 = NULL;
    int w = 0, h = 0;
    long obs = exr_read_attribute(path, "restir.var_obs", text, sizeof text, why) == 0 ? strtol(text, &end, 10) : -1;
    int usable = end && end != text && *end == '\0' && obs >= 1 && obs <= (1L << 20) &&
                 exr_read_layer(path, "m2", &m2, &w, &h, why) == 0 && w == a->params.width && h == a->params.height;
    for (size_t i = 0; usable && i < 3 * (size_t)w * (size_t)h; i++)
        usable = isfinite(m2[i]) && m2[i] >= 0.0f;
    reference_accum_track_variance(a, usable ? m2 : NULL, (int)obs);
    free(m2);
}

int reference_checkpoint_resume(struct reference_checkpoint *c, struct reference_accum *a, int *resumed, char *msg)
{
    const char *path = c->path, *run = c->run;
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
    long done =
        exr_read_attribute(path, "restir.samples", text, sizeof text, why) == 0 ? strtol(text, &end, 10) : -1;
    if (!end || end == text || *end != '\0' || errno != 0 || done < 1 || done > (1L << 20)) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: restir.samples is missing or not a sample count", path);
        return -1;
    }
    if (!reference_accum_can_resume((int)done, a->spp)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 done > a->spp
                     ? "%.300s holds %ld samples, more than --spp %d"
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
            snprintf(msg, RESTIR_MSG_LEN, "%.300s: pixel (%zu, %zu) is %f; remove the checkpoint to start over",
                     path, i / 3 % (size_t)w, i / 3 / (size_t)w, (double)mean[i]);
            free(mean);
            return -1;
        }
    reference_accum_resume(a, mean, (int)done);
    free(mean);
    if (c->target > 0.0)
        resume_variance(path, a);
    *resumed = 1;
    return 0;
}

void reference_checkpoint_init(struct reference_checkpoint *c, const struct reference_accum *a, const char *out,
                               double every, const char *method, const char *scene)
{
    memset(c, 0, sizeof *c);
    checkpoint_path(out, c->path, sizeof c->path);
    reference_describe(a, c->run, sizeof c->run);
    c->method = method;
    c->scene = scene;
    c->every = every;
    /* a kill during an earlier run's write leaves its temporary behind */
    io_remove_stale_temporaries(c->path);
    io_remove_stale_temporaries(out);
}

int reference_checkpoint_render(struct reference_checkpoint *c, struct reference_accum *a, char *msg)
{
    struct progress pg;
    progress_begin(&pg, "reference", a->spp);
    double last = omp_get_wtime();
    int rc = 0;
    if (c->target > 0.0 && !a->m2)
        reference_accum_track_variance(a, NULL, 0);
    while (a->done < a->spp && !cli_stop_signal) {
        const double t0 = omp_get_wtime();
        reference_accum_step(a);
        c->t_render += omp_get_wtime() - t0;
        progress_update(&pg, a->done);
        if (c->target > 0.0 && reference_accum_relmse_estimate(a) <= c->target)
            a->spp = a->done; /* reached: the image holds what it needs */
        if (c->every >= 0.0 && a->done < a->spp && !cli_stop_signal && omp_get_wtime() - last >= c->every) {
            if ((rc = save(c, a, msg)) != 0)
                break;
            last = omp_get_wtime();
        }
    }
    progress_end(&pg);
    if (rc == 0 && a->done < a->spp && c->every >= 0.0 && save(c, a, msg) != 0) { /* stopped by a signal */
        char why[RESTIR_MSG_LEN];
        snprintf(why, sizeof why, "%s", msg);
        snprintf(msg, RESTIR_MSG_LEN, "interrupted by %s at %d of %d samples, and the checkpoint failed: %.400s",
                 cli_stop_signal_name(), a->done, a->spp, why);
        rc = -1;
    }
    return rc;
}

void reference_checkpoint_remove(const struct reference_checkpoint *c)
{
    if (remove(c->path) != 0 && errno != ENOENT)
        cli_error("warning: cannot remove %s: %s", c->path, strerror(errno));
}

void reference_checkpoint_discard(const char *out)
{
    struct reference_checkpoint c;
    checkpoint_path(out, c.path, sizeof c.path);
    reference_checkpoint_remove(&c);
}

/* PLAN_REFERENCE_CHECKPOINT_SECONDS, or the environment's RESTIR_REFERENCE_CHECKPOINT_SECONDS
 * when it is a number >= 0 (anything else is ignored, with a warning). */
static double plan_checkpoint_seconds(void)
{
    const char *text = getenv("RESTIR_REFERENCE_CHECKPOINT_SECONDS");
    if (!text)
        return PLAN_REFERENCE_CHECKPOINT_SECONDS;
    char *end = NULL;
    const double s = strtod(text, &end);
    if (end == text || *end != '\0' || !(s >= 0.0 && s < 1e9)) {
        cli_error("warning: RESTIR_REFERENCE_CHECKPOINT_SECONDS='%.40s' is not a number of seconds >= 0; saving "
                  "every %.0f s",
                  text, PLAN_REFERENCE_CHECKPOINT_SECONDS);
        return PLAN_REFERENCE_CHECKPOINT_SECONDS;
    }
    return s;
}

int reference_job_finish(float *ref, const char *out, int w, int h, char *msg)
{
    int rc = 0;
    if (!ref || exr_write_rgb(out, ref, w, h, msg) != 0) {
        cli_error("%s", msg);
        rc = !ref && cli_stop_signal ? 128 + (int)cli_stop_signal : EXIT_RUNTIME;
    } else {
        reference_checkpoint_discard(out);
    }
    free(ref);
    return rc;
}

float *reference_render_resumable(const struct scene *s, const struct method *method, const struct render_params *p,
                                  const struct camera *cam, const struct camera *open, int spp, const char *out,
                                  char *msg)
{
    struct reference_accum a;
    reference_accum_init(&a, s, method, p, cam, open, spp);
    struct reference_checkpoint c;
    reference_checkpoint_init(&c, &a, out, plan_checkpoint_seconds(), method->name, s->name);
    int resumed = 0;
    if (reference_checkpoint_resume(&c, &a, &resumed, msg) != 0) {
        reference_accum_fini(&a);
        return NULL;
    }
    if (resumed)
        printf("resuming %s from %d of %d samples\n", c.path, a.done, spp);
    if (reference_checkpoint_render(&c, &a, msg) != 0) {
        reference_accum_fini(&a);
        return NULL;
    }
    if (a.done < spp) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "interrupted by %s at %d of %d samples; checkpoint %.300s (the same job continues)",
                 cli_stop_signal_name(), a.done, spp, c.path);
        reference_accum_fini(&a);
        return NULL;
    }
    float *img = a.mean;
    free(a.chunk);
    return img;
}
