/* regir.c: ReGIR's per-frame grid of light reservoirs (regir.h): the grid over the shading points,
 * its occupied cells, and the RIS that fills their slots. */
#include "methods/restir_di/regir.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/restir_di/di_sample.h"
#include "render/tiles.h"

/* With di.regir_source=bvh, the share of candidates drawn by power: the BVH's importance is taken
 * at the cell's centre, where a light facing away from the centre but toward another point of the
 * cell can have probability 0; the power share keeps every light of positive power drawable (to
 * the alias table's resolution of one 24-bit uniform, as everywhere lights are drawn by power), so
 * the slots cover p_c's whole support. */
#define REGIR_POWER_SHARE 0.25f

void regir_init(struct regir_grid *r, const struct scene *s, const struct di_settings *ds)
{
    memset(r, 0, sizeof(*r));
    if (ds->regir_source == REGIR_SOURCE_BVH)
        light_cut_order_init(&r->order, &s->light_bvh, s->num_emitters);
    r->slots = ds->regir_slots;
    r->window = ds->light_candidates;
    r->block_cap = ds->regir_grid * ds->regir_grid * ds->regir_grid;
    r->block = xmalloc(sizeof(int) * (size_t)r->block_cap);
}

void regir_fini(struct regir_grid *r)
{
    light_pool_fini(&r->store);
    light_cut_order_fini(&r->order);
    free(r->cuts);
    free(r->block_first);
    free(r->block_slots);
    free(r->block);
    free(r->cells);
    memset(r, 0, sizeof(*r));
}

