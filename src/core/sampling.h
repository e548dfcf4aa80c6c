/* sampling.h: warps from the unit square to common domains, with their densities, and an alias
 * table for discrete distributions. Must never depend on scene or render code. */
#ifndef RESTIR_CORE_SAMPLING_H
#define RESTIR_CORE_SAMPLING_H

#include "vec3.h"

#define RESTIR_PI 3.14159265358979323846f
#define RESTIR_INV_PI 0.31830988618379067154f

/* Shirley-Chiu concentric map of [0,1)^2 to the unit disk (area-preserving up to pi). */
void warp_concentric_disk(float u1, float u2, float *x, float *y);
/* Inverse of warp_concentric_disk (for round-trip tests). */
void warp_concentric_disk_inverse(float x, float y, float *u1, float *u2);

/* Cosine-weighted hemisphere around +z; density cos(theta)/pi in solid angle. */
vec3 warp_cosine_hemisphere(float u1, float u2);
float warp_cosine_hemisphere_pdf(vec3 local_dir);

/* Uniform point on a triangle as barycentrics (b1, b2); density 1/area in area measure. */
void warp_uniform_triangle(float u1, float u2, float *b1, float *b2);

/* Uniform direction on the unit sphere; density 1/(4 pi). */
vec3 warp_uniform_sphere(float u1, float u2);

/* Walker/Vose alias table: O(1) sampling of index i with probability w_i / sum w. */
struct alias_table {
    int n;
    float *prob;  /* acceptance probability of bucket i */
    int *alias;   /* index taken when bucket i rejects */
    float *pmf;   /* normalized probability of each index */
    double total; /* sum of the input weights */
};

/* Builds the table; returns 0 on success, -1 when n < 1 or the weights are negative, not finite
 * or all zero. The caller owns *t and releases it with alias_table_fini. */
int alias_table_init(struct alias_table *t, const float *weights, int n);
void alias_table_fini(struct alias_table *t);
/* Samples an index from one uniform u in [0,1). */
int alias_table_sample(const struct alias_table *t, float u);

#endif
