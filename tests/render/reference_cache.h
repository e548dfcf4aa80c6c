/* reference_cache.h: the reference runs of the unbiasedness tests, rendered once per test process.
 * Run k of a reference is pt with seed REFERENCE_CACHE_SEED0 + k: a deterministic image of what
 * pt's samples depend on (reference_describe: scene content, resolution, camera and shutter, pt's
 * parameters) and its spp. Cases that compare different methods or settings with the same
 * reference therefore see the same K images; the cache keeps each run's image and hands the same
 * floats to every case, so a test's outcome is bit for bit what rendering them again would give,
 * at a fraction of the time (most cases of a test share a handful of references).
 * A hit is checked: run 0 is rendered again and must equal the stored image exactly, so a
 * parameter that changes pt's samples but is missing from reference_describe fails the test
 * instead of silently comparing against another integrand. */
#ifndef RESTIR_TEST_REFERENCE_CACHE_H
#define RESTIR_TEST_REFERENCE_CACHE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/pt/reference.h"
#include "methods/renderer.h"
#include "test_util.h"

#define REFERENCE_CACHE_SEED0 900000
#define REFERENCE_CACHE_MAX 48

struct reference_cache_entry {
    char key[1024];
    int runs;      /* images held */
    float *images; /* run k at images + k * w*h*3 */
};

static struct reference_cache_entry reference_cache[REFERENCE_CACHE_MAX];
static int reference_cache_used;

/* Renders run k of the reference (p: pt's params with spp set) into out (w*h*3); open NULL: the
 * renderer's own shutter opening (none before a first frame). */
static inline void reference_cache_render(const struct scene *s, const struct render_params *p,
                                          const struct camera *cam, const struct camera *open, int k, float *out)
{
    struct render_params q = *p;
    q.seed = REFERENCE_CACHE_SEED0 + (uint64_t)k;
    struct renderer r;
    renderer_init(&r, s, method_named("pt"), &q);
    if (open)
        renderer_set_shutter_open(&r, open);
    struct frame_stats fs;
    renderer_render(&r, 0, cam, &fs);
    memcpy(out, r.image, sizeof(float) * 3 * (size_t)q.width * (size_t)q.height);
    renderer_fini(&r);
}

/* The images of runs 0 .. runs-1 of pt with params p (the reference's: method_reference_params
 * and the pin applied, spp set; its seed is ignored) seen from cam with the shutter opening at
 * open (NULL: none set), each w*h*3 floats, run k at the result + k*w*h*3. The cache owns them
 * for the life of the process; a later call may move them (copy what must outlive it).
 * Single-threaded callers only. */
static inline const float *reference_cache_runs(const struct scene *s, const struct render_params *p,
                                                const struct camera *cam, const struct camera *open, int runs)
{
    struct reference_accum a; /* only what reference_describe reads */
    memset(&a, 0, sizeof a);
    a.scene = s;
    a.params = *p;
    a.params.seed = REFERENCE_CACHE_SEED0;
    renderer_camera_view(&a.params, cam, open, &a.view);
    char key[1024];
    reference_describe(&a, key, sizeof key - 32);
    snprintf(key + strlen(key), 32, "; spp=%d", p->spp);
    const size_t floats = 3 * (size_t)p->width * (size_t)p->height;
    struct reference_cache_entry *e = NULL;
    for (int i = 0; i < reference_cache_used && !e; i++)
        if (strcmp(reference_cache[i].key, key) == 0)
            e = &reference_cache[i];
    if (e && e->runs > 0) {
        float *again = malloc(sizeof(float) * floats);
        reference_cache_render(s, p, cam, open, 0, again);
        EXPECT(memcmp(again, e->images, sizeof(float) * floats) == 0,
               "reference cache: run 0 of [%s] renders differently now (a parameter pt reads is missing "
               "from reference_describe)", key);
        free(again);
    }
    if (!e) {
        if (reference_cache_used == REFERENCE_CACHE_MAX) { /* full: forget the oldest */
            free(reference_cache[0].images);
            memmove(reference_cache, reference_cache + 1, sizeof reference_cache[0] * (REFERENCE_CACHE_MAX - 1));
            reference_cache_used--;
        }
        e = &reference_cache[reference_cache_used++];
        memset(e, 0, sizeof *e);
        snprintf(e->key, sizeof e->key, "%s", key);
    }
    if (e->runs < runs) {
        float *grown = realloc(e->images, sizeof(float) * floats * (size_t)runs);
        if (!grown) {
            fprintf(stderr, "reference cache: out of memory for %d runs of %zu floats\n", runs, floats);
            abort();
        }
        e->images = grown;
        for (int k = e->runs; k < runs; k++)
            reference_cache_render(s, p, cam, open, k, e->images + (size_t)k * floats);
        e->runs = runs;
    }
    return e->images;
}

#endif
