/* restir_gi.h: the passes of ReSTIR GI (Ouyang et al. 2021, "ReSTIR GI: Path Resampling for
 * Real-Time Path Tracing", HPG 2021) written as GRIS (004 Sec. 2, Eq. 5-7, 10) so that it is
 * unbiased by construction: initial sampling of one secondary vertex per pixel, temporal reuse of
 * the previous frame's reservoir under the validated motion vector, spatial reuse, and shading.
 *
 * Pixel i's estimate is I_i = Le(x1_i) + D_i + f_i(Y) W_Y, x1_i the primary hit of the ray through
 * the G-buffer's image position g->sub_pixel[i] (pinhole, as the G-buffer traces it):
 *   Le(x1_i)  emission seen directly (the environment for a pixel whose primary ray misses);
 *   D_i       direct light at x1_i, the NEE and BSDF-hit candidates of one path_walk_run with
 *             max_bounces = 1, weighted by their MIS as pt weighs them (paths of length 2);
 *   f_i(Y) W  the indirect light (paths of length >= 3) through the reservoir's sample Y.
 * A sample Y = (x2, seed): a surface point x2 and the 64-bit seed of the random streams of the
 * path suffix from x2 (random replay, path_walk.h). Pixel i's domain is the solid angle of the
 * direction w = normalize(x2 - x1_i) (x2 the first hit along w) times the uniform measure of the
 * suffix random numbers, and its integrand is
 *   f_i(Y) = f_s(x1_i; wo_i, w) |n_i . w| [w . ng_i > 0] Lr(x2 -> x1_i; seed),
 * n_i the shading normal as bsdf_shading_normal bends it for wo_i, and Lr the sum of m f / p over
 * the candidates of path_walk_run from x2 (normals facing x1_i) with max_bounces - 1 scattering
 * events: x2's own emission is direct light at x1_i, counted in D_i, so D_i plus the indirect
 * term estimate exactly what pt does. The target is p_hat_i = luminance(f_i).
 *
 * The shift T_{a->b} keeps x2 and the seed and connects x1_b to x2 (ReSTIR GI Eq. 11's
 * reconnection): it fails where x2 is hidden from x1_b or f_b is zero, and its Jacobian is
 *   |dw_b / dw_a| = (|ng_2 . w_b| / |x2 - x1_b|^2) / (|ng_2 . w_a| / |x2 - x1_a|^2).
 * T_{b->a} is its inverse on the samples where both succeed, and the two Jacobians multiply to 1.
 * With gi.radiance=reevaluate Lr in domain b is traced again from x2 toward x1_b with the same
 * seed (the identity on the suffix's random numbers: unbiased); with gi.radiance=stored the
 * sample's Lo is kept (the paper's form; BIASED: every material of bsdf.h has a view-dependent
 * lobe, so Lr depends on the direction toward x1).
 *
 * Ownership and threading: the caller allocates every buffer (one entry per pixel, row-major,
 * width * height of the G-buffer) and keeps two x1 buffers and two reservoir buffers that
 * ping-pong between frames. Every pass is an OpenMP loop over tiles (render/tiles.h) with one
 * random stream per (seed, frame, pixel, pass), so its output does not depend on the thread count.
 * Must never allocate per pixel or read files. */
#ifndef RESTIR_METHODS_RESTIR_GI_RESTIR_GI_H
#define RESTIR_METHODS_RESTIR_GI_RESTIR_GI_H

#include <stddef.h>
#include <stdint.h>

#include "render/gbuffer.h"
#include "render/params.h"
#include "render/path_walk.h"

/* A ReSTIR GI sample in the domain of one shading point x1 (scene units, world space). */
struct gi_sample {
    vec3 x2_p;       /* the sample point x2 */
    vec3 x2_ng;      /* x2's geometric normal, unit, facing x1 of the domain the sample lives in */
    int x2_tri;      /* x2's triangle and barycentrics (its material and textures are read there) */
    float x2_b1, x2_b2;
    uint64_t seed;   /* random streams of the path suffix from x2 (path_rng) */
    vec3 Lo;         /* radiance leaving x2 toward x1 as last evaluated (W sr^-1 m^-2 per channel) */
    vec3 f;          /* f(Y) in the domain the sample lives in: f_s |n . w| Lo */
    float cos2;      /* |ng_2 . w|, w the unit direction x1 -> x2 (Jacobian term) */
    float dist2;     /* |x2 - x1|^2 (Jacobian term) */
    int valid;       /* 0: no sample */
};

/* A GI reservoir (004 Sec. 2.6): the sample, its unbiased contribution weight W (steradians:
 * 1 / a solid-angle density), confidence c and the cached target p_hat = luminance(f) in the pixel
 * that owns it. */
