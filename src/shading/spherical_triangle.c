/* spherical_triangle.c: uniform sampling of the solid angle of a triangle (spherical_triangle.h), in
 * float, and in double where x is close to the triangle's plane.
 *
 * Arvo 1995 computes the arcs of small triangles as differences of nearly equal numbers (1 - cos,
 * u = t - cos alpha, ...), which float cannot afford; the float path writes each such difference in
 * a form without the cancellation (the identities at each step below). Against long double, over
 * 3e5 random triangles of at least 0.02 sr, its directions are off by at most 1.5e-6 of the
 * triangle's angular size where x is farther from the plane than the triangle's longer edge,
 * 3.6e-6 above 0.1 of it, 5e-5 above 1e-2 of it, but 1.6e-3 at 1e-3 of it: below
 * SPHERICAL_TRIANGLE_FLOAT_H the double form runs (off by 4e-8 there), and below 1e-4 neither
 * (callers sample by area). */
#include "shading/spherical_triangle.h"

#include <math.h>

/* Heights over the plane, in units of the longer edge: below the first the map runs in double,
 * below the second the triangle is not sampled by solid angle at all. */
#define SPHERICAL_TRIANGLE_FLOAT_H 2e-2f
#define SPHERICAL_TRIANGLE_MIN_H 1e-4f

struct dvec {
    double x, y, z;
};

