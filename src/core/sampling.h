/* sampling.h: warps from the unit square to common domains, with their densities, and an alias
 * table for discrete distributions. Must never depend on scene or render code. */
#ifndef RESTIR_CORE_SAMPLING_H
#define RESTIR_CORE_SAMPLING_H

#include "core/vec3.h"

#define RESTIR_PI 3.14159265358979323846f
#define RESTIR_INV_PI 0.31830988618379067154f

/* Shirley-Chiu concentric map of [0,1)^2 to the unit disk (area-preserving up to pi). */
void warp_concentric_disk(float u1, float u2, float *x, float *y);
/* Inverse of warp_concentric_disk (for round-trip tests). */
void warp_concentric_disk_inverse(float x, float y, float *u1, float *u2);

/* Cosine-weighted hemisphere around +z; density cos(theta)/pi in solid angle. */
vec3 warp_cosine_hemisphere(float u1, float u2);
float warp_cosine_hemisphere_pdf(vec3 local_dir);

/* Uniform point on a triangle as barycentrics (b1, b2); density 1/area in area measure.
 * Heitz 2019, "A Low-Distortion Map Between Triangle and Square": a sqrt-free map that keeps
 * neighbouring square points close on the triangle, uniform on {b1, b2 >= 0, b1 + b2 <= 1};
 * written branch-free so batch loops vectorize. */
static inline void warp_uniform_triangle(float u1, float u2, float *b1, float *b2)
{
    float lo = u1 < u2 ? u1 : u2, hi = u1 < u2 ? u2 : u1; /* halve the smaller, shift the other */
    float half = 0.5f * lo, other = hi - half;
    *b1 = u2 > u1 ? half : other;
    *b2 = u2 > u1 ? other : half;
}

/* Uniform direction on the unit sphere; density 1/(4 pi). */
vec3 warp_uniform_sphere(float u1, float u2);

/* Walker/Vose alias table: O(1) sampling of index i with probability w_i / sum w. */
struct alias_bucket {
    float prob; /* acceptance probability of the bucket's own index */
    int alias;  /* index taken when it rejects */
};

struct alias_table {
    int n;
    struct alias_bucket *bucket; /* interleaved: one cache access per sample */
    float *pmf;   /* normalized probability of each index */
    double total; /* sum of the input weights */
};

/* Builds the table; returns 0 on success, -1 when n < 1 or the weights are negative, not finite
 * or all zero. The caller owns *t and releases it with alias_table_fini. */
int alias_table_init(struct alias_table *t, const float *weights, int n);
void alias_table_fini(struct alias_table *t);
/* Samples an index from one uniform u in [0,1): the integer part of u n picks the bucket, the
 * fraction is the coin. The product is formed in double so no rounding is added; a 24-bit u
 * leaves 24 - log2(n) bits for the coin, ample for tables of up to ~1e5 entries. */
static inline int alias_table_sample(const struct alias_table *t, float u)
{
    double x = (double)u * (double)t->n;
    int i = (int)x;
    i = i >= t->n ? t->n - 1 : (i < 0 ? 0 : i);
    struct alias_bucket b = t->bucket[i];
    return x - (double)i < (double)b.prob ? i : b.alias;
}

#endif
