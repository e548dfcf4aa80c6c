/* spatial_select.c: the neighbor-selection pass (see spatial_select.h; 000 Sec. 3.5, 4.3, 5). */
#include "render/spatial_select.h"

#include "core/lowdisc.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "render/tiles.h"
#include "restir/neighbors.h"
#include "restir/select.h"

static const float *key_of(const struct gbuffer *g, int i) { return &g->select_key[(size_t)i * GBUFFER_KEY]; }

/* Pixel at offset (dx, dy) in the unit disk scaled by the radius; -1 when outside the image or the
 * pixel itself. */
static int disk_pixel(const struct render_params *p, const struct gbuffer *g, int x, int y, float dx, float dy)
{
    int nx = x + (int)lrintf(dx * p->reuse.spatial_radius), ny = y + (int)lrintf(dy * p->reuse.spatial_radius);
    if (nx < 0 || ny < 0 || nx >= g->width || ny >= g->height || (nx == x && ny == y))
        return -1;
    return ny * g->width + nx;
}

/* 000 Eq. 7 on packed keys (position, normal, depth, valid). */
static int bitterli_ok(const struct render_params *p, const float *ki, const float *kj)
{
    return kj[7] != 0.0f &&
           restir_neighbors_bitterli(&ki[3], &kj[3], ki[6], kj[6], p->reuse.spatial_normal, p->reuse.spatial_depth);
}

/* The taps land at random within the radius, so each key read is a cache miss; both selections
 * issue them ahead of the tests that read them (the key load was 60% of this pass in perf). */
static void prefetch_key(const struct gbuffer *g, int j)
{
    /* Clamped rather than branched on: GCC 12 drops a prefetch guarded by j >= 0 here. */
    __builtin_prefetch(key_of(g, j < 0 ? 0 : j));
}

/* A pixel's search, prepared one pixel ahead (see spatial_select_pass): its random stream after
 * the draws that fix where it looks, and those places, whose keys are already being fetched. */
struct pixel_search {
    pcg32 rng;
    int start;                        /* compat: first R2 offset */
    int taps[SPATIAL_MAX_NEIGHBORS];  /* bitterli: the m tries */
};

/* Bitterli et al. 2020: m uniform tries in the disk. Drawing them all before any test keeps the
 * stream's order (the tests draw nothing). */
static void draw_bitterli(const struct render_params *p, const struct gbuffer *g, int x, int y, int m,
                          struct pixel_search *ps)
{
    for (int k = 0; k < m; k++) {
        float dx, dy;
        warp_concentric_disk(pcg32_float(&ps->rng), pcg32_float(&ps->rng), &dx, &dy);
        ps->taps[k] = disk_pixel(p, g, x, y, dx, dy);
        prefetch_key(g, ps->taps[k]);
    }
}

/* ... each kept when 000 Eq. 7 holds. */
static int select_bitterli(const struct render_params *p, const struct gbuffer *g, int x, int y, int m,
                           const struct pixel_search *ps, int *out)
{
    const float *ki = key_of(g, y * g->width + x);
    int n = 0;
    for (int k = 0; k < m; k++)
        if (ps->taps[k] >= 0 && bitterli_ok(p, ki, key_of(g, ps->taps[k])))
            out[n++] = ps->taps[k];
    return n;
}

/* Candidate k of compat's search: the R2 offset start + k of the disk, or -1. */
static int compat_tap(const struct render_params *p, const struct gbuffer *g, int x, int y, const float *offsets,
                      int start, int k)
{
    const float *o = &offsets[2 * ((start + k) % R2_DISK_OFFSETS)];
    return disk_pixel(p, g, x, y, o[0], o[1]);
}

/* How many candidates ahead compat prefetches: enough to cover an L3 miss behind a few scores. */
#define COMPAT_PREFETCH 8

/* 000 Algorithm 1: a random start in the R2 offsets; the first candidates' keys are fetched. */
static void draw_compat(const struct render_params *p, const struct gbuffer *g, int x, int y, const float *offsets,
                        struct pixel_search *ps)
{
    ps->start = (int)(pcg32_next(&ps->rng) % R2_DISK_OFFSETS);
    for (int k = 0; k < p->reuse.spatial_candidates && k < COMPAT_PREFETCH; k++)
        prefetch_key(g, compat_tap(p, g, x, y, offsets, ps->start, k));
}

