/* test_api_contract.c: the bad-argument contract of every public function of librestir, from its
 * public headers alone: NULL pointers, zero and negative sizes, sizes whose products overflow,
 * out-of-range indices, and NaN, infinite and negative weights, confidences and targets. Each check
 * compares a call with what its header documents (a return code, an output left untouched or
 * zeroed, a value read as 0), and every call runs with stdout and stderr redirected to a file that
 * must stay empty: the library never prints, and a function that aborted would end the test.
 * Prints one summary line; exits 1 naming every failed check. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "restir/cells.h"
#include "restir/grad.h"
#include "restir/gris.h"
#include "restir/hd.h"
#include "restir/metrics.h"
#include "restir/mis.h"
#include "restir/neighbors.h"
#include "restir/poisson.h"
#include "restir/select.h"
#include "restir/spmis.h"
#include "restir/threads.h"
#include "restir/reservoir.h"

/* Failures are collected while stdout and stderr point at the capture file, printed afterwards. */
static int checks, failed;
static char failures[16384];

static void check_at(int ok, int line, const char *what)
{
    checks++;
    if (ok)
        return;
    failed++;
    size_t used = strlen(failures);
    if (used + 160 < sizeof failures)
        snprintf(failures + used, sizeof failures - used, "  line %d: %.120s\n", line, what);
}
#define CHECK(cond) check_at((cond) != 0, __LINE__, #cond)

static const float NaN = NAN, INF = INFINITY;

/* A float array holding `v` everywhere: the "untouched" outputs are compared against it. */
static void fill(float *a, size_t n, float v)
{
    for (size_t i = 0; i < n; i++)
        a[i] = v;
}
static int all_equal(const float *a, size_t n, float v)
{
    for (size_t i = 0; i < n; i++)
        if (memcmp(&a[i], &v, sizeof v) != 0)
            return 0;
    return 1;
}
static int all_finite(const float *a, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* ---- restir/hd.h, restir/reservoir.h, restir/select.h ------------------------------------------------ */

static void test_hd_wrs_select(void)
{
    CHECK(restir_hd_finite(1.0f) == 1 && restir_hd_finite(-FLT_MAX) == 1);
    CHECK(restir_hd_finite(NaN) == 0 && restir_hd_finite(INF) == 0 && restir_hd_finite(-INF) == 0);
    CHECK(restir_hd_weight(2.5f) == 2.5f);
    CHECK(restir_hd_weight(NaN) == 0.0f && restir_hd_weight(INF) == 0.0f && restir_hd_weight(-1.0f) == 0.0f);

    restir_reservoir_init(NULL);
    CHECK(restir_reservoir_offer(NULL, 1.0f, 0.0f) == 0);
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    CHECK(r.w_sum == 0.0f && r.selected == -1 && r.offered == 0);
    const float bad_w[4] = {NaN, INF, -INF, -1.0f};
    for (int k = 0; k < 4; k++)
        CHECK(restir_reservoir_offer(&r, bad_w[k], 0.0f) == 0);
    CHECK(restir_reservoir_offer(&r, 0.0f, 0.0f) == 0);
    CHECK(r.offered == 5 && r.w_sum == 0.0f && r.selected == -1);
    CHECK(restir_reservoir_offer(&r, 2.0f, NaN) == 0 && r.selected == -1 && r.w_sum == 2.0f); /* NaN u selects nothing */
    CHECK(restir_reservoir_offer(&r, 2.0f, 0.0f) == 1 && r.selected == 6 && r.w_sum == 4.0f);

    struct restir_reservoir a, b;
    restir_reservoir_init(&a);
    restir_reservoir_init(&b);
    CHECK(restir_reservoir_offer(&a, 1.0f, 0.0f) == 1);
    CHECK(restir_reservoir_merge(NULL, &b, 0.0f) == 0);
    CHECK(restir_reservoir_merge(&a, NULL, 0.0f) == 0 && a.offered == 1 && a.w_sum == 1.0f && a.selected == 0);
    b.offered = 3, b.selected = 1;
    const float bad_sum[4] = {NaN, INF, -2.0f, 0.0f};
    for (int k = 0; k < 4; k++) {
        b.w_sum = bad_sum[k];
        const int before = a.offered;
        CHECK(restir_reservoir_merge(&a, &b, 0.0f) == 0 && a.offered == before + 3 && a.w_sum == 1.0f && a.selected == 0);
    }
    b.w_sum = 5.0f, b.selected = -1; /* no selection: never taken */
    CHECK(restir_reservoir_merge(&a, &b, 0.0f) == 0 && a.selected == 0 && a.w_sum == 1.0f);

    restir_select_init(NULL, 3);
    restir_select_offer(NULL, 0, 1.0f, 0.5f);
    struct restir_select s;
    restir_select_init(&s, 0);
    CHECK(s.m == 1 && s.count == 0);
    restir_select_init(&s, -7);
    CHECK(s.m == 1);
    restir_select_init(&s, 1000);
    CHECK(s.m == RESTIR_SELECT_MAX && s.count == 0);
    for (int k = 0; k < 4; k++)
        restir_select_offer(&s, k, bad_w[k], 0.5f);
    restir_select_offer(&s, 9, 0.0f, 0.5f);
    CHECK(s.count == 0);
    restir_select_init(&s, 1);
    for (int k = 0; k < 4; k++)
        restir_select_offer(&s, k, bad_w[k], 0.0f);
    CHECK(s.count == 0 && s.key[0] == 0.0f);
    restir_select_offer(&s, 5, 1.0f, 0.0f);
    CHECK(s.count == 1 && s.item[0] == 5);
}

/* ---- restir/mis.h, restir/gris.h ------------------------------------------------------------- */

/* Shift callbacks for restir_gris_targets: a sample is one float; every shift succeeds with
 * Jacobian 1 and the target is the sample's value. */
static int toy_shift(void *ctx, const void *x, int from, int to, void *y, float *jacobian)
{
    (void)ctx, (void)from, (void)to;
    memcpy(y, x, sizeof(float));
    *jacobian = 1.0f;
    return 1;
}
static float toy_target(void *ctx, const void *y, int domain)
{
    (void)ctx, (void)domain;
    float v;
    memcpy(&v, y, sizeof v);
    return v;
}

static void test_mis_gris(void)
{
    enum restir_mis mode = RESTIR_MIS_BALANCE;
    CHECK(restir_mis_parse(NULL, &mode) == -1 && mode == RESTIR_MIS_BALANCE);
    CHECK(restir_mis_parse("pairwise", NULL) == -1);
    CHECK(restir_mis_parse("", &mode) == -1 && restir_mis_parse("Pairwise", &mode) == -1 && mode == RESTIR_MIS_BALANCE);
    CHECK(restir_mis_parse("1/M", &mode) == 0 && mode == RESTIR_MIS_UNIFORM);
    CHECK(strcmp(restir_mis_name((enum restir_mis)77), "unknown") == 0);
    CHECK(strcmp(restir_mis_name((enum restir_mis)-1), "unknown") == 0);
    CHECK(strcmp(restir_mis_name(RESTIR_MIS_PAIRWISE), "pairwise") == 0);
    CHECK(restir_mis_valid(RESTIR_MIS_PAIRWISE_TILED) && !restir_mis_valid((enum restir_mis)17));
    CHECK(restir_mis_needs(RESTIR_MIS_BALANCE, -1, 0) == 0 && restir_mis_needs(RESTIR_MIS_BALANCE, 0, -3) == 0);
    CHECK(restir_mis_needs((enum restir_mis)77, 1, 1) == 0);

    /* Bad confidences and targets read as 0. */
    const float c_bad[4] = {NaN, 1.0f, -1.0f, INF};
    float m[4];
    restir_mis_weights_uniform(4, c_bad, m);
    CHECK(m[0] == 0.0f && m[1] == 1.0f && m[2] == 0.0f && m[3] == 0.0f);
    const float c_none[3] = {NaN, -1.0f, 0.0f};
    restir_mis_weights_uniform(3, c_none, m);
    CHECK(fabsf(m[0] - 1.0f / 3.0f) < 1e-7f && m[1] == m[0] && m[2] == m[0]);
    /* balance, 2 domains: p row-major, p[k * 2 + j]; NaN targets of domain 1 read as 0 */
    const float c2[2] = {1.0f, 1.0f}, p_bad[4] = {1.0f, 1.0f, NaN, INF};
    restir_mis_weights_balance(2, c2, p_bad, m);
    CHECK(m[0] == 1.0f && m[1] == 0.0f);
    const float c2_bad[2] = {-INF, NaN}, p_ok[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    restir_mis_weights_pairwise(2, c2_bad, p_ok, m);
    CHECK(m[0] == 1.0f && m[1] == 0.0f);
    /* tiled: bad confidences leave everything to the canonical; NULL arrays write nothing */
    restir_mis_weights_pairwise_tiled(2, c2_bad, p_ok, m);
    CHECK(m[0] == 1.0f && m[1] == 0.0f);
    m[0] = 5.0f;
    restir_mis_weights_pairwise_tiled(2, NULL, p_ok, m);
    restir_mis_weights_pairwise_tiled(0, c2, p_ok, m);
    CHECK(m[0] == 5.0f);
    restir_mis_weights_pairwise(2, c2, p_bad, m);
    CHECK(isfinite(m[0]) && m[1] == 0.0f);
    fill(m, 4, 7.0f);
    CHECK(restir_mis_weights(RESTIR_MIS_BALANCE, 0, c2, p_ok, m) == -1 && all_equal(m, 4, 7.0f));
    CHECK(restir_mis_weights(RESTIR_MIS_BALANCE, -3, c2, p_ok, m) == -1 && all_equal(m, 4, 7.0f));
    CHECK(restir_mis_weights(RESTIR_MIS_BALANCE, 2, NULL, p_ok, m) == -1 && all_equal(m, 4, 7.0f));
    CHECK(restir_mis_weights(RESTIR_MIS_PAIRWISE, 2, c2, NULL, m) == -1 && all_equal(m, 4, 7.0f));
    CHECK(restir_mis_weights(RESTIR_MIS_BALANCE, 2, c2, p_ok, NULL) == -1);
    CHECK(restir_mis_weights((enum restir_mis)77, 2, c2, p_ok, m) == -1 && all_equal(m, 4, 7.0f));
    CHECK(restir_mis_weights(RESTIR_MIS_UNIFORM, 2, c2, NULL, m) == 0 && m[0] == 0.5f && m[1] == 0.5f);

    CHECK(restir_gris_resampling_weight(1.0f, 2.0f, 3.0f, 4.0f) == 24.0f);
    CHECK(restir_gris_resampling_weight(1.0f, 1.0f, 1.0f, 0.0f) == 0.0f);
    CHECK(restir_gris_resampling_weight(1.0f, 1.0f, 1.0f, -1.0f) == 0.0f);
    CHECK(restir_gris_resampling_weight(1.0f, 1.0f, 1.0f, NaN) == 0.0f);
    CHECK(restir_gris_resampling_weight(NaN, 1.0f, 1.0f, 1.0f) == 0.0f);
    CHECK(restir_gris_resampling_weight(1.0f, INF, 1.0f, 1.0f) == 0.0f);
    CHECK(restir_gris_resampling_weight(1.0f, 1.0f, -2.0f, 1.0f) == 0.0f);
    CHECK(restir_gris_resampling_weight(FLT_MAX, FLT_MAX, 1.0f, 1.0f) == 0.0f); /* product overflows */
    struct restir_reservoir wr = {4.0f, 0, 1}, none = {4.0f, -1, 1};
    CHECK(restir_gris_contribution_weight(&wr, 2.0f) == 2.0f);
    CHECK(restir_gris_contribution_weight(NULL, 2.0f) == 0.0f);
    CHECK(restir_gris_contribution_weight(&none, 2.0f) == 0.0f);
    CHECK(restir_gris_contribution_weight(&wr, 0.0f) == 0.0f && restir_gris_contribution_weight(&wr, -1.0f) == 0.0f);
    CHECK(restir_gris_contribution_weight(&wr, NaN) == 0.0f && restir_gris_contribution_weight(&wr, INF) == 0.0f);
    CHECK(restir_gris_confidence_merge(NaN, 10.0f) == 0.0f && restir_gris_confidence_merge(-1.0f, 10.0f) == 0.0f);
    CHECK(restir_gris_confidence_merge(5.0f, 3.0f) == 3.0f && restir_gris_confidence_merge(5.0f, 0.0f) == 5.0f);
    CHECK(restir_gris_confidence_merge(5.0f, -1.0f) == 5.0f && restir_gris_confidence_merge(INF, 3.0f) == 3.0f);

    const float P2[4] = {1.0f, 1.0f, 1.0f, 1.0f}, W2[2] = {1.0f, 1.0f}, J2[2] = {1.0f, 1.0f}, u2[2] = {0.5f, 0.5f};
    float W_out = 7.0f;
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, 2, c2, P2, W2, J2, u2, NULL) == -1);
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, 0, c2, P2, W2, J2, u2, &W_out) == -1);
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, RESTIR_GRIS_MAX_SAMPLES + 1, c2, P2, W2, J2, u2, &W_out) == -1);
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, 2, c2, P2, NULL, J2, u2, &W_out) == -1);
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, 2, c2, P2, W2, J2, NULL, &W_out) == -1);
    CHECK(restir_gris_resample((enum restir_mis)77, 2, c2, P2, W2, J2, u2, &W_out) == -1);
    const float P_nan[4] = {NaN, NaN, NaN, NaN}, W_bad[2] = {INF, -1.0f};
    W_out = 7.0f;
    CHECK(restir_gris_resample(RESTIR_MIS_BALANCE, 2, c2, P_nan, W2, J2, u2, &W_out) == -1 && W_out == 0.0f);
    W_out = 7.0f;
    CHECK(restir_gris_resample(RESTIR_MIS_PAIRWISE, 2, c2, P2, W_bad, J2, u2, &W_out) == -1 && W_out == 0.0f);
    CHECK(restir_gris_resample(RESTIR_MIS_PAIRWISE, 2, c2, P2, W2, J2, u2, &W_out) >= 0 && W_out > 0.0f);

    const struct restir_gris_shift shift = {toy_shift, toy_target, NULL, sizeof(float)};
    const struct restir_gris_shift no_shift = {NULL, toy_target, NULL, sizeof(float)};
    const struct restir_gris_shift no_target = {toy_shift, NULL, NULL, sizeof(float)};
    const float xv[2] = {1.0f, 2.0f};
    const void *x[2] = {&xv[0], &xv[1]}, *x_hole[2] = {&xv[0], NULL};
    const float cached[2] = {1.0f, 2.0f};
    float Y[2], P[4], J[2], tmp;
    fill(P, 4, 7.0f), fill(J, 2, 7.0f);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, NULL, x, cached, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &no_shift, x, cached, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &no_target, x, cached, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, NULL, cached, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x, NULL, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x, cached, NULL, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x, cached, Y, NULL, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x, cached, Y, P, NULL, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x, cached, Y, P, J, NULL) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 0, &shift, x, cached, Y, P, J, &tmp) == -1);
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, RESTIR_GRIS_MAX_SAMPLES + 1, &shift, x, cached, Y, P, J, &tmp) == -1);
    CHECK(all_equal(P, 4, 7.0f) && all_equal(J, 2, 7.0f));
    CHECK(restir_gris_targets(RESTIR_MIS_BALANCE, 2, &shift, x_hole, cached, Y, P, J, &tmp) == 0);
    CHECK(J[0] == 1.0f && J[1] == 0.0f && P[1] == 0.0f && P[3] == 0.0f); /* no sample: J = 0, targets 0 */
}