struct gi_reservoir {
    struct gi_sample y;
    float W;
    float c;
    float target;
};

static inline void gi_reservoir_clear(struct gi_reservoir *r, float c)
{
    r->y.valid = 0;
    r->W = 0.0f;
    r->c = c;
    r->target = 0.0f;
}

static inline int gi_reservoir_has_sample(const struct gi_reservoir *r) { return r->y.valid && r->W > 0.0f; }

/* A pixel's shading point x1 is a path_vertex (path_vertex_from_hit of its primary ray: wo toward
 * the camera, normals on the camera's side); tri < 0 marks a pixel without one (the primary ray
 * missed), which is no domain: its reservoir holds nothing, with confidence 0. */
static inline int gi_x1_valid(const struct path_vertex *v) { return v->tri >= 0; }

/* What every pass of one frame reads. */
struct gi_frame {
    const struct scene *s;
    const struct render_params *p; /* max_bounces, rr_bounces, mis, confidence_cap, temporal_normal,
                                      temporal_plane, gi_radiance, spatial_neighbors, seed */
    const struct camera_view *view; /* this frame (the G-buffer's camera) */
    int frame;
};

/* Initial sampling (one candidate per pixel, as ReSTIR GI): traces pixel i's primary ray
 * through g->sub_pixel[i], writes its shading point to x1[i] (valid only where g->valid[i] and the
 * ray hits), Le + D_i (or the environment seen through the pixel) to base[i], and out[i]: one
 * BSDF-sampled direction from x1 whose hit x2 gets a fresh seed and Lr from the path walk,
 * resampled with weight p_hat / p(w) (W = 1 / p(w)), c = 1 (0 without x1). No GI sample when
 * max_bounces <= 1 or the direction escapes (the environment seen from x1 is in D_i). Returns
 * the rays traced. */
long long gi_initial_pass(const struct gi_frame *fr, const struct gbuffer *g, struct path_vertex *x1, vec3 *base,
                          struct gi_reservoir *out);

/* Temporal reuse: where gbuffer_history_pixel (reading G-buffers only) finds previous pixel q,
 * GRIS merges io[i] (domain x1[i]) and prev_res[q] (domain prev_x1[q], the previous frame's x1
 * buffer) into io[i]. io holds the initial reservoirs on entry and the outputs on return; pixels
 * without history keep their input. *accepted counts the pixels merged. Returns rays traced. */
long long gi_temporal_pass(const struct gi_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct path_vertex *x1, const struct path_vertex *prev_x1,
                           const struct gi_reservoir *prev_res, struct gi_reservoir *io, long long *accepted);

/* Most spatial neighbors a merge reads (render_params_spatial_neighbors is at most 5, params.c). */
#define GI_MAX_NEIGHBORS 5

/* Spatial reuse: GRIS merge of in[i] with the reservoirs of the neighbors the selection pass
 * listed (neighbors[(size_t)i * m + k], m = render_params_spatial_neighbors(p, 1), -1 for none;
 * at most GI_MAX_NEIGHBORS are read), all in this frame's domains x1. Pixels without x1 copy
 * their input. in and out must not overlap. Returns rays traced. */
long long gi_spatial_pass(const struct gi_frame *fr, const struct gbuffer *g, const int *neighbors,
                          const struct path_vertex *x1, const struct gi_reservoir *in, struct gi_reservoir *out);

/* Final shading: rgb[3i..3i+2] = base[i] + f(Y) W_Y (f cached by the last shift into the pixel,
 * visibility included, so no ray is traced). */
void gi_shade_pass(const struct gbuffer *g, const vec3 *base, const struct gi_reservoir *res, float *rgb);

/* Shifts sample x (living in the domain its cos2 / dist2 describe) to the domain of shading point
 * to_x1: keeps x2 and the seed, tests visibility (one ray) and evaluates f there (a path walk with
 * gi.radiance=reevaluate). Returns 1 with the shifted sample in *y and |dT/dx| in *jacobian; 0
 * when the shift is undefined or the shifted sample contributes nothing (y->valid = 0, *jacobian
 * = 0). *rays counts the rays traced. Thread-safe; uses about 6 KB of stack (a path walk). */
int gi_shift(const struct scene *s, const struct render_params *p, const struct gi_sample *x,
             const struct path_vertex *to_x1, struct gi_sample *y, float *jacobian, long long *rays);

/* The renderer's non-finite guard (nonfinite.h) for GI reservoirs: one whose W, target, c or f is
 * not finite is emptied (a finite c kept, else 0). The passes already drop what they compute
 * non-finite; this catches anything else. Returns how many were discarded. */
long long gi_nonfinite_discard(struct gi_reservoir *res, size_t n);

#endif
