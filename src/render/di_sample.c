/* di_sample.c: evaluation of the ReSTIR DI integrand without visibility, shared by initial
 * sampling, temporal and spatial reuse and shading. Must never trace rays. */
#include "render/di_sample.h"

#include <stddef.h>

vec3 di_unshadowed_pdf(const struct shading_point *sp, const struct di_sample *y, float *bsdf_pdf_area)
{
    if (bsdf_pdf_area)
        *bsdf_pdf_area = 0.0f;
    if (!sp->valid || y->tri < 0)
        return v3s(0.0f);
    const int env = y->tri == DI_ENV_TRI;
    vec3 to = env ? y->p : v3_sub(y->p, sp->p);
    float d2 = env ? 1.0f : v3_length2(to);
    if (!(d2 > 0.0f))
        return v3s(0.0f);
    vec3 wi = env ? to : v3_scale(to, 1.0f / sqrtf(d2));
    float cos_x = v3_dot(sp->n, wi), cos_y = -v3_dot(y->n, wi);
    if (cos_x <= 0.0f || cos_y <= 0.0f || v3_dot(sp->ng, wi) <= 0.0f)
        return v3s(0.0f);
    float pdf_sa;
    vec3 f = bsdf_frame_eval(&sp->bf, wi, bsdf_pdf_area ? &pdf_sa : NULL);
    float g = cos_y / d2; /* solid angle to area at y */
    if (bsdf_pdf_area)
        *bsdf_pdf_area = pdf_sa * g;
    return v3_scale(v3_mul(y->Le, f), cos_x * g);
}

vec3 di_unshadowed(const struct shading_point *sp, const struct di_sample *y)
{
    return di_unshadowed_pdf(sp, y, NULL);
}

float di_target(const struct shading_point *sp, const struct di_sample *y)
{
    return v3_luminance(di_unshadowed(sp, y));
}