/* ---- restir/neighbors.h, restir/grad.h, the inline part of restir/spmis.h and restir/cells.h ---- */

static void test_per_sample(void)
{
    const float up[3] = {0.0f, 0.0f, 1.0f}, nan3[3] = {NaN, NaN, NaN}, zero3[3] = {0.0f, 0.0f, 0.0f};
    CHECK(restir_neighbors_bitterli(up, up, 1.0f, 1.0f, 0.5f, 0.1f) == 1);
    CHECK(restir_neighbors_bitterli(NULL, up, 1.0f, 1.0f, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, NULL, 1.0f, 1.0f, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, 0.0f, 0.0f, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, -1.0f, -1.0f, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, NaN, 1.0f, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, 1.0f, NaN, 0.5f, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, 1.0f, 1.0f, NaN, 0.1f) == 0);
    CHECK(restir_neighbors_bitterli(up, up, 1.0f, 1.0f, 0.5f, NaN) == 0);
    CHECK(restir_neighbors_bitterli(nan3, up, 1.0f, 1.0f, 0.5f, 0.1f) == 0);

    restir_neighbors_scorer_init(NULL, zero3, up, 1.0f, 0.05f, 8.0f);
    struct restir_neighbors_scorer sc;
    restir_neighbors_scorer_init(&sc, zero3, up, 1.0f, 0.05f, 8.0f);
    CHECK(restir_neighbors_scorer_score(&sc, zero3, up) == 1.0f);
    CHECK(restir_neighbors_scorer_score(NULL, zero3, up) == 0.0f);
    CHECK(restir_neighbors_scorer_score(&sc, NULL, up) == 0.0f &&
          restir_neighbors_scorer_score(&sc, zero3, NULL) == 0.0f);
    CHECK(restir_neighbors_scorer_score(&sc, nan3, up) == 0.0f &&
          restir_neighbors_scorer_score(&sc, zero3, nan3) == 0.0f);
    restir_neighbors_scorer_init(&sc, NULL, up, 1.0f, 0.05f, 8.0f);
    CHECK(restir_neighbors_scorer_score(&sc, zero3, up) == 0.0f);
    restir_neighbors_scorer_init(&sc, zero3, NULL, 1.0f, 0.05f, 8.0f);
    CHECK(restir_neighbors_scorer_score(&sc, zero3, up) == 0.0f);
    const float bad_d[4] = {NaN, INF, 0.0f, -INF};
    for (int k = 0; k < 4; k++) { /* s not finite and positive: every score 0 */
        restir_neighbors_scorer_init(&sc, zero3, up, bad_d[k], 0.05f, 8.0f);
        CHECK(sc.inv_s == 0.0f && restir_neighbors_scorer_score(&sc, zero3, up) == 0.0f);
        restir_neighbors_scorer_init(&sc, zero3, up, 1.0f, k < 2 ? bad_d[k] : -0.05f, 8.0f);
        CHECK(restir_neighbors_scorer_score(&sc, zero3, up) == 0.0f);
    }
    CHECK(restir_neighbors_compat(NULL, up, 1.0f, zero3, up, 0.05f, 8.0f) == 0.0f);
    CHECK(restir_neighbors_compat(zero3, up, 1.0f, NULL, up, 0.05f, 8.0f) == 0.0f);
    const float h_nan_beta = restir_neighbors_compat(zero3, up, 1.0f, zero3, up, 0.05f, NaN);
    CHECK(isfinite(h_nan_beta) && h_nan_beta >= 0.0f && h_nan_beta <= 1.0f);

    const float one3[3] = {1.0f, 1.0f, 1.0f}, two3[3] = {2.0f, 2.0f, 2.0f}, inf3[3] = {INF, INF, INF};
    float out[3] = {7.0f, 7.0f, 7.0f};
    CHECK(restir_grad_luminance(NULL) == 0.0f);
    CHECK(restir_grad_balance(NaN, 1.0f) == 0.0f && restir_grad_balance(-1.0f, 1.0f) == 0.0f);
    CHECK(restir_grad_balance(0.0f, 1.0f) == 0.0f && restir_grad_balance(-INF, 1.0f) == 0.0f);
    CHECK(restir_grad_balance(1.0f, NaN) == 1.0f && restir_grad_balance(1.0f, -1.0f) == 1.0f);
    CHECK(restir_grad_balance(1.0f, 1.0f) == 0.5f && restir_grad_balance(FLT_MAX, FLT_MAX) == 0.5f);
    const float w_inf = restir_grad_balance(INF, INF);
    CHECK(w_inf >= 0.0f && w_inf <= 1.0f);
    restir_grad_one_sided(NULL, one3, out);
    restir_grad_one_sided(one3, NULL, out);
    restir_grad_one_sided(one3, one3, NULL);
    restir_grad_pair_integrand(0, NULL, one3, out);
    restir_grad_pair_integrand(1, one3, NULL, out);
    restir_grad_pair_integrand(1, one3, one3, NULL);
    restir_grad_part(RESTIR_GRAD_POS, NULL, out);
    restir_grad_part(RESTIR_GRAD_POS, one3, NULL);
    CHECK(all_equal(out, 3, 7.0f));
    const float minus3[3] = {-1.0f, -1.0f, -1.0f};
    restir_grad_one_sided(two3, minus3, out); /* the other side's target is not positive: omega = 1 */
    CHECK(out[0] == 3.0f && out[1] == 3.0f && out[2] == 3.0f);
    CHECK(restir_grad_target(RESTIR_GRAD_ABS, NULL) == 0.0f);
    CHECK(restir_grad_target(RESTIR_GRAD_ABS, nan3) == 0.0f && restir_grad_target(RESTIR_GRAD_POS, inf3) == 0.0f);
    CHECK(restir_grad_target(RESTIR_GRAD_NEG, one3) == 0.0f && restir_grad_target(RESTIR_GRAD_ABS, one3) > 0.0f);
    const struct restir_grad_edge_test et = {0.1f, 0.9f, 0.1f};
    CHECK(restir_grad_edge(&et, 1, one3, up, 1.0f, 1, one3, up, 1.0f) == 0);
    CHECK(restir_grad_edge(NULL, 1, one3, up, 1.0f, 1, one3, up, 1.0f) == 1);
    CHECK(restir_grad_edge(&et, 1, NULL, up, 1.0f, 1, one3, up, 1.0f) == 1);
    CHECK(restir_grad_edge(&et, 1, one3, up, 1.0f, 1, one3, NULL, 1.0f) == 1);
    CHECK(restir_grad_edge(&et, 1, one3, up, 1.0f, 0, NULL, NULL, NaN) == 1);
    CHECK(restir_grad_edge(NULL, 0, NULL, NULL, NaN, 0, NULL, NULL, NaN) == 0);

    CHECK(restir_spmis_confidence_scale(4, 0, 1) == 1.0f && restir_spmis_confidence_scale(4, -3, 1) == 1.0f);
    CHECK(restir_spmis_confidence_scale(0, 8, 1) == 1.0f && restir_spmis_confidence_scale(-2, 8, 1) == 1.0f);
    CHECK(restir_spmis_confidence_scale(2, 8, 0) == 1.0f && restir_spmis_confidence_scale(2, 8, 1) == 0.25f);
    restir_spmis_conf_set(NULL, 1.0f, 1.0f, 1.0f);
    struct restir_spmis_conf k;
    restir_spmis_conf_set(&k, NaN, -1.0f, INF);
    CHECK(k.c_c == 0.0f && k.c_sigma == 0.0f && k.scale == 0.0f);
    restir_spmis_conf_set(&k, 1.0f, INF, 1.0f);
    CHECK(k.c_c == 1.0f && k.c_sigma == 0.0f && k.scale == 1.0f);
    CHECK(restir_spmis_canonical_share(&k) == 1.0);
    CHECK(restir_spmis_canonical_share(NULL) == 1.0);
    CHECK(restir_spmis_pairwise(NULL, 1.0f, 1.0f, 1.0f) == 0.0);
    struct restir_spmis_pair pair_terms;
    CHECK(restir_spmis_pair_terms(NULL, 1.0f, 1.0f, 1.0f, &pair_terms) == 0);
    CHECK(restir_spmis_noncanonical(NULL, 1.0f, 1.0f, 1.0f, 1.0) == 0.0);
    CHECK(restir_spmis_canonical_term(NULL, 1.0f, 1.0f, 1.0f, 1.0) == 0.0);
    restir_spmis_conf_set(&k, 1.0f, 1.0f, 1.0f);
    CHECK(restir_spmis_pairwise(&k, 1.0f, 1.0f, 1.0f) == 0.25);
    CHECK(restir_spmis_pair_terms(&k, 1.0f, 1.0f, 1.0f, NULL) == 0);
    CHECK(restir_spmis_pair_terms(&k, NaN, INF, -1.0f, &pair_terms) == 0 && pair_terms.pf == 0.0 &&
          pair_terms.pc == 0.0 && pair_terms.ci == 0.0);
    const float bad3[3] = {NaN, INF, -1.0f};
    for (int b = 0; b < 3; b++) { /* each bad argument read as 0 */
        CHECK(restir_spmis_pairwise(&k, bad3[b], 1.0f, 1.0f) == 0.0);
        CHECK(restir_spmis_pairwise(&k, 1.0f, bad3[b], 1.0f) == 0.0);
        CHECK(restir_spmis_pairwise(&k, 1.0f, 1.0f, bad3[b]) == 0.5);
        CHECK(restir_spmis_noncanonical(&k, bad3[b], 1.0f, 1.0f, 2.0) == 0.0);
        CHECK(restir_spmis_canonical_term(&k, bad3[b], 1.0f, 1.0f, 1.0) == 0.0);
        CHECK(restir_spmis_canonical_term(&k, 1.0f, 1.0f, bad3[b], 1.0) == 0.0);
        CHECK(restir_spmis_canonical_term(&k, 1.0f, bad3[b], 1.0f, 1.0) == 0.5);
    }

    CHECK(restir_cells_hash(12345u) == restir_cells_hash(12345u));
    CHECK(restir_cells_quantize(NaN, 4) == 0 && restir_cells_quantize(-INF, 4) == 0);
    CHECK(restir_cells_quantize(INF, 4) == 3 && restir_cells_quantize(-2.0f, 4) == 0);
    CHECK(restir_cells_quantize(2.0f, 4) == 3 && restir_cells_quantize(0.9f, 4) == 3);
    CHECK(restir_cells_key(3u, 5, NULL, 4) == restir_cells_key(3u, 5, zero3, 4));
    CHECK(restir_cells_key(3u, 5, up, 0) == restir_cells_key(3u, 5, up, 1));
    CHECK(restir_cells_key(3u, 5, up, -9) == restir_cells_key(3u, 5, up, 1));
    const float down3[3] = {-1.0f, -1.0f, -1.0f}; /* bin 0 on every axis, where NaN components go */
    CHECK(restir_cells_key(3u, 5, nan3, 4) == restir_cells_key(3u, 5, down3, 4));
}

