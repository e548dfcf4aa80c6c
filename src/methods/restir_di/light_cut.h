/* light_cut.h: a cut through the light BVH for one region of space (ReGIR's cells, regir.h): the
 * tree is opened from the root, always splitting the node of highest importance at the region's
 * centre (light_tree_importance with no receiver orientation), until LIGHT_CUT_MAX nodes partition
 * the emitters; a node is then chosen with probability proportional to its importance, and an
 * emitter inside it proportional to its power. Both steps are tables, so drawing and looking up
 * the probability of an emitter cost a scan of the cut and a binary search, where a descent of the
 * tree costs two importance evaluations per level (17 levels for 100k emitters); the probability
 * is P(e) = P(node of e) power(e) / power(node), the same number for drawing and lookup, and the
 * frequency of the draws up to the resolution of their uniforms (2^-32 for the node, summed in
 * double; 2^-24 of the node's power for the emitter).
 * Light-cut style selection after Walter et al. 2005; the importance is Conty Estevez and Kulla
 * 2018's (light_tree.h). Must never trace rays. */
#ifndef RESTIR_METHODS_RESTIR_DI_LIGHT_CUT_H
#define RESTIR_METHODS_RESTIR_DI_LIGHT_CUT_H

#include "scene/scene_types.h"

#define LIGHT_CUT_MAX 64

/* The tree's emitters in depth-first leaf order, so that every node's emitters are one range. */
struct light_cut_order {
    int *emitter_of_rank; /* rank -> emitter */
    int *rank_of_emitter; /* emitter -> rank */
    int *first;           /* per node: the rank of its first emitter */
    int *count;           /* per node: how many emitters lie below it */
    double *power_prefix; /* per rank: summed power of the ranks before it (n + 1 entries) */
    int n;
};

/* One region's cut: nodes in rank order with their probabilities. */
struct light_cut {
    int nodes;
    int first[LIGHT_CUT_MAX], count[LIGHT_CUT_MAX];
    float prob[LIGHT_CUT_MAX]; /* importance / total (0 everywhere when no node can light the region) */
};

/* Builds the order of t's emitters (num_emitters of them). Returns 0, or -1 for an empty tree. */
int light_cut_order_init(struct light_cut_order *o, const struct light_bvh *t, int num_emitters);
void light_cut_order_fini(struct light_cut_order *o);
/* The cut of tree t for the region around centre c. */
void light_cut_build(struct light_cut *cut, const struct light_bvh *t, const struct light_cut_order *o, vec3 c);
/* An emitter by the cut from two uniforms in [0, 1); -1 when the cut gives no node any probability. */
int light_cut_sample(const struct light_cut *cut, const struct light_cut_order *o, double u_node, float u_emitter);
/* The probability that light_cut_sample returns emitter e. */
float light_cut_pmf(const struct light_cut *cut, const struct light_cut_order *o, int e);

#endif
