/* light_pool.h: ReSTIR DI's light candidates, presampled once per frame (after Wyman and
 * Panteleev 2021's light tiles, as RTXDI): LIGHT_POOL_SIZE independent draws of lights_sample's
 * distribution (emitter proportional to power, uniform point on it), stored as structure of
 * arrays. A pixel takes its M candidates as one window of M consecutive entries at a uniformly
 * random offset: distinct entries of an i.i.d. pool, so the pixel's candidates are exactly M
 * i.i.d. draws of p_light and initial RIS is unchanged in distribution, while the candidate loop
 * reads contiguous memory and vectorizes. Two pixels share candidates only when their windows
 * overlap (probability about 2 M / LIGHT_POOL_SIZE), a weak correlation between pixels that no
 * pixel's expectation sees. pt's per-point strategies (lights.select=bvh, lights.sample=
 * solid-angle) have no place here: the pool is drawn before any shading point exists, and a
 * per-pixel descent would give up the shared, contiguous candidates. Must never trace rays. */
#ifndef RESTIR_METHODS_RESTIR_DI_LIGHT_POOL_H
#define RESTIR_METHODS_RESTIR_DI_LIGHT_POOL_H

#include <stdint.h>

#include "scene/scene.h"
#include "methods/restir_di/di_settings.h"

#define LIGHT_POOL_SIZE (1 << 14)

struct light_pool {
    int size;   /* LIGHT_POOL_SIZE draws, then copies of the first `window` so no window wraps */
    int window; /* the longest window a pixel takes (di.light_candidates) */
    int *tri;            /* the emitter's triangle */
    float *b1, *b2;
    float *px, *py, *pz; /* point on the light */
    float *nx, *ny, *nz; /* its emitting normal */
    float *Lr, *Lg, *Lb; /* its radiance */
    float *pdf;          /* its area density under light sampling (solid angle for the environment); for
                            ReGIR's slots the source density the MIS weights use (regir.h) */
    float *W;            /* NULL for the pool (an entry is a plain draw of pdf); ReGIR's slots: each
                            entry's unbiased contribution weight (GRIS, regir.h) */
    float *at_point;     /* 1 for a point on an emitter, 0 for an environment direction (p is then
                            the direction, n = -p): light_batch_fill measures both with one formula */
};

/* Allocates a pool for windows of up to `window` (<= LIGHT_POOL_SIZE) candidates. */
void light_pool_init(struct light_pool *lp, int window);
/* Grows lp's arrays to hold at least `entries` entries (never shrinks; contents kept), by half again
 * at least but to no more than max_entries (>= entries), and W too when with_W. For ReGIR's slots
 * (regir.c), which use the same layout for the same batch kernel. */
void light_pool_reserve(struct light_pool *lp, int entries, int max_entries, int with_W);
/* Writes entry i: the point b1, b2 of emitter em (pdf: its power-sampling area density times the
 * emitters' share 1 - env_prob), or an environment direction from the scene's sampler at u1, u2
 * (DI_ENV_TRI, p = direction, n = -p; pdf: env_prob times its solid-angle density). W untouched. */
void light_pool_put_emitter(struct light_pool *lp, const struct scene *s, int i, const struct emitter *em, float b1,
                            float b2);
void light_pool_put_env(struct light_pool *lp, const struct scene *s, int i, float u1, float u2);
/* Writes entry i as a null candidate: a point at `at` without radiance (pdf 1), whose weight is 0. */
void light_pool_put_empty(struct light_pool *lp, int i, vec3 at);
void light_pool_fini(struct light_pool *lp);
/* Draws the frame's pool (seeded by seed and frame, whatever the thread count); a scene without
 * emitters or environment, or a pool for windows of 0 candidates, is left as it is (nothing reads
 * it). With an environment each entry is a direction from its sampler with probability
 * s->env_prob (pdf env_prob times its solid-angle density), else an emitter point as before. */
void light_pool_fill(struct light_pool *lp, const struct scene *s, uint64_t seed, int frame);
/* Entry i as a ReSTIR DI light sample (what lights_point gives for it, bit for bit). */
static inline void light_pool_entry(const struct light_pool *lp, int i, int *tri, float *b1, float *b2, vec3 *p,
                                    vec3 *n, vec3 *Le)
{
    *tri = lp->tri[i];
    *b1 = lp->b1[i];
    *b2 = lp->b2[i];
    *p = v3(lp->px[i], lp->py[i], lp->pz[i]);
    *n = v3(lp->nx[i], lp->ny[i], lp->nz[i]);
    *Le = v3(lp->Lr[i], lp->Lg[i], lp->Lb[i]);
}

/* The window offset for a uniform u in [0, 1). */
static inline int light_pool_offset(float u)
{
    int o = (int)(u * (float)LIGHT_POOL_SIZE); /* exact: the product only shifts the exponent */
    return o < LIGHT_POOL_SIZE ? o : LIGHT_POOL_SIZE - 1;
}

#endif