/* ---- restir/cells.h, restir/spmis.h draws --------------------------------------------------- */

/* An 8 x 4 image in 4 x 4 tiles. Tile 0 (x < 4): cell A = its rows 0-2 (key 1), cell B = its row 3
 * (key 2); tile 1: cell C (key 1), pixel 7 not valid. Cell A's pixels 0, 1, 2 have confidences NaN,
 * +inf, -1 and pixels 0..3 weights NaN, +inf, -1, 0: A has 9 confidence and 8 contributing pixels
 * (8-11, 16-19). In B only pixel 24 has a confidence and a weight. In C pixels 4 and 5 have
 * confidence FLT_MAX each (their sum saturates). */
enum { CW = 8, CH = 4, CN = CW * CH, CELL_A = 0, CELL_B = 12, CELL_C = 16 };
static uint32_t ckey[CN];
static unsigned char cvalid[CN];
static float cconf[CN], cweight[CN], cnormal[3 * CN];
static int cobject[CN];

static void cells_scene(void)
{
    for (int i = 0; i < CN; i++) {
        const int x = i % CW, y = i / CW;
        ckey[i] = x < 4 && y == 3 ? 2u : 1u;
        cvalid[i] = i != 7;
        cconf[i] = 1.0f;
        cweight[i] = 1.0f;
        cnormal[3 * i] = cnormal[3 * i + 1] = 0.0f;
        cnormal[3 * i + 2] = 1.0f;
        cobject[i] = 0;
    }
    cconf[0] = NaN, cconf[1] = INF, cconf[2] = -1.0f;
    cweight[0] = NaN, cweight[1] = INF, cweight[2] = -1.0f, cweight[3] = 0.0f;
    for (int i = 25; i < 28; i++)
        cweight[i] = 0.0f;
    cconf[25] = 0.0f, cconf[26] = NaN, cconf[27] = -INF;
    cconf[4] = cconf[5] = FLT_MAX;
}

