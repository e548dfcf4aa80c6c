/* restir/cells.c: screen-space reuse cells (004 Sec. 5, Algorithm 1), draws from a cell (uniform and
 * Eq. 17) and the cell search (Sec. 5.1). Must never depend on a ray tracer, files or the renderer. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/cells.h"
#include "restir/neighbors.h"
#include "restir/threads.h"

int restir_cells_init(struct restir_cells *c, int width, int height, int tile)
{
    if (!c)
        return -1;
    memset(c, 0, sizeof(*c));
    if (width < 1 || height < 1 || tile < 1 || tile > RESTIR_CELLS_MAX_TILE)
        return -1;
    /* Pixel, cell and entry indices are ints (w h + tile too), and every array must be addressable. */
    if ((size_t)width > ((size_t)INT_MAX - RESTIR_CELLS_MAX_TILE) / (size_t)height ||
        (size_t)width * (size_t)height > SIZE_MAX / sizeof(struct restir_cells_tap))
        return -1;
    size_t n = (size_t)width * (size_t)height;
    c->width = width;
    c->height = height;
    c->tile = tile;
    c->tiles_x = (width + tile - 1) / tile;
    c->tiles_y = (height + tile - 1) / tile;
    size_t ntiles = (size_t)c->tiles_x * (size_t)c->tiles_y;
    c->tile_base = malloc(sizeof(int) * ntiles);
    c->entry = malloc(sizeof(int) * n);
    c->cell_of = malloc(sizeof(int) * n);
    c->slot_of = malloc(sizeof(int) * n);
    c->count = calloc(n, sizeof(int)); /* 0 at every index that names no cell (cell_ok) */
    c->contributing = calloc(n, sizeof(int));
    c->conf_sum = malloc(sizeof(float) * n);
    c->cdf = malloc(sizeof(double) * n);
    c->conf_cdf = malloc(sizeof(double) * n);
    c->key = malloc(sizeof(uint32_t) * n);
    /* 32-byte records on 32-byte boundaries: a tap never straddles two cache lines */
    c->tap = aligned_alloc(32, sizeof(struct restir_cells_tap) * n);
    if (!c->tile_base || !c->entry || !c->cell_of || !c->slot_of || !c->count || !c->contributing ||
        !c->conf_sum || !c->cdf || !c->conf_cdf || !c->key || !c->tap) {
        restir_cells_fini(c);
        return -1;
    }
    /* Before the first build no pixel is in a cell and no tap is accepted (cell_search). */
    for (size_t i = 0; i < n; i++) {
        c->cell_of[i] = -1;
        c->tap[i] = (struct restir_cells_tap){-1, -1, 0.0f, {0.0f, 0.0f, 0.0f}, {0, 0}};
    }
    /* A tile's entries start after all pixels of the tiles before it (row-major tile order). */
    int base = 0;
    for (int ty = 0; ty < c->tiles_y; ty++) {
        int h = (ty + 1) * tile <= height ? tile : height - ty * tile;
        for (int tx = 0; tx < c->tiles_x; tx++) {
            int w = (tx + 1) * tile <= width ? tile : width - tx * tile;
            c->tile_base[ty * c->tiles_x + tx] = base;
            base += w * h;
        }
    }
    return 0;
}

void restir_cells_fini(struct restir_cells *c)
{
    if (!c)
        return;
    free(c->tile_base);
    free(c->entry);
    free(c->cell_of);
    free(c->slot_of);
    free(c->count);
    free(c->contributing);
    free(c->conf_sum);
    free(c->cdf);
    free(c->conf_cdf);
    free(c->key);
    free(c->tap);
    memset(c, 0, sizeof(*c));
}

/* A weight or confidence that is negative, NaN or infinite counts as 0: one inf would take every
 * other pixel's probability to 0 and make 1 / (N P) overflow. */
static float usable(float v) { return isfinite(v) && v > 0.0f ? v : 0.0f; }

/* Order inside a tile: by key, then contributing before not, then pixel index. */
struct tile_item {
    uint32_t key;
    int contributing;
    int pixel;
};

static int item_before(const struct tile_item *a, const struct tile_item *b)
{
    if (a->key != b->key)
        return a->key < b->key;
    if (a->contributing != b->contributing)
        return a->contributing > b->contributing;
    return a->pixel < b->pixel;
}

/* Algorithm 1 for one tile: the tile's valid pixels sorted by (key, contributing, pixel) into its
 * range of `entry` (insertion sort of at most 256 items; a tile holds a few keys), then one sweep
 * that writes each cell's count, contributing count, confidence sum and prefix sums. */
