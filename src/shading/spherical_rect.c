/* spherical_rect.c: uniform sampling of the solid angle of a rectangle (spherical_rect.h), in float.
 *
 * The algebra, in the frame of spherical_rect.h (rectangle [x0, x1] x [y0, y1] at height -h): the
 * planes through x and the edges x = x_i and y = y_j have unit normals whose dot products give the
 * corner angles acos(+-p_i q_j), p_i = x_i / sqrt(x_i^2 + h^2), q_j = y_j / sqrt(y_j^2 + h^2), so the
 * solid angle (sum of the angles - 2 pi, Urena et al. 2013 Eq. 3) is
 *     omega = asin(p1 q1) + asin(p0 q0) - asin(p1 q0) - asin(p0 q1),
 * and asin(p_i q_j) = atan(x_i y_j / (h sqrt(x_i^2 + y_j^2 + h^2))) (1 - p^2 q^2 factors exactly).
 * The sub-rectangle [x0, xu] has the corner angles of the x0 edge plus acos(q0 t) + acos(-q1 t) at
 * the xu edge, t = xu / sqrt(xu^2 + h^2); setting its solid angle to u omega gives
 *     acos(q0 t) + acos(-q1 t) = pi + phi,  phi = u omega + asin(p0 q1) - asin(p0 q0),
 * whose solution (Urena et al. Sec. 4.1, with a = pi + phi) is
 *     xu = -sgn(N) h sin(phi) / sqrt(N^2 - (1 - q0^2) sin^2(phi)),  N = q0 cos(phi) - q1,
 * a form without the division by sin(a) of the paper, whose sign changes over a's range [0, 2 pi].
 * Along the line x = xu the solid angle is uniform in the sine of elevation y / sqrt(r^2 + y^2),
 * r^2 = xu^2 + h^2 (Urena et al. Sec. 4.2). */
#include "shading/spherical_rect.h"

#include <math.h>

static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }

float spherical_rect_init(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly)
{
    const vec3 d = v3_sub(corner, x);
    r->x0 = v3_dot(d, ux);
    r->y0 = v3_dot(d, uy);
    r->x1 = r->x0 + lx;
    r->y1 = r->y0 + ly;
    r->h = fabsf(v3_dot(d, v3_cross(ux, uy)));
    r->omega = 0.0f;
    /* x (almost) in the rectangle's plane: the corner terms divide by h, the sampler by 1 - q^2 */
    if (!(r->h > 1e-4f * (lx + ly)) || !(lx > 0.0f && ly > 0.0f))
        return 0.0f;
    /* asin(p_i q_j) as atan(x_i y_j / (h |corner_ij - x|)), its value without asin's loss near +-1
     * (x close to the plane: with asinf the solid angle was off by 1e-3 at h = 1e-3 of the size) */
    const float h2 = r->h * r->h, xx0 = r->x0 * r->x0, xx1 = r->x1 * r->x1, yy0 = r->y0 * r->y0, yy1 = r->y1 * r->y1;
    const float a00 = atanf(r->x0 * r->y0 / (r->h * sqrtf(xx0 + yy0 + h2)));
    const float a01 = atanf(r->x0 * r->y1 / (r->h * sqrtf(xx0 + yy1 + h2)));
    const float a10 = atanf(r->x1 * r->y0 / (r->h * sqrtf(xx1 + yy0 + h2)));
    const float a11 = atanf(r->x1 * r->y1 / (r->h * sqrtf(xx1 + yy1 + h2)));
    r->phi0 = a01 - a00;
    const float omega = (a11 - a10) - r->phi0;
    r->omega = omega > 0.0f && isfinite(omega) ? omega : 0.0f;
    return r->omega;
}

void spherical_rect_sample(const struct spherical_rect *r, float u, float v, float *s, float *t)
{
    /* the first coordinate: the sub-rectangle [x0, xu] of solid angle u omega */
    const float h2 = r->h * r->h;
    const float l0 = sqrtf(r->y0 * r->y0 + h2), q0 = r->y0 / l0, q1 = r->y1 / sqrtf(r->y1 * r->y1 + h2);
    const float cos2_0 = h2 / (l0 * l0); /* 1 - q0^2 without its cancellation near the plane */
    const float phi = u * r->omega + r->phi0;
    const float sin_phi = sinf(phi), cos_phi = cosf(phi);
    const float n = q0 * cos_phi - q1;
    const float den = n * n - cos2_0 * sin_phi * sin_phi;
    const float num = (n < 0.0f ? sin_phi : -sin_phi) * r->h;
    /* den -> 0: xu -> +-infinity, which the clamp takes to the edge its sign points to */
    float xu = den > 0.0f ? num / sqrtf(den) : (num > 0.0f ? r->x1 : r->x0);
    xu = clampf(xu, r->x0, r->x1);
    /* the second: uniform in the sine of elevation along x = xu */
    const float rr2 = xu * xu + r->h * r->h;
    const float e0 = r->y0 / sqrtf(rr2 + r->y0 * r->y0), e1 = r->y1 / sqrtf(rr2 + r->y1 * r->y1);
    const float e = e0 + v * (e1 - e0);
    const float c2 = (1.0f - e) * (1.0f + e);
    float yv = c2 > 1e-12f ? e * sqrtf(rr2 / c2) : (e > 0.0f ? r->y1 : r->y0);
    yv = clampf(yv, r->y0, r->y1);
    *s = xu - r->x0;
    *t = yv - r->y0;
}
