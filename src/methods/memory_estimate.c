/* memory_estimate.c: renderer memory from two small builds (memory_estimate.h). */
#include "methods/memory_estimate.h"

#include <malloc.h>
#include <stdio.h>
#include <string.h>

#if defined(__SANITIZE_ADDRESS__)
/* Under AddressSanitizer the heap is ASan's, which glibc's mallinfo2 does not see; its own
 * allocator statistics say the same thing. */
size_t __sanitizer_get_current_allocated_bytes(void);
static size_t heap_in_use(void) { return __sanitizer_get_current_allocated_bytes(); }
#else
static size_t heap_in_use(void)
{
    struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd; /* arena chunks in use + mmap'ed chunks (the large buffers) */
}
#endif

/* Heap growth of building (and keeping) one renderer at w x h. */
static double build_bytes(const struct scene *s, const struct method *method, const struct render_params *p, int w, int h)
{
    struct render_params q = *p;
    q.width = w;
    q.height = h;
    struct renderer r;
    size_t before = heap_in_use();
    renderer_init(&r, s, method, &q);
    size_t after = heap_in_use();
    renderer_fini(&r);
    return (double)after - (double)before;
}

size_t renderer_estimate_bytes(const struct scene *s, const struct method *method, const struct render_params *p,
                               double *bytes_per_pixel)
{
    /* sizes that are whole tiles and reuse-cell tiles, so per-tile buffers scale exactly */
    const int w1 = 128, h1 = 64, w2 = 256, h2 = 128;
    double b1 = build_bytes(s, method, p, w1, h1), b2 = build_bytes(s, method, p, w2, h2);
    double per_pixel = (b2 - b1) / ((double)w2 * h2 - (double)w1 * h1);
    double fixed = b1 - per_pixel * (double)w1 * h1;
    if (per_pixel < 0.0)
        per_pixel = 0.0;
    if (fixed < 0.0)
        fixed = 0.0;
    if (bytes_per_pixel)
        *bytes_per_pixel = per_pixel;
    return (size_t)(fixed + per_pixel * (double)p->width * (double)p->height);
}

size_t memory_available_bytes(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return 0;
    char line[256];
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1)
            break;
    fclose(f);
    return (size_t)kb * 1024u;
}
