/* rng.h: PCG32 random streams seeded by a hash of (seed, frame, pixel, pass), so every random
 * number is reproducible whatever the thread count. Must never depend on global state. */
#ifndef RESTIR_CORE_RNG_H
#define RESTIR_CORE_RNG_H

#include <stdint.h>

typedef struct pcg32 {
    uint64_t state;
    uint64_t inc;
} pcg32;

/* splitmix64 finalizer: a strong 64-bit mix used to build stream seeds. */
static inline uint64_t rng_mix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static inline uint32_t pcg32_next(pcg32 *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* PCG32 seeding as in O'Neill's reference: state and stream select the sequence. */
static inline pcg32 pcg32_make(uint64_t state, uint64_t stream)
{
    pcg32 r;
    r.state = 0u;
    r.inc = (stream << 1u) | 1u;
    pcg32_next(&r);
    r.state += state;
    pcg32_next(&r);
    return r;
}

/* Uniform float in [0, 1): 24 random mantissa bits, never exactly 1. */
static inline float pcg32_float(pcg32 *r) { return (float)(pcg32_next(r) >> 8) * 0x1.0p-24f; }

/* The 64-bit key of one (seed, frame, pixel, pass): the project-wide seeding rule (DESIGN.md), which
 * rng_for turns into a PCG32 stream and pt's Sobol' sampler into its dimensions' keys. */
static inline uint64_t rng_key(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t pass)
{
    return rng_mix64(seed ^ rng_mix64(frame ^ rng_mix64(pixel ^ rng_mix64(pass))));
}

/* Stream for one (seed, frame, pixel, pass). */
static inline pcg32 rng_for(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t pass)
{
    uint64_t h = rng_key(seed, frame, pixel, pass);
    return pcg32_make(h, rng_mix64(h ^ 0x5851f42d4c957f2dull));
}

#endif
