/* spherical_triangle.c: uniform sampling of the solid angle of a triangle (spherical_triangle.h).
 * Everything in double: the arcs of small or distant triangles are differences of nearly equal
 * numbers, and the callers switch to area sampling below a solid angle where even double loses the
 * spherical form (lights.c). */
#include "shading/spherical_triangle.h"

#include <math.h>

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

double spherical_triangle_solid_angle(vec3 x, vec3 a, vec3 b, vec3 c)
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

int spherical_triangle_sample(vec3 x, vec3 a, vec3 b, vec3 c, double omega, float u1, float u2, vec3 *dir)
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
