/* renderer.h: runs a registered method (method.h) frame by frame: the cameras and the image every
 * method has, the method's own state behind a pointer, per-pass timings, and what a method exposes
 * of its last frame (renderer_inspect). Must never read or write files or name a method. */
#ifndef RESTIR_METHODS_RENDERER_H
#define RESTIR_METHODS_RENDERER_H

#include <omp.h>

#include "denoise/denoise.h"
#include "methods/method.h"
#include "methods/passes.h"
#include "render/gbuffer.h"
#include "render/params.h"
#include "render/temporal_flags.h"
#include "scene/camera.h"

struct spmis_frame;

struct frame_stats {
    double ms[PASS_MAX]; /* milliseconds per pass id (passes.h); 0 for the passes the method has not run */
    double ms_total;
    /* bit id: pass id ran in the method's reconstruct (renderer_reconstruct), which a compare row that
     * averages instances runs once: their other instances' frame time leaves it out */
    unsigned long long reconstructed;
    long long rays;
    long long temporal_accepted; /* pixels whose history passed validation */
    long long neighbors_selected; /* spatial neighbors the selection pass found */
    long long valid_pixels;
    long long edge_pairs;        /* grestir-pt: pairs the spatial pass searched a neighbor for */
    long long pair_neighbors;    /* grestir-pt: neighbor pairs found */
    double l2_residual, l1_residual; /* gradient methods: relative residuals of the solves */
    long long nonfinite;             /* NaN / infinite reservoirs and radiance values discarded (nonfinite.h) */
    struct temporal_counts temporal; /* path reservoirs: pixels with temporal candidates per technique */
    struct denoise_stats denoise;    /* denoise=svgf|atrous: pixels left raw, histories reset */
};

/* The method-independent part of a renderer; everything else is the method's own state. */
struct renderer {
    const struct scene *scene;
    struct render_params p;       /* with the method's defaults applied */
    const struct method *method;
    void *state;                  /* the method's (struct method.create) */
    int frame;                    /* the frame being rendered, or the last one */
    int prev_frame;               /* the frame rendered before it (valid when rendered > 1) */
    int lights_changed;           /* 1 when this frame's animated emitters differ from the previous rendered
                                     frame's (scene_lights_differ); 0 on the first frame */
    int lights_moved;             /* 1 when some moving emitter's pose differs from the previous rendered frame's
                                     (scene_lights_moved): restir-di then measures an old sample in the old
                                     frame's geometry (scene_occluded_previous_batch) */
    int rendered;                 /* frames rendered so far */
    struct camera_view prev_view; /* the previous frame's view (valid after the first frame) */
    struct camera prev_cam;       /* the last frame's camera: where the next frame's shutter opens */
    int has_prev_cam;
    float *image;                 /* this frame's radiance, RGB (gradient methods: the reconstruction
                                     recon selects, L2 for recon=both) */
    float *denoised;              /* denoise=svgf|atrous: this frame denoised, RGB (NULL: off); the
                                     frame in image is never changed by it */
    struct denoiser *denoiser;    /* its state (history), NULL: off */
    struct gbuffer *denoise_gbuffer; /* the G-buffer traced for it when the method keeps none */
    int denoise_frames;           /* frames denoised so far */
};

/* What a method exposes of its last frame, for debug views and metrics; NULL / 0 where it has
 * none. Pointers stay valid until the next renderer_render or renderer_fini. */
struct renderer_inspect {
    const struct gbuffer *gbuffer; /* the last frame's G-buffer */
    const unsigned char *age;      /* per pixel: frames its surface has been in view (history
                                      chain length by G-buffer validation, capped at 255) */
    const int *neighbors;          /* selection pass output, neighbors_per_pixel per pixel (-1: none) */
    int neighbors_per_pixel;
    const struct spmis_frame *spmis; /* spatial.reuse=spmis: the last frame's cells */
    const unsigned char *temporal_flags; /* path reservoirs: TEMPORAL_* bits per pixel (pt_splat.h) */
    const float *temporal_gradient; /* A-SVGF's lambda per pixel for the denoiser, or NULL (restir-di) */
    const void *reservoirs;        /* the last frame's final reservoirs, read by confidence() */
    float (*confidence)(const void *reservoirs, int pixel);
};

