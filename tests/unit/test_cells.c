/* test_cells.c: unit and chi-square tests of the reuse cells (004 Sec. 5, Algorithm 1, Sec. 5.1).
 * Must never depend on a ray tracer, files, the renderer or anything beyond restir/cells.h. */
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "restir/cells.h"
#include "restir/neighbors.h"
#include "stat/chi2_util.h"
#include "test_util.h"

#define FAMILY_ALPHA 0.01
#define CONTROL_P 1e-6
#define DRAWS 1000000
#define SEARCH_DRAWS 400000
/* Chi-square tests in the family: 5 weighted picks, 2 confidence picks, 4 uniform picks, 3 search laws. */
#define NUM_TESTS 14
#define TWO_PI 6.28318530717958647692

static double alpha_i;

/* ---- 1. PCG hash and cell keys -------------------------------------------------------------- */

/* Bucket of a normal component by the header's rule: floor((n + 1) bins / 2), clamped. */
static int ref_bucket(double n, int bins)
{
    double q = floor((n + 1.0) * bins / 2.0);
    if (q < 0.0)
        return 0;
    return q >= bins ? bins - 1 : (int)q;
}

static void test_hash_and_key(void)
{
    /* Values of the definition (state = v * 747796405 + 2891336453; word = ((state >> ((state >>
     * 28) + 4)) ^ state) * 277803737; (word >> 22) ^ word), worked out independently in 64-bit
     * integer arithmetic modulo 2^32. */
    static const uint32_t in[7] = {0u, 1u, 2u, 42u, 0x12345678u, 0xffffffffu, 0x80000000u};
    static const uint32_t out[7] = {129708002u, 2831084092u, 2055130248u, 1223963391u,
                                    2572358369u, 3861530882u, 566699590u};
    for (int i = 0; i < 7; i++)
        EXPECT(restir_cells_hash(in[i]) == out[i], "pcg_hash(0x%x) = %u, expected %u", (unsigned)in[i],
               (unsigned)restir_cells_hash(in[i]), (unsigned)out[i]);
    /* v = 0 step by step: state = 2891336453 = 0xAC564B05, shift 0xA + 4 = 14,
     * 0xAC564B05 ^ (0xAC564B05 >> 14) = 0xAC54FA5C. */
    {
        uint32_t state = 2891336453u;
        EXPECT(state == 0xAC564B05u && (state >> 28) == 10u, "v = 0 state");
        uint32_t x = (state >> 14) ^ state;
        EXPECT(x == 0xAC54FA5Cu, "v = 0 xorshift 0x%x", (unsigned)x);
        uint32_t word = x * 277803737u;
        EXPECT(((word >> 22) ^ word) == 129708002u, "v = 0 hand evaluation %u", (unsigned)((word >> 22) ^ word));
    }

    /* Same inputs, same key. */
    const float nz[3] = {0.0f, 0.0f, 1.0f};
    const float nz_copy[3] = {0.0f, 0.0f, 1.0f};
    EXPECT(restir_cells_key(5u, 3, nz, 8) == restir_cells_key(5u, 3, nz_copy, 8), "same inputs same key");

    /* Negative components do not wrap: -1 is bucket 0, +1 is bucket bins - 1. */
    const int bins = 8;
    const float nm1[3] = {-1.0f, 0.0f, 0.0f}, np1[3] = {1.0f, 0.0f, 0.0f};
    const float nm099[3] = {-0.99f, 0.0f, 0.0f}, np099[3] = {0.99f, 0.0f, 0.0f};
    const float nm15[3] = {-1.5f, 0.0f, 0.0f}, np15[3] = {1.5f, 0.0f, 0.0f};
    const float nb1[3] = {-0.7f, 0.0f, 0.0f}, nbl[3] = {0.7f, 0.0f, 0.0f}; /* buckets 1 and 6 */
    uint32_t km1 = restir_cells_key(9u, 2, nm1, bins), kp1 = restir_cells_key(9u, 2, np1, bins);
    uint32_t km099 = restir_cells_key(9u, 2, nm099, bins), kp099 = restir_cells_key(9u, 2, np099, bins);
    EXPECT(km1 != kp1, "normals (-1,0,0) and (1,0,0) share a key");
    EXPECT(km099 != kp099, "normals (-0.99,0,0) and (0.99,0,0) share a key");
    EXPECT(km099 != kp1 && km1 != kp099, "(-0.99,0,0) / (-1,0,0) share a key with a +x normal");
    EXPECT(km1 == km099, "-1 and -0.99 are both bucket 0 (bins 8) but got different keys");
    EXPECT(kp1 == kp099, "+1 and 0.99 are both bucket bins-1 (bins 8) but got different keys");
    EXPECT(restir_cells_key(9u, 2, nm15, bins) == km1, "-1.5 must clamp to bucket 0 like -1");
    EXPECT(restir_cells_key(9u, 2, np15, bins) == kp1, "+1.5 must clamp to bucket bins-1 like +1");
    EXPECT(restir_cells_key(9u, 2, nb1, bins) != km1, "-0.7 (bucket 1) shares a key with -1 (bucket 0)");
    EXPECT(restir_cells_key(9u, 2, nbl, bins) != kp1, "0.7 (bucket 6) shares a key with +1 (bucket 7)");

    /* Keys are equal exactly when the bucket triples are equal: values at bucket centres and
     * near (but not on) bucket edges, plus +-1 and out-of-range values, for bins 4 and 8. */
    for (int bi = 0; bi < 2; bi++) {
        const int nb = bi == 0 ? 4 : 8;
        double vals[64];
        int nv = 0;
        for (int b = 0; b < nb; b++) {
            double lo = -1.0 + 2.0 * b / nb, hi = -1.0 + 2.0 * (b + 1) / nb;
            vals[nv++] = lo + 1e-3;
            vals[nv++] = 0.5 * (lo + hi);
            vals[nv++] = hi - 1e-3;
        }
        vals[nv++] = -1.0;
        vals[nv++] = 1.0;
        vals[nv++] = -2.0;
        vals[nv++] = 3.0;
        /* One component varies, the others are fixed; and all three vary together on a subset. */
        int bad = 0, pairs = 0;
        for (int comp = 0; comp < 3; comp++) {
            for (int a = 0; a < nv; a++)
                for (int b = 0; b < nv; b++) {
                    float na[3] = {0.1f, -0.3f, 0.6f}, nbv[3] = {0.1f, -0.3f, 0.6f};
                    na[comp] = (float)vals[a];
                    nbv[comp] = (float)vals[b];
                    int same = ref_bucket(vals[a], nb) == ref_bucket(vals[b], nb);
                    int keq = restir_cells_key(3u, 1, na, nb) == restir_cells_key(3u, 1, nbv, nb);
                    pairs++;
                    if (same != keq) {
                        if (bad < 5)
                            printf("  key/bucket mismatch: bins %d comp %d values %g %g\n", nb, comp, vals[a],
                                   vals[b]);
                        bad++;
                    }
                }
        }
        /* Full triples over bucket centres: nb^3 distinct triples must give nb^3 distinct keys. */
        static uint32_t keys[512];
        int nk = 0;
        for (int b0 = 0; b0 < nb; b0++)
            for (int b1 = 0; b1 < nb; b1++)
                for (int b2 = 0; b2 < nb; b2++) {
                    float n3[3] = {(float)(-1.0 + (2.0 * b0 + 1.0) / nb), (float)(-1.0 + (2.0 * b1 + 1.0) / nb),
                                   (float)(-1.0 + (2.0 * b2 + 1.0) / nb)};
                    keys[nk++] = restir_cells_key(3u, 1, n3, nb);
                }
        int dup = 0;
        for (int i = 0; i < nk; i++)
            for (int j = i + 1; j < nk; j++)
                dup += keys[i] == keys[j];
        EXPECT(bad == 0, "bins %d: %d of %d value pairs disagree with bucket equality", nb, bad, pairs);
        EXPECT(dup == 0, "bins %d: %d equal keys among the %d bucket triples", nb, dup, nk);
    }

    /* Different object or tile gives a different key. */
    static uint32_t ks[64 * 8];
    int nk = 0;
    static const int32_t objs[8] = {0, 1, 2, 3, -1, 7, 1000, -123456};
    for (uint32_t t = 0; t < 64; t++)
        for (int o = 0; o < 8; o++)
            ks[nk++] = restir_cells_key(t, objs[o], nz, 8);
    int dup = 0;
    for (int i = 0; i < nk; i++)
        for (int j = i + 1; j < nk; j++)
            dup += ks[i] == ks[j];
    EXPECT(dup == 0, "%d equal keys among 64 tiles x 8 objects with one normal", dup);
    EXPECT(restir_cells_key(0u, 0, nz, 8) != restir_cells_key(1u, 0, nz, 8), "tile 0 vs 1");
    EXPECT(restir_cells_key(0u, 0, nz, 8) != restir_cells_key(0u, 1, nz, 8), "object 0 vs 1");
    printf("hash/key: %d pcg values, bucket-equivalence for bins 4 and 8, %d tile x object keys distinct\n", 7, nk);
}

