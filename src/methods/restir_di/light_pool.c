/* light_pool.c: the per-frame light-candidate pool of ReSTIR DI's initial RIS. */
#include "methods/restir_di/light_pool.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "methods/restir_di/di_sample.h"
#include "render/tiles.h"
#include "scene/env_light.h"
#include "shading/lights.h"

/* Entries drawn per random stream; chunks are filled in parallel. */
#define LIGHT_POOL_CHUNK 1024

void light_pool_reserve(struct light_pool *lp, int entries, int max_entries, int with_W)
{
    RESTIR_CHECK(entries >= 0 && max_entries >= entries);
    if (entries <= lp->size && (!with_W || lp->W))
        return;
    /* grown by half again at least (never past max_entries), so that a grid whose cells fill up frame by
     * frame reallocates (and copies) a few times, not every frame */
    size_t grown = (size_t)lp->size + (size_t)lp->size / 2;
    grown = grown < (size_t)max_entries ? grown : (size_t)max_entries;
    const size_t n = entries <= lp->size ? (size_t)lp->size : (size_t)entries > grown ? (size_t)entries : grown;
    lp->tri = xrealloc(lp->tri, sizeof(int) * n);
    float **f[] = {&lp->b1, &lp->b2, &lp->px, &lp->py, &lp->pz, &lp->nx, &lp->ny, &lp->nz,
                   &lp->Lr, &lp->Lg, &lp->Lb, &lp->pdf, &lp->at_point};
    for (size_t k = 0; k < sizeof(f) / sizeof(f[0]); k++)
        *f[k] = xrealloc(*f[k], sizeof(float) * n);
    if (with_W || lp->W)
        lp->W = xrealloc(lp->W, sizeof(float) * n);
    lp->size = (int)n;
}

void light_pool_init(struct light_pool *lp, int window)
{
    RESTIR_CHECK(window >= 0 && window <= LIGHT_POOL_SIZE);
    memset(lp, 0, sizeof(*lp));
    lp->window = window;
    light_pool_reserve(lp, LIGHT_POOL_SIZE + window, LIGHT_POOL_SIZE + window, 0);
}

void light_pool_fini(struct light_pool *lp)
{
    float *f[] = {lp->b1, lp->b2, lp->px, lp->py, lp->pz, lp->nx, lp->ny, lp->nz, lp->Lr, lp->Lg, lp->Lb, lp->pdf,
                  lp->at_point, lp->W};
    for (size_t k = 0; k < sizeof(f) / sizeof(f[0]); k++)
        free(f[k]);
    free(lp->tri);
    memset(lp, 0, sizeof(*lp));
}

void light_pool_put_emitter(struct light_pool *lp, const struct scene *s, int i, const struct emitter *em, float b1,
                            float b2)
{
    struct light_sample ls;
    lights_emitter_point(s, em, b1, b2, &ls);
    lp->tri[i] = ls.tri;
    lp->b1[i] = b1;
    lp->b2[i] = b2;
    lp->px[i] = ls.p.x, lp->py[i] = ls.p.y, lp->pz[i] = ls.p.z;
    lp->nx[i] = ls.n.x, lp->ny[i] = ls.n.y, lp->nz[i] = ls.n.z;
    lp->Lr[i] = ls.Le.x, lp->Lg[i] = ls.Le.y, lp->Lb[i] = ls.Le.z;
    lp->pdf[i] = ls.pdf_area * (1.0f - s->env_prob); /* the emitters' share of the mixture */
    lp->at_point[i] = 1.0f;
}

void light_pool_put_empty(struct light_pool *lp, int i, vec3 at)
{
    lp->tri[i] = -1;
    lp->b1[i] = lp->b2[i] = 0.0f;
    lp->px[i] = at.x, lp->py[i] = at.y, lp->pz[i] = at.z;
    lp->nx[i] = 0.0f, lp->ny[i] = 1.0f, lp->nz[i] = 0.0f;
    lp->Lr[i] = lp->Lg[i] = lp->Lb[i] = 0.0f;
    lp->pdf[i] = 1.0f;
    lp->at_point[i] = 1.0f;
}

void light_pool_put_env(struct light_pool *lp, const struct scene *s, int i, float u1, float u2)
{
    float pdf;
    vec3 d = env_sample(s->env_sampler, u1, u2, &pdf);
    vec3 Le = environment_radiance(s->env, d);
    lp->tri[i] = DI_ENV_TRI;
    lp->b1[i] = lp->b2[i] = 0.0f;
    lp->px[i] = d.x, lp->py[i] = d.y, lp->pz[i] = d.z;
    lp->nx[i] = -d.x, lp->ny[i] = -d.y, lp->nz[i] = -d.z;
    lp->Lr[i] = Le.x, lp->Lg[i] = Le.y, lp->Lb[i] = Le.z;
    lp->pdf[i] = s->env_prob * pdf;
    lp->at_point[i] = 0.0f;
}

void light_pool_fill(struct light_pool *lp, const struct scene *s, uint64_t seed, int frame)
{
    if ((s->num_emitters <= 0 && !s->env) || lp->window <= 0)
        return;
    const int chunks = LIGHT_POOL_SIZE / LIGHT_POOL_CHUNK;
#pragma omp parallel for schedule(static)
    for (int c = 0; c < chunks; c++) {
        pcg32 rng = rng_for(seed, (uint64_t)frame, (uint64_t)c, RNG_PASS_LIGHT_POOL);
        for (int i = c * LIGHT_POOL_CHUNK; i < (c + 1) * LIGHT_POOL_CHUNK; i++) {
            /* lights_sample's three uniforms: emitter by the alias table, then the triangle warp; with
             * an environment the first also chooses between it and the emitters */
            float u0 = pcg32_float(&rng);
            if (s->env && u0 < s->env_prob) {
                float u1 = pcg32_float(&rng), u2 = pcg32_float(&rng);
                light_pool_put_env(lp, s, i, u1, u2);
                continue;
            }
            if (s->env)
                u0 = (u0 - s->env_prob) / (1.0f - s->env_prob);
            int e = alias_table_sample(&s->emitter_table, u0);
            float u1 = pcg32_float(&rng), u2 = pcg32_float(&rng), b1, b2;
            warp_uniform_triangle(u1, u2, &b1, &b2);
            light_pool_put_emitter(lp, s, i, &s->emitters[e], b1, b2);
        }
    }
    /* The tail repeats the head, so a window that starts near the end reads on without wrapping. */
    const size_t tail = (size_t)lp->window;
    memcpy(lp->tri + LIGHT_POOL_SIZE, lp->tri, tail * sizeof(int));
    float *f[] = {lp->b1, lp->b2, lp->px, lp->py, lp->pz, lp->nx, lp->ny, lp->nz, lp->Lr, lp->Lg, lp->Lb, lp->pdf,
                  lp->at_point};
    for (size_t k = 0; k < sizeof(f) / sizeof(f[0]); k++)
        memcpy(f[k] + LIGHT_POOL_SIZE, f[k], tail * sizeof(float));
}
