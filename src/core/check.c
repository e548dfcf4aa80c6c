/* check.c: allocation helpers that stop the program with a message when memory runs out.
 * Must never depend on scene, render or I/O code. */
#include "core/check.h"

void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) {
        fprintf(stderr, "out of memory allocating %zu bytes\n", n);
        exit(1);
    }
    return p;
}

void *xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q) {
        fprintf(stderr, "out of memory allocating %zu bytes\n", n);
        exit(1);
    }
    return q;
}

/* Blocks of at least this many bytes get their pages backed when they are allocated. calloc hands
 * out large blocks as untouched zero pages that fault on their first write, which put the faults
 * of every G-buffer, reservoir and history buffer into the first two frames (restir-di on
 * many-lights at 640x360: 240 ms each against 120 ms for the frames after). */
#define PREFAULT_MIN_BYTES (64u * 1024u)
#define PREFAULT_STRIDE 4096

void *xcalloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p) {
        fprintf(stderr, "out of memory allocating %zu x %zu bytes\n", count, size);
        exit(1);
    }
    const size_t bytes = count * size; /* calloc refused an overflowing product */
    if (bytes >= PREFAULT_MIN_BYTES) {
        /* A zero into each page keeps the block's contents. In parallel, with the static schedule
         * the passes use, so that on a NUMA machine the pages land near the threads that write
         * them (first touch). */
        volatile char *c = p;
        const long pages = (long)((bytes + PREFAULT_STRIDE - 1) / PREFAULT_STRIDE);
#pragma omp parallel for schedule(static)
        for (long k = 0; k < pages; k++)
            c[k * PREFAULT_STRIDE] = 0;
    }
    return p;
}
