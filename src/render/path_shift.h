/* path_shift.h: the ReSTIR PT sample (a path with what its shifts need), the pixel domains it
 * moves between, and the shift mappings with their Jacobian determinants (000 Eq. 1 and 6;
 * Lin et al. 2022 Sec. 7): reconnection, random replay, and the hybrid shift.
 *
 * A path x_1 .. x_D (D >= 2, x_D on an emitter) is stored as: its primary ray's sub-pixel
 * offset u, the seed of its per-vertex random streams (path_walk.h), and its reconnection vertex
 * x_k with everything after it. A shift keeps u (up to a domain's sub-pixel translation, a
 * bijection of the unit square with |T'| = 1: 000 footnote 1, Zhang et al. 2024), replays the
 * BSDF random numbers of x_1 .. x_{k-2} from the target pixel, connects y_{k-1} to x_k, and keeps
 * the suffix. Its Jacobian is
 *   |T'| = prod_{j<=k-2} p(w_j)/p(w'_j)  *  (|cos'_k| / d'^2) / (|cos_k| / d^2)
 * (replayed solid-angle densities, then the solid angle of x_k seen from the new y_{k-1}).
 * The shift kind fixes k: reconnection k = 2, replay k = D, hybrid k = the first j in [2, D-1]
 * where x_{j-1} and x_j are both rough and farther apart than a distance threshold, else D. The
 * target re-checks that rule so the shift stays a bijection.
 *
 * Environment light: a path may end in a direction w of the environment, a vertex at
 * infinity. When it is the reconnection vertex (k = D), the shift keeps the direction: y_{k-1}
 * connects along w, the ray must escape the scene, and the direction's solid-angle measure does
 * not depend on the point it is seen from, so the reconnection factor of |T'| is 1 (no distance
 * or cosine term; the replayed density ratio stays). Must never depend on reservoirs. */
#ifndef RESTIR_RENDER_PATH_SHIFT_H
#define RESTIR_RENDER_PATH_SHIFT_H

#include "render/path_walk.h"
#include "render/shift_kind.h"
#include "scene/camera.h"

struct shift_params {
    enum shift_kind kind;
    float min_roughness; /* hybrid: a vertex is rough when its GGX alpha is at least this */
    float min_distance;  /* hybrid: reconnection segments must be longer (scene units; scene and
                            absolute distance modes) */
    enum shift_distance_mode distance_mode;
    float distance_factor; /* relative mode: ... longer than this times the camera's distance to their
                              first vertex */
    vec3 camera;         /* relative mode: the camera position of the domain paths are created in
                            (path_sample_from_candidate); shifts use their target domain's */
    const unsigned char *rough; /* per material: 1 when rough (path_shift_rough_table); NULL: computed
                                   on every query */
};

/* Fills rough[m] for every material of s (s->num_materials entries) from sp->min_roughness. */
void path_shift_rough_table(const struct scene *s, const struct shift_params *sp, unsigned char *rough);

struct path_sample {
    int length;          /* D; 0 = no sample */
    int rc;              /* reconnection vertex index k in [2, D] */
    int rc_env;          /* k = D and x_D is the environment in direction rc_w (rc_p is unused) */
    float u[2];          /* sub-pixel offset of the primary ray, [0,1)^2 */
    float lens[2];       /* thin-lens sample, [0,1)^2 (0 with a pinhole) */
    float time;          /* shutter time, [0,1) (camera_view_pose; 0 without motion blur) */
    uint64_t seed;       /* per-vertex random streams */
    vec3 x1_p;           /* the primary hit x_1 in the domain the path lives in (reservoir splatting
                            keeps it): point, triangle and barycentrics */
    int x1_tri;
    float x1_b1, x1_b2;
    vec3 rc_p;           /* x_k */
    vec3 rc_n;           /* x_k's geometric normal on the side of x_{k-1} (emitting normal if k = D) */
    vec3 rc_w;           /* k < D: unit direction x_k -> x_{k+1}; rc_env: direction x_{D-1} -> x_D */
    vec3 rc_L;           /* k < D: radiance arriving at x_k along rc_w; k = D: Le of x_D */
    int rc_material;     /* k < D: material at x_k */
    int rc_tri;          /* k < D: x_k's triangle and barycentrics (textures are read there) */
    float rc_b1, rc_b2;
    /* Jacobian terms of this path in the domain it lives in: */
    float rc_cos;        /* |rc_n . (x_{k-1} - x_k)| / |x_{k-1} - x_k| (1 if rc_env) */
    float rc_dist2;      /* |x_k - x_{k-1}|^2 (1 if rc_env) */
    float prefix_pdf;    /* prod of solid-angle densities of w_1 .. w_{k-2} */
    vec3 f;              /* contribution in its domain */
};