static int in_list(int v, const int *list, int n)
{
    for (int k = 0; k < n; k++)
        if (list[k] == v)
            return 1;
    return 0;
}

static const int a_pixels[12] = {0, 1, 2, 3, 8, 9, 10, 11, 16, 17, 18, 19};
static const int a_contributing[8] = {8, 9, 10, 11, 16, 17, 18, 19};
static const int a_confident[9] = {3, 8, 9, 10, 11, 16, 17, 18, 19};

/* 1 when r is a cell of c's last build (or -1 when allowed). */
static int is_cell(const struct restir_cells *c, int r)
{
    return r == CELL_A || r == CELL_B || r == CELL_C ? c->count[r] > 0 : 0;
}

static void test_cells(void)
{
    cells_scene();
    struct restir_cells c, z;
    memset(&z, 0, sizeof z);
    CHECK(restir_cells_init(NULL, CW, CH, 4) == -1);
    const int bad_sizes[][3] = {{0, CH, 4},       {CW, 0, 4},      {-1, CH, 4},        {CW, -5, 4},
                                {CW, CH, 0},      {CW, CH, -2},    {CW, CH, 17},       {INT_MAX, INT_MAX, 16},
                                {65536, 32768, 8}, {INT_MAX, 1, 4}, {INT_MIN, INT_MIN, 4}};
    for (size_t b = 0; b < sizeof bad_sizes / sizeof bad_sizes[0]; b++) {
        memset(&c, 0x5a, sizeof c);
        CHECK(restir_cells_init(&c, bad_sizes[b][0], bad_sizes[b][1], bad_sizes[b][2]) == -1);
        CHECK(c.width == 0 && c.entry == NULL && c.tap == NULL && c.n_cells == 0);
    }
    restir_cells_fini(NULL);
    restir_cells_fini(&c); /* zeroed by the failed init */
    restir_cells_fini(&c);

    /* A zeroed struct (never initialized) is refused everywhere. */
    double prob = 7.0;
    CHECK(restir_cells_build(&z, ckey, cvalid, cconf, cweight) == -1 && z.n_cells == 0);
    CHECK(restir_cells_pack_taps(&z, cnormal, cobject) == -1);
    CHECK(restir_cells_others(&z, 0, -1) == 0 && restir_cells_confidence_others(&z, 0, -1, cconf) == 0.0f);
    CHECK(restir_cells_pick_uniform(&z, 0, -1, 0.5f) == -1);
    CHECK(restir_cells_pick_weighted(&z, 0, -1, 0.5f, &prob) == -1 && prob == 0.0);

    CHECK(restir_cells_init(&c, CW, CH, 4) == 0);
    /* Before the first build no pixel is in a cell. */
    float u[3 * 64];
    fill(u, 3 * 64, 0.5f);
    const struct restir_cells_search s0 = {12, 30.0f, 1.25f, 0.5f,
                                           RESTIR_CELLS_SCORE_CONFIDENCE, NULL, NULL, 0.05f, 8.0f};
    for (int cell = 0; cell < CN; cell++)
        CHECK(restir_cells_others(&c, cell, -1) == 0);
    prob = 7.0;
    CHECK(restir_cells_pick_confidence(&c, 0, -1, 0.5f, &prob) == -1 && prob == 0.0);
    CHECK(restir_cells_search(&c, &s0, 9, cnormal, cobject, u) == -1);
    CHECK(restir_cells_search_packed(&c, &s0, 9, u) == -1);

    CHECK(restir_cells_build(NULL, ckey, cvalid, cconf, cweight) == -1);
    CHECK(restir_cells_build(&c, NULL, cvalid, cconf, cweight) == -1);
    CHECK(restir_cells_build(&c, ckey, NULL, cconf, cweight) == -1);
    CHECK(restir_cells_build(&c, ckey, cvalid, NULL, cweight) == -1);
    CHECK(restir_cells_build(&c, ckey, cvalid, cconf, NULL) == -1);
    CHECK(c.n_cells == 0 && c.cell_of[9] == -1);
    CHECK(restir_cells_build(&c, ckey, cvalid, cconf, cweight) == 0);
    CHECK(c.n_cells == 3 && c.cell_of[9] == CELL_A && c.cell_of[24] == CELL_B && c.cell_of[4] == CELL_C);
    CHECK(c.cell_of[7] == -1);
    CHECK(c.count[CELL_A] == 12 && c.contributing[CELL_A] == 8 && c.conf_sum[CELL_A] == 9.0f);
    CHECK(c.count[CELL_B] == 4 && c.contributing[CELL_B] == 1 && c.conf_sum[CELL_B] == 1.0f);
    CHECK(c.count[CELL_C] == 15 && c.conf_sum[CELL_C] == FLT_MAX); /* saturated, not +inf */

    /* Searches before restir_cells_pack_taps: every tap rejected, the pixel's own cell. */
    CHECK(restir_cells_search_packed(&c, &s0, 9, u) == CELL_A);
    CHECK(restir_cells_pack_taps(NULL, cnormal, cobject) == -1);
    CHECK(restir_cells_pack_taps(&c, NULL, cobject) == -1 && restir_cells_pack_taps(&c, cnormal, NULL) == -1);
    CHECK(c.tap[9].cell == -1);
    CHECK(restir_cells_pack_taps(&c, cnormal, cobject) == 0 && c.tap[9].cell == CELL_A);

    /* Cells that are not cells: no pixel, no draw. */
    const int not_cells[] = {-1, -7, INT_MIN, 1, 5, CELL_A + 1, CN - 1, CN, CN + 3, INT_MAX};
    for (size_t b = 0; b < sizeof not_cells / sizeof not_cells[0]; b++) {
        const int cell = not_cells[b];
        CHECK(restir_cells_others(&c, cell, -1) == 0);
        CHECK(restir_cells_confidence_others(&c, cell, -1, cconf) == 0.0f);
        CHECK(restir_cells_pick_uniform(&c, cell, -1, 0.5f) == -1);
        prob = 7.0;
        CHECK(restir_cells_pick_confidence(&c, cell, -1, 0.5f, &prob) == -1 && prob == 0.0);
        prob = 7.0;
        CHECK(restir_cells_pick_weighted(&c, cell, -1, 0.5f, &prob) == -1 && prob == 0.0);
    }
    CHECK(restir_cells_others(NULL, CELL_A, -1) == 0);
    CHECK(restir_cells_confidence_others(NULL, CELL_A, -1, cconf) == 0.0f);
    CHECK(restir_cells_confidence_others(&c, CELL_A, -1, NULL) == 0.0f);
    CHECK(restir_cells_pick_uniform(NULL, CELL_A, -1, 0.5f) == -1);
    CHECK(restir_cells_pick_confidence(NULL, CELL_A, -1, 0.5f, NULL) == -1);
    CHECK(restir_cells_pick_weighted(NULL, CELL_A, -1, 0.5f, NULL) == -1);

    /* Excluded pixels outside the cell exclude nothing. */
    const int outside[] = {-1, -100, INT_MIN, 24, 7, CN, INT_MAX};
    for (size_t b = 0; b < sizeof outside / sizeof outside[0]; b++) {
        CHECK(restir_cells_others(&c, CELL_A, outside[b]) == 12);
        CHECK(restir_cells_confidence_others(&c, CELL_A, outside[b], cconf) == 9.0f);
    }
    CHECK(restir_cells_others(&c, CELL_A, 9) == 11 && restir_cells_confidence_others(&c, CELL_A, 9, cconf) == 8.0f);
    /* the excluded pixel's NaN / inf / negative confidence reads as 0, as in the build */
    CHECK(restir_cells_confidence_others(&c, CELL_A, 0, cconf) == 9.0f);
    CHECK(restir_cells_confidence_others(&c, CELL_A, 1, cconf) == 9.0f);
    CHECK(restir_cells_confidence_others(&c, CELL_A, 2, cconf) == 9.0f);
    const float conf_c = restir_cells_confidence_others(&c, CELL_C, 4, cconf);
    CHECK(isfinite(conf_c) && conf_c >= 0.0f);

    /* Draws with u outside [0,1): clamped, NaN as 0, never the excluded pixel, never a pixel of weight
     * or confidence 0 (NaN, inf and negative ones included). */
    const float bad_u[] = {NaN, -INF, -1.0f, -0.0f, 1.0f, 1.5f, INF, 0.999999f};
    for (size_t b = 0; b < sizeof bad_u / sizeof bad_u[0]; b++) {
        const int pu = restir_cells_pick_uniform(&c, CELL_A, 8, bad_u[b]);
        CHECK(in_list(pu, a_pixels, 12) && pu != 8);
        prob = 0.0;
        const int pw = restir_cells_pick_weighted(&c, CELL_A, 8, bad_u[b], &prob);
        CHECK(in_list(pw, a_contributing, 8) && pw != 8 && prob == 1.0 / 7.0);
        CHECK(restir_cells_pick_weighted(&c, CELL_A, 8, bad_u[b], NULL) == pw);
        prob = 0.0;
        const int pc = restir_cells_pick_confidence(&c, CELL_A, -1, bad_u[b], &prob);
        CHECK(in_list(pc, a_confident, 9) && prob == 1.0 / 9.0);
        CHECK(restir_cells_pick_confidence(&c, CELL_A, -1, bad_u[b], NULL) == pc);
    }
    CHECK(restir_cells_pick_uniform(&c, CELL_A, -1, NaN) == restir_cells_pick_uniform(&c, CELL_A, -1, 0.0f));
    CHECK(restir_cells_pick_uniform(&c, CELL_A, -1, INF) == restir_cells_pick_uniform(&c, CELL_A, -1, 0.9999f));
    CHECK(restir_cells_pick_weighted(&c, CELL_A, -1, NaN, NULL) ==
          restir_cells_pick_weighted(&c, CELL_A, -1, 0.0f, NULL));
    int bad_drawn = 0;
    for (int t = 0; t < 1000; t++) {
        const float ut = (float)t / 1000.0f;
        bad_drawn += !in_list(restir_cells_pick_weighted(&c, CELL_A, -1, ut, NULL), a_contributing, 8);
        bad_drawn += !in_list(restir_cells_pick_confidence(&c, CELL_A, -1, ut, NULL), a_confident, 9);
    }
    CHECK(bad_drawn == 0);
    prob = 7.0; /* B: pixel 24 alone has a confidence and a weight */
    CHECK(restir_cells_pick_confidence(&c, CELL_B, 24, 0.5f, &prob) == -1 && prob == 0.0);
    prob = 7.0;
    CHECK(restir_cells_pick_weighted(&c, CELL_B, 24, 0.5f, &prob) == -1 && prob == 0.0);
    CHECK(restir_cells_pick_uniform(&c, CELL_B, 24, 0.5f) >= 25);

    /* The search: bad arguments, then bad parameters and u that must not crash or leave the cells. */
    struct restir_cells_search s = s0;
    CHECK(restir_cells_search(NULL, &s, 9, cnormal, cobject, u) == -1);
    CHECK(restir_cells_search(&c, NULL, 9, cnormal, cobject, u) == -1);
    CHECK(restir_cells_search(&c, &s, 9, NULL, cobject, u) == -1);
    CHECK(restir_cells_search(&c, &s, 9, cnormal, NULL, u) == -1);
    CHECK(restir_cells_search(&c, &s, 9, cnormal, cobject, NULL) == -1);
    CHECK(restir_cells_search_packed(NULL, &s, 9, u) == -1 && restir_cells_search_packed(&c, NULL, 9, u) == -1);
    CHECK(restir_cells_search_packed(&c, &s, 9, NULL) == -1 && restir_cells_search_packed(&z, &s, 0, u) == -1);
    const int bad_pixels[] = {-1, INT_MIN, CN, INT_MAX, 7 /* in no cell */};
    for (size_t b = 0; b < sizeof bad_pixels / sizeof bad_pixels[0]; b++) {
        CHECK(restir_cells_search(&c, &s, bad_pixels[b], cnormal, cobject, u) == -1);
        CHECK(restir_cells_search_packed(&c, &s, bad_pixels[b], u) == -1);
    }
    s.score = RESTIR_CELLS_SCORE_COMPAT; /* without positions and depths */
    CHECK(restir_cells_search(&c, &s, 9, cnormal, cobject, u) == -1 && restir_cells_search_packed(&c, &s, 9, u) == -1);
    s = s0;
    s.steps = -4;
    CHECK(restir_cells_search(&c, &s, 9, cnormal, cobject, u) == CELL_A &&
          restir_cells_search_packed(&c, &s, 9, u) == CELL_A);
    const float bad_f[] = {NaN, INF, -INF, -3.0f, 0.0f, FLT_MAX};
    int stray = 0, differ = 0;
    for (size_t b = 0; b < sizeof bad_f / sizeof bad_f[0]; b++) {
        for (int field = 0; field < 4; field++) {
            s = s0;
            s.steps = 64;
            float ub[3 * 64];
            fill(ub, 3 * 64, 0.3f);
            if (field == 0)
                s.radius = bad_f[b];
            else if (field == 1)
                s.growth = bad_f[b];
            else if (field == 2)
                s.normal_min = bad_f[b];
            else
                for (int t = 0; t < 64; t++)
                    ub[3 * t + (t % 3)] = bad_f[b]; /* bad u in every role */
            for (int px = 0; px < CN; px++) {
                const int r1 = restir_cells_search(&c, &s, px, cnormal, cobject, ub);
                const int r2 = restir_cells_search_packed(&c, &s, px, ub);
                stray += px == 7 ? r1 != -1 : !is_cell(&c, r1);
                differ += r1 != r2;
            }
        }
    }
    CHECK(stray == 0 && differ == 0);
    s = s0;
    s.score = (enum restir_cells_score)9; /* weighs as RESTIR_CELLS_SCORE_CONFIDENCE */
    struct restir_cells_search s_conf = s0;
    s_conf.steps = s.steps = 16;
    for (int t = 0; t < 3 * 16; t++)
        u[t] = (float)((t * 37) % 100) / 100.0f;
    CHECK(restir_cells_search(&c, &s, 9, cnormal, cobject, u) ==
          restir_cells_search(&c, &s_conf, 9, cnormal, cobject, u));

    /* The draws of restir/spmis.h. */
    struct restir_spmis_draws d;
    float ud[RESTIR_SPMIS_MAX_DRAWS + 8];
    fill(ud, RESTIR_SPMIS_MAX_DRAWS + 8, 0.25f);
    d.count = 12345;
    CHECK(restir_spmis_canonical_draws(NULL, CELL_A, 8, 4, RESTIR_SPMIS_PICK_UNIFORM, ud, &d) == -1 &&
          d.count == 12345);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 4, RESTIR_SPMIS_PICK_UNIFORM, ud, NULL) == -1);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 4, RESTIR_SPMIS_PICK_UNIFORM, NULL, &d) == -1 &&
          d.count == 12345);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 4, (enum restir_spmis_pick)5, ud, &d) == -1 && d.count == 12345);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 4, (enum restir_spmis_pick)-1, ud, &d) == -1 && d.count == 12345);
    CHECK(restir_spmis_neighbor_draws(NULL, CELL_A, 8, 4, ud, &d) == -1 && d.count == 12345);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 4, ud, NULL) == -1);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 4, NULL, &d) == -1 && d.count == 12345);
    for (size_t b = 0; b < sizeof not_cells / sizeof not_cells[0]; b++) {
        d.count = 12345;
        CHECK(restir_spmis_canonical_draws(&c, not_cells[b], 8, 4, RESTIR_SPMIS_PICK_UNIFORM, ud, &d) == 0 &&
              d.count == 0);
        d.count = 12345;
        CHECK(restir_spmis_canonical_draws(&c, not_cells[b], 8, 0, RESTIR_SPMIS_PICK_CONFIDENCE, ud, &d) == 0 &&
              d.count == 0);
        d.count = 12345;
        CHECK(restir_spmis_neighbor_draws(&c, not_cells[b], 8, 4, ud, &d) == 0 && d.count == 0);
        d.count = 12345;
        CHECK(restir_spmis_neighbor_draws(&c, not_cells[b], 8, 0, ud, &d) == 0 && d.count == 0);
    }
    /* enumeration (n <= 0) needs no u */
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 0, RESTIR_SPMIS_PICK_UNIFORM, NULL, &d) == 0 && d.count == 11);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, -6, RESTIR_SPMIS_PICK_UNIFORM, NULL, &d) == 0 && d.count == 11);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 0, NULL, &d) == 0 && d.count == 7);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, -1, NULL, &d) == 0 && d.count == 7);
    int bad_draw = 0;
    for (int k = 0; k < d.count; k++)
        bad_draw += !in_list(d.pixel[k], a_contributing, 8) || d.pixel[k] == 8 || d.factor[k] != 1.0;
    CHECK(bad_draw == 0);
    /* too many draws: capped */
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, INT_MAX, RESTIR_SPMIS_PICK_UNIFORM, ud, &d) == 0 &&
          d.count == RESTIR_SPMIS_MAX_DRAWS);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 100000, ud, &d) == 0 && d.count == RESTIR_SPMIS_MAX_DRAWS);
    /* u outside [0,1): every draw a proper pixel with a finite positive factor */
    for (size_t b = 0; b < sizeof bad_u / sizeof bad_u[0]; b++) {
        float ub[8];
        fill(ub, 8, bad_u[b]);
        bad_draw = 0;
        for (int pick = 0; pick < 2; pick++) {
            CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 8, (enum restir_spmis_pick)pick, ub, &d) == 0 &&
                  d.count == 8);
            for (int k = 0; k < d.count; k++)
                bad_draw += !in_list(d.pixel[k], pick ? a_confident : a_pixels, pick ? 9 : 12) || d.pixel[k] == 8 ||
                            !(d.factor[k] > 0.0 && isfinite(d.factor[k]));
        }
        CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 8, ub, &d) == 0 && d.count == 8);
        for (int k = 0; k < d.count; k++)
            bad_draw += !in_list(d.pixel[k], a_contributing, 8) || d.pixel[k] == 8 ||
                        d.factor[k] != 1.0 / (8.0 * (1.0 / 7.0)); /* 1 / (N P), P = 1 / 7 */
        CHECK(bad_draw == 0);
    }
    /* no other confidence / no other contributing pixel: no draw */
    CHECK(restir_spmis_canonical_draws(&c, CELL_B, 24, 4, RESTIR_SPMIS_PICK_CONFIDENCE, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_B, 24, 4, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_B, 24, 0, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_canonical_draws(&c, CELL_B, 24, 4, RESTIR_SPMIS_PICK_UNIFORM, ud, &d) == 0 && d.count == 4);

    /* A rebuild in which B's index falls inside cell A: it names no cell any more. */
    uint32_t key_one[CN];
    for (int i = 0; i < CN; i++)
        key_one[i] = 1u;
    CHECK(restir_cells_build(&c, key_one, cvalid, cconf, cweight) == 0 && c.n_cells == 2 && c.count[CELL_A] == 16);
    CHECK(restir_cells_others(&c, CELL_B, -1) == 0 && restir_cells_others(&c, CELL_B, 9) == 0);
    CHECK(restir_cells_confidence_others(&c, CELL_B, -1, cconf) == 0.0f);
    CHECK(restir_cells_pick_uniform(&c, CELL_B, -1, 0.5f) == -1);
    CHECK(restir_cells_pick_weighted(&c, CELL_B, -1, 0.5f, NULL) == -1);
    CHECK(restir_cells_pick_confidence(&c, CELL_B, -1, 0.5f, NULL) == -1);
    CHECK(restir_spmis_canonical_draws(&c, CELL_B, 24, 0, RESTIR_SPMIS_PICK_UNIFORM, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_B, 24, 0, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_B, 24, 3, ud, &d) == 0 && d.count == 0);

    /* A rebuild with every weight and confidence bad: cells stay, nothing contributes. */
    float conf_bad[CN], weight_bad[CN];
    for (int i = 0; i < CN; i++)
        conf_bad[i] = weight_bad[i] = i % 3 == 0 ? NaN : (i % 3 == 1 ? -INF : INF);
    CHECK(restir_cells_build(&c, ckey, cvalid, conf_bad, weight_bad) == 0 && c.n_cells == 3);
    CHECK(c.contributing[CELL_A] == 0 && c.conf_sum[CELL_A] == 0.0f && c.conf_sum[CELL_C] == 0.0f);
    CHECK(restir_cells_pick_weighted(&c, CELL_A, -1, 0.5f, NULL) == -1);
    CHECK(restir_cells_pick_confidence(&c, CELL_A, -1, 0.5f, NULL) == -1);
    CHECK(restir_spmis_neighbor_draws(&c, CELL_A, 8, 4, ud, &d) == 0 && d.count == 0);
    CHECK(restir_spmis_canonical_draws(&c, CELL_A, 8, 4, RESTIR_SPMIS_PICK_CONFIDENCE, ud, &d) == 0 && d.count == 0);
    CHECK(restir_cells_pack_taps(&c, cnormal, cobject) == 0);
    s = s0;
    CHECK(restir_cells_search_packed(&c, &s, 9, u) == CELL_A); /* every tap weighs 0: the own cell */
    /* the renderer's shape of failure: an invalid pixel's cell is -1 */
    memset(cvalid, 0, sizeof cvalid);
    CHECK(restir_cells_build(&c, ckey, cvalid, cconf, cweight) == 0 && c.n_cells == 0);
    CHECK(restir_cells_others(&c, CELL_A, -1) == 0 && restir_cells_pick_uniform(&c, CELL_A, -1, 0.5f) == -1);
    restir_cells_fini(&c);
    CHECK(c.width == 0 && c.entry == NULL);
    restir_cells_fini(&c);
}