/* ---- 2. Construction ------------------------------------------------------------------------ */

struct gbuf {
    int w, h, n;
    uint32_t *key;
    unsigned char *valid;
    float *conf, *weight;
};

static void gbuf_alloc(struct gbuf *g, int w, int h)
{
    g->w = w;
    g->h = h;
    g->n = w * h;
    g->key = calloc((size_t)g->n, sizeof(uint32_t));
    g->valid = calloc((size_t)g->n, 1);
    g->conf = calloc((size_t)g->n, sizeof(float));
    g->weight = calloc((size_t)g->n, sizeof(float));
}

static void gbuf_free(struct gbuf *g)
{
    free(g->key);
    free(g->valid);
    free(g->conf);
    free(g->weight);
}

static int tile_of(int w, int tile, int p)
{
    int tiles_x = (w + tile - 1) / tile;
    return (p / w / tile) * tiles_x + (p % w) / tile;
}

/* Random G-buffer: per tile a few key values drawn from a small global set (so equal keys recur
 * in different tiles), invalid pixels (and one fully invalid tile), confidences with zeros, and
 * Eq. 17 weights that are zero for ~40% of the pixels, spanning six decades otherwise. */
static void gbuf_random(struct gbuf *g, int tile, uint64_t seed, float invalid_frac)
{
    static const uint32_t keyset[7] = {0u, 1u, 7u, 0x80000000u, 0xffffffffu, 12345u, 0xdeadbeefu};
    pcg32 rng = rng_for(seed, 0u, 0u, 0u);
    for (int p = 0; p < g->n; p++) {
        int t = tile_of(g->w, tile, p);
        int r = (int)(pcg32_next(&rng) % 4u);
        if (t % 5 == 0)
            r = 0; /* some tiles hold a single key */
        g->key[p] = keyset[(t * 3 + r) % 7];
        float uv = pcg32_float(&rng);
        g->valid[p] = uv < invalid_frac ? 0 : (unsigned char)(uv < 0.6f ? 1 : (uv < 0.8f ? 2 : 255));
        if (t == 2)
            g->valid[p] = 0;
        g->conf[p] = pcg32_float(&rng) < 0.1f ? 0.0f : 20.0f * pcg32_float(&rng);
        g->weight[p] = pcg32_float(&rng) < 0.4f ? 0.0f : (float)exp(log(1e-3) + log(1e6) * pcg32_float(&rng));
    }
}

/* Brute-force check of a build against its G-buffer; returns the number of failed checks. */
static int check_cells(const struct restir_cells *c, const struct gbuf *g, const char *what)
{
    const int n = g->n, T = c->tile;
    int fails0 = test_failed_count;
    int bad_invalid = 0, bad_valid = 0, bad_entry = 0, bad_tilekey = 0, bad_prefix = 0, bad_order = 0;
    int bad_conf = 0, bad_cdf = 0, bad_cover = 0, bad_share = 0, bad_base = 0, bad_counts = 0, bad_conf_cdf = 0;
    int n_valid = 0;
    char *is_cell = calloc((size_t)n, 1);
    int *cover = calloc((size_t)n, sizeof(int));
    EXPECT(c->width == g->w && c->height == g->h, "%s: sizes", what);
    for (int p = 0; p < n; p++) {
        if (!g->valid[p]) {
            if (c->cell_of[p] != -1 || c->slot_of[p] != -1)
                bad_invalid++;
            continue;
        }
        n_valid++;
        int cell = c->cell_of[p], slot = c->slot_of[p];
        if (cell < 0 || cell >= n || slot < 0 || slot >= n || c->entry[slot] != p || slot < cell ||
            slot >= cell + c->count[cell]) {
            bad_valid++;
            continue;
        }
        is_cell[cell] = 1;
    }
    int n_distinct = 0;
    for (int cell = 0; cell < n; cell++) {
        if (!is_cell[cell])
            continue;
        n_distinct++;
        int cnt = c->count[cell], con = c->contributing[cell];
        if (c->entry[cell] < 0 || c->entry[cell] >= n) {
            bad_counts++;
            continue;
        }
        int t = tile_of(g->w, T, c->entry[cell]);
        if (cnt < 1 || cnt > T * T || con < 0 || con > cnt || cell + cnt > n) {
            bad_counts++;
            continue;
        }
        double conf = 0.0, prefix = 0.0;
        int ncon = 0;
        double conf_prefix = 0.0;
        for (int k = 0; k < cnt; k++) {
            int s = cell + k, p = c->entry[s];
            cover[s]++;
            if (p < 0 || p >= n || !g->valid[p] || c->cell_of[p] != cell || c->slot_of[p] != s) {
                bad_entry++;
                continue;
            }
            if (g->key[p] != c->key[cell] || tile_of(g->w, T, p) != t)
                bad_tilekey++;
            int contributes = g->weight[p] > 0.0f;
            ncon += contributes;
            if (contributes != (k < con))
                bad_prefix++;
            if (k > 0 && k != con && c->entry[s - 1] >= p)
                bad_order++;
            conf += g->conf[p];
            conf_prefix += (double)g->conf[p];
            if (fabs(c->conf_cdf[s] - conf_prefix) > 1e-12 * conf_prefix)
                bad_conf_cdf++;
            if (contributes) {
                prefix += (double)g->weight[p];
                if (fabs(c->cdf[s] - prefix) > 1e-12 * prefix)
                    bad_cdf++;
            }
        }
        if (ncon != con)
            bad_prefix++;
        if (fabs((double)c->conf_sum[cell] - conf) > 1e-5 * conf + 1e-5)
            bad_conf++;
    }
    int covered = 0;
    for (int s = 0; s < n; s++) {
        if (cover[s] > 1)
            bad_cover++;
        covered += cover[s] > 0;
    }
    /* Per tile: brute-force (tile, key) groups; equal key <=> same cell; the tile's cells fill
     * tile_base[t] .. tile_base[t] + (valid pixels of the tile). */
    int groups = 0;
    int ntiles = c->tiles_x * c->tiles_y;
    EXPECT(c->tiles_x == (g->w + T - 1) / T && c->tiles_y == (g->h + T - 1) / T, "%s: tile counts", what);
    int *pix = malloc(sizeof(int) * (size_t)(T * T));
    for (int t = 0; t < ntiles; t++) {
        int tx = t % c->tiles_x, ty = t / c->tiles_x, np = 0;
        for (int y = ty * T; y < (ty + 1) * T && y < g->h; y++)
            for (int x = tx * T; x < (tx + 1) * T && x < g->w; x++)
                if (g->valid[y * g->w + x])
                    pix[np++] = y * g->w + x;
        for (int a = 0; a < np; a++) {
            int first = 1;
            for (int b = 0; b < a; b++)
                if (g->key[pix[b]] == g->key[pix[a]])
                    first = 0;
            groups += first;
            for (int b = 0; b < np; b++)
                if ((g->key[pix[a]] == g->key[pix[b]]) != (c->cell_of[pix[a]] == c->cell_of[pix[b]]))
                    bad_share++;
        }
        if (np > 0) {
            int lo = n, hi = -1;
            for (int a = 0; a < np; a++) {
                int s = c->slot_of[pix[a]];
                lo = s < lo ? s : lo;
                hi = s > hi ? s : hi;
            }
            if (lo != c->tile_base[t] || hi != c->tile_base[t] + np - 1)
                bad_base++;
        }
    }
    free(pix);
    EXPECT(bad_invalid == 0, "%s: %d invalid pixels with cell_of/slot_of != -1", what, bad_invalid);
    EXPECT(bad_valid == 0, "%s: %d valid pixels whose cell_of/slot_of/entry disagree", what, bad_valid);
    EXPECT(bad_counts == 0, "%s: %d cells with impossible count/contributing", what, bad_counts);
    EXPECT(bad_entry == 0, "%s: %d cell entries not pointing back to the cell", what, bad_entry);
    EXPECT(bad_tilekey == 0, "%s: %d entries with another key or tile than their cell", what, bad_tilekey);
    EXPECT(bad_prefix == 0, "%s: %d contributing-prefix violations", what, bad_prefix);
    EXPECT(bad_order == 0, "%s: %d entries out of increasing pixel order in their group", what, bad_order);
    EXPECT(bad_conf == 0, "%s: %d cells with a wrong conf_sum", what, bad_conf);
    EXPECT(bad_cdf == 0, "%s: %d cdf entries that are not the inclusive prefix sums", what, bad_cdf);
    EXPECT(bad_conf_cdf == 0, "%s: %d conf_cdf entries that are not the inclusive confidence prefix sums", what,
           bad_conf_cdf);
    EXPECT(bad_cover == 0, "%s: %d entry slots in more than one cell", what, bad_cover);
    EXPECT(covered == n_valid, "%s: cell ranges cover %d slots, %d valid pixels", what, covered, n_valid);
    EXPECT(bad_share == 0, "%s: %d pixel pairs where equal key in a tile != same cell", what, bad_share);
    EXPECT(bad_base == 0, "%s: %d tiles whose cells do not start at tile_base and fill it", what, bad_base);
    EXPECT(c->n_cells == groups, "%s: n_cells %d, brute-force (tile, key) groups %d", what, c->n_cells, groups);
    EXPECT(n_distinct == groups, "%s: %d distinct cell_of values, %d groups", what, n_distinct, groups);
    free(is_cell);
    free(cover);
    printf("  %s: %d valid of %d pixels, %d cells\n", what, n_valid, n, groups);
    return test_failed_count - fails0;
}

