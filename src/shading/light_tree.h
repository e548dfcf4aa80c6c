/* light_tree.h: choosing an emitter for a shading point by the emitter BVH (scene_light_bvh.h):
 * descend from the root, taking each child with probability proportional to its importance at the
 * point, a bound of the light it can send there from its power, distance and orientation bounds
 * (Conty Estevez & Kulla 2018, Sec. 4.2, Eq. 3, in the form of pbrt-v4's BVHLightSampler). The
 * probability of an emitter is the product of the choices on its path, so light_tree_pmf is exact,
 * not an estimate. Must never depend on render passes. */
#ifndef RESTIR_SHADING_LIGHT_TREE_H
#define RESTIR_SHADING_LIGHT_TREE_H

#include "scene/scene_types.h"

/* The importance of node nd for a shading point p with unit normal n (which side of the surface
 * does not matter: |cos|), in power / area units; 0 when no emitter below can light p. n = 0 stands
 * for a receiver of every orientation (ReGIR's cells): the receiver's cosine bound is then 1. */
float light_tree_importance(const struct light_bvh_node *nd, vec3 p, vec3 n);
/* An emitter for point p with normal n from one uniform u in [0, 1): its index, with its
 * probability in *pmf; -1 (and *pmf = 0) when the tree is empty or no emitter can light p. */
int light_tree_sample(const struct light_bvh *t, vec3 p, vec3 n, float u, float *pmf);
/* The probability that light_tree_sample(t, p, n, .) returns emitter e (0 for an index out of
 * range). The same arithmetic in the same order as the sampler's, so the two agree bit for bit. */
float light_tree_pmf(const struct light_bvh *t, vec3 p, vec3 n, int e);
/* light_tree_sample, also writing to *pmf_pair the probability that the descent reaches the chosen
 * leaf's parent times the sum of that parent's two children's probabilities: the probability of
 * choosing either of two sibling leaves (the two halves of a rectangle, lights.c) in one product. */
int light_tree_sample_pair(const struct light_bvh *t, vec3 p, vec3 n, float u, float *pmf, float *pmf_pair);
/* light_tree_sample_pair's pmf_pair for emitter e's leaf, bit for bit (its sibling gives the same). */
float light_tree_pmf_pair(const struct light_bvh *t, vec3 p, vec3 n, int e);

#endif