/* ---- restir/metrics.h ------------------------------------------------------------------------ */

static void test_metrics(void)
{
    const float img[6] = {1.0f, 0.5f, 1.0f, 0.5f, 1.0f, 1.5f}, ref[6] = {1.0f, 0.0f, 2.0f, 0.5f, 1.0f, 0.5f};
    struct restir_metrics_error e, sentinel;
    memset(&sentinel, 0x5a, sizeof sentinel);
    e = sentinel;
    CHECK(restir_metrics_compute(NULL, ref, 2, NULL, &e) == -1);
    CHECK(restir_metrics_compute(img, NULL, 2, NULL, &e) == -1);
    CHECK(restir_metrics_compute(img, ref, 2, NULL, NULL) == -1);
    CHECK(restir_metrics_compute(img, ref, 0, NULL, &e) == -1);
    CHECK(restir_metrics_compute(img, ref, SIZE_MAX, NULL, &e) == -1);
    CHECK(restir_metrics_compute(img, ref, SIZE_MAX / 3 + 1, NULL, &e) == -1);
    const unsigned char none[2] = {0, 0};
    CHECK(restir_metrics_compute(img, ref, 2, none, &e) == -1);
    CHECK(memcmp(&e, &sentinel, sizeof e) == 0);
    CHECK(restir_metrics_compute(img, ref, 2, NULL, &e) == 0 && isfinite(e.relmse) && e.relmse > 0.0);
    const float neg[6] = {-1.0f, -2.0f, -3.0f, -1.0f, -2.0f, -3.0f};
    CHECK(restir_metrics_compute(neg, neg, 2, NULL, &e) == 0 && e.relmse == 0.0 && e.mape == 0.0 && e.smape == 0.0);
    const float img_nan[6] = {NaN, 0.5f, 1.0f, 0.5f, 1.0f, 1.5f}, img_inf[6] = {INF, 0.5f, 1.0f, 0.5f, 1.0f, 1.5f};
    CHECK(restir_metrics_compute(img_nan, ref, 2, NULL, &e) == 0 && isnan(e.relmse) && isnan(e.smape));
    CHECK(restir_metrics_compute(img_inf, ref, 2, NULL, &e) == 0 && !isfinite(e.relmse) && !isfinite(e.luma_rmse));
    const unsigned char second[2] = {0, 1}; /* the NaN pixel masked out */
    CHECK(restir_metrics_compute(img_nan, ref, 2, second, &e) == 0 && isfinite(e.relmse) && isfinite(e.smape));

    double lum[2] = {7.0, 7.0}, sm = 7.0;
    CHECK(restir_metrics_luminance(NULL, 2, lum) == -1 && restir_metrics_luminance(img, 2, NULL) == -1);
    CHECK(restir_metrics_luminance(img, SIZE_MAX, lum) == -1);
    CHECK(restir_metrics_luminance(img, 0, lum) == 0 && lum[0] == 7.0 && lum[1] == 7.0);
    CHECK(restir_metrics_luminance(img, 2, lum) == 0 && lum[0] != 7.0);
    CHECK(restir_metrics_smape_luminance(NULL, ref, 2, NULL, &sm) == -1);
    CHECK(restir_metrics_smape_luminance(lum, NULL, 2, NULL, &sm) == -1);
    CHECK(restir_metrics_smape_luminance(lum, ref, 2, NULL, NULL) == -1);
    CHECK(restir_metrics_smape_luminance(lum, ref, 0, NULL, &sm) == -1);
    CHECK(restir_metrics_smape_luminance(lum, ref, 2, none, &sm) == -1);
    CHECK(restir_metrics_smape_luminance(lum, ref, SIZE_MAX, NULL, &sm) == -1 && sm == 7.0);
    CHECK(restir_metrics_compute(img, ref, 2, NULL, &e) == 0);
    CHECK(restir_metrics_smape_luminance(lum, ref, 2, NULL, &sm) == 0 && sm == e.smape);

    float map[2] = {7.0f, 7.0f};
    CHECK(restir_metrics_mape_map(NULL, ref, 2, map) == -1 && restir_metrics_mape_map(img, NULL, 2, map) == -1);
    CHECK(restir_metrics_mape_map(img, ref, 2, NULL) == -1 && restir_metrics_mape_map(img, ref, SIZE_MAX, map) == -1);
    CHECK(restir_metrics_mape_map(img, ref, 0, map) == 0 && all_equal(map, 2, 7.0f));
    CHECK(restir_metrics_mape_map(img, ref, 2, map) == 0 && all_finite(map, 2) && map[0] > 0.0f);
    CHECK(restir_metrics_mape_map(img_nan, ref, 2, map) == 0 && isnan(map[0]));
    map[0] = map[1] = 7.0f;
    CHECK(restir_metrics_relmse_map(NULL, ref, 2, map) == -1 && restir_metrics_relmse_map(img, NULL, 2, map) == -1);
    CHECK(restir_metrics_relmse_map(img, ref, 2, NULL) == -1 &&
          restir_metrics_relmse_map(img, ref, SIZE_MAX, map) == -1);
    CHECK(restir_metrics_relmse_map(img, ref, 0, map) == 0 && all_equal(map, 2, 7.0f));
    CHECK(restir_metrics_relmse_map(img, ref, 2, map) == 0 && all_finite(map, 2) && map[0] > 0.0f);
    CHECK(restir_metrics_relmse_map(img_nan, ref, 2, map) == 0 && isnan(map[0]));

    /* gradient relMSE on a 2 x 1 image */
    const float g[6] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    CHECK(isnan(restir_metrics_gradient_relmse(NULL, g, ref, 2, 1)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, NULL, ref, 2, 1)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, g, NULL, 2, 1)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, g, ref, 0, 1)) &&
          isnan(restir_metrics_gradient_relmse(g, g, ref, 2, 0)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, g, ref, -2, 1)) &&
          isnan(restir_metrics_gradient_relmse(g, g, ref, 2, -1)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, g, ref, 1, 1)));
    CHECK(isnan(restir_metrics_gradient_relmse(g, g, ref, INT_MAX, INT_MAX)));
    CHECK(isfinite(restir_metrics_gradient_relmse(g, g, ref, 2, 1)));
    /* the trimmed relMSE, the worst-pairs mask and gradient MAPE: the same arguments, and the fraction */
    unsigned char wm[2] = {9, 9};
    CHECK(isnan(restir_metrics_gradient_relmse_trimmed(NULL, g, ref, 2, 1, 0.01)) &&
          isnan(restir_metrics_gradient_relmse_trimmed(g, g, NULL, 2, 1, 0.01)));
    CHECK(isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 1, 1, 0.01)) &&
          isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, INT_MAX, INT_MAX, 0.01)));
    CHECK(isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, NAN)) &&
          isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, -0.5)) &&
          isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, 1.0)) &&
          isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, INFINITY)));
    CHECK(isnan(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, 0.5))); /* 0.5 of 1 pair leaves none */
    CHECK(restir_metrics_gradient_relmse_trimmed(g, g, ref, 2, 1, 0.01) ==
          restir_metrics_gradient_relmse(g, g, ref, 2, 1));
    CHECK(restir_metrics_gradient_worst_pairs(NULL, g, ref, 2, 1, 0.01, wm) == -1 &&
          restir_metrics_gradient_worst_pairs(g, g, ref, 2, 1, 0.01, NULL) == -1 &&
          restir_metrics_gradient_worst_pairs(g, g, ref, 0, 1, 0.01, wm) == -1 &&
          restir_metrics_gradient_worst_pairs(g, g, ref, 2, 1, NAN, wm) == -1 &&
          restir_metrics_gradient_worst_pairs(g, g, ref, 2, 1, 1.0, wm) == -1 && wm[0] == 9 && wm[1] == 9);
    CHECK(restir_metrics_gradient_worst_pairs(g, g, ref, 2, 1, 0.5, wm) == 1 && wm[0] == 1 && wm[1] == 0);
    CHECK(isnan(restir_metrics_gradient_mape(NULL, g, ref, 2, 1)) &&
          isnan(restir_metrics_gradient_mape(g, g, NULL, 2, 1)));
    CHECK(isnan(restir_metrics_gradient_mape(g, g, ref, -2, 1)) && isnan(restir_metrics_gradient_mape(g, g, ref, 1, 1)));
    CHECK(isnan(restir_metrics_gradient_mape(g, g, ref, INT_MAX, INT_MAX)));
    CHECK(isfinite(restir_metrics_gradient_mape(g, g, ref, 2, 1)));
    CHECK(restir_metrics_definitions() != NULL && restir_metrics_definitions()[0] != '\0');

    /* FLIP on the 2 x 1 image: -1 and nothing written for NULL, sizes, a bad ppd; NaN pixels make the mean NaN */
    for (int hdr = 0; hdr < 2; hdr++) {
        int (*flip)(const float *, const float *, int, int, double, float *, double *) =
            hdr ? restir_metrics_flip : restir_metrics_flip_ldr;
        float fmap[2] = {7.0f, 7.0f};
        double fmean = 7.0;
        CHECK(flip(NULL, ref, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == -1);
        CHECK(flip(img, NULL, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == -1);
        CHECK(flip(img, ref, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, NULL) == -1);
        CHECK(flip(img, ref, 0, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == -1);
        CHECK(flip(img, ref, 2, -1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == -1);
        CHECK(flip(img, ref, INT_MAX, INT_MAX, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == -1);
        CHECK(flip(img, ref, 2, 1, NaN, fmap, &fmean) == -1 && flip(img, ref, 2, 1, INF, fmap, &fmean) == -1);
        CHECK(flip(img, ref, 2, 1, 0.0, fmap, &fmean) == -1 && flip(img, ref, 2, 1, -1.0, fmap, &fmean) == -1);
        CHECK(flip(img, ref, 2, 1, 2.0 * RESTIR_METRICS_FLIP_PPD_MAX, fmap, &fmean) == -1);
        CHECK(all_equal(fmap, 2, 7.0f) && fmean == 7.0);
        CHECK(flip(img, ref, 2, 1, RESTIR_METRICS_FLIP_PPD, NULL, &fmean) == 0 && isfinite(fmean) && fmean > 0.0);
        CHECK(flip(img, img, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == 0 && fmean == 0.0 &&
              all_equal(fmap, 2, 0.0f));
        CHECK(flip(img_nan, ref, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == 0 && isnan(fmean));
        CHECK(flip(img_inf, ref, 2, 1, RESTIR_METRICS_FLIP_PPD, fmap, &fmean) == 0 && isnan(fmean));
    }
    CHECK(fabs(restir_metrics_flip_ppd(0.7, 0.7, 3840) - RESTIR_METRICS_FLIP_PPD) < 1e-12);
    CHECK(isnan(restir_metrics_flip_ppd(0.0, 0.7, 3840)) && isnan(restir_metrics_flip_ppd(0.7, NaN, 3840)) &&
          isnan(restir_metrics_flip_ppd(0.7, 0.7, 0)) && isnan(restir_metrics_flip_ppd(INF, 0.7, 3840)));

    /* correlation: 2 runs of a 3 x 2 luminance image */
    float runs[12];
    for (int k = 0; k < 12; k++)
        runs[k] = 1.0f + 0.25f * (float)((k * 7) % 5);
    CHECK(isfinite(restir_metrics_spatial_covariance(runs, 2, 3, 2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(NULL, 2, 3, 2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 1, 3, 2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, -2, 3, 2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 2, 0, 2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 2, 3, -2, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 2, 3, 2, -1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, INT_MAX, INT_MAX, INT_MAX, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 2, 3, 2, 1, NaN, NULL)));
    const unsigned char mask6[6] = {0, 0, 0, 0, 0, 0};
    CHECK(isnan(restir_metrics_spatial_covariance(runs, 2, 3, 2, 1, 1e-4f, mask6)));
    CHECK(isfinite(restir_metrics_spatial_covariance(runs, 2, 3, 2, INT_MAX, 1e-4f, NULL)));
    /* temporal: 2 runs of 2 frames of 3 x 1 */
    CHECK(isfinite(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, 1, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(NULL, 2, 2, 3, 1, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 1, 2, 3, 1, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 0, 3, 1, 0, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, 1, 2, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, 1, -1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 0, 1, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, -1, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, INT_MAX, INT_MAX, INT_MAX, INT_MAX, 1, 1e-4f, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, 1, 1, NaN, NULL)));
    CHECK(isnan(restir_metrics_temporal_autocovariance(runs, 2, 2, 3, 1, 1, 1e-4f, mask6)));

    /* hard pixels on a 3 x 2 G-buffer */
    float normals[18], depth[6];
    for (int i = 0; i < 6; i++) {
        normals[3 * i] = normals[3 * i + 1] = 0.0f;
        normals[3 * i + 2] = 1.0f;
        depth[i] = 1.0f + 0.01f * (float)i;
    }
    unsigned char hard[6];
    float ratio[6];
    memset(hard, 7, sizeof hard);
    CHECK(restir_metrics_hard_pixels(NULL, depth, NULL, 3, 2, 30.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, NULL, NULL, 3, 2, 30.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, 30.0f, 0.5f, 0.1f, 0.5f, NULL, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 0, 2, 30.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, -2, 30.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, NaN, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, -1.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, INT_MAX, 2, 1.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 65536, 65536, 1.0f, 0.5f, 0.1f, 0.5f, hard, ratio) == -1);
    int untouched = 1;
    for (int i = 0; i < 6; i++)
        untouched &= hard[i] == 7;
    CHECK(untouched);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, INF, 0.5f, 0.1f, 0.5f, hard, NULL) == 3);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, 30.0f, 0.5f, 0.1f, NaN, hard, ratio) == 0);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, 30.0f, 0.5f, 0.1f, -1.0f, hard, ratio) == 0);
    CHECK(restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, 30.0f, 0.5f, 0.1f, INF, hard, ratio) == 6);
    const unsigned char valid4[6] = {1, 1, 0, 1, 1, 0};
    CHECK(restir_metrics_hard_pixels(normals, depth, valid4, 3, 2, 30.0f, 0.5f, 0.1f, 2.0f, hard, ratio) == 4);
    CHECK(hard[2] == 0 && ratio[2] == -1.0f);
    depth[0] = NaN, normals[3] = NaN, depth[4] = -INF;
    const int nh = restir_metrics_hard_pixels(normals, depth, NULL, 3, 2, 30.0f, NaN, NaN, 0.5f, hard, ratio);
    CHECK(nh == 3 && all_finite(ratio, 6));
}