static int clamp_index(float t, int n)
{
    int i = (int)t; /* t >= 0 up to rounding; a NaN cannot reach here (only valid points are binned) */
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

static int grid_index(const struct regir_grid *r, vec3 p)
{
    const float inv = 1.0f / r->cell;
    const int ix = clamp_index((p.x - r->lo.x) * inv, r->dims[0]);
    const int iy = clamp_index((p.y - r->lo.y) * inv, r->dims[1]);
    const int iz = clamp_index((p.z - r->lo.z) * inv, r->dims[2]);
    return (iz * r->dims[1] + iy) * r->dims[0] + ix;
}

int regir_block_of(const struct regir_grid *r, vec3 p) { return r->block[grid_index(r, p)]; }

void regir_build(struct regir_grid *r, const struct gbuffer *g, const struct di_settings *ds)
{
    const int n = g->width * g->height;
    vec3 lo = v3s(FLT_MAX), hi = v3s(-FLT_MAX);
    r->valid_pixels = 0;
    for (int i = 0; i < n; i++) {
        const struct shading_point *sp = gbuffer_shading(g, i);
        if (!sp->valid)
            continue;
        r->valid_pixels++;
        lo = v3_min(lo, sp->p);
        hi = v3_max(hi, sp->p);
    }
    r->n_blocks = 0;
    r->entries = r->max_entries = 0;
    if (lo.x > hi.x) { /* no valid pixel: no cell */
        r->dims[0] = r->dims[1] = r->dims[2] = 1;
        r->lo = v3s(0.0f);
        r->cell = 1.0f;
        r->block[0] = -1;
        return;
    }
    const vec3 ext = v3_sub(hi, lo);
    const float longest = fmaxf(ext.x, fmaxf(ext.y, ext.z));
    r->cell = longest > 0.0f ? longest / (float)ds->regir_grid : 1.0f;
    r->lo = lo;
    const float e[3] = {ext.x, ext.y, ext.z};
    for (int k = 0; k < 3; k++) {
        const int d = (int)(e[k] / r->cell) + 1;
        r->dims[k] = d < ds->regir_grid ? d : ds->regir_grid;
    }
    const int cells = r->dims[0] * r->dims[1] * r->dims[2];
    for (int c = 0; c < cells; c++)
        r->block[c] = -1;
    for (int i = 0; i < n; i++) {
        const struct shading_point *sp = gbuffer_shading(g, i);
        if (sp->valid)
            r->block[grid_index(r, sp->p)] = 0; /* occupied; numbered below */
    }
    for (int c = 0; c < cells; c++) {
        if (r->block[c] < 0)
            continue;
        if (r->n_blocks == r->cells_cap) {
            r->cells_cap = r->cells_cap ? 2 * r->cells_cap : 256;
            r->cells = xrealloc(r->cells, sizeof(int) * (size_t)r->cells_cap);
            r->block_first = xrealloc(r->block_first, sizeof(int) * (size_t)r->cells_cap);
            r->block_slots = xrealloc(r->block_slots, sizeof(int) * (size_t)r->cells_cap);
            if (r->order.n > 0) /* di.regir_source=bvh: a cut per block */
                r->cuts = xrealloc(r->cuts, sizeof(struct light_cut) * (size_t)r->cells_cap);
        }
        r->cells[r->n_blocks] = c;
        r->block_slots[r->n_blocks] = 0;
        r->block[c] = r->n_blocks++;
    }
    /* slots per block: the windows of its pixels, at most di.regir_slots, at least 1 */
    for (int i = 0; i < n; i++) {
        const struct shading_point *sp = gbuffer_shading(g, i);
        if (sp->valid) {
            int *slots = &r->block_slots[r->block[grid_index(r, sp->p)]];
            *slots = *slots + r->window < r->slots ? *slots + r->window : r->slots;
        }
    }
    int entries = 0;
    for (int b = 0; b < r->n_blocks; b++) {
        r->block_slots[b] = r->block_slots[b] > 0 ? r->block_slots[b] : 1;
        r->block_first[b] = entries;
        entries += r->block_slots[b] + r->window;
    }
    r->entries = entries; /* the store grows to them in regir_fill, which di.initial=auto may skip */
    const long long most_cells = (long long)ds->regir_grid * ds->regir_grid * ds->regir_grid;
    const long long most = (most_cells < n ? most_cells : n) * (long long)(r->slots + r->window);
    r->max_entries = most > entries ? (most < INT_MAX ? (int)most : INT_MAX) : entries;
}

/* The centre of grid cell c. */
static vec3 cell_centre(const struct regir_grid *r, int c)
{
    const int ix = c % r->dims[0], iy = (c / r->dims[0]) % r->dims[1], iz = c / (r->dims[0] * r->dims[1]);
    return v3_add(r->lo, v3_scale(v3((float)ix + 0.5f, (float)iy + 0.5f, (float)iz + 0.5f), r->cell));
}

/* What a cell needs to weigh an emitter: its centre, the radius R of its bounding ball and the
 * half-edge h of its box, widened by a margin for the rounding of the points binned into it. */
struct cell_view {
    vec3 centre;
    float radius, half;
};

static struct cell_view cell_view_of(const struct regir_grid *r, int c)
{
    struct cell_view v;
    v.centre = cell_centre(r, c);
    const float scale = fabsf(v.centre.x) + fabsf(v.centre.y) + fabsf(v.centre.z) + r->cell;
    v.half = 0.5f * r->cell * (1.0f + 1e-3f) + 1e-5f * scale;
    v.radius = v.half * 1.7320508f;
    return v;
}

/* p_c of emitter em times its area (regir.h): lum(Le) min(A / dbar^2, 2 pi); 0 when even the
 * farthest corner of the (widened) cell lies on the emitter's back side, where every point of the
 * cell sees the emitter's back and p_hat is 0. */
static float cell_weight(const struct scene *s, const struct emitter *em, const struct cell_view *v)
{
    const vec3 to_cell = v3_sub(v->centre, em->v0);
    const float reach = v->half * (fabsf(em->n.x) + fabsf(em->n.y) + fabsf(em->n.z));
    if (v3_dot(em->n, to_cell) + reach <= 0.0f)
        return 0.0f;
    const float area = s->tri_area[em->tri];
    const vec3 centroid = v3_add(em->v0, v3_scale(v3_add(em->e1, em->e2), 1.0f / 3.0f));
    const float d = v3_length(v3_sub(v->centre, centroid)), R = v->radius;
    const float k = d + 1.1547f * R, dbar = d + R * R * R / (k * k);
    const float solid = area / (dbar * dbar);
    return v3_luminance(em->Le) * (solid < 6.2831853f ? solid : 6.2831853f);
}

/* The source probability of emitter e for block b, from its power and (bvh) cut probabilities: one
 * expression, so that a slot's q and regir_light_pdf's agree bit for bit. */
static float source_pmf(const struct regir_grid *r, const struct scene *s, enum regir_source src, int b, int e)
{
    const float power = s->emitter_table.pmf[e];
    if (src == REGIR_SOURCE_POWER)
        return power;
    const float cut = light_cut_pmf(&r->cuts[b], &r->order, e);
    return REGIR_POWER_SHARE * power + (1.0f - REGIR_POWER_SHARE) * cut;
}

/* An emitter from block b's source, with its source probability in *pmf; -1 (a null candidate of
 * weight 0) when the cut gives no node any probability, so that every emitter's probability stays
 * exactly source_pmf's. */
static int source_draw(const struct regir_grid *r, const struct scene *s, enum regir_source src, int b, pcg32 *rng,
                       float *pmf)
{
    /* the branch by one uniform, the draw by fresh ones: a remapped uniform would leave the alias
     * table fewer than its 24 bits (a share of 1/4 costs two), and coarser draws than pmf says */
    const float u = pcg32_float(rng);
    int e;
    if (src == REGIR_SOURCE_POWER) {
        e = alias_table_sample(&s->emitter_table, u);
    } else if (u < REGIR_POWER_SHARE) {
        e = alias_table_sample(&s->emitter_table, pcg32_float(rng));
    } else {
        const double u_node = (double)pcg32_next(rng) * 0x1.0p-32; /* 32 bits for the node */
        e = light_cut_sample(&r->cuts[b], &r->order, u_node, pcg32_float(rng));
    }
    *pmf = e >= 0 ? source_pmf(r, s, src, b, e) : 0.0f;
    return e;
}

/* Slot i of a cell: RIS over K source candidates toward p_c (regir.h), or with probability env_prob
 * an environment direction. */
static void fill_slot(const struct regir_grid *r, int b, int i, const struct scene *s, const struct di_settings *ds,
                      const struct cell_view *v, pcg32 *rng)
{
    struct light_pool *st = (struct light_pool *)&r->store; /* the slots of block b: this thread's alone */
    if (s->env && pcg32_float(rng) < s->env_prob) {
        const float u1 = pcg32_float(rng), u2 = pcg32_float(rng);
        light_pool_put_env(st, s, i, u1, u2);
        st->W[i] = st->pdf[i] > 0.0f ? 1.0f / st->pdf[i] : 0.0f;
        return;
    }
    const int K = ds->regir_candidates;
    float w_sum = 0.0f, chosen_weight = 0.0f, chosen_pmf = 0.0f;
    int chosen = -1;
    for (int j = 0; j < K; j++) {
        float pmf;
        const int e = source_draw(r, s, ds->regir_source, b, rng, &pmf);
        const float cw = e >= 0 && pmf > 0.0f ? cell_weight(s, &s->emitters[e], v) : 0.0f;
        const float w = cw > 0.0f ? cw / pmf : 0.0f; /* pmf > 0 here; cw <= lum(Le) 2 pi */
        w_sum += w;
        if (w > 0.0f && pcg32_float(rng) * w_sum < w)
            chosen = e, chosen_weight = cw, chosen_pmf = pmf;
    }
    if (chosen < 0) { /* an empty reservoir: W = 0, which no pixel can select */
        light_pool_put_empty(st, i, v->centre);
        st->W[i] = 0.0f;
        return;
    }
    float b1, b2;
    warp_uniform_triangle(pcg32_float(rng), pcg32_float(rng), &b1, &b2);
    const struct emitter *em = &s->emitters[chosen];
    light_pool_put_emitter(st, s, i, em, b1, b2);
    const float area = s->tri_area[em->tri], share = 1.0f - s->env_prob;
    /* W = (1/K sum_j w_j) / p_c(y) with p_c(y) = cell_weight / A; divided by the emitters' share */
    st->W[i] = (w_sum / (float)K) * area / (chosen_weight * share);
    st->pdf[i] = share * chosen_pmf / area; /* q: the source density in area measure */
}

void regir_fill(struct regir_grid *r, const struct scene *s, const struct di_settings *ds, uint64_t seed, int frame)
{
    if (s->num_emitters < 1) /* refused by the method's check; nothing to sample */
        return;
    const uint64_t stream = rng_stream_id(REGIR_STREAM);
    struct light_pool *st = &r->store;
    light_pool_reserve(st, r->entries, r->max_entries, 1);
    st->window = r->window;
#pragma omp parallel for schedule(static)
    for (int b = 0; b < r->n_blocks; b++) {
        pcg32 rng = rng_for(seed, (uint64_t)frame, (uint64_t)b, stream);
        const struct cell_view v = cell_view_of(r, r->cells[b]);
        if (ds->regir_source == REGIR_SOURCE_BVH)
            light_cut_build(&r->cuts[b], &s->light_bvh, &r->order, v.centre);
        const int first = r->block_first[b], slots = r->block_slots[b];
        for (int k = 0; k < slots; k++)
            fill_slot(r, b, first + k, s, ds, &v, &rng);
        /* the tail repeats the head (slot k mod slots), so a window that starts late reads on */
        for (int k = slots; k < slots + r->window; k++) {
            const int from = first + k % slots, to = first + k;
            st->tri[to] = st->tri[from];
            float *f[] = {st->b1, st->b2, st->px, st->py, st->pz, st->nx, st->ny, st->nz,
                          st->Lr, st->Lg, st->Lb, st->pdf, st->at_point, st->W};
            for (size_t a = 0; a < sizeof(f) / sizeof(f[0]); a++)
                f[a][to] = f[a][from];
        }
    }
}

double regir_fill_share(const struct regir_grid *r, const struct di_settings *ds)
{
    double slots = 0.0;
    for (int b = 0; b < r->n_blocks; b++)
        slots += r->block_slots[b];
    const double own = (double)r->valid_pixels * ds->light_candidates;
    return own > 0.0 ? slots * ds->regir_candidates / own : 0.0;
}

float regir_light_pdf(const struct regir_grid *r, const struct scene *s, const struct di_settings *ds, int b, int tri)
{
    const int e = tri >= 0 && tri < s->num_tris ? s->tri_emitter[tri] : -1;
    if (e < 0 || b < 0)
        return 0.0f;
    return (1.0f - s->env_prob) * source_pmf(r, s, ds->regir_source, b, e) / s->tri_area[tri];
}

float regir_cell_weight(const struct regir_grid *r, const struct scene *s, int b, int e)
{
    const struct cell_view v = cell_view_of(r, r->cells[b]);
    return cell_weight(s, &s->emitters[e], &v);
}