/* Everything a build defines (the cell ranges and per-cell values), for bitwise comparison. */
static int same_build(const struct restir_cells *a, const struct restir_cells *b, const struct gbuf *g)
{
    if (a->n_cells != b->n_cells)
        return 0;
    for (int p = 0; p < g->n; p++) {
        if (a->cell_of[p] != b->cell_of[p] || a->slot_of[p] != b->slot_of[p])
            return 0;
        int cell = a->cell_of[p];
        if (cell < 0)
            continue;
        int s = a->slot_of[p];
        if (a->entry[s] != b->entry[s] || a->count[cell] != b->count[cell] ||
            a->contributing[cell] != b->contributing[cell] ||
            memcmp(&a->conf_sum[cell], &b->conf_sum[cell], sizeof(float)) != 0 || a->key[cell] != b->key[cell])
            return 0;
        if (s - cell < a->contributing[cell] && memcmp(&a->cdf[s], &b->cdf[s], sizeof(double)) != 0)
            return 0;
        if (memcmp(&a->conf_cdf[s], &b->conf_cdf[s], sizeof(double)) != 0)
            return 0;
    }
    return 1;
}

static void test_build(void)
{
    struct restir_cells bad;
    EXPECT(restir_cells_init(&bad, 37, 21, 0) == -1, "tile 0 must be refused");
    EXPECT(restir_cells_init(&bad, 37, 21, 17) == -1, "tile 17 must be refused");
    EXPECT(restir_cells_init(&bad, 0, 21, 8) == -1, "width 0 must be refused");
    EXPECT(restir_cells_init(&bad, 37, -1, 8) == -1, "height -1 must be refused");
    restir_cells_fini(&bad);

    static const int tiles[4] = {8, 5, 16, 1};
    for (int ti = 0; ti < 4; ti++) {
        const int T = tiles[ti];
        struct gbuf g1, g2;
        gbuf_alloc(&g1, 37, 21);
        gbuf_alloc(&g2, 37, 21);
        gbuf_random(&g1, T, 100u + (uint64_t)T, 0.15f);
        gbuf_random(&g2, T, 200u + (uint64_t)T, 0.35f);
        struct restir_cells c, c1;
        EXPECT(restir_cells_init(&c, 37, 21, T) == 0, "init 37x21 tile %d", T);
        EXPECT(restir_cells_init(&c1, 37, 21, T) == 0, "init 37x21 tile %d", T);
        char what[96];

        omp_set_num_threads(2);
        restir_cells_build(&c, g1.key, g1.valid, g1.conf, g1.weight);
        snprintf(what, sizeof what, "tile %2d, data 1, 2 threads", T);
        check_cells(&c, &g1, what);
        omp_set_num_threads(1);
        restir_cells_build(&c1, g1.key, g1.valid, g1.conf, g1.weight);
        EXPECT(same_build(&c, &c1, &g1), "tile %d data 1: 1 and 2 threads build different cells", T);

        /* Rebuild into the same struct with other data: no reallocation, nothing stale. */
        const void *ptrs[10] = {c.tile_base, c.entry, c.cell_of, c.slot_of, c.count,
                                c.contributing, c.conf_sum, c.cdf, c.conf_cdf, c.key};
        omp_set_num_threads(2);
        restir_cells_build(&c, g2.key, g2.valid, g2.conf, g2.weight);
        const void *after[10] = {c.tile_base, c.entry, c.cell_of, c.slot_of, c.count,
                                 c.contributing, c.conf_sum, c.cdf, c.conf_cdf, c.key};
        EXPECT(memcmp(ptrs, after, sizeof ptrs) == 0, "tile %d: build reallocated an array", T);
        snprintf(what, sizeof what, "tile %2d, data 2 rebuilt, 2 threads", T);
        check_cells(&c, &g2, what);
        omp_set_num_threads(1);
        restir_cells_build(&c1, g2.key, g2.valid, g2.conf, g2.weight);
        EXPECT(same_build(&c, &c1, &g2), "tile %d data 2: 1 and 2 threads build different cells", T);
        /* And back to data 1 with 3 threads. */
        omp_set_num_threads(3);
        restir_cells_build(&c, g1.key, g1.valid, g1.conf, g1.weight);
        omp_set_num_threads(1);
        restir_cells_build(&c1, g1.key, g1.valid, g1.conf, g1.weight);
        EXPECT(same_build(&c, &c1, &g1), "tile %d data 1 again: 3 and 1 threads differ", T);

        /* 3. M and c_sigma of a merge, exclude inside, outside the cell, -1. */
        int bad_m = 0, bad_c = 0, checked = 0;
        for (int p = 0; p < g1.n; p++) {
            int cell = c.cell_of[p];
            if (cell < 0)
                continue;
            /* exclude = each member, a pixel of another cell, an invalid pixel, -1 */
            if (restir_cells_others(&c, cell, p) != c.count[cell] - 1)
                bad_m++;
            if (restir_cells_others(&c, cell, -1) != c.count[cell])
                bad_m++;
            double want = (double)c.conf_sum[cell] - g1.conf[p];
            want = want > 0.0 ? want : 0.0;
            double got = restir_cells_confidence_others(&c, cell, p, g1.conf);
            if (fabs(got - want) > 1e-4 * (double)c.conf_sum[cell] + 1e-6)
                bad_c++;
            if (restir_cells_confidence_others(&c, cell, -1, g1.conf) != c.conf_sum[cell])
                bad_c++;
            for (int q = 0; q < g1.n; q++) {
                if (c.cell_of[q] == cell)
                    continue;
                if (restir_cells_others(&c, cell, q) != c.count[cell])
                    bad_m++;
                if (restir_cells_confidence_others(&c, cell, q, g1.conf) != c.conf_sum[cell])
                    bad_c++;
            }
            checked++;
        }
        EXPECT(bad_m == 0, "tile %d: %d wrong restir_cells_others", T, bad_m);
        EXPECT(bad_c == 0, "tile %d: %d wrong restir_cells_confidence_others", T, bad_c);
        printf("  tile %2d: others / confidence_others checked for %d pixels x all excludes\n", T, checked);

        restir_cells_fini(&c);
        restir_cells_fini(&c1);
        EXPECT(c.entry == NULL && c.cell_of == NULL, "fini clears the struct");
        gbuf_free(&g1);
        gbuf_free(&g2);
    }
    omp_set_num_threads(2);
}

/* ---- 4. Draws from a cell ------------------------------------------------------------------- */

/* 16 x 8 pixels, tile 8: tile 1 holds the test cell (key 1000, 20 pixels, 13 contributing with
 * weights over five decades) behind a key-5 cell; tile 0 holds a cell with exactly one
 * contributing pixel (key 77), one with none (key 88) and a single-pixel cell (key 99). */
#define PW 16
#define PH 8
#define NA 20
#define NA_CON 13
static const float wa[NA_CON] = {0.05f, 2.0f, 30.0f, 0.5f, 7.0f, 120.0f, 1.0f, 15.0f, 0.2f, 60.0f, 3.0f, 0.02f, 9.0f};