/* ---- restir/poisson.h, restir/threads.h ----------------------------------------------------- */

static void test_poisson_threads(void)
{
    enum { PW = 5, PH = 4, PN = 3 * PW * PH };
    float primal[PN], dx[PN], dy[PN], out[PN];
    for (int k = 0; k < PN; k++) {
        primal[k] = 0.5f + 0.01f * (float)k;
        dx[k] = dy[k] = 0.01f;
    }
    struct restir_poisson_stats st, st0;
    memset(&st0, 0x5a, sizeof st0);
    st = st0;
    fill(out, PN, 7.0f);
    const enum restir_poisson_solver CG = RESTIR_POISSON_CG, DCT = RESTIR_POISSON_DCT;
    const double tol = RESTIR_POISSON_TOL;
    CHECK(restir_poisson_l2(PW, PH, NULL, dx, dy, 0.2f, CG, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, NULL, dy, 0.2f, CG, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, NULL, 0.2f, CG, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, tol, 100, NULL, &st) == -1);
    CHECK(restir_poisson_l2(0, PH, primal, dx, dy, 0.2f, CG, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, -1, primal, dx, dy, 0.2f, DCT, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(INT_MAX, INT_MAX, primal, dx, dy, 0.2f, CG, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(INT_MAX - 1, 2, primal, dx, dy, 0.2f, CG, tol, 100, out, &st) == -1);
    const float bad_alpha[] = {0.0f, -0.2f, NaN, INF, -INF};
    for (size_t b = 0; b < sizeof bad_alpha / sizeof bad_alpha[0]; b++) {
        CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, bad_alpha[b], DCT, tol, 100, out, &st) == -1);
        CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, bad_alpha[b], 2, RESTIR_POISSON_PRECOND_JACOBI, 5, out, &st) ==
              -1);
        CHECK(isnan(restir_poisson_l1_energy(PW, PH, primal, dx, dy, bad_alpha[b], primal)));
    }
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, (enum restir_poisson_solver)7, tol, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, 0.0, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, -1.0, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, (double)NAN, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, (double)INFINITY, 100, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, tol, 0, out, &st) == -1);
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, tol, -5, out, &st) == -1);
    const enum restir_poisson_precond MG = RESTIR_POISSON_PRECOND_MULTIGRID;
    CHECK(restir_poisson_l1(PW, PH, NULL, dx, dy, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, NULL, dy, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, dx, NULL, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, 2, MG, 4, NULL, &st) == -1);
    CHECK(restir_poisson_l1(0, PH, primal, dx, dy, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, -3, primal, dx, dy, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(INT_MAX, 3, primal, dx, dy, 0.2f, 2, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, -1, MG, 4, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, 2, MG, 0, out, &st) == -1);
    CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, 2, (enum restir_poisson_precond)9, 4, out, &st) == -1);
    CHECK(all_equal(out, PN, 7.0f) && memcmp(&st, &st0, sizeof st) == 0);
    CHECK(isnan(restir_poisson_l1_energy(PW, PH, NULL, dx, dy, 0.2f, primal)));
    CHECK(isnan(restir_poisson_l1_energy(PW, PH, primal, NULL, dy, 0.2f, primal)));
    CHECK(isnan(restir_poisson_l1_energy(PW, PH, primal, dx, NULL, 0.2f, primal)));
    CHECK(isnan(restir_poisson_l1_energy(PW, PH, primal, dx, dy, 0.2f, NULL)));
    CHECK(isnan(restir_poisson_l1_energy(0, PH, primal, dx, dy, 0.2f, primal)));
    CHECK(isnan(restir_poisson_l1_energy(PW, -PH, primal, dx, dy, 0.2f, primal)));
    CHECK(isnan(restir_poisson_l1_energy(INT_MAX, INT_MAX, primal, dx, dy, 0.2f, primal)));

    /* Non-finite inputs read as 0: solves succeed with finite output (the DCT ones where librestir
     * has FFTW; without it they return -1 and leave out untouched). */
    primal[0] = NaN, primal[7] = INF, dx[3] = -INF, dy[10] = NaN, primal[12] = -5.0f;
    CHECK(restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, CG, tol, 1000, out, NULL) == 0 && all_finite(out, PN));
    fill(out, PN, 7.0f);
    int rc = restir_poisson_l2(PW, PH, primal, dx, dy, 0.2f, DCT, 0.0, 0, out, &st);
    CHECK(rc == 0 ? all_finite(out, PN) && st.iterations == 0 : rc == -1 && all_equal(out, PN, 7.0f));
    CHECK(restir_poisson_has_dct() == (rc == 0));
    CHECK(restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, RESTIR_POISSON_L1_MAX_ITERATIONS + 1, MG, 4, out, NULL) == -1);
    fill(out, PN, 7.0f);
    rc = restir_poisson_l1(PW, PH, primal, dx, dy, 0.2f, 3, MG, 4, out, NULL);
    CHECK(rc == 0 ? all_finite(out, PN) : rc == -1 && all_equal(out, PN, 7.0f));
    rc = restir_poisson_l1(1, 1, primal, dx, dy, 0.2f, 0, RESTIR_POISSON_PRECOND_JACOBI, 1, out, NULL);
    CHECK(rc == 0 ? isfinite(out[0]) : rc == -1);
    const double energy = restir_poisson_l1_energy(PW, PH, primal, dx, dy, 0.2f, primal);
    CHECK(isfinite(energy) && energy >= 0.0);
    restir_poisson_release_plans();
    restir_poisson_release_plans();

    const int before = restir_threads_get();
    CHECK(before >= 1);
    CHECK(restir_threads_set(-1) == -1 && restir_threads_set(INT_MIN) == -1 && restir_threads_get() == before);
    CHECK(restir_threads_set(1) == 0 && restir_threads_get() == 1);
    CHECK(restir_threads_set(0) == 0 && restir_threads_get() >= 1);
}

