/* di_sample.h: the ReSTIR DI sample (a point on an emissive triangle, area measure), its
 * reservoir, and the target function p_hat (001 Sec. 1: luminance of the unshadowed
 * contribution). Must never trace rays. */
#ifndef RESTIR_METHODS_RESTIR_DI_DI_SAMPLE_H
#define RESTIR_METHODS_RESTIR_DI_DI_SAMPLE_H

#include "render/gbuffer.h"

struct di_sample {
    int tri;          /* emissive triangle, -1 for "no sample", DI_ENV_TRI for the environment */
    float b1, b2;     /* barycentrics on it */
    vec3 p, n;        /* point and emitting normal (cached from tri, b1, b2); for the environment
                         p is the unit direction toward it and n = -p */
    vec3 Le;          /* emitted radiance (front side) */
};

/* The tri of an environment sample: a direction, measured in solid angle where an emitter point is
 * measured in area (the sample space is the union of both; every pdf and target of a sample is in
 * its own part's measure, and reuse maps a sample to itself, so GRIS needs nothing more). */
#define DI_ENV_TRI 0x7fffffff

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
 * pdf times cos_y / d^2, no visibility term), 0 where the contribution is 0. For an environment
 * sample: the contribution Le f cos_x and the solid-angle density. */
vec3 di_unshadowed_pdf(const struct shading_point *sp, const struct di_sample *y, float *bsdf_pdf_area);
/* Target function p_hat(x, y) = luminance of di_unshadowed (001 Sec. 1). */
float di_target(const struct shading_point *sp, const struct di_sample *y);
/* out[k] = di_target(sp[k], y[k]) for n pairs, bit for bit, evaluated across the pairs with
 * vector instructions (SIMD across pixels: the reuse merges' targets; core/simd.h). */
void di_target_many(int n, const struct shading_point *const *sp, const struct di_sample *const *y, float *out);

/* Empties every reservoir of res[0..n) whose W, target or confidence is not finite (render/nonfinite.h's
 * rule, so one bad value cannot spread through reuse); returns how many it emptied. Threads: OpenMP. */
long long nonfinite_discard_di(struct di_reservoir *res, size_t n);

#endif
