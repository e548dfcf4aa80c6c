/* restir_di.h: the passes of ReSTIR DI (Bitterli et al. 2020; 001; 004 Sec. 2): initial RIS,
 * temporal reuse, spatial reuse and shading. Each is a plain function over per-pixel arrays.
 * Must never allocate per pixel or read files. */
#ifndef RESTIR_METHODS_RESTIR_DI_RESTIR_DI_H
#define RESTIR_METHODS_RESTIR_DI_RESTIR_DI_H

#include "methods/restir_di/di_sample.h"
#include "render/params.h"
#include "methods/restir_di/di_settings.h"

struct light_pool;
struct regir_grid;
/* Initial RIS: light + BSDF candidates combined by MIS into one reservoir per pixel, c = 1; the
 * light candidates are a window of the frame's pool lp (light_pool.h, filled for this frame, for
 * windows of at least di.light_candidates), or, when rg is not NULL, of the slots of the pixel's
 * ReGIR cell (regir.h, built over g and filled for this frame). With di.visibility_reuse the
 * selected sample is then dropped when occluded. Returns rays traced. */
long long di_initial_pass(const struct scene *s, const struct light_pool *lp, const struct regir_grid *rg,
                          const struct render_params *p, int frame, const struct gbuffer *g, struct di_reservoir *out);

/* Temporal reuse (001): reprojects each pixel into the previous frame, validates against the
 * previous G-buffer and merges the history reservoir by GRIS. io holds the initial reservoirs on
 * entry and the temporal outputs on return. Returns the number of pixels whose history was
 * accepted and adds the shadow rays of visibility-aware targets (di_visibility.h) to *rays.
 * prev_t is the previous frame's time (animated emitters' strengths and poses then); moved: 1 when
 * emitters moved since, and the previous frame's geometry is posed for its shadow rays
 * (scene_motion_pose_previous at prev_t; scene_can_trace_previous must hold).
 * confidence_grad: NULL, or per pixel the temporal gradient lambda (di_gradient.h) that scales the
 * history's confidence by (1 - lambda)^10 in pixel i's merge (di.gradient_confidence, BIASED). */
long long di_temporal_pass(const struct scene *s, const struct render_params *p, int frame, float prev_t,
                           int moved, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct di_reservoir *prev_res, const float *confidence_grad, struct di_reservoir *io,
                           long long *rays);

/* Spatial reuse: GRIS merge of the neighbors' reservoirs; neighbors holds the selection pass's
 * lists (render_params_spatial_neighbors(p, 0) per pixel, -1 for none). Returns shadow rays traced. */
long long di_spatial_pass(const struct scene *s, const struct render_params *p, int frame, const struct gbuffer *g,
                          const int *neighbors, const struct di_reservoir *in, struct di_reservoir *out);

/* Stochastic pairwise MIS spatial reuse (004 Algorithm 2) from the cells and chosen cells in f
 * (reuse_cells.h): di_spmis_weights fills f->conf and f->weight (Eq. 17) from the temporal
 * outputs; di_spmis_canonical_pass computes m~_c (lines 6-12, Eq. 18-19) into f->m_c;
 * di_spmis_reuse_pass merges the canonical and N drawn neighbors (lines 13-20, Eq. 14-16). Light
 * samples live in one space for every pixel: each shift is the identity with Jacobian 1. The two
 * passes return the shadow rays of visibility-aware targets. */
struct spmis_frame;
void di_spmis_weights(const struct render_params *p, const struct gbuffer *g, const struct di_reservoir *in,
                      struct spmis_frame *f);
long long di_spmis_canonical_pass(const struct scene *s, const struct render_params *p, int frame,
                                  const struct gbuffer *g, const struct di_reservoir *in, struct spmis_frame *f);
long long di_spmis_reuse_pass(const struct scene *s, const struct render_params *p, int frame, const struct gbuffer *g,
                              const struct di_reservoir *in, const struct spmis_frame *f, struct di_reservoir *out);

/* Final shading: primary emission + f(Y) W_Y, with one shadow ray unless the reservoir's target
 * already includes visibility at the pixel (di_targets_visible). Returns rays traced. */
long long di_shade_pass(const struct scene *s, const struct render_params *p, const struct gbuffer *g,
                        const struct di_reservoir *res, float *rgb);

#endif
