/* spherical_rect.c: uniform sampling of the solid angle of a rectangle (spherical_rect.h).
 *
 * The algebra, in the frame of spherical_rect.h (rectangle [x0, x1] x [y0, y1] at height -h): the
 * planes through x and the edges x = x_i and y = y_j have unit normals whose dot products give the
 * corner angles acos(+-p_i q_j), p_i = x_i / sqrt(x_i^2 + h^2), q_j = y_j / sqrt(y_j^2 + h^2), so the
 * solid angle (sum of the angles - 2 pi, Urena et al. 2013 Eq. 3) is
 *     omega = asin(p1 q1) + asin(p0 q0) - asin(p1 q0) - asin(p0 q1),
 * where asin(p_i q_j) = atan(x_i y_j / (h d_ij)) = arg(h d_ij + i x_i y_j), d_ij = |corner_ij - x|
 * (1 - p^2 q^2 factors exactly). The four arguments add as the argument of the product
 *     z = (h d11 + i x1 y1) (h d00 + i x0 y0) (h d10 - i x1 y0) (h d01 - i x0 y1),
 * one atan2 instead of four arcsines, and the product, in double, keeps the digits a sum of four
 * angles of size pi / 2 loses for a small rectangle (omega mod 2 pi, and omega lies in (0, 2 pi)); the
 * sampler turns arg(p) for asin(p0 q1) - asin(p0 q0) by u omega without another atan2.
 * The sub-rectangle [x0, xu] has the corner angles of the x0 edge plus acos(q0 t) + acos(-q1 t) at
 * the xu edge, t = xu / sqrt(xu^2 + h^2); setting its solid angle to u omega gives
 *     acos(q0 t) + acos(-q1 t) = pi + phi,  phi = u omega + asin(p0 q1) - asin(p0 q0),
 * whose solution (Urena et al. Sec. 4.1, with a = pi + phi) is
 *     xu = -sgn(N) h sin(phi) / sqrt(N^2 - (1 - q0^2) sin^2(phi)),  N = q0 cos(phi) - q1,
 * a form without the division by sin(a) of the paper, whose sign changes over a's range [0, 2 pi].
 * Along the line x = xu the solid angle is uniform in the sine of elevation y / sqrt(r^2 + y^2),
 * r^2 = xu^2 + h^2 (Urena et al. Sec. 4.2).
 *
 * Close to the plane N and the square root's argument are differences of numbers near 1 that must
 * resolve h: in float the points moved by up to 1.2e-2 of the rectangle's size at h = 1e-3 of it and
 * 5.8e-5 above h = 0.1 of it (against double, 10^6 random configurations above 0.02 sr), so the frame
 * and p are double and the map runs in double below SPHERICAL_RECT_FLOAT_H. The solid angle is float
 * (atan2f of the product's parts), the density's precision. */
#include "shading/spherical_rect.h"

#include <math.h>

/* Below this height over the rectangle's lx + ly the map runs in double. */
#define SPHERICAL_RECT_FLOAT_H 0.1

static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }
static double corner_distance(double d2, int precise) { return precise ? sqrt(d2) : (double)sqrtf((float)d2); }

int spherical_rect_frame(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly)
{
    /* the frame in double: h is a difference of nearly equal products close to the plane */
    const double dx = (double)corner.x - x.x, dy = (double)corner.y - x.y, dz = (double)corner.z - x.z;
    const vec3 nz = v3_cross(ux, uy);
    r->x0 = dx * ux.x + dy * ux.y + dz * ux.z;
    r->y0 = dx * uy.x + dy * uy.y + dz * uy.z;
    r->x1 = r->x0 + lx;
    r->y1 = r->y0 + ly;
    r->h = fabs(dx * nz.x + dy * nz.y + dz * nz.z);
    r->omega = 0.0f;
    /* x (almost) in the rectangle's plane: the corner terms divide by h, the map by 1 - q^2 */
    return r->h > 1e-4 * (lx + ly) && lx > 0.0f && ly > 0.0f && isfinite(r->h);
}

float spherical_rect_solid_angle(struct spherical_rect *r)
{
    const double lx = r->x1 - r->x0, ly = r->y1 - r->y0;
    const double h = r->h, h2 = h * h, xx0 = r->x0 * r->x0, xx1 = r->x1 * r->x1, yy0 = r->y0 * r->y0,
                 yy1 = r->y1 * r->y1;
    /* the four corner factors (real, imaginary); the distances in float (an error of 6e-8 of c moves
     * the argument by less than 6e-8) unless the map needs arg(p) in double */
    const int precise = h < SPHERICAL_RECT_FLOAT_H * (lx + ly);
    const double c00 = h * corner_distance(xx0 + yy0 + h2, precise), s00 = r->x0 * r->y0;
    const double c01 = h * corner_distance(xx0 + yy1 + h2, precise), s01 = r->x0 * r->y1;
    const double c10 = h * corner_distance(xx1 + yy0 + h2, precise), s10 = r->x1 * r->y0;
    const double c11 = h * corner_distance(xx1 + yy1 + h2, precise), s11 = r->x1 * r->y1;
    /* p = (c01 + i s01) (c00 - i s00), whose argument phi0 lies in (-pi, pi) */
    r->pr = c01 * c00 + s01 * s00;
    r->pi = s01 * c00 - c01 * s00;
    /* omega = arg((c11 + i s11) (c10 - i s10) conj(p)), scaled into float's range: atan2f of the
     * product's parts keeps float's precision of omega (the cancellation happened in double) */
    const double qr = c11 * c10 + s11 * s10, qi = s11 * c10 - c11 * s10;
    const double wr = qr * r->pr + qi * r->pi, wi = qi * r->pr - qr * r->pi, scale = 1.0 / (fabs(wr) + fabs(wi));
    float omega = atan2f((float)(wi * scale), (float)(wr * scale));
    omega = omega < 0.0f ? omega + 6.28318531f : omega;
    r->omega = omega > 0.0f && isfinite(omega) ? omega : 0.0f;
    return r->omega;
}

