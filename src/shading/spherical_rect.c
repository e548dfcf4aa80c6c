/* spherical_rect.c: uniform sampling of the solid angle of a rectangle (spherical_rect.h), in float,
 * and in double for points close to the rectangle's plane.
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
 * r^2 = xu^2 + h^2 (Urena et al. Sec. 4.2).
 *
 * Close to the plane N and the square root's argument are differences of numbers near 1 that must
 * resolve h: in float the points moved by up to 1.2e-2 of the rectangle's size at h = 1e-3 of it and
 * 5.8e-5 above h = 0.1 of it (against double, 10^6 random configurations above 0.02 sr), so below
 * SPHERICAL_RECT_FLOAT_H the map runs in double. */
#include "shading/spherical_rect.h"

#include <math.h>

/* Below this height over the rectangle's lx + ly, the map is evaluated in double. */
#define SPHERICAL_RECT_FLOAT_H 0.1f

static float clampf(float v, float lo, float hi) { return v < lo ? lo : (v > hi ? hi : v); }
static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* The corner term asin(p q) = atan(x y / (h |corner - x|)) in float and in double. */
static float corner_term(float x, float y, float h) { return atanf(x * y / (h * sqrtf(x * x + y * y + h * h))); }
static double corner_term_d(double x, double y, double h) { return atan(x * y / (h * sqrt(x * x + y * y + h * h))); }

float spherical_rect_init(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly)
{
    const vec3 d = v3_sub(corner, x);
    r->x0 = v3_dot(d, ux);
    r->y0 = v3_dot(d, uy);
    r->x1 = r->x0 + lx;
    r->y1 = r->y0 + ly;
    r->h = fabsf(v3_dot(d, v3_cross(ux, uy)));
    r->omega = 0.0f;
    /* x (almost) in the rectangle's plane: even double loses the map there */
    if (!(r->h > 1e-4f * (lx + ly)) || !(lx > 0.0f && ly > 0.0f) || !isfinite(r->h))
        return 0.0f;
    r->precise = r->h < SPHERICAL_RECT_FLOAT_H * (lx + ly);
    double omega;
    if (r->precise) {
        /* the frame again in double: h is a difference of nearly equal products here */
        const double dx = (double)corner.x - x.x, dy = (double)corner.y - x.y, dz = (double)corner.z - x.z;
        const vec3 nz = v3_cross(ux, uy);
        r->d.x0 = dx * ux.x + dy * ux.y + dz * ux.z;
        r->d.y0 = dx * uy.x + dy * uy.y + dz * uy.z;
        r->d.x1 = r->d.x0 + lx;
        r->d.y1 = r->d.y0 + ly;
        r->d.h = fabs(dx * nz.x + dy * nz.y + dz * nz.z);
        const double a00 = corner_term_d(r->d.x0, r->d.y0, r->d.h), a01 = corner_term_d(r->d.x0, r->d.y1, r->d.h);
        r->d.phi0 = a01 - a00;
        omega = (corner_term_d(r->d.x1, r->d.y1, r->d.h) - corner_term_d(r->d.x1, r->d.y0, r->d.h)) - r->d.phi0;
        r->d.omega = omega;
    } else {
        const float a00 = corner_term(r->x0, r->y0, r->h), a01 = corner_term(r->x0, r->y1, r->h);
        r->phi0 = a01 - a00;
        omega = (corner_term(r->x1, r->y1, r->h) - corner_term(r->x1, r->y0, r->h)) - r->phi0;
    }
    r->omega = omega > 0.0 && isfinite(omega) ? (float)omega : 0.0f;
    return r->omega;
}

/* The map in double (r->precise). */
static void sample_precise(const struct spherical_rect *r, float u, float v, float *s, float *t)
{
    const double h = r->d.h, h2 = h * h, x0 = r->d.x0, x1 = r->d.x1, y0 = r->d.y0, y1 = r->d.y1;
    const double l0 = sqrt(y0 * y0 + h2), q0 = y0 / l0, q1 = y1 / sqrt(y1 * y1 + h2);
    const double phi = u * r->d.omega + r->d.phi0;
    const double sin_phi = sin(phi), cos_phi = cos(phi);
    const double n = q0 * cos_phi - q1;
    const double den = n * n - h2 / (l0 * l0) * sin_phi * sin_phi;
    const double num = (n < 0.0 ? sin_phi : -sin_phi) * h;
    const double xu = clampd(den > 0.0 ? num / sqrt(den) : (num > 0.0 ? x1 : x0), x0, x1);
    const double rr2 = xu * xu + h2;
    const double e0 = y0 / sqrt(rr2 + y0 * y0), e1 = y1 / sqrt(rr2 + y1 * y1);
    const double e = e0 + v * (e1 - e0), c2 = (1.0 - e) * (1.0 + e);
    const double yv = clampd(c2 > 1e-30 ? e * sqrt(rr2 / c2) : (e > 0.0 ? y1 : y0), y0, y1);
    *s = clampf((float)(xu - x0), 0.0f, r->x1 - r->x0);
    *t = clampf((float)(yv - y0), 0.0f, r->y1 - r->y0);
}

void spherical_rect_sample(const struct spherical_rect *r, float u, float v, float *s, float *t)
{
    if (r->precise) {
        sample_precise(r, u, v, s, t);
        return;
    }
    /* the first coordinate: the sub-rectangle [x0, xu] of solid angle u omega */
    const float h2 = r->h * r->h;
    const float l0 = sqrtf(r->y0 * r->y0 + h2), q0 = r->y0 / l0, q1 = r->y1 / sqrtf(r->y1 * r->y1 + h2);
    const float phi = u * r->omega + r->phi0;
    const float sin_phi = sinf(phi), cos_phi = cosf(phi);
    const float n = q0 * cos_phi - q1;
    const float den = n * n - h2 / (l0 * l0) * sin_phi * sin_phi; /* 1 - q0^2 = h^2 / l0^2 */
    const float num = (n < 0.0f ? sin_phi : -sin_phi) * r->h;
    /* den -> 0: xu -> +-infinity, which the clamp takes to the edge its sign points to */
    float xu = den > 0.0f ? num / sqrtf(den) : (num > 0.0f ? r->x1 : r->x0);
    xu = clampf(xu, r->x0, r->x1);
    /* the second: uniform in the sine of elevation along x = xu */
    const float rr2 = xu * xu + h2;
    const float e0 = r->y0 / sqrtf(rr2 + r->y0 * r->y0), e1 = r->y1 / sqrtf(rr2 + r->y1 * r->y1);
    const float e = e0 + v * (e1 - e0);
    const float c2 = (1.0f - e) * (1.0f + e);
    float yv = c2 > 1e-12f ? e * sqrtf(rr2 / c2) : (e > 0.0f ? r->y1 : r->y0);
    yv = clampf(yv, r->y0, r->y1);
    *s = xu - r->x0;
    *t = yv - r->y0;
}