/* Whether temporal reuse may read last frame's reservoirs in a method that cannot measure an old sample
 * under the old frame's lights (restir-pt, restir-gi and the gradient methods over restir-pt): there is
 * a history and this frame's animated emitters are the previous frame's. On a frame whose lights
 * changed such a method drops its temporal reuse (the frame is its own samples and spatial reuse,
 * unbiased: render.animated_unbiased, where keeping the history instead is off by -30% right after a
 * switch-on), and the next frame's history holds only the current lights. restir-di instead measures
 * each domain under its own frame's lights (di_relight). */
static inline int renderer_history_reusable(const struct renderer *r, int has_history)
{
    return has_history && !r->lights_changed;
}

/* p must have passed render_params_validate and method_check_settings. Allocates the method's
 * state; aborts when memory runs out. */
void renderer_init(struct renderer *r, const struct scene *s, const struct method *method,
                   const struct render_params *p);
void renderer_fini(struct renderer *r);
/* Renders frame number `frame` seen by cam into r->image, and with denoise=svgf|atrous denoises it
 * into r->denoised (after the method's passes, the reconstruction and the non-finite guard, so
 * r->image is bit for bit what it is without denoising). */
/* The shutter opens at the previous frame's camera (camera.shutter > 0), or at cam for the first. */
void renderer_render(struct renderer *r, int frame, const struct camera *cam, struct frame_stats *st);
/* The camera the next frame's shutter opens at (instead of the last frame's camera): a single
 * frame of a sequence rendered on its own, e.g. a reference, sees the same motion blur. */
void renderer_set_shutter_open(struct renderer *r, const struct camera *open);
/* The view a frame of p is rendered through: cam with p's lens settings over the scene camera's,
 * and with camera.shutter > 0 the shutter opening at `open` (NULL: cam, no motion). */
void renderer_camera_view(const struct render_params *p, const struct camera *cam, const struct camera *open,
                          struct camera_view *v);
/* A method with a reconstruct (the gradient methods: screened Poisson, L2 and L1 unless recon=l2)
 * recomputes r->image and its derived outputs from its radiance and signed outputs (renderer_output),
 * timed into st->ms. renderer_render calls it; call it again after changing those inputs (e.g.
 * averaging instances, 002 Sec. 5). Does nothing for the other methods. */
void renderer_reconstruct(struct renderer *r, struct frame_stats *st);
/* The denoisers' view of a G-buffer (borrowed pointers into g). */
void renderer_denoise_guide(const struct gbuffer *g, struct denoise_guide *out);
/* What the method exposes of its last frame (struct renderer_inspect). */
void renderer_inspect(const struct renderer *r, struct renderer_inspect *out);
/* The pixels of output k of r->method->outputs (method.h) for the last frame: borrowed,
 * width x height x channels floats, valid until the next renderer_render or renderer_fini, and
 * writable (instances averaged into the first, then renderer_reconstruct). NULL when k is out of
 * range or the settings leave that output out. */
float *renderer_output(const struct renderer *r, int k);

/* After a frame of a METHOD_HISTORY method: mask[i] = 1 for the valid pixels of the last frame
 * whose temporal history was rejected (G-buffer validation, 001) in any of its last `frames`
 * frames, i.e. the disoccluded pixels of 004 Sec. 6.2; 0 elsewhere. Returns the number of pixels
 * marked (0, mask all 0, for methods without history). */
#define DISOCCLUSION_FRAMES 4 /* the window of 004 Sec. 6.2's disocclusion masks */
long long renderer_disoccluded(const struct renderer *r, int frames, unsigned char *mask);
/* The number of valid pixels (primary ray hit) of the last frame's G-buffer; -1 without one. */
long long renderer_valid_pixels(const struct renderer *r);

/* Accumulates the milliseconds of stmt into st->ms[pass]: the per-pass timing of every method. */
#define RENDERER_TIMED(st, pass, stmt)                                                         \
    do {                                                                                       \
        double t0_ = omp_get_wtime();                                                          \
        stmt;                                                                                  \
        (st)->ms[pass] += 1e3 * (omp_get_wtime() - t0_);                                       \
    } while (0)

#endif