static void pick_scene(struct gbuf *g, int *a_pix)
{
    gbuf_alloc(g, PW, PH);
    pcg32 rng = rng_for(31u, 0u, 0u, 0u);
    for (int p = 0; p < g->n; p++) {
        g->valid[p] = 1;
        g->key[p] = 5u;
        g->conf[p] = 1.0f + (float)(p % 7);
        g->weight[p] = 0.5f + pcg32_float(&rng);
    }
    /* Tile 1 (x 8..15): every third pixel in raster order of the tile is in the test cell. */
    int na = 0, con = 0;
    for (int y = 0; y < PH; y++)
        for (int x = 8; x < 16; x++) {
            int p = y * PW + x, k = y * 8 + (x - 8);
            if (k % 3 == 1 && na < NA) {
                g->key[p] = 1000u;
                /* contributing and not interleaved in pixel order */
                g->weight[p] = (na % 3 != 2 && con < NA_CON) ? wa[con++] : 0.0f;
                a_pix[na++] = p;
            } else if (k % 11 == 0) {
                g->valid[p] = 0;
            }
        }
    /* Tile 0: key 77 (4 pixels, one contributing), key 88 (3 pixels, none), key 99 (1 pixel). */
    static const int p77[4] = {0, 17, 34, 51}, p88[3] = {3, 36, 52};
    for (int i = 0; i < 4; i++) {
        g->key[p77[i]] = 77u;
        g->weight[p77[i]] = i == 2 ? 4.0f : 0.0f;
        g->conf[p77[i]] = i == 2 ? 3.0f : 0.0f; /* one pixel with confidence > 0 */
    }
    for (int i = 0; i < 3; i++) {
        g->key[p88[i]] = 88u;
        g->weight[p88[i]] = 0.0f;
    }
    g->conf[a_pix[5]] = 0.0f; /* a zero-confidence pixel inside the test cell */
    g->key[5 * PW + 6] = 99u;
}

static void test_picks(void)
{
    struct gbuf g;
    int a_pix[NA];
    pick_scene(&g, a_pix);
    struct restir_cells c;
    EXPECT(restir_cells_init(&c, PW, PH, 8) == 0, "init pick scene");
    restir_cells_build(&c, g.key, g.valid, g.conf, g.weight);
    check_cells(&c, &g, "pick scene");
    const int cell = c.cell_of[a_pix[0]];
    const int con = c.contributing[cell], cnt = c.count[cell];
    EXPECT(cnt == NA && con == NA_CON, "test cell: count %d contributing %d", cnt, con);
    EXPECT(cell > c.tile_base[1], "test cell must not be the first cell of its tile (%d)", cell);

    /* Excludes: contributing pixel in the middle, first, last, a non-contributing one, -1. */
    const int ex[5] = {c.entry[cell + con / 2], c.entry[cell], c.entry[cell + con - 1], c.entry[cell + con + 2], -1};
    static const char *ex_name[5] = {"middle contributing", "first contributing", "last contributing",
                                     "non-contributing", "-1"};
    static double obs_all[5][NA];
    for (int e = 0; e < 5; e++) {
        double count[NA] = {0}, prob[NA], obs[NA], total = 0.0;
        for (int k = 0; k < con; k++)
            if (c.entry[cell + k] != ex[e])
                total += (double)g.weight[c.entry[cell + k]];
        long bad_ret = 0, bad_prob = 0, excluded = 0;
        double max_rel = 0.0;
        pcg32 rng = rng_for(41u, (uint64_t)e, 0u, 0u);
        for (long d = 0; d < DRAWS; d++) {
            double pr = -1.0;
            int q = restir_cells_pick_weighted(&c, cell, ex[e], pcg32_float(&rng), &pr);
            if (q == ex[e] && q >= 0) {
                excluded++;
                continue;
            }
            if (q < 0 || c.cell_of[q] != cell || c.slot_of[q] - cell >= con) {
                bad_ret++;
                continue;
            }
            count[c.slot_of[q] - cell] += 1.0;
            double want = (double)g.weight[q] / total, rel = fabs(pr - want) / want;
            if (rel > max_rel)
                max_rel = rel;
            if (rel > 1e-9)
                bad_prob++;
        }
        EXPECT(excluded == 0, "weighted, exclude %s: excluded pixel returned %ld times", ex_name[e], excluded);
        EXPECT(bad_ret == 0, "weighted, exclude %s: %ld non-contributing / foreign / -1 returns", ex_name[e], bad_ret);
        EXPECT(bad_prob == 0, "weighted, exclude %s: *prob wrong in %ld picks (max rel %.3g)", ex_name[e], bad_prob,
               max_rel);
        int m = 0;
        for (int k = 0; k < con; k++) {
            if (c.entry[cell + k] == ex[e])
                continue;
            prob[m] = (double)g.weight[c.entry[cell + k]] / total;
            obs[m] = count[k];
            m++;
        }
        memcpy(obs_all[e], count, sizeof count);
        int dof;
        double p = chi2_counts(obs, prob, m, DRAWS, &dof);
        printf("weighted pick, exclude %-19s: chi-square over %2d pixels p = %.4f (dof %d, alpha %.3g), max "
               "rel *prob error %.2g\n",
               ex_name[e], m, p, dof, alpha_i, max_rel);
        EXPECT(p >= alpha_i, "weighted pick exclude %s: chi-square p %g < %g", ex_name[e], p, alpha_i);
    }
    /* Power: the exclude = -1 counts are far from uniform. */
    {
        double uni[NA_CON];
        for (int k = 0; k < con; k++)
            uni[k] = 1.0 / con;
        int dof;
        double pc = chi2_counts(obs_all[4], uni, con, DRAWS, &dof);
        printf("  control: weighted counts vs uniform: p = %.3g\n", pc);
        EXPECT(pc < CONTROL_P, "chi-square must reject uniform (p = %g)", pc);
    }

    /* Edge u values and the equivalence of an outside exclude with -1. */
    const float umax = 0x1.fffffep-1f;
    double pr;
    EXPECT(restir_cells_pick_weighted(&c, cell, -1, 0.0f, &pr) == c.entry[cell], "u = 0 picks the first");
    EXPECT(restir_cells_pick_weighted(&c, cell, -1, umax, &pr) == c.entry[cell + con - 1], "u -> 1 picks the last");
    EXPECT(restir_cells_pick_weighted(&c, cell, c.entry[cell], 0.0f, &pr) == c.entry[cell + 1],
           "u = 0 with the first excluded picks the second");
    EXPECT(restir_cells_pick_weighted(&c, cell, c.entry[cell + con - 1], umax, &pr) == c.entry[cell + con - 2],
           "u -> 1 with the last excluded picks the one before");
    {
        const int outside = 10; /* a key-5 pixel of tile 1 with weight > 0 */
        EXPECT(c.cell_of[outside] >= 0 && c.cell_of[outside] != cell && g.weight[outside] > 0.0f, "outside pixel");
        const int invalid_px = 0 * PW + 8 + 0; /* k = 0: k % 11 == 0 -> invalid */
        EXPECT(c.cell_of[invalid_px] == -1, "invalid pixel");
        pcg32 rng = rng_for(42u, 0u, 0u, 0u);
        int diff = 0;
        for (int d = 0; d < 20000; d++) {
            float u = pcg32_float(&rng);
            double p0, p1, p2;
            int a = restir_cells_pick_weighted(&c, cell, -1, u, &p0);
            int b = restir_cells_pick_weighted(&c, cell, outside, u, &p1);
            int b2 = restir_cells_pick_weighted(&c, cell, invalid_px, u, &p2);
            diff += a != b || p0 != p1 || a != b2 || p0 != p2;
            diff += restir_cells_pick_uniform(&c, cell, -1, u) != restir_cells_pick_uniform(&c, cell, outside, u);
            diff += restir_cells_pick_uniform(&c, cell, -1, u) != restir_cells_pick_uniform(&c, cell, invalid_px, u);
        }
        EXPECT(diff == 0, "exclude outside the cell differs from -1 in %d draws", diff);
    }

    /* -1 when the only contributing pixel is excluded, or none contributes. */
    {
        const int c77 = c.cell_of[0], only = 34, c88 = c.cell_of[3], c99 = c.cell_of[5 * PW + 6];
        EXPECT(c.count[c77] == 4 && c.contributing[c77] == 1 && c.entry[c77] == only, "key 77 cell layout");
        EXPECT(c.count[c88] == 3 && c.contributing[c88] == 0, "key 88 cell layout");
        EXPECT(c.count[c99] == 1, "key 99 cell layout");
        static const float us[4] = {0.0f, 0.3f, 0.7f, 0x1.fffffep-1f};
        for (int i = 0; i < 4; i++) {
            pr = 7.0;
            int q = restir_cells_pick_weighted(&c, c77, only, us[i], &pr);
            EXPECT(q == -1 && pr == 0.0, "only contributor excluded: got %d prob %g", q, pr);
            q = restir_cells_pick_weighted(&c, c77, -1, us[i], &pr);
            EXPECT(q == only && pr == 1.0, "only contributor, exclude -1: got %d prob %g", q, pr);
            q = restir_cells_pick_weighted(&c, c77, 17, us[i], &pr);
            EXPECT(q == only && pr == 1.0, "only contributor, non-contributor excluded: got %d prob %g", q, pr);
            for (int x = -1; x < 4; x++) {
                int exv = x < 0 ? -1 : (x == 0 ? 3 : (x == 1 ? 36 : (x == 2 ? 52 : only)));
                pr = 7.0;
                q = restir_cells_pick_weighted(&c, c88, exv, us[i], &pr);
                EXPECT(q == -1 && pr == 0.0, "no contributor (exclude %d): got %d prob %g", exv, q, pr);
            }
            EXPECT(restir_cells_pick_uniform(&c, c99, 5 * PW + 6, us[i]) == -1, "uniform with M = 0 must give -1");
            EXPECT(restir_cells_pick_uniform(&c, c99, -1, us[i]) == 5 * PW + 6, "uniform, single pixel, exclude -1");
            EXPECT(restir_cells_others(&c, c99, 5 * PW + 6) == 0, "M = 0");
            q = restir_cells_pick_uniform(&c, c88, 36, us[i]);
            EXPECT(q == 3 || q == 52, "uniform over a non-contributing cell: got %d", q);
        }
    }

    /* Confidence draws (P = c_i / c_sigma over the others): exclude the middle slot and -1; the
     * zero-confidence pixel is never returned. */
    {
        const int cex[2] = {c.entry[cell + cnt / 2], -1};
        static const char *cex_name[2] = {"middle", "-1"};
        for (int e = 0; e < 2; e++) {
            double count[NA] = {0}, prob[NA], obs[NA], total = 0.0;
            for (int k = 0; k < cnt; k++)
                if (c.entry[cell + k] != cex[e])
                    total += (double)g.conf[c.entry[cell + k]];
            EXPECT_NEAR(total, restir_cells_confidence_others(&c, cell, cex[e], g.conf), 1e-5 * total,
                        "confidence others");
            long bad_ret = 0, bad_prob = 0, excluded = 0, zero = 0;
            pcg32 rng = rng_for(44u, (uint64_t)e, 0u, 0u);
            for (long d = 0; d < DRAWS; d++) {
                double pr = -1.0;
                int q = restir_cells_pick_confidence(&c, cell, cex[e], pcg32_float(&rng), &pr);
                if (q >= 0 && q == cex[e]) {
                    excluded++;
                    continue;
                }
                if (q < 0 || c.cell_of[q] != cell) {
                    bad_ret++;
                    continue;
                }
                zero += g.conf[q] == 0.0f;
                count[c.slot_of[q] - cell] += 1.0;
                double want = (double)g.conf[q] / total;
                if (!(fabs(pr - want) <= 1e-9 * want))
                    bad_prob++;
            }
            int m = 0;
            for (int k = 0; k < cnt; k++) {
                int q = c.entry[cell + k];
                if (q == cex[e] || g.conf[q] == 0.0f)
                    continue;
                prob[m] = (double)g.conf[q] / total;
                obs[m] = count[k];
                m++;
            }
            EXPECT(excluded == 0, "confidence exclude %s: excluded pixel returned %ld times", cex_name[e], excluded);
            EXPECT(bad_ret == 0, "confidence exclude %s: %ld returns outside the cell or -1", cex_name[e], bad_ret);
            EXPECT(zero == 0, "confidence exclude %s: zero-confidence pixel returned %ld times", cex_name[e], zero);
            EXPECT(bad_prob == 0, "confidence exclude %s: *prob wrong in %ld picks", cex_name[e], bad_prob);
            int dof;
            double p = chi2_counts(obs, prob, m, DRAWS, &dof);
            printf("confidence pick, exclude %-6s: chi-square over %2d pixels p = %.4f (dof %d, alpha %.3g)\n",
                   cex_name[e], m, p, dof, alpha_i);
            EXPECT(p >= alpha_i, "confidence pick exclude %s: chi-square p %g < %g", cex_name[e], p, alpha_i);
        }
        const int c77 = c.cell_of[0];
        static const float us[3] = {0.0f, 0.5f, 0x1.fffffep-1f};
        for (int i = 0; i < 3; i++) {
            double pr = 7.0;
            int q = restir_cells_pick_confidence(&c, c77, 34, us[i], &pr);
            EXPECT(q == -1 && pr == 0.0, "confidence: others sum to 0 must give -1 (got %d, prob %g)", q, pr);
            q = restir_cells_pick_confidence(&c, c77, -1, us[i], &pr);
            EXPECT(q == 34 && pr == 1.0, "confidence: single positive pixel (got %d, prob %g)", q, pr);
        }
    }

    /* Uniform draws: exclude middle slot, first slot, last slot (non-contributing), -1. */
    const int uex[4] = {c.entry[cell + cnt / 2], c.entry[cell], c.entry[cell + cnt - 1], -1};
    static const char *uex_name[4] = {"middle", "first slot", "last slot", "-1"};
    for (int e = 0; e < 4; e++) {
        double count[NA] = {0}, prob[NA], obs[NA];
        long bad = 0, excluded = 0;
        pcg32 rng = rng_for(43u, (uint64_t)e, 0u, 0u);
        for (long d = 0; d < DRAWS; d++) {
            int q = restir_cells_pick_uniform(&c, cell, uex[e], pcg32_float(&rng));
            if (q >= 0 && q == uex[e]) {
                excluded++;
                continue;
            }
            if (q < 0 || c.cell_of[q] != cell) {
                bad++;
                continue;
            }
            count[c.slot_of[q] - cell] += 1.0;
        }
        int mo = restir_cells_others(&c, cell, uex[e]), m = 0;
        EXPECT(mo == (uex[e] < 0 ? cnt : cnt - 1), "uniform %s: M = %d", uex_name[e], mo);
        for (int k = 0; k < cnt; k++) {
            if (c.entry[cell + k] == uex[e])
                continue;
            prob[m] = 1.0 / mo;
            obs[m] = count[k];
            m++;
        }
        EXPECT(excluded == 0, "uniform exclude %s: excluded pixel returned %ld times", uex_name[e], excluded);
        EXPECT(bad == 0, "uniform exclude %s: %ld returns outside the cell", uex_name[e], bad);
        int dof;
        double p = chi2_counts(obs, prob, m, DRAWS, &dof);
        printf("uniform pick, exclude %-10s: chi-square over %2d pixels p = %.4f (dof %d, alpha %.3g)\n", uex_name[e],
               m, p, dof, alpha_i);
        EXPECT(p >= alpha_i, "uniform pick exclude %s: chi-square p %g < %g", uex_name[e], p, alpha_i);
    }
    restir_cells_fini(&c);
    gbuf_free(&g);
}