int main(void)
{
    /* Everything the library might print lands in `capture`, which must stay empty. */
    fflush(stdout);
    fflush(stderr);
    FILE *capture = tmpfile();
    const int saved_out = dup(1), saved_err = dup(2);
    if (!capture || saved_out < 0 || saved_err < 0 || dup2(fileno(capture), 1) < 0 || dup2(fileno(capture), 2) < 0) {
        fprintf(stderr, "api_contract: cannot redirect stdout and stderr\n");
        return 1;
    }
    test_hd_wrs_select();
    test_mis_gris();
    test_per_sample();
    test_cells();
    test_metrics();
    test_poisson_threads();
    fflush(stdout);
    fflush(stderr);
    dup2(saved_out, 1);
    dup2(saved_err, 2);
    close(saved_out);
    close(saved_err);
    const long printed = fseek(capture, 0, SEEK_END) == 0 ? ftell(capture) : -1;
    fclose(capture);
    check_at(printed == 0, __LINE__, "nothing written to stdout or stderr");

    if (failed) {
        printf("api_contract: %d of %d checks failed:\n%s", failed, checks, failures);
        if (printed > 0)
            printf("  (%ld bytes were written to stdout / stderr)\n", printed);
        return 1;
    }
    printf("api_contract: %d checks passed, nothing printed\n", checks);
    return 0;
}
