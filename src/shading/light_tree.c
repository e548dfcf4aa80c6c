/* light_tree.c: emitter selection by importance down the emitter BVH (light_tree.h). */
#include "shading/light_tree.h"

#include <math.h>

/* Deepest path a tree can have (scene_light_bvh.c splits in halves past depth 48). */
#define LIGHT_TREE_MAX_DEPTH 128

static float safe_sqrt(float x) { return x > 0.0f ? sqrtf(x) : 0.0f; }

/* cos(max(0, a - b)) and sin(max(0, a - b)) from the angles' cosines and sines. */
static float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b)
{
    return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
static float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b)
{
    return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

float light_tree_importance(const struct light_bvh_node *nd, vec3 p, vec3 n)
{
    const vec3 to_p = v3_sub(p, nd->center);
    const float d2_center = v3_length2(to_p);
    /* the distance term, kept away from 0 inside the box (Conty Estevez & Kulla 2018, Sec. 4.2) */
    const float d2 = max_f(d2_center, nd->d2_min);
    const vec3 wi = d2_center > 0.0f ? v3_scale(to_p, 1.0f / sqrtf(d2_center)) : nd->axis;
    /* theta_w: between the cone's axis and the direction to p */
    const float cos_w = v3_dot(nd->axis, wi), sin_w = safe_sqrt(1.0f - cos_w * cos_w);
    /* theta_b: half-angle of the box's bounding sphere seen from p (every direction from inside) */
    const float r2 = nd->radius2;
    const float cos_b = d2_center <= r2 ? -1.0f : safe_sqrt(1.0f - r2 / d2_center);
    const float sin_b = d2_center <= r2 ? 0.0f : sqrtf(r2 / d2_center);
    const float sin_o = nd->sin_o;
    /* theta' = max(0, theta_w - theta_o - theta_b): the smallest angle between an emitting normal
     * below and a direction from the node toward p */
    const float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, nd->cos_o);
    const float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, nd->cos_o);
    const float cos_t = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if (cos_t <= nd->cos_e)
        return 0.0f;
    /* theta_i': the smallest angle between p's normal and a direction toward the node; a receiver
     * without orientation (n = 0) drops the term */
    const float cos_i = fabsf(v3_dot(wi, n)), sin_i = safe_sqrt(1.0f - cos_i * cos_i);
    const int oriented = n.x != 0.0f || n.y != 0.0f || n.z != 0.0f;
    const float cos_ti = oriented ? cos_sub_clamped(sin_i, cos_i, sin_b, cos_b) : 1.0f;
    const float importance = nd->power * cos_t * cos_ti / d2;
    return importance > 0.0f ? importance : 0.0f;
}

/* The probabilities of taking the first and the second child at interior node k, each a child's
 * importance over both children's (the second not as 1 - the first, which would lose its relative
 * precision when it is small). Returns 0 when neither child can light p. */
static int child_probs(const struct light_bvh *t, int k, vec3 p, vec3 n, float prob[2])
{
    const float c0 = light_tree_importance(&t->nodes[k + 1], p, n);
    const float c1 = light_tree_importance(&t->nodes[t->nodes[k].second], p, n);
    const float sum = c0 + c1;
    if (!(sum > 0.0f))
        return 0;
    prob[0] = c0 / sum;
    prob[1] = c1 / sum;
    return 1;
}

/* A tree of one emitter (the root a leaf) chooses it with probability 1 where it can light p. */
static float single_emitter_prob(const struct light_bvh *t, vec3 p, vec3 n)
{
    return light_tree_importance(&t->nodes[0], p, n) > 0.0f ? 1.0f : 0.0f;
}

int light_tree_sample_pair(const struct light_bvh *t, vec3 p, vec3 n, float u, float *pmf, float *pmf_pair)
{
    *pmf = 0.0f;
    *pmf_pair = 0.0f;
    if (t->num_nodes < 1)
        return -1;
    if (t->nodes[0].second < 0) { /* a single emitter: chosen wherever it can light p */
        *pmf = *pmf_pair = single_emitter_prob(t, p, n);
        return *pmf > 0.0f ? t->nodes[0].emitter : -1;
    }
    /* u is remapped into each chosen interval, so one uniform makes the whole descent (its 24 bits
     * resolve leaves down to a probability of about 2^-24, as the alias table's) */
    float prob = 1.0f;
    int k = 0;
    while (t->nodes[k].second >= 0) {
        float pc[2];
        if (!child_probs(t, k, p, n, pc))
            return -1;
        *pmf_pair = prob * (pc[0] + pc[1]); /* the last one written is the leaf's parent's */
        if (u < pc[0]) {
            u = min_f(u / pc[0], 0x1.fffffep-1f);
            prob *= pc[0];
            k = k + 1;
        } else {
            u = min_f((u - pc[0]) / (1.0f - pc[0]), 0x1.fffffep-1f);
            prob *= pc[1];
            k = t->nodes[k].second;
        }
    }
    *pmf = prob;
    return t->nodes[k].emitter;
}

int light_tree_sample(const struct light_bvh *t, vec3 p, vec3 n, float u, float *pmf)
{
    float pair;
    return light_tree_sample_pair(t, p, n, u, pmf, &pair);
}

/* light_tree_pmf, or with pair set the probability of e's leaf's parent times the sum of its two
 * children's probabilities (light_tree_sample_pair's pmf_pair): the same products in the same order. */
static float path_prob(const struct light_bvh *t, vec3 p, vec3 n, int e, int pair)
{
    if (e < 0 || e >= (t->num_nodes + 1) / 2) /* one emitter per leaf: 2 n - 1 nodes */
        return 0.0f;
    if (t->nodes[0].second < 0)
        return single_emitter_prob(t, p, n);
    /* the path root -> leaf, gathered leaf -> root, then multiplied in the sampler's order */
    int path[LIGHT_TREE_MAX_DEPTH], depth = 0;
    for (int k = t->emitter_leaf[e]; k >= 0 && depth < LIGHT_TREE_MAX_DEPTH; k = t->nodes[k].parent)
        path[depth++] = k;
    if (path[depth - 1] != 0)
        return 0.0f; /* deeper than any tree scene_light_bvh.c builds */
    float prob = 1.0f;
    for (int d = depth - 1; d > 0; d--) {
        float pc[2];
        if (!child_probs(t, path[d], p, n, pc))
            return 0.0f;
        prob *= pair && d == 1 ? pc[0] + pc[1] : pc[path[d - 1] == path[d] + 1 ? 0 : 1];
    }
    return prob;
}

float light_tree_pmf(const struct light_bvh *t, vec3 p, vec3 n, int e) { return path_prob(t, p, n, e, 0); }

float light_tree_pmf_pair(const struct light_bvh *t, vec3 p, vec3 n, int e) { return path_prob(t, p, n, e, 1); }
