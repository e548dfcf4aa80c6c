/* spatial_select.c: the neighbor-selection pass (see spatial_select.h; 000 Sec. 3.5, 4.3, 5). */
#include "spatial_select.h"

#include "core/lowdisc.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "restir/neighbors.h"
#include "tiles.h"

static const float *key_of(const struct gbuffer *g, int i) { return &g->select_key[(size_t)i * GBUFFER_KEY]; }

/* Pixel at offset (dx, dy) in the unit disk scaled by the radius; -1 when outside the image or the
 * pixel itself. */
static int disk_pixel(const struct render_params *p, const struct gbuffer *g, int x, int y, float dx, float dy)
{
    int nx = x + (int)lrintf(dx * p->spatial_radius), ny = y + (int)lrintf(dy * p->spatial_radius);
    if (nx < 0 || ny < 0 || nx >= g->width || ny >= g->height || (nx == x && ny == y))
        return -1;
    return ny * g->width + nx;
}

/* 000 Eq. 7 on packed keys (position, normal, depth, valid). */
static int bitterli_ok(const struct render_params *p, const float *ki, const float *kj)
{
    return kj[7] != 0.0f &&
           restir_bitterli_compatible(&ki[3], &kj[3], ki[6], kj[6], p->spatial_normal, p->spatial_depth);
}

/* Bitterli et al. 2020: m uniform tries, each kept when 000 Eq. 7 holds. */
static int select_bitterli(const struct render_params *p, const struct gbuffer *g, int x, int y, int m,
                           pcg32 *rng, int *out)
{
    const float *ki = key_of(g, y * g->width + x);
    int n = 0;
    for (int k = 0; k < m; k++) {
        float dx, dy;
        warp_concentric_disk(pcg32_float(rng), pcg32_float(rng), &dx, &dy);
        int j = disk_pixel(p, g, x, y, dx, dy);
        if (j >= 0 && bitterli_ok(p, ki, key_of(g, j)))
            out[n++] = j;
    }
    return n;
}

/* 000 Algorithm 1 with early stopping (Sec. 5); binary uses Eq. 7 as the score (Sec. 7.4). */
static int select_compat(const struct render_params *p, const struct gbuffer *g, int x, int y, int m, int binary,
                         const float *offsets, pcg32 *rng, int *out)
{
    const float *ki = key_of(g, y * g->width + x);
    struct restir_select sel;
    restir_select_init(&sel, m);
    int start = (int)(pcg32_next(rng) % R2_DISK_OFFSETS), good = 0;
    for (int k = 0; k < p->spatial_candidates; k++) {
        const float *o = &offsets[2 * ((start + k) % R2_DISK_OFFSETS)];
        int j = disk_pixel(p, g, x, y, o[0], o[1]);
        if (j < 0)
            continue;
        const float *kj = key_of(g, j);
        if (kj[7] == 0.0f)
            continue; /* no primary hit */
        float h = binary ? (bitterli_ok(p, ki, kj) ? 1.0f : 0.0f)
                         : restir_compat_score(ki, &ki[3], ki[6], kj, &kj[3], p->spatial_omega, p->spatial_beta);
        if (!(h > 0.0f))
            continue;
        restir_select_offer(&sel, j, h, pcg32_float(rng));
        if (p->spatial_early_stop && h > 0.5f && ++good > m)
            break;
    }
    for (int k = 0; k < sel.count; k++)
        out[k] = sel.item[k];
    return sel.count;
}

long long spatial_select_pass(const struct render_params *p, int path_reuse, const struct gbuffer *g, int frame,
                              const float *disk_offsets, int *out)
{
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const int m = render_params_spatial_neighbors(p, path_reuse);
    long long found = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : found)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                int i = y * w + x, n = 0;
                int *list = &out[(size_t)i * m];
                if (g->valid[i]) {
                    pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_SELECT);
                    if (p->spatial_select == SELECT_BITTERLI)
                        n = select_bitterli(p, g, x, y, m, &rng, list);
                    else
                        n = select_compat(p, g, x, y, m, p->spatial_select == SELECT_COMPAT_BINARY, disk_offsets,
                                          &rng, list);
                }
                found += n;
                for (int k = n; k < m; k++)
                    list[k] = -1;
            }
        }
    }
    return found;
}
