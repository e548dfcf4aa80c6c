/* vec3.h: small inline 3-vector math (float) and orthonormal frames.
 * Must never depend on anything but <math.h>. */
#ifndef RESTIR_CORE_VEC3_H
#define RESTIR_CORE_VEC3_H

#include <math.h>

typedef struct vec3 {
    float x, y, z;
} vec3;

static inline vec3 v3(float x, float y, float z) { vec3 r = {x, y, z}; return r; }
static inline vec3 v3s(float s) { return v3(s, s, s); }
static inline vec3 v3_add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline vec3 v3_sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline vec3 v3_mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline vec3 v3_scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline vec3 v3_neg(vec3 a) { return v3(-a.x, -a.y, -a.z); }
static inline vec3 v3_madd(vec3 a, vec3 b, float s) { return v3(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
static inline vec3 v3_lerp(vec3 a, vec3 b, float t) { return v3_madd(v3_scale(a, 1.0f - t), b, t); }
static inline float v3_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 v3_cross(vec3 a, vec3 b)
{
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float v3_length2(vec3 a) { return v3_dot(a, a); }
static inline float v3_length(vec3 a) { return sqrtf(v3_dot(a, a)); }
static inline vec3 v3_normalize(vec3 a)
{
    float l = v3_length(a);
    return l > 0.0f ? v3_scale(a, 1.0f / l) : a;
}
static inline float v3_max_component(vec3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }
static inline int v3_equal(vec3 a, vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
static inline int v3_is_finite(vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* max/min as plain comparisons: unlike fmaxf/fminf (IEEE NaN rules) they vectorize to
 * maxps/minps. With a NaN argument they return the second operand. */
static inline float max_f(float a, float b) { return a > b ? a : b; }
static inline float min_f(float a, float b) { return a < b ? a : b; }

/* Componentwise min / max (box bounds). */
static inline vec3 v3_min(vec3 a, vec3 b) { return v3(min_f(a.x, b.x), min_f(a.y, b.y), min_f(a.z, b.z)); }
static inline vec3 v3_max(vec3 a, vec3 b) { return v3(max_f(a.x, b.x), max_f(a.y, b.y), max_f(a.z, b.z)); }

/* Rec. 709 luminance, as DESIGN.md defines it. */
static inline float v3_luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* Orthonormal frame around a unit normal n (Duff et al. 2017, branchless). */
typedef struct frame {
    vec3 t, b, n;
} frame;

static inline frame frame_from_normal(vec3 n)
{
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    frame f;
    f.t = v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.b = v3(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}
static inline vec3 frame_to_world(const frame *f, vec3 l)
{
    return v3_add(v3_add(v3_scale(f->t, l.x), v3_scale(f->b, l.y)), v3_scale(f->n, l.z));
}
static inline vec3 frame_to_local(const frame *f, vec3 w)
{
    return v3(v3_dot(w, f->t), v3_dot(w, f->b), v3_dot(w, f->n));
}

#endif