/* ---- 5. Cell search -------------------------------------------------------------------------- */

struct scene {
    int w, h, tile;
    int *object;
    float *normal;
    struct gbuf g;
    struct restir_cells c;
};

static void scene_alloc(struct scene *s, int w, int h, int tile)
{
    s->w = w;
    s->h = h;
    s->tile = tile;
    gbuf_alloc(&s->g, w, h);
    s->object = calloc((size_t)(w * h), sizeof(int));
    s->normal = calloc((size_t)(3 * w * h), sizeof(float));
    for (int p = 0; p < w * h; p++) {
        s->object[p] = 1;
        s->normal[3 * p + 2] = 1.0f;
        s->g.valid[p] = 1;
        s->g.conf[p] = 1.0f;
        s->g.weight[p] = 1.0f;
    }
}

/* Keys from (tile, object, normal), then the cells. */
static void scene_build(struct scene *s)
{
    for (int p = 0; p < s->w * s->h; p++)
        s->g.key[p] = restir_cells_key((uint32_t)tile_of(s->w, s->tile, p), s->object[p], &s->normal[3 * p], 8);
    EXPECT(restir_cells_init(&s->c, s->w, s->h, s->tile) == 0, "scene init");
    restir_cells_build(&s->c, s->g.key, s->g.valid, s->g.conf, s->g.weight);
}

static void scene_free(struct scene *s)
{
    restir_cells_fini(&s->c);
    gbuf_free(&s->g);
    free(s->object);
    free(s->normal);
}

static void random_u(pcg32 *rng, float *u, int steps)
{
    for (int i = 0; i < 3 * steps; i++)
        u[i] = pcg32_float(rng);
}

/* Tap t (radius rt) aimed at the pixel offset (dx, dy): the inverse of the documented polar map. */
static void aim_tap(float *u, int t, float rt, int dx, int dy)
{
    double r = sqrt((double)dx * dx + (double)dy * dy), a = r / rt;
    double phi = atan2((double)dy, (double)dx);
    if (phi < 0.0)
        phi += TWO_PI;
    u[3 * t] = (float)(a * a);
    u[3 * t + 1] = (float)(phi / TWO_PI);
    if (u[3 * t + 1] >= 1.0f)
        u[3 * t + 1] = 0.0f;
}

/* Is tap pixel q (or -1 outside) accepted for `pixel` by the documented rules? */
static int tap_accepted(const struct scene *s, const struct restir_cells_search *sp, int pixel, int q)
{
    if (q < 0 || s->c.cell_of[q] < 0 || s->object[q] != s->object[pixel])
        return 0;
    const float *n = &s->normal[3 * pixel], *m = &s->normal[3 * q];
    return n[0] * m[0] + n[1] * m[1] + n[2] * m[2] >= sp->normal_min;
}

