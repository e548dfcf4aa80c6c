/* light_pool.c: the per-frame light-candidate pool of ReSTIR DI's initial RIS. */
#include "light_pool.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "shading/lights.h"
#include "tiles.h"

/* Entries drawn per random stream; chunks are filled in parallel. */
#define LIGHT_POOL_CHUNK 1024

void light_pool_init(struct light_pool *lp, int window)
{
    RESTIR_CHECK(window >= 0 && window <= LIGHT_POOL_SIZE);
    memset(lp, 0, sizeof(*lp));
    lp->window = window;
    lp->size = LIGHT_POOL_SIZE + window;
    size_t n = (size_t)lp->size;
    lp->emitter = xmalloc(sizeof(int) * n);
    lp->tri = xmalloc(sizeof(int) * n);
    float **f[] = {&lp->b1, &lp->b2, &lp->px, &lp->py, &lp->pz, &lp->nx, &lp->ny, &lp->nz,
                   &lp->Lr, &lp->Lg, &lp->Lb, &lp->pdf};
    for (size_t k = 0; k < sizeof(f) / sizeof(f[0]); k++)
        *f[k] = xmalloc(sizeof(float) * n);
}

void light_pool_fini(struct light_pool *lp)
{
    float *f[] = {lp->b1, lp->b2, lp->px, lp->py, lp->pz, lp->nx, lp->ny, lp->nz, lp->Lr, lp->Lg, lp->Lb, lp->pdf};
    for (size_t k = 0; k < sizeof(f) / sizeof(f[0]); k++)
        free(f[k]);
    free(lp->emitter);
    free(lp->tri);
    memset(lp, 0, sizeof(*lp));
}

static void put(struct light_pool *lp, int i, int e, float b1, float b2, const struct scene *s)
{
    const struct emitter *em = &s->emitters[e];
    lp->emitter[i] = e;
    lp->tri[i] = em->tri;
    lp->b1[i] = b1;
    lp->b2[i] = b2;
    vec3 p = v3_add(em->v0, v3_add(v3_scale(em->e1, b1), v3_scale(em->e2, b2)));
    lp->px[i] = p.x, lp->py[i] = p.y, lp->pz[i] = p.z;
    lp->nx[i] = em->n.x, lp->ny[i] = em->n.y, lp->nz[i] = em->n.z;
    lp->Lr[i] = em->Le.x, lp->Lg[i] = em->Le.y, lp->Lb[i] = em->Le.z;
    lp->pdf[i] = em->pdf_area;
}

void light_pool_fill(struct light_pool *lp, const struct scene *s, uint64_t seed, int frame)
{
    if (s->num_emitters <= 0)
        return;
    const int chunks = LIGHT_POOL_SIZE / LIGHT_POOL_CHUNK;
#pragma omp parallel for schedule(static)
    for (int c = 0; c < chunks; c++) {
        pcg32 rng = rng_for(seed, (uint64_t)frame, (uint64_t)c, RNG_PASS_LIGHT_POOL);
        for (int i = c * LIGHT_POOL_CHUNK; i < (c + 1) * LIGHT_POOL_CHUNK; i++) {
            /* lights_sample's three uniforms: emitter by the alias table, then the triangle warp */
            int e = alias_table_sample(&s->emitter_table, pcg32_float(&rng));
            float u1 = pcg32_float(&rng), u2 = pcg32_float(&rng), b1, b2;
            warp_uniform_triangle(u1, u2, &b1, &b2);
            put(lp, i, e, b1, b2, s);
        }
    }
    for (int i = 0; i < lp->window; i++) /* the tail: windows that start near the end read on */
        put(lp, LIGHT_POOL_SIZE + i, lp->emitter[i], lp->b1[i], lp->b2[i], s);
}