static int build_tile(struct restir_cells *c, int t, const uint32_t *key, const unsigned char *valid,
                      const float *conf, const float *weight)
{
    struct tile_item items[RESTIR_CELLS_MAX_TILE * RESTIR_CELLS_MAX_TILE];
    int tx = t % c->tiles_x, ty = t / c->tiles_x, n = 0;
    int x0 = tx * c->tile, y0 = ty * c->tile;
    int x1 = x0 + c->tile < c->width ? x0 + c->tile : c->width;
    int y1 = y0 + c->tile < c->height ? y0 + c->tile : c->height;
    for (int y = y0; y < y1; y++) {
        for (int x = x0; x < x1; x++) {
            int i = y * c->width + x;
            c->cell_of[i] = -1;
            c->slot_of[i] = -1;
            if (!valid[i])
                continue;
            struct tile_item it = {key[i], usable(weight[i]) > 0.0f, i};
            int k = n++;
            while (k > 0 && item_before(&it, &items[k - 1])) {
                items[k] = items[k - 1];
                k--;
            }
            items[k] = it;
        }
    }
    int base = c->tile_base[t], cells = 0;
    for (int k = 0; k < n;) {
        int cell = base + k, end = k;
        int contributing = 0;
        float conf_sum = 0.0f;
        double prefix = 0.0, conf_prefix = 0.0;
        while (end < n && items[end].key == items[k].key) {
            int i = items[end].pixel, slot = base + end;
            c->entry[slot] = i;
            c->cell_of[i] = cell;
            c->slot_of[i] = slot;
            conf_sum += usable(conf[i]);
            conf_prefix += (double)usable(conf[i]);
            c->conf_cdf[slot] = conf_prefix;
            if (items[end].contributing) {
                contributing++;
                prefix += (double)usable(weight[i]);
            }
            c->cdf[slot] = prefix;
            c->count[slot] = c->contributing[slot] = 0; /* set below at the cell's own index */
            end++;
        }
        c->count[cell] = end - k;
        c->contributing[cell] = contributing;
        c->conf_sum[cell] = conf_sum <= FLT_MAX ? conf_sum : FLT_MAX; /* a sum past the float range */
        c->key[cell] = items[k].key;
        cells++;
        k = end;
    }
    /* The slots of the tile's pixels in no cell name no cell either. */
    for (int k = n; k < (x1 - x0) * (y1 - y0); k++)
        c->count[base + k] = c->contributing[base + k] = 0;
    return cells;
}

int restir_cells_build(struct restir_cells *c, const uint32_t *key, const unsigned char *valid, const float *conf,
                       const float *weight)
{
    if (!c || !c->tile_base || !key || !valid || !conf || !weight)
        return -1;
    const int ntiles = c->tiles_x * c->tiles_y;
    int cells = 0;
#pragma omp parallel for schedule(static) reduction(+ : cells) num_threads(restir_threads_get())
    for (int t = 0; t < ntiles; t++)
        cells += build_tile(c, t, key, valid, conf, weight);
    c->n_cells = cells;
    return 0;
}

/* 0 when `cell` is outside [0, w h). Inside it, count[cell] (and contributing[cell]) is 0 at
 * every index that is not a cell of the last build (zeroed by init and by every build), so a
 * function that reads count or contributing needs no other test to treat it as an empty cell. */
static inline int cell_in_range(const struct restir_cells *c, int cell)
{
    return c && cell >= 0 && cell < c->width * c->height;
}

/* 1 when `cell` is a cell of the last build. */
static inline int cell_ok(const struct restir_cells *c, int cell)
{
    return cell_in_range(c, cell) && c->count[cell] > 0;
}

static int in_cell(const struct restir_cells *c, int cell, int pixel)
{
    return pixel >= 0 && pixel < c->width * c->height && c->cell_of[pixel] == cell;
}

int restir_cells_others(const struct restir_cells *c, int cell, int exclude)
{
    if (!cell_in_range(c, cell))
        return 0; /* elsewhere count is 0 and no pixel is in the cell when it is not a cell */
    return c->count[cell] - in_cell(c, cell, exclude);
}

float restir_cells_confidence_others(const struct restir_cells *c, int cell, int exclude, const float *conf)
{
    if (!cell_ok(c, cell) || !conf)
        return 0.0f;
    float s = c->conf_sum[cell] - (in_cell(c, cell, exclude) ? usable(conf[exclude]) : 0.0f);
    return s > 0.0f ? s : 0.0f;
}

