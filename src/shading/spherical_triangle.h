/* spherical_triangle.h: directions uniform in the solid angle a triangle subtends from a point
 * (Arvo 1995, "Stratified Sampling of Spherical Triangles"), for emitter sampling by solid angle.
 * Must never depend on scenes or render passes. */
#ifndef RESTIR_SHADING_SPHERICAL_TRIANGLE_H
#define RESTIR_SHADING_SPHERICAL_TRIANGLE_H

#include "core/vec3.h"

/* Solid angle (steradians) of triangle a, b, c seen from x, by Van Oosterom and Strackee 1983:
 * tan(omega / 2) = |A . (B x C)| / (|A||B||C| + (A.B)|C| + (A.C)|B| + (B.C)|A|) with A = a - x, ...
 * In double precision; 0 for a degenerate triangle or x in its plane. */
double spherical_triangle_solid_angle(vec3 x, vec3 a, vec3 b, vec3 c);

/* A direction from x uniform in the solid angle of triangle a, b, c (Arvo 1995) from u1, u2 in
 * [0,1): the area fraction u1 selects the sub-triangle A B C', u2 the point along the arc from B
 * to C'. omega is spherical_triangle_solid_angle(x, a, b, c), which the caller has computed to
 * decide whether to sample this way and to weigh the sample; the direction's density is 1 / omega
 * over the spherical triangle. Writes the unit direction to *dir. Returns 0 when the triangle
 * subtends no solid angle (omega <= 0, x in its plane, a degenerate triangle). */
int spherical_triangle_sample(vec3 x, vec3 a, vec3 b, vec3 c, double omega, float u1, float u2, vec3 *dir);

#endif
