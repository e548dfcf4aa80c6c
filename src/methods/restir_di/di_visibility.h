/* di_visibility.h: visibility in ReSTIR DI's targets. With di.visibility_reuse the initial sample
 * is kept only when visible (Bitterli et al. 2020, Algorithm 5), so a reservoir's target is
 * p_hat(x, y) V(x, y); the resampling MIS weights then compare targets that include visibility from
 * each domain (004 Eq. 10 with p_hat_{<-k} = p_hat_k V_k), traced per merge, which is RTXDI's
 * ray-traced bias correction. Without those rays (di.visibility_mis=none) a domain that cannot see
 * a sample still gets MIS weight for it and the estimate darkens (BIASED). */
#ifndef RESTIR_METHODS_RESTIR_DI_DI_VISIBILITY_H
#define RESTIR_METHODS_RESTIR_DI_DI_VISIBILITY_H

#include "methods/restir_di/di_sample.h"
#include "render/params.h"
#include "methods/restir_di/di_settings.h"

/* 1 when every reservoir target includes visibility at its own pixel: reuse then traces the
 * cross-domain shadow rays, and shading needs none. Without reuse (ris-di) that holds for either
 * di.visibility_mis, since only the initial, visibility-tested targets reach shading. */
static inline int di_targets_visible(const struct render_params *p)
{
    return di_settings_of(p)->visibility_reuse &&
           (di_reuse_settings_of(p)->visibility_mis == DI_VIS_MIS_RAYS || (!p->reuse.temporal && !p->reuse.spatial));
}

/* 1 when the light point y is unoccluded from sp (one shadow ray). */
int di_sample_visible(const struct scene *s, const struct shading_point *sp, const struct di_sample *y);
/* The shadow ray di_sample_visible traces, for batched tracing; 0 when there is none to trace
 * (the points coincide: visible). */
int di_visibility_query(const struct shading_point *sp, const struct di_sample *y, struct ray_query *q);

/* The target of domain sp at y as the reservoirs define it: p_hat(y) V(x, y) when
 * with_visibility, else the unshadowed p_hat(y). The shadow ray is traced (and counted in *rays)
 * only where p_hat > 0. */
float di_domain_target(const struct scene *s, int with_visibility, const struct shading_point *sp,
                       const struct di_sample *y, long long *rays);

/* di_domain_target for n pairs (sp[e], y[e]) into out[e], the same values bit for bit: the
 * targets across the pairs with vector instructions (di_target_many; simd=off runs its baseline
 * kernels) and, with visibility, the shadow rays of the positive ones traced together
 * (scene_occluded_batch: Embree streams unless rays.streams=off). previous: NULL, or per pair 1
 * where the domain is the previous frame's and its ray is traced in that frame's geometry
 * (scene_occluded_previous_batch: moving emitters where they were; y[e] must then hold the light
 * point where it was). q, ray_entry and occluded are the caller's scratch of n each, so that
 * nothing is allocated per call. Returns the rays counted, as n calls of di_domain_target would. */
long long di_domain_target_many(const struct scene *s, int with_visibility, int n,
                                const struct shading_point *const *sp, const struct di_sample *const *y, float *out,
                                const unsigned char *previous, struct ray_query *q, int *ray_entry,
                                unsigned char *occluded);

#endif