/* ... with early stopping (Sec. 5); binary uses Eq. 7 as the score (Sec. 7.4). */
static int select_compat(const struct render_params *p, const struct gbuffer *g, int x, int y, int m, int binary,
                         const float *offsets, struct pixel_search *ps, int *out)
{
    const float *ki = key_of(g, y * g->width + x);
    struct restir_neighbors_scorer scorer;
    restir_neighbors_scorer_init(&scorer, ki, &ki[3], ki[6], p->reuse.spatial_omega, p->reuse.spatial_beta);
    struct restir_select sel;
    restir_select_init(&sel, m);
    pcg32 *rng = &ps->rng;
    const int start = ps->start, K = p->reuse.spatial_candidates;
    int good = 0;
    for (int k = 0; k < K; k++) {
        if (k + COMPAT_PREFETCH < K)
            prefetch_key(g, compat_tap(p, g, x, y, offsets, start, k + COMPAT_PREFETCH));
        int j = compat_tap(p, g, x, y, offsets, start, k);
        if (j < 0)
            continue;
        const float *kj = key_of(g, j);
        if (kj[7] == 0.0f)
            continue; /* no primary hit */
        float h = binary ? (bitterli_ok(p, ki, kj) ? 1.0f : 0.0f)
                         : restir_neighbors_scorer_score(&scorer, kj, &kj[3]);
        if (!(h > 0.0f))
            continue;
        restir_select_offer(&sel, j, h, pcg32_float(rng));
        if (p->reuse.spatial_early_stop && h > 0.5f && ++good > m)
            break;
    }
    for (int k = 0; k < sel.count; k++)
        out[k] = sel.item[k];
    return sel.count;
}

/* Pixel i's stream and where it will look (valid pixels only). */
static void prepare_search(const struct render_params *p, const struct gbuffer *g, int frame, int m,
                           const float *offsets, int x, int y, struct pixel_search *ps)
{
    ps->rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)(y * g->width + x), RNG_PASS_SELECT);
    if (p->reuse.spatial_select == SELECT_BITTERLI)
        draw_bitterli(p, g, x, y, m, ps);
    else
        draw_compat(p, g, x, y, offsets, ps);
}

/* Every pixel's search costs a few G-buffer keys at random within the radius. Each pixel's
 * search is prepared while the previous one runs, so those keys arrive in time. */
long long spatial_select_pass(const struct render_params *p, int path_reuse, const struct gbuffer *g, int frame,
                              const float *disk_offsets, int *out)
{
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const int m = render_params_spatial_neighbors(p, path_reuse);
    long long found = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : found)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        const int tw = r.x1 - r.x0, npx = tw * (r.y1 - r.y0);
        struct pixel_search ps[2];
        if (g->valid[r.y0 * w + r.x0])
            prepare_search(p, g, frame, m, disk_offsets, r.x0, r.y0, &ps[0]);
        for (int k = 0; k < npx; k++) {
            const int x = r.x0 + k % tw, y = r.y0 + k / tw, i = y * w + x;
            if (k + 1 < npx) {
                const int nx = r.x0 + (k + 1) % tw, ny = r.y0 + (k + 1) / tw;
                if (g->valid[ny * w + nx])
                    prepare_search(p, g, frame, m, disk_offsets, nx, ny, &ps[(k + 1) & 1]);
            }
            int n = 0, *list = &out[(size_t)i * m];
            if (g->valid[i]) {
                if (p->reuse.spatial_select == SELECT_BITTERLI)
                    n = select_bitterli(p, g, x, y, m, &ps[k & 1], list);
                else
                    n = select_compat(p, g, x, y, m, p->reuse.spatial_select == SELECT_COMPAT_BINARY, disk_offsets,
                                      &ps[k & 1], list);
            }
            found += n;
            for (int q = n; q < m; q++)
                list[q] = -1;
        }
    }
    return found;
}
