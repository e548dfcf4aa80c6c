/* renderer.h: runs a method frame by frame: the per-frame state its passes keep (ping-pong G-buffers
 * and reservoirs, cameras) and per-pass timings. Must never read or write files. */
#ifndef RESTIR_METHODS_RENDERER_H
#define RESTIR_METHODS_RENDERER_H

#include "methods/method.h"
#include "render/di_sample.h"
#include "render/gbuffer.h"
#include "render/light_pool.h"
#include "render/params.h"
#include "render/pt_splat.h"
#include "render/restir_pt.h"

struct grad_frame;

/* PASS_CELLS .. PASS_SPMIS_REUSE are spatial.reuse=spmis's passes, split as 004 Table 2: create
 * reuse cells (Algorithm 1), cell search (Algorithm 2 line 2, Sec. 5.1), the canonical weight
 * (lines 6-12) and stochastic neighbor reuse (lines 13-20). */
enum pass_id {
    PASS_GBUFFER,
    PASS_INITIAL,
    PASS_TEMPORAL,
    PASS_SELECT,
    PASS_SPATIAL,
    PASS_CELLS,
    PASS_CELL_SEARCH,
    PASS_SPMIS_CANONICAL,
    PASS_SPMIS_REUSE,
    PASS_SHADE,
    PASS_PT,
    PASS_GPT,
    PASS_GRAD_INITIAL,
    PASS_GRAD_TEMPORAL,
    PASS_GRAD_SELECT,
    PASS_GRAD_SPATIAL,
    PASS_GRAD_SHADE,
    PASS_RECON_L2,
    PASS_RECON_L1,
    PASS_COUNT
};
extern const char *const pass_names[PASS_COUNT];

struct frame_stats {
    double ms[PASS_COUNT];
    double ms_total;
    long long rays;
    long long temporal_accepted; /* pixels whose history passed validation */
    long long neighbors_selected; /* spatial neighbors the selection pass found */
    long long valid_pixels;
    long long edge_pairs;        /* grestir-pt: pairs the spatial pass searched a neighbor for */
    long long pair_neighbors;    /* grestir-pt: neighbor pairs found */
    double l2_residual, l1_residual; /* gradient methods: relative residuals of the solves */
    long long nonfinite;             /* NaN / infinite reservoirs and radiance values discarded (nonfinite.h) */
    struct temporal_counts temporal; /* path reservoirs: pixels with temporal candidates per technique */
};

struct renderer {
    const struct scene *scene;
    struct render_params p;
    enum method_id method;
    struct gbuffer gb[2];
    int cur; /* index of the current G-buffer / history */
    int frame;
    int has_history;
    struct camera_view prev_view;
    struct camera prev_cam;       /* the last frame's camera: where the next frame's shutter opens */
    int has_prev_cam;
    struct di_reservoir *work;    /* initial, then temporal outputs */
    struct di_reservoir *hist[2]; /* spatial outputs: this frame's and the previous frame's */
    struct light_pool lights;     /* DI methods: this frame's light candidates (initial RIS) */
    struct pt_reservoir *pt_work;    /* restir-pt: as work */
    struct pt_reservoir *pt_hist[2]; /* restir-pt: as hist */
    vec3 *pt_emission;               /* restir-pt: emission seen directly by the initial paths */
    unsigned char *temporal_flags;   /* restir-pt: this frame's TEMPORAL_* bits per pixel (pt_splat.h) */
    struct pt_splat_buffers *splat;  /* temporal.reuse=splat|both: landing buckets */
    float scene_diagonal;            /* scales shift.distance */
    unsigned char *material_rough;   /* restir-pt: hybrid shift's roughness class per material */
    int *neighbors;                  /* selection pass output: spatial neighbors per pixel */
    float *disk_offsets;             /* R2 disk offsets of compat selection (R2_DISK_OFFSETS x 2) */
    struct spmis_frame *spmis;    /* spatial.reuse=spmis: cells and per-pixel scratch */
    unsigned char *age[2];        /* per pixel: frames its surface has been in view (history chain
                                     length by G-buffer validation, capped at 255); ping-pong */
    struct grad_frame *grad;      /* gradient methods: primal, gradients, reconstructions */
    float *image;                 /* this frame's radiance, RGB (gradient methods: the reconstruction
                                     recon selects, L2 for recon=both) */
};

/* p must have passed render_params_validate. */
void renderer_init(struct renderer *r, const struct scene *s, enum method_id method, const struct render_params *p);
void renderer_fini(struct renderer *r);
/* Renders frame number `frame` seen by cam into r->image. */
/* The shutter opens at the previous frame's camera (camera.shutter > 0), or at cam for the first. */
void renderer_render(struct renderer *r, int frame, const struct camera *cam, struct frame_stats *st);
/* The camera the next frame's shutter opens at (instead of the last frame's camera): a single
 * frame of a sequence rendered on its own, e.g. a reference, sees the same motion blur. */
void renderer_set_shutter_open(struct renderer *r, const struct camera *open);
/* The view a frame of p is rendered through: cam with p's lens settings over the scene camera's,
 * and with camera.shutter > 0 the shutter opening at `open` (NULL: cam, no motion). */
void renderer_camera_view(const struct render_params *p, const struct camera *cam, const struct camera *open,
                          struct camera_view *v);
/* Gradient methods: the screened Poisson reconstruction (L2; L1 too unless recon=l2) of
 * r->grad's primal and gradients into r->image, timed into st->ms. renderer_render calls it; call
 * it again after changing the inputs (e.g. averaging instances, 002 Sec. 5). */
void renderer_reconstruct(struct renderer *r, struct frame_stats *st);
/* Forgets history (the next frame starts without temporal reuse). */
void renderer_reset(struct renderer *r);

/* After a ReSTIR frame: mask[i] = 1 for the valid pixels of the last frame whose temporal
 * history was rejected (G-buffer validation, 001) in any of its last `frames` frames, i.e. the
 * disoccluded pixels of 004 Sec. 6.2; 0 elsewhere. Returns the number of pixels marked. */
#define DISOCCLUSION_FRAMES 4 /* the window of the and 004 Sec. 6.2's disocclusion masks */
long long renderer_disoccluded(const struct renderer *r, int frames, unsigned char *mask);


#endif
