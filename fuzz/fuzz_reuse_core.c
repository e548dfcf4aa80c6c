/* fuzz_reuse_core.c: libFuzzer harness for librestir's public reuse functions with fuzzed sizes and
 * values (NaN, infinities, negatives and denormals included): reservoirs (offer, merge), the
 * k-selection, MIS weights, GRIS resampling, and reuse cells with their picks, searches and SPMIS
 * draws. Each input is a sequence of operations (a byte picks one, the bytes after it are its
 * arguments, raw float bits where a float is read). Beside "no crash, no sanitizer report", each
 * call must keep its header's promises: results in range, no NaN out of any input, -1 only where
 * the header says, and the packed cell search equal to the unpacked one bit for bit. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/cells.h"
#include "restir/gris.h"
#include "restir/mis.h"
#include "restir/reservoir.h"
#include "restir/select.h"
#include "restir/spmis.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The input as a stream; reads past its end give zeros. */
struct bytes {
    const uint8_t *p;
    size_t n, at;
};

static uint8_t take_u8(struct bytes *b) { return b->at < b->n ? b->p[b->at++] : 0; }

static float take_float(struct bytes *b)
{
    uint8_t raw[4];
    for (int k = 0; k < 4; k++)
        raw[k] = take_u8(b);
    float f;
    memcpy(&f, raw, 4);
    return f;
}

/* A small signed integer: [lo, lo + span). */
static int take_int(struct bytes *b, int lo, int span) { return lo + (int)(take_u8(b) % (unsigned)span); }

#define CHECK(cond)                                                                                                    \
    do {                                                                                                               \
        if (!(cond))                                                                                                   \
            abort();                                                                                                   \
    } while (0)

static void fuzz_reservoirs(struct bytes *b)
{
    struct restir_reservoir r[2];
    restir_reservoir_init(&r[0]);
    restir_reservoir_init(&r[1]);
    const int n = take_int(b, 0, 40);
    for (int i = 0; i < n; i++) {
        struct restir_reservoir *x = &r[i & 1];
        const int before = x->offered;
        const float w = take_float(b), u = take_float(b);
        const int won = restir_reservoir_offer(x, w, u);
        CHECK(won == 0 || won == 1);
        CHECK(x->offered == before + 1 && (!won || x->selected == before));
        CHECK(x->selected >= -1 && x->selected < x->offered && !isnan(x->w_sum) && x->w_sum >= 0.0f);
    }
    const int offered = r[0].offered + r[1].offered;
    const int taken = restir_reservoir_merge(&r[0], &r[1], take_float(b));
    CHECK((taken == 0 || taken == 1) && r[0].offered == offered);
    CHECK(r[0].selected >= -1 && r[0].selected < r[0].offered && !isnan(r[0].w_sum));
    CHECK(restir_reservoir_offer(NULL, 1.0f, 0.5f) == 0 && restir_reservoir_merge(NULL, &r[1], 0.5f) == 0);
}

static void fuzz_select(struct bytes *b)
{
    struct restir_select s;
    restir_select_init(&s, take_int(b, -2, 12));
    CHECK(s.m >= 1 && s.m <= RESTIR_SELECT_MAX);
    const int n = take_int(b, 0, 40);
    for (int i = 0; i < n; i++) {
        const float w = take_float(b), u = take_float(b);
        restir_select_offer(&s, i, w, u);
        CHECK(s.count >= 0 && s.count <= s.m);
    }
    for (int k = 0; k < s.count; k++)
        CHECK(s.item[k] >= 0 && s.item[k] < n);
    for (int k = 0; k < s.count && s.m > 1; k++) /* A-ES keeps distinct items */
        for (int j = k + 1; j < s.count; j++)
            CHECK(s.item[k] != s.item[j]);
}

/* MIS weights and GRIS resampling of one merge of n domains (n out of range included). */
static void fuzz_merge(struct bytes *b)
{
    enum { N = RESTIR_GRIS_MAX_SAMPLES + 2 };
    const enum restir_mis mode = (enum restir_mis)take_int(b, -1, 7);
    const int n = take_int(b, -1, N);
    static float c[N], P[N * N], W[N], J[N], u[N], m[N];
    const int k = n > 0 ? n : 1;
    for (int i = 0; i < k; i++) {
        c[i] = take_float(b);
        W[i] = take_float(b);
        J[i] = take_float(b);
        u[i] = take_float(b);
    }
    for (int i = 0; i < k * k; i++) /* the matrix from few bytes: one float, then copies scaled */
        P[i] = i < 8 ? take_float(b) : P[i % 8] * (float)(i % 5);
    const int rc = restir_mis_weights(mode, n, c, P, m);
    CHECK(rc == 0 || rc == -1);
    CHECK(rc == -1 || (n >= 1 && restir_mis_valid(mode)));
    for (int i = 0; rc == 0 && i < n; i++)
        CHECK(isfinite(m[i]) && m[i] >= 0.0f);
    float w_out = -7.0f;
    const int chosen = restir_gris_resample(mode, n, c, P, W, J, u, &w_out);
    CHECK(chosen >= -1 && chosen < (n > 0 ? n : 1));
    if (n >= 1 && n <= RESTIR_GRIS_MAX_SAMPLES && restir_mis_valid(mode))
        CHECK(!isnan(w_out) && w_out >= 0.0f && (chosen >= 0 || w_out == 0.0f));
}

/* Reuse cells of a fuzzed image: build, pack, then picks, searches and SPMIS draws from fuzzed
 * pixels, checked against the cells they name. */
