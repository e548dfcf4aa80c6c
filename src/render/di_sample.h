/* di_sample.h: the ReSTIR DI sample (a point on an emissive triangle, area measure), its
 * reservoir, and the target function p_hat (001 Sec. 1: luminance of the unshadowed
 * contribution). Must never trace rays. */
#ifndef RESTIR_RENDER_DI_SAMPLE_H
#define RESTIR_RENDER_DI_SAMPLE_H

#include "render/gbuffer.h"

struct di_sample {
    int tri;          /* emissive triangle, -1 for "no sample" */
    float b1, b2;     /* barycentrics on it */
    vec3 p, n;        /* point and emitting normal (cached from tri, b1, b2) */
    vec3 Le;          /* emitted radiance (front side) */
};

/* A reservoir (004 Sec. 2.6): sample, unbiased contribution weight W, confidence c, and the
 * cached target of the sample at the pixel that owns the reservoir. */
struct di_reservoir {
    struct di_sample y;
    float W;
    float c;
    float target;
};

static inline void di_reservoir_clear(struct di_reservoir *r, float c)
{
    r->y.tri = -1;
    r->W = 0.0f;
    r->c = c;
    r->target = 0.0f;
}

/* Unshadowed contribution Le(y) f_r(x, wo, wi) cos_x cos_y / |x - y|^2 of light point y at the
 * shading point; zero when y is behind x's surface or x behind y's emitting side. */
vec3 di_unshadowed(const struct shading_point *sp, const struct di_sample *y);
/* di_unshadowed, and the area density with which BSDF sampling at sp produces y (solid-angle
 * pdf times cos_y / d^2, no visibility term), 0 where the contribution is 0. */
vec3 di_unshadowed_pdf(const struct shading_point *sp, const struct di_sample *y, float *bsdf_pdf_area);
/* Target function p_hat(x, y) = luminance of di_unshadowed (001 Sec. 1). */
float di_target(const struct shading_point *sp, const struct di_sample *y);

#endif