/* The pixels tap t may land on (two per axis where the rounding is within 1e-3 of a tie); -1 for
 * outside the image. Returns the number of candidates written to q[0..4). */
static int tap_pixels(const struct scene *s, int pixel, float rt, const float *u, int t, int *q)
{
    double r = rt * sqrt((double)u[3 * t]), phi = TWO_PI * u[3 * t + 1];
    double fx = pixel % s->w + r * cos(phi), fy = pixel / s->w + r * sin(phi);
    int xs[2], ys[2], nx = 1, ny = 1;
    xs[0] = (int)floor(fx + 0.5);
    ys[0] = (int)floor(fy + 0.5);
    if (fabs(fx - floor(fx) - 0.5) < 1e-3)
        xs[nx++] = xs[0] - 1;
    if (fabs(fy - floor(fy) - 0.5) < 1e-3)
        ys[ny++] = ys[0] - 1;
    int k = 0;
    for (int a = 0; a < nx; a++)
        for (int b = 0; b < ny; b++) {
            int x = xs[a], y = ys[b];
            q[k++] = (x < 0 || y < 0 || x >= s->w || y >= s->h) ? -1 : y * s->w + x;
        }
    return k;
}

static void test_search_fallback(void)
{
    /* (a) 32 x 32, tile 8: pixel (0, 0) is object 1, every other pixel of another object; pixel
     * (16, 16) is object 3 and its same-object pixels (a checkerboard) are in no cell. */
    struct scene s;
    scene_alloc(&s, 32, 32, 8);
    for (int p = 1; p < 32 * 32; p++)
        s.object[p] = 2;
    const int centre = 16 * 32 + 16;
    s.object[centre] = 3;
    for (int y = 0; y < 32; y++)
        for (int x = 0; x < 32; x++)
            if (y * 32 + x != centre && y * 32 + x != 0 && (x + y) % 2 == 0) {
                s.object[y * 32 + x] = 3;
                s.g.valid[y * 32 + x] = 0;
            }
    scene_build(&s);
    struct restir_cells_search sp = {12, 30.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.0f, 0.0f};
    float u[3 * 12];
    pcg32 rng = rng_for(51u, 0u, 0u, 0u);
    int bad_corner = 0, bad_centre = 0;
    for (int d = 0; d < 20000; d++) {
        random_u(&rng, u, 12);
        bad_corner += restir_cells_search(&s.c, &sp, 0, s.normal, s.object, u) != s.c.cell_of[0];
        bad_centre += restir_cells_search(&s.c, &sp, centre, s.normal, s.object, u) != s.c.cell_of[centre];
    }
    EXPECT(s.c.cell_of[0] >= 0 && s.c.cell_of[centre] >= 0, "fallback scene cells");
    EXPECT(bad_corner == 0, "(a) corner pixel with only outside / other-object taps: %d of 20000 not its own cell",
           bad_corner);
    EXPECT(bad_centre == 0, "(a) pixel whose same-object neighbours are in no cell: %d of 20000 not its own cell",
           bad_centre);
    /* A pixel in no cell gives -1. */
    int nocell = 17 * 32 + 17;
    EXPECT(s.c.cell_of[nocell] == -1, "no-cell pixel");
    EXPECT(restir_cells_search(&s.c, &sp, nocell, s.normal, s.object, u) == -1, "pixel in no cell must give -1");
    scene_free(&s);

    /* (b) One object; pixel (20, 20) has normal +z, every other pixel (0.6, 0, 0.8) (dot 0.8). */
    scene_alloc(&s, 40, 40, 8);
    const int p0 = 20 * 40 + 20;
    for (int p = 0; p < 40 * 40; p++)
        if (p != p0) {
            s.normal[3 * p] = 0.6f;
            s.normal[3 * p + 2] = 0.8f;
        }
    scene_build(&s);
    EXPECT(s.c.count[s.c.cell_of[p0]] == 1, "(b) the pixel is alone in its cell");
    /* With normal_min 0.7 or 0.8 (dot == normal_min is not "below") every tap inside the image is
     * accepted, so the own cell comes back exactly when no tap lands in the image off the pixel. */
    int own_rej = 0, bad_acc = 0, bad_edge = 0, none_inside = 0;
    float mins[3] = {0.9f, 0.7f, 0.8f}, rt[12], rad = sp.radius;
    for (int t = 0; t < 12; t++, rad *= sp.growth)
        rt[t] = rad;
    for (int d = 0; d < 20000; d++) {
        random_u(&rng, u, 12);
        int any_other = 0, ambiguous = 0;
        for (int t = 0; t < 12; t++) {
            int q[4], k = tap_pixels(&s, p0, rt[t], u, t, q);
            ambiguous |= k > 1;
            for (int j = 0; j < k; j++)
                any_other |= q[j] >= 0 && q[j] != p0;
        }
        if (ambiguous)
            continue;
        none_inside += !any_other;
        for (int k = 0; k < 3; k++) {
            sp.normal_min = mins[k];
            int own = restir_cells_search(&s.c, &sp, p0, s.normal, s.object, u) == s.c.cell_of[p0];
            if (k == 0)
                own_rej += !own;
            else if (k == 1)
                bad_acc += own == any_other;
            else
                bad_edge += own == any_other;
        }
    }
    printf("search (b): normal_min 0.9 (dot 0.8): %d non-own results; 0.7 and 0.8: %d / %d results disagree "
           "with 'own iff no tap in the image' (%d such u arrays)\n",
           own_rej, bad_acc, bad_edge, none_inside);
    EXPECT(own_rej == 0, "(b) dissimilar normals must be rejected: %d results not the own cell", own_rej);
    EXPECT(bad_acc == 0, "(b) normal_min 0.7: %d results disagree with acceptance of every in-image tap", bad_acc);
    EXPECT(bad_edge == 0, "(b) normal_min == dot must accept: %d results disagree", bad_edge);
    scene_free(&s);
}

/* The 7 taps the law tests (c) and (g) aim from pixel (20, 12) of a 48 x 24 scene, as offsets. */
static const int law_off[7][2] = {{-6, 0}, {7, 2}, {2, -2}, {-9, 3}, {21, -8}, {-17, 8}, {0, 14}};

/* rt[t]: sp's disk radius at tap t (12 taps); u: taps 0..6 aimed at law_off. */
static void aim_law_taps(const struct restir_cells_search *sp, float *rt, float *u)
{
    float r = sp->radius;
    for (int t = 0; t < 12; t++, r *= sp->growth)
        rt[t] = r;
    for (int t = 0; t < 7; t++)
        aim_tap(u, t, rt[t], law_off[t][0], law_off[t][1]);
}

/* SEARCH_DRAWS searches from `pixel` with the taps of u and fresh WRS numbers u[3t+2] (t < 7) from
 * rng: count[k] += 1 for each result ucell[k]; returns the number of results that are none of them. */
static long count_search_results(const struct scene *s, const struct restir_cells_search *sp, int pixel, float *u,
                                 const int *ucell, int nu, pcg32 *rng, double *count)
{
    long other = 0;
    for (long d = 0; d < SEARCH_DRAWS; d++) {
        for (int t = 0; t < 7; t++)
            u[3 * t + 2] = pcg32_float(rng);
        const int res = restir_cells_search(&s->c, sp, pixel, s->normal, s->object, u);
        int k = 0;
        while (k < nu && ucell[k] != res)
            k++;
        if (k == nu)
            other++;
        else
            count[k] += 1.0;
    }
    return other;
}

