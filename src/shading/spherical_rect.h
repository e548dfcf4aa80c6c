/* spherical_rect.h: directions uniform in the solid angle a rectangle subtends from a point
 * (Urena, Fajardo and King 2013, "An Area-Preserving Parametrization for Spherical Rectangles"),
 * for emitter sampling by solid angle. Must never depend on scenes or render passes. */
#ifndef RESTIR_SHADING_SPHERICAL_RECT_H
#define RESTIR_SHADING_SPHERICAL_RECT_H

#include "core/vec3.h"

/* Rectangle corner + [0, lx] ux + [0, ly] uy (ux, uy unit and orthogonal) as seen from a point x,
 * in the frame of ux, uy and the plane's normal with x at the origin: the rectangle spans
 * [x0, x1] x [y0, y1] at height -h (h > 0 the distance of x from the plane; which side x is on does
 * not matter). In double (spherical_rect.c says why). */
struct spherical_rect {
    double x0, y0, x1, y1, h;
    double pr, pi; /* a complex number whose argument, asin(p0 q1) - asin(p0 q0), is where the
                      area-preserving angle starts (spherical_rect.c) */
    float omega;   /* solid angle (sr) */
};

/* Sets r's frame up for x and the rectangle. Returns 0 where sampling it is not safe: x within 1e-4
 * of lx + ly of the rectangle's plane, or a degenerate rectangle. */
int spherical_rect_frame(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly);
/* The solid angle (r's frame set), stored in r->omega and returned (Urena et al. 2013, Sec. 3, as the
 * argument of a product of four corner factors, spherical_rect.c). */
float spherical_rect_solid_angle(struct spherical_rect *r);
/* spherical_rect_frame, then spherical_rect_solid_angle; 0 where the frame is not safe. */
float spherical_rect_init(struct spherical_rect *r, vec3 x, vec3 corner, vec3 ux, vec3 uy, float lx, float ly);

/* The point of the rectangle in the direction drawn from u, v in [0, 1) uniformly over the solid
 * angle r->omega (Urena et al. 2013, Algorithm 1: u picks the sub-rectangle [x0, xu] of solid angle
 * u omega, v the height along its edge uniform in the sine of elevation), as offsets s in [0, lx]
 * along ux and t in [0, ly] along uy from the corner (clamped into the rectangle). */
void spherical_rect_sample(const struct spherical_rect *r, float u, float v, float *s, float *t);

#endif