static void fuzz_cells(struct bytes *b)
{
    const int w = take_int(b, -1, 34), h = take_int(b, -1, 26), tile = take_int(b, -1, 19);
    struct restir_cells c;
    if (restir_cells_init(&c, w, h, tile) != 0) {
        CHECK(w <= 0 || h <= 0 || tile < 1 || tile > RESTIR_CELLS_MAX_TILE);
        restir_cells_fini(&c);
        return;
    }
    const size_t n = (size_t)w * (size_t)h;
    uint32_t *key = malloc(n * sizeof *key);
    unsigned char *valid = malloc(n);
    float *conf = malloc(n * sizeof *conf), *weight = malloc(n * sizeof *weight);
    float *normal = malloc(3 * n * sizeof *normal), *position = malloc(3 * n * sizeof *position);
    float *depth = malloc(n * sizeof *depth);
    int *object = malloc(n * sizeof *object);
    const float pattern[8] = {1.0f, 0.0f, 2.5f, -1.0f, NAN, INFINITY, 1e-40f, 3e38f};
    for (size_t i = 0; i < n; i++) { /* two bytes a pixel, repeated: few keys, so cells hold several */
        const uint8_t a = b->p[(2 * i) % b->n], d = b->p[(2 * i + 1) % b->n];
        key[i] = a & 3u;
        valid[i] = (a & 4u) == 0;
        conf[i] = pattern[d & 7u];
        weight[i] = pattern[(d >> 3) & 7u];
        object[i] = (a >> 3) & 1;
        for (int k = 0; k < 3; k++) {
            normal[3 * i + k] = k == 2 ? ((a >> 4) & 1 ? -1.0f : 1.0f) : 0.0f;
            position[3 * i + k] = (float)(i % 7) + (float)k;
        }
        depth[i] = pattern[(a >> 5) & 7u];
    }
    CHECK(restir_cells_build(&c, key, valid, conf, weight) == 0);
    CHECK(restir_cells_pack_taps(&c, normal, object) == 0);
    const int queries = take_int(b, 0, 16);
    for (int q = 0; q < queries; q++) {
        const int pixel = take_int(b, -1, 255) * (int)(n / 200 + 1);
        const int in_image = pixel >= 0 && (size_t)pixel < n;
        const int cell = in_image ? c.cell_of[pixel] : take_int(b, -2, 6);
        const int others = restir_cells_others(&c, cell, pixel);
        CHECK(others >= 0 && (cell >= 0 || others == 0));
        const float cs = restir_cells_confidence_others(&c, cell, pixel, conf);
        CHECK(!isnan(cs) && cs >= 0.0f);
        double prob[2] = {-1.0, -1.0};
        float pick_u[3];
        for (int k = 0; k < 3; k++)
            pick_u[k] = take_float(b);
        const int picked[3] = {restir_cells_pick_uniform(&c, cell, pixel, pick_u[0]),
                               restir_cells_pick_confidence(&c, cell, pixel, pick_u[1], &prob[0]),
                               restir_cells_pick_weighted(&c, cell, pixel, pick_u[2], &prob[1])};
        for (int k = 0; k < 2; k++)
            CHECK(prob[k] >= 0.0 && prob[k] <= 1.0 + 1e-9);
        for (int k = 0; k < 3; k++)
            CHECK(picked[k] == -1 ||
                  (picked[k] >= 0 && (size_t)picked[k] < n && c.cell_of[picked[k]] == cell && picked[k] != pixel));
        /* (one read per statement: the order of a call's or an initializer's operands is unspecified) */
        struct restir_cells_search s = {.position = position, .depth = depth};
        s.steps = take_int(b, -1, 14);
        s.radius = take_float(b);
        s.growth = take_float(b);
        s.normal_min = take_float(b);
        s.omega = take_float(b);
        s.beta = take_float(b);
        s.score = take_u8(b) & 1 ? RESTIR_CELLS_SCORE_COMPAT : RESTIR_CELLS_SCORE_CONFIDENCE;
        float u[3 * 14];
        for (int k = 0; k < 3 * 14; k++)
            u[k] = take_float(b);
        const int found = restir_cells_search(&c, &s, pixel, normal, object, u);
        CHECK(found == restir_cells_search_packed(&c, &s, pixel, u));
        CHECK(found == -1 || (found >= 0 && found < (int)n && c.count[found] > 0));
        CHECK(in_image || found == -1);
        struct restir_spmis_draws d;
        const int draws = take_int(b, -2, 20);
        const enum restir_spmis_pick pick = (enum restir_spmis_pick)take_int(b, 0, 3);
        for (int which = 0; which < 2; which++) {
            const int rc = which == 0 ? restir_spmis_canonical_draws(&c, cell, pixel, draws, pick, u, &d)
                                      : restir_spmis_neighbor_draws(&c, cell, pixel, draws, u, &d);
            CHECK(rc == 0 || (rc == -1 && which == 0 && pick > RESTIR_SPMIS_PICK_CONFIDENCE));
            for (int k = 0; rc == 0 && k < d.count; k++)
                CHECK(d.count <= RESTIR_SPMIS_MAX_DRAWS && d.pixel[k] >= 0 && (size_t)d.pixel[k] < n &&
                      c.cell_of[d.pixel[k]] == cell && d.pixel[k] != pixel && isfinite(d.factor[k]) &&
                      d.factor[k] > 0.0);
        }
    }
    free(key);
    free(valid);
    free(conf);
    free(weight);
    free(normal);
    free(position);
    free(depth);
    free(object);
    restir_cells_fini(&c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    struct bytes b = {data, size, 0};
    for (int op = 0; op < 8 && b.at < b.n; op++) {
        switch (take_u8(&b) % 4) {
        case 0:
            fuzz_reservoirs(&b);
            break;
        case 1:
            fuzz_select(&b);
            break;
        case 2:
            fuzz_merge(&b);
            break;
        default:
            fuzz_cells(&b);
            break;
        }
    }
    return 0;
}
