/* reference_checkpoint.h: a reference accumulation that survives a kill: its running mean
 * and sample count saved beside the output as FILE.checkpoint.exr, and continued from there with
 * the bytes of an uninterrupted run. `restir reference` and the reference jobs of study, compare and
 * evaluate plans use it. Must never implement a method or call into a command. */
#ifndef RESTIR_EXPERIMENTS_REFERENCE_CHECKPOINT_H
#define RESTIR_EXPERIMENTS_REFERENCE_CHECKPOINT_H

#include "experiments/reference_run.h"
#include "methods/pt/reference.h"

/* Seconds between a plan's reference job's saves: a kill costs at most this much rendering. The
 * environment's RESTIR_REFERENCE_CHECKPOINT_SECONDS (a number >= 0; 0: after every chunk) replaces it. */
#define PLAN_REFERENCE_CHECKPOINT_SECONDS 300.0

struct reference_checkpoint {
    char path[4200];            /* FILE.checkpoint.exr */
    char run[RUN_TEXT_MAX];     /* reference_describe of the accumulation: what a checkpoint must match */
    const char *method, *scene; /* restir.method and restir.scene of the saved images */
    double every;               /* seconds between saves; < 0: none, and a stop loses the work */
    double target;              /* stop once the estimated relMSE is at most this (0: render a->spp; the
                                   caller sets it after reference_checkpoint_init, before resuming) */
    int saved;                  /* saves so far, and their time and the rendering's, in seconds */
    double t_saves, t_render;
};

/* Prepares the checkpoint of the reference a accumulates into out (FILE.exr -> FILE.checkpoint.exr,
 * any other name gets ".checkpoint.exr" appended), saved every `every` seconds, and removes the
 * temporaries a kill during an earlier save left beside it and beside out. */
void reference_checkpoint_init(struct reference_checkpoint *c, const struct reference_accum *a, const char *out,
                               double every, const char *method, const char *scene);
/* Continues a from c's file when it holds this run's state, and with c->target > 0 tracks a's
 * variance (continuing the checkpoint's when it holds one, else from the resume point on).
 * Returns 0 (*resumed: 1 when it did, 0 when there is no checkpoint), or -1 with msg saying why the file cannot be used (another run's,
 * not a checkpoint, a sample count that cannot continue exactly, a non-finite pixel). */
int reference_checkpoint_resume(struct reference_checkpoint *c, struct reference_accum *a, int *resumed, char *msg);
/* Renders a's chunks until it holds a->spp samples, or (c->target > 0) until its estimated relMSE
 * (reference_accum_relmse_estimate) is at most c->target, which sets a->spp to the samples it
 * holds, or until a stop signal arrives (cli_stop_signal), printing progress, saving every
 * c->every seconds and, when c->every >= 0, at a stop. Returns 0 (a->done < a->spp: stopped), or
 * -1 with msg when a save failed. */
int reference_checkpoint_render(struct reference_checkpoint *c, struct reference_accum *a, char *msg);
/* Removes the checkpoint once the finished image is written (a missing one is fine). */
void reference_checkpoint_remove(const struct reference_checkpoint *c);
/* The same for the reference whose output is out. */
void reference_checkpoint_discard(const char *out);

/* A plan job's reference: cli_render_reference, resumable from out's checkpoint, saved every
 * PLAN_REFERENCE_CHECKPOINT_SECONDS and at a stop. The caller writes the image to out, then calls
 * reference_checkpoint_discard(out). Returns the image (w*h*3, to free), or NULL with msg (a stop,
 * after saving; a failed save; an unusable checkpoint). */
float *reference_render_resumable(const struct scene *s, const struct method *method, const struct render_params *p,
                                  const struct camera *cam, const struct camera *open, int spp, const char *out,
                                  char *msg);

/* A plan's reference job's end: writes ref (reference_render_resumable's result; NULL: msg says
 * why) to out as a plain RGB EXR, then removes the checkpoint, and frees ref. Returns 0, 128 + the
 * signal after a stop, or EXIT_RUNTIME, having said what failed. */
int reference_job_finish(float *ref, const char *out, int w, int h, char *msg);

#endif
