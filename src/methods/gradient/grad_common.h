/* grad_common.h: what the gradient-domain methods (002: gpt, grad-after-restir, grestir-pt)
 * share: the per-frame image buffers (primal, forward-difference gradients, reconstructions),
 * one-sided differences toward the four neighbors, directly seen emission, and the combination
 * of one-sided differences into gradients (002 Eq. 3 and Eq. 12).
 *
 * Sign convention (restir/grad.h): dx[a] = F(a + x) - F(a), dy[a] = F(a + y) - F(a); the last
 * column of dx and the last row of dy are 0 (those pairs leave the image; the reconstruction
 * ignores them). One-sided differences are stored per pixel and direction, os[dir][a] =
 * <Delta'_{a, a+dir}> = omega_{a,n}(x) (f_a(x) - f_n(T x) |T'|) / p(x) (Eq. 3's integrands, Eq. 11),
 * so that combining them needs no atomics: dx[a] = os[LEFT][a + 1] - os[RIGHT][a] (Eq. 12 with
 * our sign). Must never allocate per pixel. */
#ifndef RESTIR_METHODS_GRADIENT_GRAD_COMMON_H
#define RESTIR_METHODS_GRADIENT_GRAD_COMMON_H

#include <stddef.h>

#include "render/path_shift.h"

enum grad_dir { GRAD_RIGHT = 0, GRAD_LEFT, GRAD_DOWN, GRAD_UP, GRAD_DIRS };

/* Pixel offset of a direction. */
static inline void grad_dir_offset(int d, int *dx, int *dy)
{
    static const int ox[GRAD_DIRS] = {1, -1, 0, 0}, oy[GRAD_DIRS] = {0, 0, 1, -1};
    *dx = ox[d];
    *dy = oy[d];
}

/* One-sided differences: 4 directions x 3 channels per pixel, os[(d * n + i) * 3 + c]. */
static inline float *grad_os(float *os, size_t n, int d, size_t i) { return os + ((size_t)d * n + i) * 3; }

/* Clears os (4 * 3 * n floats). */
void grad_os_clear(float *os, size_t n);

/* dx, dy (RGB) += the gradients combined from the one-sided differences os (Eq. 12). */
void grad_combine(int w, int h, const float *os, float *dx, float *dy);

/* Shifts x from pixel domain `from` to `to` and writes f(T x) |T'| into other (0 where T is
 * undefined), and |T'| into *jacobian when it is not NULL (0 where T is undefined). Returns rays
 * traced. */
long long grad_shift_other(const struct scene *s, const struct shift_params *sp, const struct path_sample *x,
                           const struct pt_domain *from, const struct pt_domain *to, float other[3], float *jacobian);

/* os[dir][i] += weight * omega (f_own - f_other) for a base path x of pixel (x, y) shifted into each
 * neighbor inside the image (Eq. 3's integrand for base paths of known density: weight = m / p;
 * Eq. 11 for a ReSTIR path: weight = W). Returns rays traced. */
long long grad_one_sided_all(const struct scene *s, const struct shift_params *sp, const struct camera_view *view,
                             const struct path_sample *x, int px, int py, int w, int h, float weight, float *os,
                             size_t i);

/* dx, dy (RGB) += the forward differences of image E (RGB floats, or vec3 when packed alike): the
 * gradients of emission seen directly, taken from the primal's own estimate E of it. A primal and
 * gradients that agree exactly on E reconstruct it exactly (L2 and L1 alike: adding a consistent
 * pair (E, grad E) to the inputs shifts the solution by E), so this is Kettunen et al.'s "keep
 * directly visible emission out of the solve and add it after": shifting primary rays instead
 * gives +-Le one-sided estimates at every light edge, which the solve spreads into blobs. */
void grad_add_image_differences(int w, int h, const float *E, float *dx, float *dy);

#endif
