/* scene_light_bvh.c: the emitter BVH's construction. Each interior node splits its emitters at the
 * bucket boundary of least cost power * M_Omega * area * K_r (Conty Estevez & Kulla 2018, Eq. 2
 * and Sec. 4.3), where M_Omega is the solid angle measure of the node's normal and emission cones
 * and K_r = longest extent / extent along the split axis penalizes thin slabs. */
#include "scene/scene_light_bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

#define SPLIT_BUCKETS 12
/* Past this depth a node splits its emitters in two equal halves (a degenerate distribution cannot
 * make the tree deeper than this plus log2 of the emitter count). */
#define SAOH_MAX_DEPTH 48

struct item {
    vec3 lo, hi, centroid, axis;
    float power;
    int emitter;
};

/* The bounds of a set of emitters, as a node holds them; empty when power < 0. */
struct bounds {
    vec3 lo, hi, axis;
    float cos_o, power;
    int empty;
};

void light_cone_union(vec3 wa, float cos_a, vec3 wb, float cos_b, vec3 *w, float *cos_o)
{
    const double pi = 3.14159265358979323846;
    *w = wa;
    *cos_o = -1.0f;
    if (cos_a <= -1.0f || cos_b <= -1.0f)
        return;
    /* a single direction (every emitter's own cone) needs no acos: acos(1) is exactly 0 */
    const double ta = cos_a >= 1.0f ? 0.0 : acos(fmin(1.0, cos_a)), tb = cos_b >= 1.0f ? 0.0 : acos(fmin(1.0, cos_b));
    const double dot = fmax(-1.0, fmin(1.0, (double)v3_dot(wa, wb)));
    const double td = acos(dot);
    if (fmin(td + tb, pi) <= ta) { /* b inside a */
        *cos_o = cos_a;
        return;
    }
    if (fmin(td + ta, pi) <= tb) {
        *w = wb;
        *cos_o = cos_b;
        return;
    }
    const double to = 0.5 * (ta + td + tb);
    vec3 k = v3_cross(wa, wb);
    const float k_len = v3_length(k);
    if (to >= pi || !(k_len > 1e-12f))
        return; /* every direction */
    /* rotate wa toward wb by to - ta about k (perpendicular to wa: Rodrigues' formula's last term
     * vanishes) */
    k = v3_scale(k, 1.0f / k_len);
    const double tr = to - ta;
    *w = v3_normalize(v3_add(v3_scale(wa, (float)cos(tr)), v3_scale(v3_cross(k, wa), (float)sin(tr))));
    /* a hair wider than exact, against the rotation's rounding */
    *cos_o = (float)cos(fmin(pi, to + 1e-5));
}

static struct bounds bounds_empty(void)
{
    struct bounds b;
    memset(&b, 0, sizeof b);
    b.empty = 1;
    return b;
}

static struct bounds bounds_add(struct bounds a, const struct bounds *b)
{
    if (b->empty)
        return a;
    if (a.empty)
        return *b;
    a.lo = v3_min(a.lo, b->lo);
    a.hi = v3_max(a.hi, b->hi);
    light_cone_union(a.axis, a.cos_o, b->axis, b->cos_o, &a.axis, &a.cos_o);
    a.power += b->power;
    return a;
}

static struct bounds item_bounds(const struct item *it)
{
    struct bounds b = {it->lo, it->hi, it->axis, 1.0f, it->power, 0};
    return b;
}

/* Conty Estevez & Kulla 2018, Eq. 1: the measure of the directions a node emits into, with
 * theta_e = pi / 2 (one-sided Lambertian emitters). */
static double orientation_measure(float cos_o)
{
    const double pi = 3.14159265358979323846;
    const double to = acos(fmax(-1.0, fmin(1.0, cos_o))), tw = fmin(to + 0.5 * pi, pi), so = sin(to);
    return 2.0 * pi * (1.0 - cos(to)) + 0.5 * pi * (2.0 * tw * so - cos(to - 2.0 * tw) - 2.0 * to * so + cos(to));
}

