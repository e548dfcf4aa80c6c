/* spherical_triangle.h: directions uniform in the solid angle a triangle subtends from a point
 * (Arvo 1995, "Stratified Sampling of Spherical Triangles"), for emitter sampling by solid angle.
 * Must never depend on scenes or render passes. */
#ifndef RESTIR_SHADING_SPHERICAL_TRIANGLE_H
#define RESTIR_SHADING_SPHERICAL_TRIANGLE_H

#include "core/vec3.h"

/* Triangle v0, v0 + e1, v0 + e2 as seen from x, set up by spherical_triangle_init. */
struct spherical_triangle {
    vec3 x, v0, e1, e2;
    vec3 a;                   /* v0 - x */
    float la, lb, lc, triple; /* |a|, |a + e1|, |a + e2|, |a . (e1 x e2)| */
    float omega;              /* solid angle (sr) */
    int precise;              /* 1: x is close to the triangle's plane, and the map runs in double */
    double omega_d;           /* the solid angle in double (precise only) */
};

/* Sets t up and returns the solid angle (steradians) of the triangle seen from x, by Van Oosterom
 * and Strackee 1983: tan(omega / 2) = |A . (B x C)| / (|A||B||C| + (A.B)|C| + (A.C)|B| + (B.C)|A|)
 * with A = v0 - x, B = A + e1, C = A + e2, and A . (B x C) = A . (e1 x e2) without cancellation.
 * In float where x is at least 1e-2 of the longer edge from the plane, else in double (the sampler's
 * map loses precision there, spherical_triangle.c); 0 for a degenerate triangle or x within 1e-4 of
 * the longer edge from its plane (callers use area sampling there). */
float spherical_triangle_init(struct spherical_triangle *t, vec3 x, vec3 v0, vec3 e1, vec3 e2);

/* A direction from x uniform in the solid angle of t (Arvo 1995) from u1, u2 in [0,1): the area
 * fraction u1 selects the sub-triangle A B C', u2 the point along the arc from B to C'. Its density
 * is 1 / t->omega over the spherical triangle. Writes the direction, not normalized, to *dir.
 * Returns 0 when the triangle subtends no solid angle (t->omega 0). */
int spherical_triangle_sample(const struct spherical_triangle *t, float u1, float u2, vec3 *dir);

#endif
