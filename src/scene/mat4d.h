/* mat4d.h: row-major 4x4 transforms in double, applied to points and directions as affine maps.
 * Header-only, so the per-vertex loop inlines it. Must never depend on the scene or on assimp. */
#ifndef RESTIR_SCENE_MAT4D_H
#define RESTIR_SCENE_MAT4D_H

#include <float.h>
#include <math.h>

#include "core/vec3.h"

/* Row-major 4x4 in double (assimp's convention and ours: p' = M p for column vectors). Composed
 * in double so that a deep hierarchy does not accumulate float rounding; applied as an affine map
 * (the bottom row of node and user transforms is (0 0 0 1) in every format we read). */
typedef struct {
    double m[16];
} mat4d;

static inline mat4d mat4d_identity(void)
{
    mat4d r = {{0}};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

static inline mat4d mat4d_from_floats(const float *f)
{
    mat4d r;
    for (int i = 0; i < 16; i++)
        r.m[i] = f[i];
    return r;
}

static inline mat4d mat4d_mul(const mat4d *a, const mat4d *b)
{
    mat4d r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += a->m[4 * i + k] * b->m[4 * k + j];
            r.m[4 * i + j] = s;
        }
    return r;
}

/* Determinant of the linear part: negative means the transform mirrors, which turns
 * counter-clockwise triangles clockwise. */
static inline double mat4d_det3(const mat4d *t)
{
    const double *m = t->m;
    return m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
           m[2] * (m[4] * m[9] - m[5] * m[8]);
}

/* double to float without undefined behaviour: C leaves out-of-range conversions undefined, so
 * anything a float cannot hold becomes an infinity (or stays NaN), which the callers refuse. */
static inline float mat4d_to_float(double d)
{
    if (isnan(d))
        return NAN;
    if (d > (double)FLT_MAX)
        return INFINITY;
    if (d < -(double)FLT_MAX)
        return -INFINITY;
    return (float)d;
}

static inline vec3 mat4d_point(const mat4d *t, double x, double y, double z)
{
    const double *m = t->m;
    return v3(mat4d_to_float(m[0] * x + m[1] * y + m[2] * z + m[3]),
              mat4d_to_float(m[4] * x + m[5] * y + m[6] * z + m[7]),
              mat4d_to_float(m[8] * x + m[9] * y + m[10] * z + m[11]));
}

static inline vec3 mat4d_dir(const mat4d *t, double x, double y, double z)
{
    const double *m = t->m;
    return v3(mat4d_to_float(m[0] * x + m[1] * y + m[2] * z), mat4d_to_float(m[4] * x + m[5] * y + m[6] * z),
              mat4d_to_float(m[8] * x + m[9] * y + m[10] * z));
}

/* A normal under t: the inverse transpose of the linear part applied to (x, y, z), computed as
 * the cofactor matrix times sign(det) (the inverse transpose up to the positive factor |det|),
 * not normalized. Tangent planes map to tangent planes, so it stays perpendicular to the surface
 * under non-uniform scales and shears. */
static inline vec3 mat4d_normal(const mat4d *t, double x, double y, double z)
{
    const double *m = t->m;
    const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
    const double s = mat4d_det3(t) < 0.0 ? -1.0 : 1.0;
    return v3(mat4d_to_float(s * ((e * i - f * h) * x - (d * i - f * g) * y + (d * h - e * g) * z)),
              mat4d_to_float(s * (-(b * i - c * h) * x + (a * i - c * g) * y - (a * h - b * g) * z)),
              mat4d_to_float(s * ((b * f - c * e) * x - (a * f - c * d) * y + (a * e - b * d) * z)));
}

#endif