static double split_cost(const struct bounds *b, double k_r)
{
    if (b->empty)
        return 0.0;
    const vec3 d = v3_sub(b->hi, b->lo);
    const double area = 2.0 * ((double)d.x * d.y + (double)d.y * d.z + (double)d.z * d.x);
    /* a flat or point-like box still costs by its power and orientation */
    return (double)b->power * orientation_measure(b->cos_o) * (area > 0.0 ? area : 1e-12) * k_r;
}

static float axis_of(vec3 v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

static int bucket_of(const struct item *it, int axis, float lo, float extent)
{
    int k = (int)(SPLIT_BUCKETS * (axis_of(it->centroid, axis) - lo) / extent);
    return k < 0 ? 0 : k >= SPLIT_BUCKETS ? SPLIT_BUCKETS - 1 : k;
}

/* Where the items go: those of bucket < split along axis (buckets over [lo, lo + extent]) left. */
struct split {
    int axis, bucket;
    float lo, extent;
};

/* The split of items[0 .. n-1] of least cost. Returns 0 when every centroid coincides (no split
 * separates them). */
static int best_split(const struct item *items, int n, struct split *best_split)
{
    vec3 clo = items[0].centroid, chi = items[0].centroid, lo = items[0].lo, hi = items[0].hi;
    for (int i = 1; i < n; i++) {
        clo = v3_min(clo, items[i].centroid);
        chi = v3_max(chi, items[i].centroid);
        lo = v3_min(lo, items[i].lo);
        hi = v3_max(hi, items[i].hi);
    }
    const vec3 ext = v3_sub(hi, lo);
    const float longest = v3_max_component(ext);
    double best = INFINITY;
    for (int a = 0; a < 3; a++) {
        const float cext = axis_of(chi, a) - axis_of(clo, a);
        if (!(cext > 0.0f))
            continue;
        struct bounds bucket[SPLIT_BUCKETS];
        int count[SPLIT_BUCKETS] = {0};
        for (int k = 0; k < SPLIT_BUCKETS; k++)
            bucket[k] = bounds_empty();
        for (int i = 0; i < n; i++) {
            const int k = bucket_of(&items[i], a, axis_of(clo, a), cext);
            const struct bounds ib = item_bounds(&items[i]);
            bucket[k] = bounds_add(bucket[k], &ib);
            count[k]++;
        }
        const double k_r = axis_of(ext, a) > 0.0f ? (double)longest / axis_of(ext, a) : 1.0;
        struct bounds left = bounds_empty(); /* grown bucket by bucket: the same unions, in the same order */
        int nl = 0;
        for (int s = 1; s < SPLIT_BUCKETS; s++) {
            left = bounds_add(left, &bucket[s - 1]), nl += count[s - 1];
            struct bounds right = bounds_empty();
            for (int k = s; k < SPLIT_BUCKETS; k++)
                right = bounds_add(right, &bucket[k]);
            if (nl == 0 || nl == n)
                continue;
            const double cost = split_cost(&left, k_r) + split_cost(&right, k_r);
            if (cost < best) {
                best = cost;
                *best_split = (struct split){a, s, axis_of(clo, a), cext};
            }
        }
    }
    return best < INFINITY;
}

/* Moves the items that go left to the front; returns how many there are. */
static int partition(struct item *items, int n, const struct split *sp)
{
    int left = 0;
    for (int i = 0; i < n; i++)
        if (bucket_of(&items[i], sp->axis, sp->lo, sp->extent) < sp->bucket) {
            struct item tmp = items[left];
            items[left++] = items[i];
            items[i] = tmp;
        }
    return left;
}

/* What a node holds of its bounds. */
static void node_set(struct light_bvh_node *nd, const struct bounds *bd)
{
    const vec3 diag = v3_sub(bd->hi, bd->lo);
    nd->center = v3_scale(v3_add(bd->lo, bd->hi), 0.5f);
    nd->radius2 = 0.25f * v3_length2(diag);
    nd->d2_min = 0.5f * v3_length(diag);
    nd->axis = bd->axis;
    nd->cos_o = bd->cos_o;
    nd->sin_o = sqrtf(fmaxf(0.0f, 1.0f - bd->cos_o * bd->cos_o));
    nd->power = bd->power;
}

struct builder {
    struct light_bvh *t;
    struct item *items;
};

/* Builds the subtree of items[first .. first + n - 1] at the next free node; returns its bounds. */
static struct bounds build(struct builder *b, int first, int n, int parent, int depth)
{
    const int at = b->t->num_nodes++;
    struct light_bvh_node *nd = &b->t->nodes[at];
    nd->parent = parent;
    nd->cos_e = 0.0f;
    struct bounds bd;
    if (n == 1) {
        const struct item *it = &b->items[first];
        bd = item_bounds(it);
        nd->second = -1;
        nd->emitter = it->emitter;
        b->t->emitter_leaf[it->emitter] = at;
    } else {
        struct split sp;
        int nl = n / 2;
        if (depth < SAOH_MAX_DEPTH && best_split(b->items + first, n, &sp))
            nl = partition(b->items + first, n, &sp);
        const struct bounds left = build(b, first, nl, at, depth + 1);
        nd = &b->t->nodes[at];
        nd->second = b->t->num_nodes;
        nd->emitter = -1;
        const struct bounds right = build(b, first + nl, n - nl, at, depth + 1);
        bd = bounds_add(left, &right);
        nd = &b->t->nodes[at];
    }
    node_set(nd, &bd);
    return bd;
}

/* Emitter e of s as a leaf item of the given power. */
static struct item emitter_item(const struct scene *s, int e, float power)
{
    const struct emitter *em = &s->emitters[e];
    const vec3 v1 = v3_add(em->v0, em->e1), v2 = v3_add(em->v0, em->e2);
    struct item it;
    it.lo = v3_min(em->v0, v3_min(v1, v2));
    it.hi = v3_max(em->v0, v3_max(v1, v2));
    it.centroid = v3_scale(v3_add(em->v0, v3_add(v1, v2)), 1.0f / 3.0f);
    it.axis = em->n;
    it.power = power;
    it.emitter = e;
    return it;
}

void scene_light_bvh_build(struct scene *s, const float *power)
{
    struct light_bvh *t = &s->light_bvh;
    memset(t, 0, sizeof *t);
    const int n = s->num_emitters;
    if (n < 1)
        return;
    struct item *items = xmalloc(sizeof(*items) * (size_t)n);
    for (int e = 0; e < n; e++)
        items[e] = emitter_item(s, e, power[e]);
    t->nodes = xmalloc(sizeof(*t->nodes) * (size_t)(2 * n - 1));
    t->emitter_leaf = xmalloc(sizeof(int) * (size_t)n);
    struct builder b = {t, items};
    build(&b, 0, n, -1, 0);
    free(items);
}

void scene_light_bvh_refit(struct scene *s)
{
    struct light_bvh *t = &s->light_bvh;
    if (t->num_nodes < 1)
        return;
    struct bounds *b = xmalloc(sizeof(*b) * (size_t)t->num_nodes);
    for (int i = t->num_nodes - 1; i >= 0; i--) { /* depth-first order: children after their parent */
        struct light_bvh_node *nd = &t->nodes[i];
        if (nd->second < 0) {
            const struct item it = emitter_item(s, nd->emitter, nd->power);
            b[i] = item_bounds(&it);
        } else {
            b[i] = bounds_add(b[i + 1], &b[nd->second]);
        }
        node_set(nd, &b[i]);
    }
    free(b);
}

void scene_light_bvh_free(struct light_bvh *t)
{
    free(t->nodes);
    free(t->emitter_leaf);
    memset(t, 0, sizeof *t);
}
