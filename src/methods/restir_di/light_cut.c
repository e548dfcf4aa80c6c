/* light_cut.c: cuts through the light BVH for regions of space (light_cut.h). */
#include "methods/restir_di/light_cut.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "shading/light_tree.h"

int light_cut_order_init(struct light_cut_order *o, const struct light_bvh *t, int num_emitters)
{
    memset(o, 0, sizeof(*o));
    if (t->num_nodes < 1 || num_emitters < 1)
        return -1;
    const int nn = t->num_nodes;
    o->n = num_emitters;
    o->emitter_of_rank = xmalloc(sizeof(int) * (size_t)num_emitters);
    o->rank_of_emitter = xmalloc(sizeof(int) * (size_t)num_emitters);
    o->first = xmalloc(sizeof(int) * (size_t)nn);
    o->count = xmalloc(sizeof(int) * (size_t)nn);
    o->power_prefix = xmalloc(sizeof(double) * ((size_t)num_emitters + 1));
    /* depth-first node order: leaves meet in rank order, and a node's subtree is the nodes after it */
    int rank = 0;
    o->power_prefix[0] = 0.0;
    for (int k = 0; k < nn; k++) {
        o->first[k] = rank;
        const struct light_bvh_node *nd = &t->nodes[k];
        if (nd->second >= 0)
            continue;
        o->emitter_of_rank[rank] = nd->emitter;
        o->rank_of_emitter[nd->emitter] = rank;
        o->power_prefix[rank + 1] = o->power_prefix[rank] + (double)nd->power;
        rank++;
    }
    /* leaves below a node: its own for a leaf, else its children's (both after it) */
    for (int k = nn - 1; k >= 0; k--)
        o->count[k] = t->nodes[k].second < 0 ? 1 : o->count[k + 1] + o->count[t->nodes[k].second];
    return 0;
}

void light_cut_order_fini(struct light_cut_order *o)
{
    free(o->emitter_of_rank);
    free(o->rank_of_emitter);
    free(o->first);
    free(o->count);
    free(o->power_prefix);
    memset(o, 0, sizeof(*o));
}

void light_cut_build(struct light_cut *cut, const struct light_bvh *t, const struct light_cut_order *o, vec3 c)
{
    int node[LIGHT_CUT_MAX];
    float imp[LIGHT_CUT_MAX];
    int n = 1;
    node[0] = 0;
    imp[0] = light_tree_importance(&t->nodes[0], c, v3s(0.0f));
    while (n < LIGHT_CUT_MAX) { /* open the most important interior node */
        int best = -1;
        for (int j = 0; j < n; j++)
            if (t->nodes[node[j]].second >= 0 && imp[j] > 0.0f && (best < 0 || imp[j] > imp[best]))
                best = j;
        if (best < 0)
            break;
        const int k = node[best], second = t->nodes[k].second;
        node[best] = k + 1;
        imp[best] = light_tree_importance(&t->nodes[k + 1], c, v3s(0.0f));
        node[n] = second;
        imp[n] = light_tree_importance(&t->nodes[second], c, v3s(0.0f));
        n++;
    }
    /* rank order (node order is depth-first), so that lookups can bisect */
    for (int j = 1; j < n; j++)
        for (int i = j; i > 0 && node[i - 1] > node[i]; i--) {
            const int tn = node[i];
            node[i] = node[i - 1], node[i - 1] = tn;
            const float ti = imp[i];
            imp[i] = imp[i - 1], imp[i - 1] = ti;
        }
    double total = 0.0;
    for (int j = 0; j < n; j++)
        total += imp[j];
    cut->nodes = n;
    for (int j = 0; j < n; j++) {
        cut->first[j] = o->first[node[j]];
        cut->count[j] = o->count[node[j]];
        cut->prob[j] = total > 0.0 ? (float)(imp[j] / total) : 0.0f;
    }
}

int light_cut_sample(const struct light_cut *cut, const struct light_cut_order *o, double u_node, float u_emitter)
{
    int j = -1, last = -1;
    double acc = 0.0; /* in double: a small node's share is not lost against the running sum */
    for (int i = 0; i < cut->nodes && j < 0; i++) {
        acc += cut->prob[i];
        last = cut->prob[i] > 0.0f ? i : last;
        if (u_node < acc && cut->prob[i] > 0.0f)
            j = i;
    }
    j = j >= 0 ? j : last; /* rounding left u past the summed probabilities */
    if (j < 0)
        return -1;
    const double *pp = o->power_prefix;
    const int first = cut->first[j], end = first + cut->count[j];
    const double target = pp[first] + (double)u_emitter * (pp[end] - pp[first]);
    /* the first rank r in [first, end) with pp[r + 1] > target: its power is positive */
    int lo = first, hi = end - 1;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (pp[mid + 1] > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    while (lo > first && !(pp[lo + 1] > pp[lo])) /* target rounded onto the end: the last positive */
        lo--;
    return pp[lo + 1] > pp[lo] ? o->emitter_of_rank[lo] : -1;
}

float light_cut_pmf(const struct light_cut *cut, const struct light_cut_order *o, int e)
{
    if (e < 0 || e >= o->n)
        return 0.0f;
    const int r = o->rank_of_emitter[e];
    int lo = 0, hi = cut->nodes - 1; /* the cut node whose range holds r */
    while (lo < hi) {
        const int mid = (lo + hi + 1) / 2;
        if (cut->first[mid] <= r)
            lo = mid;
        else
            hi = mid - 1;
    }
    const double *pp = o->power_prefix;
    const int first = cut->first[lo], end = first + cut->count[lo];
    const double node_power = pp[end] - pp[first];
    if (!(node_power > 0.0) || r < first || r >= end)
        return 0.0f;
    return (float)((double)cut->prob[lo] * ((pp[r + 1] - pp[r]) / node_power));
}