int restir_cells_pick_uniform(const struct restir_cells *c, int cell, int exclude, float u)
{
    int m = restir_cells_others(c, cell, exclude);
    if (m <= 0)
        return -1;
    /* u * M clamped into [0, M - 1] before the cast (u outside [0,1), NaN reads as 0) */
    const float t = u * (float)m;
    int k = t >= 0.0f ? (t < (float)m ? (int)t : m - 1) : 0;
    /* Skip the excluded pixel's slot: the M others stay equally likely. */
    if (in_cell(c, cell, exclude) && cell + k >= c->slot_of[exclude])
        k++;
    return c->entry[cell + k];
}

/* Draws slot s in [cell, cell + len) with probability (cdf[s] - cdf[s - 1]) / total, the slot of
 * `exclude` cut out, by inverting the inclusive prefix sums of the cell with u: the Eq. 17 ones over
 * its contributing pixels (weighted) or the confidence ones over all its pixels. */
static int pick_from_cdf(const struct restir_cells *c, int weighted, int cell, int exclude, float u, double *prob)
{
    double unused;
    if (!prob)
        prob = &unused;
    *prob = 0.0;
    if (!cell_in_range(c, cell))
        return -1;
    /* the contributing pixels come first in the cell, so the Eq. 17 prefix sums cover them */
    const double *cdf = weighted ? c->cdf : c->conf_cdf;
    const int len = weighted ? c->contributing[cell] : c->count[cell];
    if (len <= 0) /* also when `cell` is not a cell */
        return -1;
    int last = cell + len - 1;
    double total = cdf[last];
    int xs = -1; /* slot of the excluded pixel when it lies in the range */
    double w_x = 0.0;
    if (in_cell(c, cell, exclude) && c->slot_of[exclude] <= last) {
        xs = c->slot_of[exclude];
        w_x = cdf[xs] - (xs > cell ? cdf[xs - 1] : 0.0);
    }
    double others = total - w_x;
    if (!(others > 0.0) || (xs >= 0 && len == 1))
        return -1;
    double t = (double)(u > 0.0f ? u : 0.0f) * others; /* NaN reads as 0 */
    if (xs >= 0 && t >= (xs > cell ? cdf[xs - 1] : 0.0))
        t += w_x; /* skip the excluded interval */
    int lo = cell, hi = last;
    while (lo < hi) {
        int mid = (lo + hi) >> 1; /* lo + hi >= 0 */
        if (cdf[mid] > t)
            hi = mid;
        else
            lo = mid + 1;
    }
    /* Rounding (t on the edge of the cut, or on a step too small for the running sum) can land on
     * the excluded slot or on a zero-width one: take the nearest slot of positive width instead.
     * One exists, since others > 0, so a draw never fails here and the N draws of a merge are
     * always N (004 Appendix B needs E[K(i)] = N P(i)). */
    double w = lo == xs ? 0.0 : cdf[lo] - (lo > cell ? cdf[lo - 1] : 0.0);
    for (int d = 1; !(w > 0.0) && d <= len; d++) {
        for (int sgn = -1; sgn <= 1 && !(w > 0.0); sgn += 2) {
            int s2 = lo + sgn * d;
            if (s2 < cell || s2 > last || s2 == xs)
                continue;
            double ws = cdf[s2] - (s2 > cell ? cdf[s2 - 1] : 0.0);
            if (ws > 0.0) {
                lo = s2;
                w = ws;
            }
        }
    }
    if (!(w > 0.0))
        return -1;
    *prob = w / others;
    return c->entry[lo];
}

int restir_cells_pick_weighted(const struct restir_cells *c, int cell, int exclude, float u, double *prob)
{
    return pick_from_cdf(c, 1, cell, exclude, u, prob);
}

int restir_cells_pick_confidence(const struct restir_cells *c, int cell, int exclude, float u, double *prob)
{
    return pick_from_cdf(c, 0, cell, exclude, u, prob);
}

int restir_cells_pack_taps(struct restir_cells *c, const float *normal, const int *object)
{
    if (!c || !c->tap || !normal || !object)
        return -1;
    const long n = (long)c->width * (long)c->height;
#pragma omp parallel for schedule(static) num_threads(restir_threads_get())
    for (long q = 0; q < n; q++) {
        struct restir_cells_tap *t = &c->tap[q];
        const int cell = c->cell_of[q];
        t->cell = cell;
        t->object = object[q];
        t->conf_sum = cell >= 0 ? c->conf_sum[cell] : 0.0f;
        t->normal[0] = normal[3 * q], t->normal[1] = normal[3 * q + 1], t->normal[2] = normal[3 * q + 2];
        t->pad[0] = t->pad[1] = 0;
    }
    return 0;
}

