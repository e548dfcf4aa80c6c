/* restir_pt.h: the passes of ReSTIR PT (Lin et al. 2022; 004 Sec. 2; 000 Sec. 3) with sub-pixel
 * (area) reservoirs (Zhang et al. 2024): initial path resampling, temporal reuse along the
 * fractional backward motion vector, spatial reuse, and shading by f(Y) W_Y.
 * Must never allocate per pixel or read files. */
#ifndef RESTIR_METHODS_RESTIR_PT_RESTIR_PT_H
#define RESTIR_METHODS_RESTIR_PT_RESTIR_PT_H

#include "render/gbuffer.h"
#include "render/params.h"
#include "render/path_shift.h"
#include "methods/restir_pt/restir_pt_settings.h"

/* A path reservoir (004 Sec. 2.6): the path, its unbiased contribution weight W, confidence c and
 * the cached target p_hat = luminance(f) in the pixel that owns it. */
struct pt_reservoir {
    struct path_sample y;
    float W;
    float c;
    float target;
};

static inline void pt_reservoir_clear(struct pt_reservoir *r, float c)
{
    r->y.length = 0;
    r->W = 0.0f;
    r->c = c;
    r->target = 0.0f;
}

static inline int pt_reservoir_has_sample(const struct pt_reservoir *r) { return r->y.length >= 2 && r->W > 0.0f; }

/* The domain of pixel (x, y) of the current frame: spatial shifts keep the sub-pixel offset. */
static inline struct pt_domain pt_pixel_domain(const struct camera_view *view, int x, int y)
{
    struct pt_domain d = {view, x, y, {(float)x, (float)y}, 0};
    return d;
}

/* What every pass of one frame reads. */
struct pt_frame {
    const struct scene *s;
    const struct render_params *p;
    struct shift_params shift;
    const struct camera_view *view;      /* this frame */
    const struct camera_view *prev_view; /* the previous frame (temporal reuse) */
    int frame;
};

/* The shift parameters the render parameters ask for; scene_diagonal scales shift.distance. */
void pt_shift_params(const struct render_params *p, float scene_diagonal, vec3 camera, struct shift_params *out);

/* Initial sampling: pt.candidates paths per pixel by the shared path walk, each from its own
 * jittered primary ray, every NEE/BSDF candidate resampled with weight m f / p into one
 * reservoir, c = number of paths; emission seen directly goes to `emission` (paths of length 1
 * are not resampled). The primary rays must not share random numbers with the G-buffer: neighbor
 * and history selection read the G-buffer, and the sub-pixel position is part of the sample, so
 * a shared jitter would make the selected domains depend on the sample and bias GRIS. The
 * G-buffer of restir-pt is therefore traced through pixel centres. Returns rays traced. */
long long pt_initial_pass(const struct pt_frame *fr, const struct gbuffer *g, struct pt_reservoir *out,
                          vec3 *emission);

/* Temporal reuse by backprojection: the previous pixel under the sub-pixel position plus backward
 * motion (validated on G-buffers as 001) is merged by GRIS with shifts between the two frames. io
 * holds the initial reservoirs on entry and the outputs on return; flags (one per pixel) receive
 * temporal_flags.h's TEMPORAL_BP_* bits. Returns rays traced; *accepted counts pixels that reused
 * history. (Splatting: pt_splat.h.) */
long long pt_temporal_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct pt_reservoir *prev_res, struct pt_reservoir *io, long long *accepted,
                           unsigned char *flags);

/* Spatial reuse: GRIS merge with shifts of the neighbors listed by the selection pass
 * (render_params_spatial_neighbors(p, 1) per pixel, -1 for none). Returns rays traced. */
long long pt_spatial_pass(const struct pt_frame *fr, const struct gbuffer *g, const int *neighbors,
                          const struct pt_reservoir *in, struct pt_reservoir *out);

/* Stochastic pairwise MIS spatial reuse (004 Algorithm 2) from the cells and chosen cells in f
 * (reuse_cells.h). pt_spmis_weights fills f->conf and f->weight (Eq. 17) from the temporal
 * outputs; pt_spmis_canonical_pass computes m~_c (Algorithm 2 lines 6-12, Eq. 18-19) into f->m_c;
 * pt_spmis_reuse_pass merges the canonical and N drawn neighbors (lines 13-20, Eq. 14-16) into
 * out. Return rays traced. */
struct spmis_frame;
void pt_spmis_weights(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                      struct spmis_frame *f);
long long pt_spmis_canonical_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                                  struct spmis_frame *f);
long long pt_spmis_reuse_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                              const struct spmis_frame *f, struct pt_reservoir *out);

/* Final shading: emission seen directly + f(Y) W_Y (f cached by the last shift into the pixel,
 * visibility included, so no ray is traced). */
void pt_shade_pass(const struct gbuffer *g, const struct pt_reservoir *res, const vec3 *emission, float *rgb);

/* Empties every reservoir of res[0..n) whose W, target or confidence is not finite (render/nonfinite.h's
 * rule, so one bad value cannot spread through reuse); returns how many it emptied. Threads: OpenMP. */
long long nonfinite_discard_pt(struct pt_reservoir *res, size_t n);

#endif