static struct dvec dv(vec3 v) { return (struct dvec){v.x, v.y, v.z}; }
static struct dvec dsub(struct dvec a, struct dvec b) { return (struct dvec){a.x - b.x, a.y - b.y, a.z - b.z}; }
static struct dvec dscale(struct dvec a, double s) { return (struct dvec){a.x * s, a.y * s, a.z * s}; }
static struct dvec dadd(struct dvec a, struct dvec b) { return (struct dvec){a.x + b.x, a.y + b.y, a.z + b.z}; }
static double ddot(struct dvec a, struct dvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static struct dvec dcross(struct dvec a, struct dvec b)
{
    return (struct dvec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static double dlen(struct dvec a) { return sqrt(ddot(a, a)); }

/* a / |a|; 0 for a zero vector. */
static struct dvec dnorm(struct dvec a)
{
    double l = dlen(a);
    return l > 0.0 ? dscale(a, 1.0 / l) : (struct dvec){0.0, 0.0, 0.0};
}

/* The part of v orthogonal to unit u, normalized. */
static struct dvec dorthogonal(struct dvec v, struct dvec u) { return dnorm(dsub(v, dscale(u, ddot(v, u)))); }

static double dclamp1(double v) { return v < -1.0 ? -1.0 : (v > 1.0 ? 1.0 : v); }

/* The solid angle in double (Van Oosterom and Strackee 1983, spherical_triangle.h). */
static double solid_angle_d(vec3 x, vec3 a, vec3 b, vec3 c)
{
    const struct dvec A = dsub(dv(a), dv(x)), B = dsub(dv(b), dv(x)), C = dsub(dv(c), dv(x));
    const double la = dlen(A), lb = dlen(B), lc = dlen(C);
    const double num = fabs(ddot(A, dcross(B, C)));
    const double den = la * lb * lc + ddot(A, B) * lc + ddot(A, C) * lb + ddot(B, C) * la;
    if (!(num > 0.0) || !(la > 0.0 && lb > 0.0 && lc > 0.0))
        return 0.0;
    double omega = 2.0 * atan2(num, den); /* den < 0: the half-angle lies in (pi/2, pi) */
    return omega > 0.0 ? omega : 0.0;
}

/* Arvo's map in double, unit vectors from x normalized each time. */
static int sample_d(vec3 x, vec3 a, vec3 b, vec3 c, double omega, float u1, float u2, vec3 *dir)
{
    if (!(omega > 0.0))
        return 0;
    const struct dvec A = dnorm(dsub(dv(a), dv(x))), B = dnorm(dsub(dv(b), dv(x))), C = dnorm(dsub(dv(c), dv(x)));
    /* The angle alpha at vertex A, between the great circles A B and A C, as its cosine and sine from
     * the sides' plane normals (no trigonometry: Arvo's formulas need only these and omega). */
    const struct dvec n_ab = dnorm(dcross(A, B)), n_ac = dnorm(dcross(A, C));
    if (dlen(n_ab) == 0.0 || dlen(n_ac) == 0.0)
        return 0;
    const double cos_alpha = dclamp1(ddot(n_ab, n_ac)), sin_alpha = dlen(dcross(n_ab, n_ac));
    /* Arvo 1995 Fig. 2: the sub-triangle A B C' of area u1 * omega, then C' on the arc A C. With
     * phi = u1 omega - alpha: s = sin(phi), t = cos(phi) by the angle-difference identities. */
    const double area_sub = (double)u1 * omega;
    const double sin_area = sin(area_sub), cos_area = cos(area_sub);
    const double s = sin_area * cos_alpha - cos_area * sin_alpha, t = cos_area * cos_alpha + sin_area * sin_alpha;
    const double cos_c = ddot(A, B); /* the arc A B */
    const double u = t - cos_alpha, v = s + sin_alpha * cos_c;
    const double den = (v * s + u * t) * sin_alpha;
    double q = den != 0.0 ? ((v * t - u * s) * cos_alpha - v) / den : 1.0;
    q = dclamp1(q); /* cos of the arc A C' */
    const struct dvec C1 = dadd(dscale(A, q), dscale(dorthogonal(C, A), sqrt(fmax(0.0, 1.0 - q * q))));
    /* u2 along the arc from B to C': cos of the arc B P uniform in [cos(B C'), 1]. */
    const double z = 1.0 - (double)u2 * (1.0 - ddot(C1, B));
    const struct dvec P = dadd(dscale(B, z), dscale(dorthogonal(C1, B), sqrt(fmax(0.0, 1.0 - z * z))));
    const double lp = dlen(P);
    if (!(lp > 0.0))
        return 0;
    *dir = v3((float)(P.x / lp), (float)(P.y / lp), (float)(P.z / lp));
    return 1;
}

float spherical_triangle_init(struct spherical_triangle *t, vec3 x, vec3 v0, vec3 e1, vec3 e2)
{
    t->x = x, t->v0 = v0, t->e1 = e1, t->e2 = e2;
    t->a = v3_sub(v0, x);
    t->omega = 0.0f;
    const vec3 n = v3_cross(e1, e2);
    const float triple = fabsf(v3_dot(t->a, n)), n2 = v3_length2(n);
    const float edge2 = fmaxf(v3_length2(e1), v3_length2(e2));
    /* h = triple / |n| against the longer edge, squared: no square root */
    const float h2_rel = triple * triple / (n2 * edge2);
    if (!(h2_rel > SPHERICAL_TRIANGLE_MIN_H * SPHERICAL_TRIANGLE_MIN_H) || !isfinite(h2_rel))
        return 0.0f;
    t->precise = h2_rel < SPHERICAL_TRIANGLE_FLOAT_H * SPHERICAL_TRIANGLE_FLOAT_H;
    if (t->precise) {
        t->omega_d = solid_angle_d(x, v0, v3_add(v0, e1), v3_add(v0, e2));
        t->omega = (float)t->omega_d;
        return t->omega;
    }
    const vec3 b = v3_add(t->a, e1), c = v3_add(t->a, e2);
    t->la = v3_length(t->a), t->lb = v3_length(b), t->lc = v3_length(c);
    t->triple = triple;
    const float den = t->la * t->lb * t->lc + v3_dot(t->a, b) * t->lc + v3_dot(t->a, c) * t->lb + v3_dot(b, c) * t->la;
    const float omega = 2.0f * atan2f(triple, den); /* den < 0: the half-angle lies in (pi/2, pi) */
    t->omega = omega > 0.0f ? omega : 0.0f;
    return t->omega;
}

int spherical_triangle_sample(const struct spherical_triangle *t, float u1, float u2, vec3 *dir)
{
    if (!(t->omega > 0.0f))
        return 0;
    if (t->precise)
        return sample_d(t->x, t->v0, v3_add(t->v0, t->e1), v3_add(t->v0, t->e2), t->omega_d, u1, u2, dir);
    const float la = t->la, lb = t->lb;
    const vec3 A = v3_scale(t->a, 1.0f / la), B = v3_scale(v3_add(t->a, t->e1), 1.0f / lb);
    /* The angle alpha at A between the planes (A, B) and (A, C), whose normals are a x e1 and a x e2
     * (b = a + e1); (a x e1) x (a x e2) = a (a . (e1 x e2)) gives its sine. */
    const vec3 n_ab = v3_cross(t->a, t->e1), n_ac = v3_cross(t->a, t->e2);
    const float l_ac = v3_length(n_ac), inv = 1.0f / (v3_length(n_ab) * l_ac);
    const float cos_alpha = v3_dot(n_ab, n_ac) * inv, sin_alpha = la * t->triple * inv;
    /* A - B = a (lb - la) / (la lb) - e1 / lb with lb - la = (2 a.e1 + e1.e1) / (la + lb), and
     * 1 - cos c = |A - B|^2 / 2 (c the arc A B) */
    const float dl = (2.0f * v3_dot(t->a, t->e1) + v3_length2(t->e1)) / (la + lb);
    const vec3 a_b = v3_sub(v3_scale(t->a, dl / (la * lb)), v3_scale(t->e1, 1.0f / lb));
    const float one_minus_cos_c = 0.5f * v3_length2(a_b);
    /* Arvo 1995 Fig. 2 with the sub-triangle's area u1 omega = 2 theta: s = sin(2 theta - alpha),
     * t = cos(2 theta - alpha), u = t - cos alpha = 2 sin theta sin(alpha - theta),
     * v = s + sin alpha cos c = 2 sin theta cos(theta - alpha) - sin alpha (1 - cos c), and the cosine
     * q of the arc A C' as 1 - q = 2 sin theta (v sin theta + u cos theta) / ((v s + u t) sin alpha). */
    const float theta = 0.5f * u1 * t->omega, sh = sinf(theta), ch = cosf(theta);
    const float s2 = 2.0f * sh * ch, c2 = 1.0f - 2.0f * sh * sh;
    const float s = s2 * cos_alpha - c2 * sin_alpha, tt = c2 * cos_alpha + s2 * sin_alpha;
    const float u = 2.0f * sh * (sin_alpha * ch - cos_alpha * sh);
    const float v = 2.0f * sh * (ch * cos_alpha + sh * sin_alpha) - sin_alpha * one_minus_cos_c;
    const float den = (v * s + u * tt) * sin_alpha;
    float omq = den != 0.0f ? 2.0f * sh * (v * sh + u * ch) / den : 0.0f;
    omq = omq < 0.0f ? 0.0f : (omq > 2.0f ? 2.0f : omq);
    const float sin_ac = sqrtf(omq * (2.0f - omq));
    /* C' = A q + C_perp sin(A C'), C_perp the unit direction of e2 - (e2.A) A (c's part along A
     * cancels exactly), of length |a x e2| / la; D = C' - B without forming C' */
    const vec3 c_perp = v3_scale(v3_sub(t->e2, v3_scale(A, v3_dot(t->e2, A))), la / l_ac);
    const vec3 d = v3_add(a_b, v3_sub(v3_scale(c_perp, sin_ac), v3_scale(A, omq)));
    /* u2 along the arc from B to C': 1 - cos of the arc B P uniform in [0, 1 - B.C'], 1 - B.C' =
     * |D|^2 / 2, and the direction of C' orthogonal to B is D - (D.B) B */
    const float w = u2 * 0.5f * v3_length2(d);
    const vec3 d_perp = v3_sub(d, v3_scale(B, v3_dot(d, B)));
    const float l_perp = v3_length(d_perp);
    if (!(l_perp > 0.0f)) {
        *dir = B;
        return 1;
    }
    *dir = v3_add(v3_scale(B, 1.0f - w), v3_scale(d_perp, sqrtf(w * (2.0f - w)) / l_perp));
    return 1;
}