/* What a tap sees of pixel q: from the packed records when tap is not NULL, else from the arrays. */
static inline struct restir_cells_tap tap_at(const struct restir_cells *c, const struct restir_cells_tap *tap,
                                            const float *normal, const int *object, int q)
{
    if (tap)
        return tap[q];
    struct restir_cells_tap t = {c->cell_of[q], object[q], 0.0f, {normal[3 * (size_t)q], normal[3 * (size_t)q + 1],
                                                                   normal[3 * (size_t)q + 2]}, {0, 0}};
    t.conf_sum = t.cell >= 0 ? c->conf_sum[t.cell] : 0.0f;
    return t;
}

/* The search of restir_cells_search over either data layout (tap_at). */
static inline int cell_search(const struct restir_cells *c, const struct restir_cells_search *s, int pixel,
                              const struct restir_cells_tap *tap, const float *normal, const int *object,
                              const float *u)
{
    if (!s || !u || pixel < 0 || pixel >= c->width * c->height || c->cell_of[pixel] < 0)
        return -1;
    const int compat = s->score == RESTIR_CELLS_SCORE_COMPAT;
    if (compat && (!s->position || !s->depth))
        return -1;
    const int x = pixel % c->width, y = pixel / c->width;
    const struct restir_cells_tap me = tap_at(c, tap, normal, object, pixel);
    struct restir_neighbors_scorer scorer = {{0.0f}, {0.0f}, 0.0f, 0.0f, -1};
    if (compat)
        restir_neighbors_scorer_init(&scorer, s->position + 3 * (size_t)pixel, me.normal, s->depth[pixel], s->omega,
                                  s->beta);
    double w_sum = 0.0;
    int chosen = -1;
    /* The radius stops growing at 1e7 px, far beyond any image, so the tap law is unchanged in
     * practice while lrintf stays defined (growth^steps can overflow a float). */
    const float r_max = 1e7f;
    /* Taps go in chunks: first each tap's pixel (-1 outside the image), prefetching the packed
     * records, then the tests, so the taps' cache misses overlap instead of waiting on each other
     * behind the data-dependent branches of the tests. */
    enum { CHUNK = 16 };
    int qs[CHUNK];
    float radius = fminf(s->radius, r_max);
    for (int t0 = 0; t0 < s->steps; t0 += CHUNK) {
        const int t1 = s->steps - t0 < CHUNK ? s->steps : t0 + CHUNK;
        for (int t = t0; t < t1; t++, radius = fminf(radius * s->growth, r_max)) {
            /* A uniform point in the disk (polar map: r = R sqrt(u), area-uniform). */
            float r = radius * sqrtf(u[3 * t]), phi = 6.28318530717958647f * u[3 * t + 1];
            /* Unsigned sums wrap a negative coordinate past the image, so one test per axis rejects
             * both sides; an offset lrintf cannot represent (u outside [0,1), NaN radius or growth)
             * gives an unspecified value there, still tested, never an undefined sum. */
            const unsigned long qx = (unsigned long)x + (unsigned long)lrintf(r * cosf(phi));
            const unsigned long qy = (unsigned long)y + (unsigned long)lrintf(r * sinf(phi));
            const int outside = qx >= (unsigned long)c->width || qy >= (unsigned long)c->height;
            const int q = outside ? -1 : (int)qy * c->width + (int)qx;
            qs[t - t0] = q;
            if (tap && q >= 0)
                __builtin_prefetch(&tap[q]);
            if (compat && q >= 0)
                __builtin_prefetch(s->position + 3 * (size_t)q);
        }
        for (int t = t0; t < t1; t++) {
            if (qs[t - t0] < 0)
                continue;
            const struct restir_cells_tap q = tap_at(c, tap, normal, object, qs[t - t0]);
            if (q.cell < 0 || q.object != me.object)
                continue;
            if (me.normal[0] * q.normal[0] + me.normal[1] * q.normal[1] + me.normal[2] * q.normal[2] <
                s->normal_min)
                continue;
            double w = q.conf_sum;
            if (compat)
                w *= restir_neighbors_scorer_score(&scorer, s->position + 3 * (size_t)qs[t - t0], q.normal);
            if (!(w > 0.0))
                continue;
            w_sum += w;
            if ((double)u[3 * t + 2] * w_sum < w) /* Chao 1982 streaming WRS */
                chosen = q.cell;
        }
    }
    return chosen >= 0 ? chosen : c->cell_of[pixel];
}

int restir_cells_search(const struct restir_cells *c, const struct restir_cells_search *s, int pixel,
                       const float *normal, const int *object, const float *u)
{
    if (!c || !normal || !object)
        return -1;
    return cell_search(c, s, pixel, NULL, normal, object, u);
}

int restir_cells_search_packed(const struct restir_cells *c, const struct restir_cells_search *s, int pixel,
                              const float *u)
{
    if (!c || !c->tap)
        return -1;
    return cell_search(c, s, pixel, c->tap, NULL, NULL, u);
}
