/* tiles.h: how passes split the image into tiles for the OpenMP parallel-for, and the stream
 * ids of the seeding rule. Must never hold state. */
#ifndef RESTIR_RENDER_TILES_H
#define RESTIR_RENDER_TILES_H

#include <stdint.h>

/* Tiles are 64 x 4 pixels, so a tile row spans 64 bytes of a byte mask and 256 of a float plane:
 * two threads share at most the cache lines at a tile row's two ends (the planes are not 64-byte
 * aligned). With 8 x 8 tiles, horizontally adjacent tiles, often on different threads, shared
 * most lines of every plane; that false sharing kept the G-buffer pass from scaling at all
 * (59 ms on 1 thread, 50 on 2; 27-31 ms with 64 x 4). */
#define RESTIR_TILE_W 64
#define RESTIR_TILE_H 4

struct tile_range {
    int x0, y0, x1, y1;
};

static inline int tile_count(int width, int height)
{
    return ((width + RESTIR_TILE_W - 1) / RESTIR_TILE_W) * ((height + RESTIR_TILE_H - 1) / RESTIR_TILE_H);
}

static inline struct tile_range tile_get(int width, int height, int tile)
{
    int tiles_x = (width + RESTIR_TILE_W - 1) / RESTIR_TILE_W;
    struct tile_range r;
    r.x0 = (tile % tiles_x) * RESTIR_TILE_W;
    r.y0 = (tile / tiles_x) * RESTIR_TILE_H;
    r.x1 = r.x0 + RESTIR_TILE_W < width ? r.x0 + RESTIR_TILE_W : width;
    r.y1 = r.y0 + RESTIR_TILE_H < height ? r.y0 + RESTIR_TILE_H : height;
    return r;
}

/* A walk over the pixels of one tile, row by row, left to right:
 *     for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px))
 * Every pass runs this loop inside its OpenMP loop over tiles. */
struct tile_pixel {
    struct tile_range r;
    int width;
    int x, y, i; /* i = y * width + x; -1 once the walk is past the last pixel */
};

/* The pixel after (x, y) in r, or -1 after the last. */
static inline int tile_pixel_after(const struct tile_range *r, int width, int x, int y)
{
    if (x + 1 < r->x1)
        return y * width + x + 1;
    return y + 1 < r->y1 ? (y + 1) * width + r->x0 : -1;
}

static inline struct tile_pixel tile_first_pixel(int width, int height, int tile)
{
    struct tile_pixel px;
    px.r = tile_get(width, height, tile);
    px.width = width;
    px.x = px.r.x0;
    px.y = px.r.y0;
    px.i = px.r.x0 < px.r.x1 && px.r.y0 < px.r.y1 ? px.y * width + px.x : -1;
    return px;
}

static inline void tile_advance(struct tile_pixel *px)
{
    px->i = tile_pixel_after(&px->r, px->width, px->x, px->y);
    if (++px->x >= px->r.x1) {
        px->x = px->r.x0;
        px->y++;
    }
}

/* The pixel the walk visits next (-1: none): what a pass prefetches for while it works on px. */
static inline int tile_peek(const struct tile_pixel *px) { return tile_pixel_after(&px->r, px->width, px->x, px->y); }

/* Prefetches the cache lines of bytes [p, p + n) for reading. */
static inline void prefetch_bytes(const void *p, unsigned n)
{
    const char *c = (const char *)p;
    for (unsigned k = 0; k < n; k += 64)
        __builtin_prefetch(c + k);
    __builtin_prefetch(c + n - 1);
}

/* Stream ids per pass, the fourth term of the (seed, frame, pixel, pass) seeding rule. */
enum rng_pass {
    RNG_PASS_GBUFFER = 1,
    RNG_PASS_PT,
    RNG_PASS_DI_INITIAL,
    RNG_PASS_DI_TEMPORAL,
    RNG_PASS_DI_SPATIAL,
    RNG_PASS_DI_SHADE,
    RNG_PASS_PT_INITIAL,
    RNG_PASS_PT_TEMPORAL,
    RNG_PASS_PT_SPATIAL,
    RNG_PASS_SELECT,
    RNG_PASS_CELL_SEARCH,
    RNG_PASS_SPMIS_CANONICAL,
    RNG_PASS_SPMIS_REUSE,
    RNG_PASS_GPT,
    RNG_PASS_GRAD_INITIAL,
    RNG_PASS_GRAD_TEMPORAL,
    RNG_PASS_GRAD_SELECT,
    RNG_PASS_GRAD_SPATIAL,
    RNG_PASS_LIGHT_POOL,
    RNG_PASS_GI_INITIAL,
    RNG_PASS_GI_TEMPORAL,
    RNG_PASS_GI_SPATIAL,
    RNG_PASS_PT_SOBOL, /* not a PCG32 stream: the key of pt's Sobol' dimensions (pt.c) */
    RNG_PASS_TEMPORAL_PERMUTATION, /* one draw per frame: the permutation's tile offset (gbuffer.h) */
    RNG_PASS_COUNT     /* one past the last: the toolkit's ids are the small integers below it */
};

/* The stream id of a named stream, for a method's own passes (listed in its row's `streams`, which
 * the registry checks for collisions when it is built): the 64-bit FNV-1a hash of the name with its
 * top bit set, so that no name can take one of the toolkit's small ids above (kept as they are so that
 * the images they seed do not move). Compilers fold it to a constant for a literal name; a pass takes
 * it once, outside its pixel loop. */
static inline uint64_t rng_stream_id(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (const unsigned char *c = (const unsigned char *)name; *c; c++)
        h = (h ^ *c) * 0x100000001b3ull;
    return h | (1ull << 63);
}

#endif