/* (c) The WRS law for fixed tap positions, and membership for random taps. */
static void test_search_law(void)
{
    /* 48 x 24, tile 8 (6 x 3 tiles), one object and normal except a block of object 2 and a block
     * of dissimilar normals; each tile's confidence per pixel is 1 + (tile % 4). */
    struct scene s;
    scene_alloc(&s, 48, 24, 8);
    for (int p = 0; p < 48 * 24; p++) {
        int x = p % 48, y = p / 48;
        s.g.conf[p] = 1.0f + (float)(tile_of(48, 8, p) % 4);
        if (x >= 40 && y < 8)
            s.object[p] = 2;
        if (x < 8 && y >= 16) {
            s.normal[3 * p] = 1.0f;
            s.normal[3 * p + 2] = 0.0f;
        }
    }
    scene_build(&s);
    const int x0 = 20, y0 = 12, pixel = y0 * 48 + x0; /* tile (2, 1) */
    struct restir_cells_search sp = {7, 10.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.0f, 0.0f};
    /* Taps: 0 -> tile (1,1), 1 -> tile (3,1), 2 -> own tile, 3 -> tile (1,1) again, 4 -> object 2
     * (rejected), 5 -> dissimilar normal (rejected) , 6 -> outside the image (rejected). */
    const int (*off)[2] = law_off;
    float rt[12], u[3 * 12];
    aim_law_taps(&sp, rt, u);
    int cells[7], acc[7];
    for (int t = 0; t < 7; t++) {
        int q[4];
        int k = tap_pixels(&s, pixel, rt[t], u, t, q);
        EXPECT(k == 1, "aimed tap %d is unambiguous", t);
        acc[t] = tap_accepted(&s, &sp, pixel, q[0]);
        cells[t] = acc[t] ? s.c.cell_of[q[0]] : -1;
        EXPECT(q[0] == (off[t][1] + y0 < 0 || off[t][1] + y0 >= 24 ? -1 : (y0 + off[t][1]) * 48 + x0 + off[t][0]),
               "aimed tap %d lands on its target", t);
    }
    EXPECT(acc[0] && acc[1] && acc[2] && acc[3] && !acc[4] && !acc[5] && !acc[6], "aimed taps accepted as planned");
    /* Expected law: each accepted tap's cell with weight conf_sum. */
    int ucell[7], nu = 0;
    double pw[7] = {0}, wtot = 0.0;
    for (int t = 0; t < 7; t++) {
        if (!acc[t])
            continue;
        int k = 0;
        while (k < nu && ucell[k] != cells[t])
            k++;
        if (k == nu)
            ucell[nu++] = cells[t];
        pw[k] += s.c.conf_sum[cells[t]];
        wtot += s.c.conf_sum[cells[t]];
    }
    for (int k = 0; k < nu; k++)
        pw[k] /= wtot;
    for (int law = 0; law < 2; law++) {
        double count[7] = {0};
        pcg32 rng = rng_for(61u, (uint64_t)law, 0u, 0u);
        const long other = count_search_results(&s, &sp, pixel, u, ucell, nu, &rng, count);
        EXPECT(other == 0, "law %d: %ld results outside the accepted taps' cells", law, other);
        int dof;
        double p = chi2_counts(count, pw, nu, SEARCH_DRAWS, &dof);
        printf("search (c) law %d, %d accepted taps over %d cells (expected", law, 4, nu);
        for (int k = 0; k < nu; k++)
            printf(" %.4f/%.4f", pw[k], count[k] / SEARCH_DRAWS);
        printf("): p = %.4f (dof %d, alpha %.3g)\n", p, dof, alpha_i);
        EXPECT(p >= alpha_i, "search law %d chi-square p %g < %g", law, p, alpha_i);
        /* Second law: the same cells reached in another tap order (rejected taps first). */
        static const int perm[7] = {2, 0, 6, 3, 5, 4, 1}; /* |offset| <= tap radius */
        float v[3 * 12];
        for (int t = 0; t < 7; t++)
            aim_tap(v, t, rt[t], off[perm[t]][0], off[perm[t]][1]);
        int ok = 1;
        for (int t = 0; t < 7; t++) {
            int q[4];
            if (tap_pixels(&s, pixel, rt[t], v, t, q) != 1 ||
                tap_accepted(&s, &sp, pixel, q[0]) != acc[perm[t]] ||
                (acc[perm[t]] && s.c.cell_of[q[0]] != cells[perm[t]]))
                ok = 0;
        }
        EXPECT(ok, "permuted taps land as planned");
        if (law == 0) {
            for (int t = 0; t < 7; t++) {
                u[3 * t] = v[3 * t];
                u[3 * t + 1] = v[3 * t + 1];
            }
        }
    }

    /* Membership over fully random u arrays, 12 taps; and steps = 1 exactness. Confidences > 0
     * everywhere, so every accepted tap is a candidate of positive weight. */
    struct restir_cells_search sp12 = {12, 30.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.0f, 0.0f};
    float rt12[12], r = sp12.radius;
    for (int t = 0; t < 12; t++, r *= sp12.growth)
        rt12[t] = r;
    pcg32 rng = rng_for(62u, 0u, 0u, 0u);
    long bad_member = 0, bad_single = 0, own_count = 0, single_acc = 0, tested = 0;
    static const int pixels[4] = {12 * 48 + 20, 0, 23 * 48 + 47, 20 * 48 + 3};
    for (int d = 0; d < 20000; d++) {
        int pix = pixels[d % 4];
        random_u(&rng, u, 12);
        int res = restir_cells_search(&s.c, &sp12, pix, s.normal, s.object, u);
        int maybe_none = 1, member = 0;
        for (int t = 0; t < 12; t++) {
            int q[4], k = tap_pixels(&s, pix, rt12[t], u, t, q), all = 1;
            for (int j = 0; j < k; j++) {
                int a = tap_accepted(&s, &sp12, pix, q[j]);
                all &= a;
                if (a && s.c.cell_of[q[j]] == res)
                    member = 1;
            }
            if (all)
                maybe_none = 0;
        }
        if (res == s.c.cell_of[pix])
            own_count++;
        if (!member && !(maybe_none && res == s.c.cell_of[pix]))
            bad_member++;
        /* steps = 1 */
        struct restir_cells_search one = sp12;
        one.steps = 1;
        int q[4];
        if (tap_pixels(&s, pix, rt12[0], u, 0, q) == 1) {
            tested++;
            int a = tap_accepted(&s, &one, pix, q[0]);
            single_acc += a;
            int want = a ? s.c.cell_of[q[0]] : s.c.cell_of[pix];
            bad_single += restir_cells_search(&s.c, &one, pix, s.normal, s.object, u) != want;
        }
    }
    printf("search (c) random taps: 20000 searches, own cell %ld; steps 1: %ld of %ld taps accepted\n", own_count,
           single_acc, tested);
    EXPECT(bad_member == 0, "(c) %ld results not the cell of any accepted tap (nor the fallback)", bad_member);
    EXPECT(bad_single == 0, "(c) steps = 1: %ld results differ from the tap's cell / own cell", bad_single);

    /* (e) Determinism: same inputs same result; u is not modified; thread count of the build
     * does not matter. */
    struct restir_cells c2;
    EXPECT(restir_cells_init(&c2, 48, 24, 8) == 0, "init c2");
    omp_set_num_threads(1);
    restir_cells_build(&c2, s.g.key, s.g.valid, s.g.conf, s.g.weight);
    omp_set_num_threads(2);
    long nondet = 0, umod = 0;
    for (int d = 0; d < 5000; d++) {
        int pix = (int)(pcg32_next(&rng) % (uint32_t)(48 * 24));
        random_u(&rng, u, 12);
        float ucopy[36];
        memcpy(ucopy, u, sizeof ucopy);
        int a = restir_cells_search(&s.c, &sp12, pix, s.normal, s.object, u);
        umod += memcmp(ucopy, u, sizeof ucopy) != 0;
        int b = restir_cells_search(&s.c, &sp12, pix, s.normal, s.object, ucopy);
        int c = restir_cells_search(&c2, &sp12, pix, s.normal, s.object, u);
        nondet += a != b || a != c;
    }
    EXPECT(nondet == 0, "(e) %ld searches not deterministic in their inputs", nondet);
    EXPECT(umod == 0, "(e) search modified u in %ld calls", umod);
    restir_cells_fini(&c2);
    scene_free(&s);
}

/* (d) The radius grows: 200 x 64, pixel (4, 32) of object 1; everything with x < 100 other than
 * the pixel is object 2, x >= 100 is object 1. */
static void test_search_growth(void)
{
    struct scene s;
    scene_alloc(&s, 200, 64, 8);
    const int pixel = 32 * 200 + 4;
    for (int p = 0; p < 200 * 64; p++)
        if (p % 200 < 100 && p != pixel)
            s.object[p] = 2;
    scene_build(&s);
    struct restir_cells_search grow = {6, 10.0f, 2.0f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.0f, 0.0f},
                              fixed = {6, 10.0f, 1.0f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.0f, 0.0f};
    float u[18];
    pcg32 rng = rng_for(71u, 0u, 0u, 0u);
    long far_grow = 0, far_fixed = 0, too_far = 0;
    const int own = s.c.cell_of[pixel];
    for (int d = 0; d < 20000; d++) {
        random_u(&rng, u, 6);
        int a = restir_cells_search(&s.c, &grow, pixel, s.normal, s.object, u);
        int b = restir_cells_search(&s.c, &fixed, pixel, s.normal, s.object, u);
        if (a != own) {
            far_grow++;
            /* the cell lies in the far region */
            if (a < 0 || s.c.entry[a] % 200 < 100)
                too_far++;
        }
        far_fixed += b != own;
    }
    printf("search (d): growth 2 x 6 taps finds a far cell in %ld / 20000 searches, fixed radius 10 in %ld\n",
           far_grow, far_fixed);
    EXPECT(far_grow > 200, "(d) growing radius reaches the far region only %ld times", far_grow);
    EXPECT(far_fixed == 0, "(d) a fixed radius 10 reached a cell 96+ pixels away %ld times", far_fixed);
    EXPECT(too_far == 0, "(d) %ld far cells not in the far region", too_far);
    scene_free(&s);
}