/* A pixel integration domain: a pixel seen through a camera view, and the translation of the
 * sub-pixel square into a common image frame: a path with offset u in domain A has offset
 * wrap(u + origin_A - origin_B) in domain B (with clip: u + origin_A - origin_B where that is in
 * [0,1)^2, else none). Current-frame pixels use their own coordinates as
 * origin (spatial shifts keep u); a previous-frame pixel uses its coordinates minus the backward
 * motion vector (temporal shifts follow the fractional motion, Zhang et al. 2024). */
struct pt_domain {
    const struct camera_view *view;
    int x, y;
    float origin[2];
    int clip; /* a shift from or to this domain translates u without wrapping and is undefined where
                 the offset leaves [0,1)^2 (temporal.subpixel=search) */
};

/* Fills the reconnection data of a candidate just produced by a path walk (seed and u already
 * set by the caller), choosing k by the shift kind. */
void path_sample_from_candidate(const struct scene *s, const struct shift_params *sp, const struct path_walk *w,
                                const struct path_candidate *c, struct path_sample *out);

/* Shifts path x from domain `from` to domain `to`. Returns 1 with the shifted path in *y and
 * |dT/dx| in *jacobian; 0 when the shift is undefined at x or the shifted path contributes
 * nothing (*y then has length 0). *rays counts the rays traced. */
int path_shift(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
               const struct pt_domain *from, const struct pt_domain *to, struct path_sample *y, float *jacobian,
               long long *rays);

/* Reservoir splatting's shift (Liu et al. 2025): path x of the previous frame, seen through
 * from_view at its shutter time, keeps its primary hit x_1 (and its lens sample) and moves to
 * the current frame at shutter time `time`: its primary ray is the one from the same lens point
 * through x_1, so the image position follows x_1's projection. The rest of the path is shifted
 * from the kept x_1 as path_shift does from a traced one (replay to x_{k-1}, reconnect to x_k).
 * Returns 1 with the pixel it lands in (*pixel, row-major in to_view's image), the shifted path in
 * *y (u is its sub-pixel offset there) and |dT/dx| in *jacobian; 0 when x_1 projects outside the
 * image, is hidden from the new lens point, or the shifted path contributes nothing. `time_scale`
 * multiplies the Jacobian (the shutter-time map's; 1 when the time is kept). */
int path_shift_splat(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
                     const struct camera_view *from_view, const struct camera_view *to_view, float time,
                     float time_scale, int *pixel, struct path_sample *y, float *jacobian, long long *rays);

/* Where path x's primary hit lands in view at shutter time `time` (image position; no ray is
 * traced). Returns 0 when it is behind the lens or outside the image. */
int path_splat_position(const struct path_sample *x, const struct camera_view *view, float time, float *px,
                        float *py);

/* The image position of the primary ray of a path with offset u in pixel (x, y). */
static inline void path_image_position(int x, int y, const float u[2], float *px, float *py)
{
    *px = (float)x + u[0];
    *py = (float)y + u[1];
}

#endif