float spherical_rect_init(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly)
{
    return spherical_rect_frame(r, x, corner, ux, uy, lx, ly) ? spherical_rect_solid_angle(r) : 0.0f;
}

/* The map in double, for x close to the plane (r->h below SPHERICAL_RECT_FLOAT_H of the size). */
static void sample_precise(const struct spherical_rect *r, float u, float v, float *s, float *t)
{
    const double h = r->h, h2 = h * h, x0 = r->x0, x1 = r->x1, y0 = r->y0, y1 = r->y1;
    /* the first coordinate: the sub-rectangle [x0, xu] of solid angle u omega */
    const double l0 = sqrt(y0 * y0 + h2), q0 = y0 / l0, q1 = y1 / sqrt(y1 * y1 + h2);
    /* phi = u omega + arg(p) by the angle-sum identities: one sincos, no atan2 */
    const double lp = sqrt(r->pr * r->pr + r->pi * r->pi), c0 = r->pr / lp, s0 = r->pi / lp;
    const double su = sin(u * (double)r->omega), cu = cos(u * (double)r->omega);
    const double sin_phi = s0 * cu + c0 * su, cos_phi = c0 * cu - s0 * su;
    const double n = q0 * cos_phi - q1;
    const double den = n * n - h2 / (l0 * l0) * sin_phi * sin_phi; /* 1 - q0^2 = h^2 / l0^2 */
    const double num = (n < 0.0 ? sin_phi : -sin_phi) * h;
    /* den -> 0: xu -> +-infinity, which the clamp takes to the edge its sign points to */
    const double xu = clampd(den > 0.0 ? num / sqrt(den) : (num > 0.0 ? x1 : x0), x0, x1);
    /* the second: uniform in the sine of elevation along x = xu */
    const double rr2 = xu * xu + h2;
    const double e0 = y0 / sqrt(rr2 + y0 * y0), e1 = y1 / sqrt(rr2 + y1 * y1);
    const double e = e0 + v * (e1 - e0), c2 = (1.0 - e) * (1.0 + e);
    const double yv = clampd(c2 > 1e-30 ? e * sqrt(rr2 / c2) : (e > 0.0 ? y1 : y0), y0, y1);
    *s = (float)(xu - x0);
    *t = (float)(yv - y0);
}

void spherical_rect_sample(const struct spherical_rect *r, float u, float v, float *s, float *t)
{
    if (r->h < SPHERICAL_RECT_FLOAT_H * (r->x1 - r->x0 + r->y1 - r->y0)) {
        sample_precise(r, u, v, s, t);
        return;
    }
    /* the same in float */
    const float h = (float)r->h, h2 = h * h, x0 = (float)r->x0, x1 = (float)r->x1, y0 = (float)r->y0,
                y1 = (float)r->y1;
    const float inv_l0 = 1.0f / sqrtf(y0 * y0 + h2), q0 = y0 * inv_l0, q1 = y1 / sqrtf(y1 * y1 + h2);
    const float pr = (float)r->pr, pi = (float)r->pi; /* scaled: p's magnitude may leave float's range */
    const float inv_lp = 1.0f / sqrtf(pr * pr + pi * pi), c0 = pr * inv_lp, s0 = pi * inv_lp;
    const float su = sinf(u * r->omega), cu = cosf(u * r->omega);
    const float sin_phi = s0 * cu + c0 * su, cos_phi = c0 * cu - s0 * su;
    const float n = q0 * cos_phi - q1;
    const float den = n * n - h2 * inv_l0 * inv_l0 * sin_phi * sin_phi;
    const float num = (n < 0.0f ? sin_phi : -sin_phi) * h;
    const float xu = clampf(den > 0.0f ? num / sqrtf(den) : (num > 0.0f ? x1 : x0), x0, x1);
    const float rr2 = xu * xu + h2;
    const float e0 = y0 / sqrtf(rr2 + y0 * y0), e1 = y1 / sqrtf(rr2 + y1 * y1);
    const float e = e0 + v * (e1 - e0), c2 = (1.0f - e) * (1.0f + e);
    const float yv = clampf(c2 > 1e-12f ? e * sqrtf(rr2 / c2) : (e > 0.0f ? y1 : y0), y0, y1);
    *s = xu - x0;
    *t = yv - y0;
}