/* A 77 x 41 scene (tile 8) with a second object on 15% of the pixels, random normals (some below
 * the 0.9 similarity), invalid pixels, zero and positive confidences; built. */
static void random_scene(struct scene *s, pcg32 *rng)
{
    scene_alloc(s, 77, 41, 8);
    for (int p = 0; p < 77 * 41; p++) {
        s->object[p] = pcg32_float(rng) < 0.15f ? 2 : 1;
        float nx = 0.6f * (pcg32_float(rng) - 0.5f), ny = 0.6f * (pcg32_float(rng) - 0.5f), nz = 1.0f;
        float len = sqrtf(nx * nx + ny * ny + nz * nz);
        s->normal[3 * p] = nx / len, s->normal[3 * p + 1] = ny / len, s->normal[3 * p + 2] = nz / len;
        s->g.valid[p] = pcg32_float(rng) < 0.9f;
        s->g.conf[p] = pcg32_float(rng) < 0.2f ? 0.0f : 20.0f * pcg32_float(rng);
    }
    scene_build(s);
}

/* (f) The packed search (restir_cells_pack_taps + restir_cells_search_packed, what the renderer
 * runs) returns exactly the cell of the reference search over the separate arrays, for every
 * pixel of a scene with a second object on 15% of the pixels, random normals (some below the 0.9
 * similarity), invalid pixels, zero and positive confidences, odd size and tiles; on 1 and 2
 * threads of the packing. */
static void test_search_packed(void)
{
    struct scene s;
    pcg32 rng = rng_for(83u, 0u, 0u, 0u);
    random_scene(&s, &rng);
    const struct restir_cells_search sp = {12,   30.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE,
                                          NULL, NULL,  0.0f,  0.0f};
    float u[36];
    long differ = 0, own = 0, searched = 0;
    for (int threads = 1; threads <= 2; threads++) {
        omp_set_num_threads(threads);
        restir_cells_pack_taps(&s.c, s.normal, s.object);
        for (int rep = 0; rep < 4; rep++)
            for (int p = 0; p < 77 * 41; p++) {
                random_u(&rng, u, 12);
                const int a = restir_cells_search(&s.c, &sp, p, s.normal, s.object, u);
                const int b = restir_cells_search_packed(&s.c, &sp, p, u);
                differ += a != b;
                own += a >= 0 && a == s.c.cell_of[p];
                searched += a >= 0;
            }
    }
    printf("search (f): packed vs arrays: %ld of %ld searches differ (%ld kept the own cell)\n", differ, searched, own);
    EXPECT(differ == 0, "(f) the packed search differs in %ld searches", differ);
    EXPECT(own < searched / 2 && own > 0, "(f) the scene does not exercise the search (%ld own of %ld)", own, searched);
    scene_free(&s);
}

/* (g) spmis.search_score=compat: with fixed taps, the WRS law is conf_sum times 000's score of the
 * tapped pixel (Eq. 14-15, positions on a tilted plane, one depth) over the accepted taps; a tap
 * whose score is 0 (normal facing away, still similar enough to pass normal_min -1) is rejected;
 * and the packed search equals the array search for every pixel of a random scene. */
static void test_search_compat(void)
{
    struct scene s;
    scene_alloc(&s, 48, 24, 8);
    float *pos = calloc(3 * 48 * 24, sizeof(float)), *depth = calloc(48 * 24, sizeof(float));
    for (int p = 0; p < 48 * 24; p++) {
        const int x = p % 48, y = p / 48;
        s.g.conf[p] = 1.0f + (float)(tile_of(48, 8, p) % 4);
        pos[3 * p] = 0.1f * (float)x, pos[3 * p + 1] = 0.1f * (float)y, pos[3 * p + 2] = 0.03f * (float)(x + y);
        depth[p] = 10.0f;
        if (x < 8 && y >= 16) { /* facing away: passes normal_min = -1, scores 0 */
            s.normal[3 * p + 2] = -1.0f;
        }
    }
    scene_build(&s);
    const int x0 = 20, y0 = 12, pixel = y0 * 48 + x0;
    struct restir_cells_search sp = {7, 10.0f, 1.25f, -1.0f, RESTIR_CELLS_SCORE_COMPAT, pos, depth, 0.05f, 8.0f};
    /* Taps (law_off): 0 -> tile (1,1), 1 -> tile (3,1), 2 -> own tile, 3 -> tile (1,1) again
     * farther, 4 -> far tile (5,0), 5 -> the facing-away block (score 0), 6 -> outside the image. */
    float rt[12], u[3 * 12];
    aim_law_taps(&sp, rt, u);
    int ucell[7], nu = 0, accepted = 0;
    double pw[7] = {0}, wtot = 0.0;
    for (int t = 0; t < 7; t++) {
        int q[4];
        EXPECT(tap_pixels(&s, pixel, rt[t], u, t, q) == 1, "compat: aimed tap %d is unambiguous", t);
        if (!tap_accepted(&s, &sp, pixel, q[0]))
            continue;
        const double w = s.c.conf_sum[s.c.cell_of[q[0]]] *
                         restir_neighbors_compat(&pos[3 * pixel], &s.normal[3 * pixel], depth[pixel], &pos[3 * q[0]],
                                             &s.normal[3 * q[0]], sp.omega, sp.beta);
        if (!(w > 0.0))
            continue;
        accepted++;
        int k = 0;
        while (k < nu && ucell[k] != s.c.cell_of[q[0]])
            k++;
        if (k == nu)
            ucell[nu++] = s.c.cell_of[q[0]];
        pw[k] += w;
        wtot += w;
    }
    EXPECT(accepted == 5 && nu == 4, "compat: %d taps with a positive weight over %d cells, planned 5 over 4",
           accepted, nu);
    for (int k = 0; k < nu; k++)
        pw[k] /= wtot;
    double count[7] = {0};
    pcg32 rng = rng_for(67u, 0u, 0u, 0u);
    const long other = count_search_results(&s, &sp, pixel, u, ucell, nu, &rng, count);
    EXPECT(other == 0, "compat law: %ld results outside the positive taps' cells", other);
    int dof;
    const double p = chi2_counts(count, pw, nu, SEARCH_DRAWS, &dof);
    printf("search (g) compat law, %d taps over %d cells (expected", accepted, nu);
    for (int k = 0; k < nu; k++)
        printf(" %.4f/%.4f", pw[k], count[k] / SEARCH_DRAWS);
    printf("): p = %.4f (dof %d, alpha %.3g)\n", p, dof, alpha_i);
    EXPECT(p >= alpha_i, "compat search law chi-square p %g < %g", p, alpha_i);
    free(pos), free(depth);
    scene_free(&s);
    /* Packed = arrays under compat, random scene. */
    rng = rng_for(89u, 0u, 0u, 0u);
    random_scene(&s, &rng);
    pos = calloc(3 * 77 * 41, sizeof(float)), depth = calloc(77 * 41, sizeof(float));
    for (int q = 0; q < 77 * 41; q++) {
        pos[3 * q] = 0.05f * (float)(q % 77), pos[3 * q + 1] = 0.05f * (float)(q / 77),
                pos[3 * q + 2] = pcg32_float(&rng);
        depth[q] = 2.0f + 8.0f * pcg32_float(&rng);
    }
    restir_cells_pack_taps(&s.c, s.normal, s.object);
    const struct restir_cells_search cs = {12,  30.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_COMPAT,
                                          pos, depth, 0.05f, 8.0f};
    const struct restir_cells_search conf = {12, 30.0f, 1.25f, 0.9f, RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0, 0};
    long differ = 0, searched = 0, law_differs = 0;
    float uu[36];
    for (int q = 0; q < 77 * 41; q++) {
        random_u(&rng, uu, 12);
        const int a = restir_cells_search(&s.c, &cs, q, s.normal, s.object, uu);
        differ += a != restir_cells_search_packed(&s.c, &cs, q, uu);
        law_differs += a != restir_cells_search(&s.c, &conf, q, s.normal, s.object, uu);
        searched += a >= 0;
    }
    printf("search (g) compat: packed vs arrays: %ld of %ld searches differ; %ld differ from the confidence "
           "search\n",
           differ, searched, law_differs);
    EXPECT(differ == 0, "(g) the packed compat search differs in %ld searches", differ);
    EXPECT(law_differs > searched / 20, "(g) compat scores change only %ld of %ld choices", law_differs, searched);
    free(pos), free(depth);
    scene_free(&s);
}

int main(void)
{
    alpha_i = chi2_sidak(FAMILY_ALPHA, NUM_TESTS);
    test_hash_and_key();
    test_build();
    test_picks();
    test_search_fallback();
    test_search_law();
    test_search_growth();
    test_search_packed();
    test_search_compat();
    return test_finish();
}
