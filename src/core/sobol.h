/* sobol.h: Owen-scrambled, shuffled Sobol' points for low-discrepancy sampling (pt's
 * `sampler=sobol`). Must never depend on scenes or render passes.
 *
 * Only the first two Sobol' dimensions are used, a (0,2)-sequence in base 2: dimension 0 is the van
 * der Corput sequence (index bits reversed), dimension 1 has the binary Pascal matrix as its
 * generator (direction numbers v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1)), so no table is needed.
 * Every further pair or single dimension of a sample is "padded": it uses the same 2-D sequence with
 * its own random index shuffle and scramble, as Burley 2020 ("Practical Hash-based Owen
 * Scrambling", JCGT 9(4)) does, which keeps each pair a (0,m,2)-net over any 2^m consecutive
 * samples while decorrelating the pairs from each other.
 *
 * Scrambling is Burley's hash-based nested uniform (Owen) scramble: in the bit-reversed domain a
 * hash whose bit k depends only on bits below k (additions and products with even constants) flips
 * each digit of the point depending only on the digits before it. Each scrambled point is uniform in
 * [0,1)^2, so an estimator averaging f over the points is unbiased whatever the seed, and points of
 * different seeds are independent. The index shuffle is the same scramble applied to the sample
 * index: it maps the first 2^m indices onto one aligned block of 2^m indices, so the net property
 * survives it. */
#ifndef RESTIR_CORE_SOBOL_H
#define RESTIR_CORE_SOBOL_H

#include <stdint.h>

static inline uint32_t sobol_reverse_bits(uint32_t x)
{
    x = __builtin_bswap32(x); /* the bytes; then the bits within each byte */
    x = ((x & 0x0f0f0f0fu) << 4) | ((x & 0xf0f0f0f0u) >> 4);
    x = ((x & 0x33333333u) << 2) | ((x & 0xccccccccu) >> 2);
    return ((x & 0x55555555u) << 1) | ((x & 0xaaaaaaaau) >> 1);
}

/* Sobol' dimension 0 of index i as 32 fraction bits: the van der Corput radical inverse. */
static inline uint32_t sobol_dim0(uint32_t i) { return sobol_reverse_bits(i); }

/* Sobol' dimension 1 before its bit reversal: output digit r (r = 0 the most significant) is the
 * parity of the index bits c with r a subset of c (C(c, r) odd by Lucas' theorem: the binary Pascal
 * matrix, whose columns are the direction numbers v_1 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1) of the
 * primitive polynomial x + 1), held at bit r: the superset-parity transform in five steps. */
static inline uint32_t sobol_dim1_reversed(uint32_t i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    i ^= (i >> 16) & 0x0000ffffu;
    return i;
}

/* Sobol' dimension 1 of index i as 32 fraction bits. */
static inline uint32_t sobol_dim1(uint32_t i) { return sobol_reverse_bits(sobol_dim1_reversed(i)); }

/* Burley 2020's Laine-Karras-style hash: bit k of the result depends only on bits <= k of x and on
 * the seed (an addition and products with even constants), so applied to bit-reversed fraction bits
 * it flips each digit depending only on the digits before it: a nested uniform (Owen) scramble. */
static inline uint32_t sobol_lk_hash(uint32_t x, uint32_t seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* 32 fraction bits to a float in [0, 1): the top 24 bits, never 1. */
static inline float sobol_to_float(uint32_t x) { return (float)(x >> 8) * 0x1.0p-24f; }

/* The three 32-bit seeds of a padded dimension from its 64-bit key (a well-mixed hash of seed,
 * pixel, frame and dimension number): the index shuffle's, and the scrambles of the two
 * coordinates. */
static inline uint32_t sobol_seed_shuffle(uint64_t key) { return (uint32_t)key; }
static inline uint32_t sobol_seed_x(uint64_t key) { return (uint32_t)(key >> 32); }
static inline uint32_t sobol_seed_y(uint64_t key) { return (uint32_t)((key * 0xd1b54a32d192ed03ull) >> 32); }

/* The index shuffle of the dimension named by `key`: the nested scramble of the index's bits, which
 * maps any aligned block of 2^m indices onto an aligned block of 2^m indices. */
static inline uint32_t sobol_shuffle(uint32_t index, uint64_t key)
{
    return sobol_reverse_bits(sobol_lk_hash(sobol_reverse_bits(index), sobol_seed_shuffle(key)));
}

/* Point `index` of the padded pair named by `key` (a well-mixed 64-bit hash: its bits are the seeds):
 * u[0], u[1] in [0,1). The shuffled index is
 * i = scramble(index); u[0] = scramble(dim0(i)), u[1] = scramble(dim1(i)), with the bit reversals
 * that cancel left out (dim0(i) = reverse(i)). */
static inline void sobol_sample_2d(uint32_t index, uint64_t key, float u[2])
{
    const uint32_t i = sobol_shuffle(index, key);
    u[0] = sobol_to_float(sobol_reverse_bits(sobol_lk_hash(i, sobol_seed_x(key))));
    u[1] = sobol_to_float(sobol_reverse_bits(sobol_lk_hash(sobol_dim1_reversed(i), sobol_seed_y(key))));
}

/* Point `index` of the padded single dimension named by `key`, in [0,1): a scrambled, shuffled van
 * der Corput sequence (stratified over any 2^m consecutive samples). */
static inline float sobol_sample_1d(uint32_t index, uint64_t key)
{
    const uint32_t i = sobol_shuffle(index, key);
    return sobol_to_float(sobol_reverse_bits(sobol_lk_hash(i, sobol_seed_x(key))));
}

#endif
