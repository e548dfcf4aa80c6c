/* test_neighbor_select.c: statistical and exact tests of compatibility-guided neighbor selection
 * (000 Sec. 4.3-5). Proves that:
 *  - restir_select with m = 1 (A-Chao) selects item i of a stream with probability w_i / sum w
 *    (chi-square over items, weights spanning five decades, zero and negative weights never
 *    selected);
 *  - with m > 1 (A-ES) it returns min(m, #positive) distinct positive-weight items, and the
 *    selected SET is distributed as successive weighted sampling without replacement: chi-square
 *    over all unordered pairs (m = 2) and triples (m = 3), plus m = 3 inclusion probabilities
 *    against an exact enumeration of ordered triples;
 *  - the chi-square has power: it rejects uniform selection, a product-proportional pair law and
 *    a naive "largest u w" sampler (negative controls);
 *  - restir_neighbors_compat matches a double evaluation of 000 Eq. 14-15 to 1e-5 relative;
 *  - r2_disk_offsets gives 8192 points in the unit disk whose radial and 16x16-cell counts are
 *    far closer to uniform than random points.
 * Fixed seeds; the chi-square family rejects a correct implementation with probability 0.01
 * (Sidak-corrected). Must never depend on Embree, files or render passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chi2_util.h"
#include "core/lowdisc.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "restir/neighbors.h"
#include "restir/select.h"
#include "test_util.h"

#define FAMILY_ALPHA 0.01
#define CONTROL_P 1e-6 /* negative controls must be rejected at least this strongly */
#define TRIALS 1000000
#define CONTROL_TRIALS 200000

/* A-Chao stream: weights over five decades, zero and negative weights interleaved. */
#define N1 12
static const float w1[N1] = {0.01f, 3.0f, 0.0f, 120.0f, 0.4f, -1.0f, 1000.0f, 7.0f, 0.0f, 25.0f, 0.05f, 2.0f};

/* A-ES m = 2 stream. */
#define N2 8
static const float w2[N2] = {0.02f, 1.0f, 0.0f, 5.0f, 0.3f, 40.0f, 0.0f, 2.5f};

/* A-ES m = 3 stream (offered in a fresh random order every trial); NPOS3 positive weights. */
#define N3 9
#define NPOS3 7
static const float w3[N3] = {0.5f, 0.0f, 8.0f, 1.0f, 0.1f, 20.0f, 0.0f, 3.0f, 2.0f};

/* Chi-square tests in the family: m = 1, m = 2 pairs, m = 3 triples, m = 3 inclusion per item. */
#define NUM_TESTS (3 + NPOS3)

static double alpha_i;

static double wsum(const float *w, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        if (w[i] > 0.0f)
            s += w[i];
    return s;
}

/* ---- 1. m = 1: A-Chao ---------------------------------------------------------------------- */

static void test_chao(void)
{
    double count[N1] = {0};
    long bad_count = 0, bad_item = 0;
    pcg32 rng = rng_for(11u, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct restir_select s;
        restir_select_init(&s, 1);
        for (int i = 0; i < N1; i++)
            restir_select_offer(&s, i, w1[i], pcg32_float(&rng));
        if (s.count != 1) {
            bad_count++;
            continue;
        }
        if (s.item[0] < 0 || s.item[0] >= N1) {
            bad_item++;
            continue;
        }
        count[s.item[0]] += 1.0;
    }
    EXPECT(bad_count == 0, "m = 1: count != 1 in %ld trials", bad_count);
    EXPECT(bad_item == 0, "m = 1: item index out of range in %ld trials", bad_item);

    double total = wsum(w1, N1), prob[N1], uniform[N1], obs[N1];
    int npos = 0;
    for (int i = 0; i < N1; i++) {
        if (!(w1[i] > 0.0f)) {
            EXPECT(count[i] == 0.0, "m = 1: weight %g item %d selected %.0f times", (double)w1[i], i, count[i]);
            continue;
        }
        prob[npos] = w1[i] / total;
        obs[npos] = count[i];
        printf("  m=1 item %2d (w %7.2f): freq %.6f expected %.6f\n", i, (double)w1[i], count[i] / TRIALS,
               prob[npos]);
        npos++;
    }
    int dof;
    double p = chi2_counts(obs, prob, npos, TRIALS, &dof);
    printf("m=1 A-Chao chi-square over %d items (%d trials): p = %.4f (dof %d, alpha %.3g)\n", npos, TRIALS,
           p, dof, alpha_i);
    EXPECT(p >= alpha_i, "m = 1 chi-square p %g < %g", p, alpha_i);

    /* Negative control: the same counts against uniform selection over the positive items. */
    for (int k = 0; k < npos; k++)
        uniform[k] = 1.0 / npos;
    double pc = chi2_counts(obs, uniform, npos, TRIALS, &dof);
    printf("  control: m=1 counts vs uniform selection: p = %.3g\n", pc);
    EXPECT(pc < CONTROL_P, "chi-square must reject uniform selection (p = %g)", pc);
    /* A subtler one: 2% of the heaviest item's probability moved to the second heaviest. */
    int top = 0, second;
    for (int k = 0; k < npos; k++)
        if (prob[k] > prob[top])
            top = k;
    second = top == 0 ? 1 : 0;
    for (int k = 0; k < npos; k++)
        if (k != top && prob[k] > prob[second])
            second = k;
    double shifted[N1];
    memcpy(shifted, prob, sizeof(double) * (size_t)npos);
    shifted[second] += 0.02 * shifted[top];
    shifted[top] *= 0.98;
    pc = chi2_counts(obs, shifted, npos, TRIALS, &dof);
    printf("  control: m=1 counts vs 2%% of the top probability moved: p = %.3g\n", pc);
    EXPECT(pc < CONTROL_P, "chi-square must reject a 2%% shift (p = %g)", pc);
}

/* ---- 2. m > 1: A-ES ------------------------------------------------------------------------ */

/* Validates one A-ES result: exact size, distinct items, positive weights only. Returns 0 if bad. */
static int valid_result(const struct restir_select *s, const float *w, int n, int want, long *bad_size,
                        long *bad_dup, long *bad_zero)
{
    if (s->count != want) {
        (*bad_size)++;
        return 0;
    }
    for (int a = 0; a < s->count; a++) {
        int ia = s->item[a];
        if (ia < 0 || ia >= n || !(w[ia] > 0.0f)) {
            (*bad_zero)++;
            return 0;
        }
        for (int b = 0; b < a; b++)
            if (s->item[b] == ia) {
                (*bad_dup)++;
                return 0;
            }
    }
    return 1;
}

static void sort_items(int *v, int k)
{
    for (int a = 1; a < k; a++)
        for (int b = a; b > 0 && v[b - 1] > v[b]; b--) {
            int t = v[b];
            v[b] = v[b - 1];
            v[b - 1] = t;
        }
}

/* Exact pair probability of successive weighted sampling without replacement. */
static double pair_prob(const float *w, double total, int i, int j)
{
    double wi = w[i], wj = w[j];
    return (wi / total) * (wj / (total - wi)) + (wj / total) * (wi / (total - wj));
}

/* Naive wrong rule: keep the two largest u * w (not u^(1/w)). */
static void naive_top2(const float *w, int n, pcg32 *rng, int out[2])
{
    float k0 = -1.0f, k1 = -1.0f;
    out[0] = out[1] = -1;
    for (int i = 0; i < n; i++) {
        if (!(w[i] > 0.0f))
            continue;
        float key = pcg32_float(rng) * w[i];
        if (key > k0) {
            k1 = k0;
            out[1] = out[0];
            k0 = key;
            out[0] = i;
        } else if (key > k1) {
            k1 = key;
            out[1] = i;
        }
    }
}

static void test_aes_pairs(void)
{
    static double count[N2 * N2];
    long bad_size = 0, bad_dup = 0, bad_zero = 0;
    pcg32 rng = rng_for(12u, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct restir_select s;
        restir_select_init(&s, 2);
        for (int i = 0; i < N2; i++)
            restir_select_offer(&s, i, w2[i], pcg32_float(&rng));
        if (!valid_result(&s, w2, N2, 2, &bad_size, &bad_dup, &bad_zero))
            continue;
        int v[2] = {s.item[0], s.item[1]};
        sort_items(v, 2);
        count[v[0] * N2 + v[1]] += 1.0;
    }
    EXPECT(bad_size == 0, "m = 2: wrong result size in %ld trials", bad_size);
    EXPECT(bad_dup == 0, "m = 2: duplicate items in %ld trials", bad_dup);
    EXPECT(bad_zero == 0, "m = 2: zero-weight or out-of-range item in %ld trials", bad_zero);

    double total = wsum(w2, N2), prob[N2 * N2], prod[N2 * N2], obs[N2 * N2], prod_sum = 0.0, psum = 0.0;
    int cells = 0;
    for (int i = 0; i < N2; i++)
        for (int j = i + 1; j < N2; j++) {
            if (!(w2[i] > 0.0f) || !(w2[j] > 0.0f))
                continue;
            prob[cells] = pair_prob(w2, total, i, j);
            prod[cells] = (double)w2[i] * w2[j];
            prod_sum += prod[cells];
            psum += prob[cells];
            obs[cells] = count[i * N2 + j];
            cells++;
        }
    EXPECT_NEAR(psum, 1.0, 1e-12, "pair probabilities sum to 1");
    int dof;
    double p = chi2_counts(obs, prob, cells, TRIALS, &dof);
    printf("m=2 A-ES chi-square over %d unordered pairs (%d trials): p = %.4f (dof %d, alpha %.3g)\n", cells,
           TRIALS, p, dof, alpha_i);
    EXPECT(p >= alpha_i, "m = 2 pair chi-square p %g < %g", p, alpha_i);

    /* Negative controls: a plausible wrong law (pair probability proportional to w_i w_j, i.e.
     * conditional Poisson sampling) against the same counts, and the naive sampler's counts
     * against the correct law. */
    for (int c = 0; c < cells; c++)
        prod[c] /= prod_sum;
    double pc = chi2_counts(obs, prod, cells, TRIALS, &dof);
    printf("  control: m=2 counts vs pair law proportional to w_i w_j: p = %.3g\n", pc);
    EXPECT(pc < CONTROL_P, "chi-square must reject the product pair law (p = %g)", pc);

    static double ncount[N2 * N2];
    pcg32 nrng = rng_for(13u, 0u, 0u, 0u);
    for (long t = 0; t < CONTROL_TRIALS; t++) {
        int v[2];
        naive_top2(w2, N2, &nrng, v);
        sort_items(v, 2);
        ncount[v[0] * N2 + v[1]] += 1.0;
    }
    cells = 0;
    for (int i = 0; i < N2; i++)
        for (int j = i + 1; j < N2; j++)
            if (w2[i] > 0.0f && w2[j] > 0.0f)
                obs[cells++] = ncount[i * N2 + j];
    pc = chi2_counts(obs, prob, cells, CONTROL_TRIALS, &dof);
    printf("  control: naive top-2 by u*w sampler (%d trials) vs exact pair law: p = %.3g\n", CONTROL_TRIALS,
           pc);
    EXPECT(pc < CONTROL_P, "chi-square must reject the naive u*w sampler (p = %g)", pc);
}

static void test_aes_triples(void)
{
    static double count[N3 * N3 * N3];
    double incl[N3] = {0};
    long bad_size = 0, bad_dup = 0, bad_zero = 0;
    pcg32 rng = rng_for(14u, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        int order[N3];
        for (int i = 0; i < N3; i++)
            order[i] = i;
        for (int i = N3 - 1; i > 0; i--) { /* Fisher-Yates: stream order must not matter */
            int j = (int)(pcg32_next(&rng) % (uint32_t)(i + 1));
            int tmp = order[i];
            order[i] = order[j];
            order[j] = tmp;
        }
        struct restir_select s;
        restir_select_init(&s, 3);
        for (int i = 0; i < N3; i++)
            restir_select_offer(&s, order[i], w3[order[i]], pcg32_float(&rng));
        if (!valid_result(&s, w3, N3, 3, &bad_size, &bad_dup, &bad_zero))
            continue;
        int v[3] = {s.item[0], s.item[1], s.item[2]};
        sort_items(v, 3);
        count[(v[0] * N3 + v[1]) * N3 + v[2]] += 1.0;
        for (int k = 0; k < 3; k++)
            incl[v[k]] += 1.0;
    }
    EXPECT(bad_size == 0, "m = 3: wrong result size in %ld trials", bad_size);
    EXPECT(bad_dup == 0, "m = 3: duplicate items in %ld trials", bad_dup);
    EXPECT(bad_zero == 0, "m = 3: zero-weight or out-of-range item in %ld trials", bad_zero);

    /* Exact law: sum over the 3! orders of successive-sampling probabilities. */
    static double exact[N3 * N3 * N3];
    double total = wsum(w3, N3), pincl[N3] = {0};
    for (int i = 0; i < N3; i++)
        for (int j = 0; j < N3; j++)
            for (int k = 0; k < N3; k++) {
                if (i == j || j == k || i == k || !(w3[i] > 0.0f) || !(w3[j] > 0.0f) || !(w3[k] > 0.0f))
                    continue;
                double wi = w3[i], wj = w3[j], wk = w3[k];
                double pr = (wi / total) * (wj / (total - wi)) * (wk / (total - wi - wj));
                int v[3] = {i, j, k};
                sort_items(v, 3);
                exact[(v[0] * N3 + v[1]) * N3 + v[2]] += pr;
                pincl[i] += pr; /* each ordered triple counts once for each member */
                pincl[j] += pr;
                pincl[k] += pr;
            }
    double prob[128], obs[128], psum = 0.0, isum = 0.0;
    int cells = 0;
    for (int i = 0; i < N3; i++)
        for (int j = i + 1; j < N3; j++)
            for (int k = j + 1; k < N3; k++) {
                if (!(w3[i] > 0.0f) || !(w3[j] > 0.0f) || !(w3[k] > 0.0f))
                    continue;
                prob[cells] = exact[(i * N3 + j) * N3 + k];
                obs[cells] = count[(i * N3 + j) * N3 + k];
                psum += prob[cells];
                cells++;
            }
    EXPECT_NEAR(psum, 1.0, 1e-12, "triple probabilities sum to 1");
    int dof;
    double p = chi2_counts(obs, prob, cells, TRIALS, &dof);
    printf("m=3 A-ES chi-square over %d unordered triples (%d trials, shuffled streams): p = %.4f (dof %d)\n",
           cells, TRIALS, p, dof);
    EXPECT(p >= alpha_i, "m = 3 triple chi-square p %g < %g", p, alpha_i);

    /* Inclusion probabilities: each is a binomial proportion; two-sided z-test per item. */
    for (int i = 0; i < N3; i++) {
        isum += pincl[i];
        if (!(w3[i] > 0.0f)) {
            EXPECT(incl[i] == 0.0, "m = 3: zero-weight item %d included %.0f times", i, incl[i]);
            continue;
        }
        double f = incl[i] / TRIALS, sigma = sqrt(pincl[i] * (1.0 - pincl[i]) / TRIALS);
        double z = (f - pincl[i]) / sigma, pz = erfc(fabs(z) / sqrt(2.0));
        printf("  m=3 item %d (w %5.2f): inclusion %.5f exact %.5f (%+.2f sigma, p = %.3f)\n", i, (double)w3[i],
               f, pincl[i], z, pz);
        EXPECT(pz >= alpha_i, "m = 3 inclusion of item %d: %.5f vs %.5f (p %g)", i, f, pincl[i], pz);
    }
    EXPECT_NEAR(isum, 3.0, 1e-12, "inclusion probabilities sum to m");
}

/* Fewer positive items than m, all-zero streams, and m clamped to [1, RESTIR_SELECT_MAX]. */
static void test_degenerate(void)
{
    static const float w[6] = {0.0f, 2.0f, -1.0f, 0.5f, 0.0f, 9.0f}; /* positive: 1, 3, 5 */
    pcg32 rng = rng_for(15u, 0u, 0u, 0u);
    long bad = 0;
    for (int m = 3; m <= RESTIR_SELECT_MAX; m++)
        for (int t = 0; t < 1000; t++) {
            struct restir_select s;
            restir_select_init(&s, m);
            for (int i = 0; i < 6; i++)
                restir_select_offer(&s, i, w[i], pcg32_float(&rng));
            if (s.count != 3) {
                bad++;
                continue;
            }
            int v[3] = {s.item[0], s.item[1], s.item[2]};
            sort_items(v, 3);
            if (v[0] != 1 || v[1] != 3 || v[2] != 5)
                bad++;
        }
    EXPECT(bad == 0, "m >= 3 over 3 positive items: result != {1, 3, 5} in %ld trials", bad);

    static const float one[5] = {0.0f, 0.0f, 4.0f, -3.0f, 0.0f};
    bad = 0;
    for (int m = 1; m <= 4; m++)
        for (int t = 0; t < 1000; t++) {
            struct restir_select s;
            restir_select_init(&s, m);
            for (int i = 0; i < 5; i++)
                restir_select_offer(&s, i, one[i], pcg32_float(&rng));
            if (s.count != 1 || s.item[0] != 2)
                bad++;
        }
    EXPECT(bad == 0, "a single positive item must be the whole result for every m (%ld bad)", bad);

    for (int m = 1; m <= 3; m++) {
        struct restir_select s;
        restir_select_init(&s, m);
        for (int i = 0; i < 5; i++)
            restir_select_offer(&s, i, i == 3 ? -2.0f : 0.0f, pcg32_float(&rng));
        EXPECT(s.count == 0, "m = %d: no positive weights must select nothing (count %d)", m, s.count);
    }
    /* u = 0 (key log 0 = -inf) must still fill a free slot and lose to any finite key. */
    {
        struct restir_select s;
        restir_select_init(&s, 2);
        restir_select_offer(&s, 0, 1.0f, 0.0f);
        restir_select_offer(&s, 1, 1.0f, 0.5f);
        EXPECT(s.count == 2, "u = 0 fills a free slot (count %d)", s.count);
        restir_select_offer(&s, 2, 1.0f, 0.25f);
        int v[2] = {s.item[0], s.item[1]};
        sort_items(v, 2);
        EXPECT(s.count == 2 && v[0] == 1 && v[1] == 2, "u = 0 item replaced first: {%d, %d}", v[0], v[1]);
    }

    struct restir_select s;
    restir_select_init(&s, 0);
    EXPECT(s.m == 1 && s.count == 0, "m = 0 clamps to 1 (m %d)", s.m);
    restir_select_init(&s, 100);
    EXPECT(s.m == RESTIR_SELECT_MAX, "m = 100 clamps to %d (m %d)", RESTIR_SELECT_MAX, s.m);
}

/* ---- 3. restir_neighbors_compat (000 Eq. 14-15) --------------------------------------------------- */

static double compat_ref(const float x[3], const float nx[3], float d, const float y[3], const float ny[3],
                         float omega, float beta)
{
    const double pi = 3.14159265358979323846;
    double dist = 0.0, dot = 0.0;
    for (int k = 0; k < 3; k++) {
        double e = (double)x[k] - (double)y[k];
        dist += e * e;
        dot += (double)nx[k] * (double)ny[k];
    }
    dist = sqrt(dist);
    double s = sqrt((double)omega * (double)d * (double)d / pi);
    return exp(-dist / s) * pow(dot > 0.0 ? dot : 0.0, (double)beta);
}

static void check_compat(const char *what, const float x[3], const float nx[3], float d, const float y[3],
                         const float ny[3], float omega, float beta, int print)
{
    double got = restir_neighbors_compat(x, nx, d, y, ny, omega, beta);
    double ref = compat_ref(x, nx, d, y, ny, omega, beta);
    if (print)
        printf("  compat %-34s got %.9g ref %.9g\n", what, got, ref);
    if (ref == 0.0)
        EXPECT(got == 0.0, "compat %s: %.9g, expected exactly 0", what, got);
    else
        EXPECT(fabs(got - ref) <= 1e-5 * ref, "compat %s: %.9g vs %.9g (rel %.3g)", what, got, ref,
               fabs(got - ref) / ref);
}

static void norm3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
}

static void test_compat(void)
{
    const float om = 0.05f, beta = 8.0f; /* the paper's values */
    float x[3] = {1.0f, 2.0f, 3.0f}, z[3] = {0.0f, 0.0f, 1.0f}, mz[3] = {0.0f, 0.0f, -1.0f};
    float xn[3] = {1.0f, 0.0f, 0.0f}, tilt[3] = {0.0f, 0.5f, 0.86602540378f};
    float nd[3] = {1.0f, 2.0f, 2.0f};
    norm3(nd);

    EXPECT(restir_neighbors_compat(x, z, 4.0f, x, z, om, beta) == 1.0f, "identical points and normals give 1 (%.9g)",
           (double)restir_neighbors_compat(x, z, 4.0f, x, z, om, beta));
    check_compat("identical, normal (1,2,2)/3", x, nd, 4.0f, x, nd, om, beta, 1);

    float y1[3] = {1.1f, 2.0f, 3.0f}; /* 0.1 away at d = 2: s = sqrt(0.05 * 4 / pi) = 0.2523 */
    check_compat("dist 0.1, d 2", x, z, 2.0f, y1, z, om, beta, 1);
    double s = sqrt(0.05 * 4.0 / 3.14159265358979323846);
    double ref = exp(-0.1 / s);
    double got = restir_neighbors_compat(x, z, 2.0f, y1, z, om, beta);
    EXPECT(fabs(got - ref) <= 1e-5 * ref, "exp(-0.1 / s): %.9g vs %.9g", got, ref);

    float y2[3] = {0.7f, 2.4f, 3.5f};
    check_compat("dist 0.71, d 10", x, z, 10.0f, y2, z, om, beta, 1);
    check_compat("dist 0.71, d 1.5", x, z, 1.5f, y2, z, om, beta, 1);
    check_compat("30 deg normals, same point", x, z, 3.0f, x, tilt, om, beta, 1);
    got = restir_neighbors_compat(x, z, 3.0f, x, tilt, om, beta);
    ref = pow(cos(3.14159265358979323846 / 6.0), 8.0);
    EXPECT(fabs(got - ref) <= 1e-5 * ref, "cos(30 deg)^8: %.9g vs %.9g", got, ref);
    check_compat("30 deg normals, dist 0.71, d 5", x, z, 5.0f, y2, tilt, om, beta, 1);
    check_compat("omega 0.2, beta 2", x, nd, 5.0f, y2, tilt, 0.2f, 2.0f, 1);
    check_compat("omega 0.01, beta 1", x, nd, 0.8f, y1, z, 0.01f, 1.0f, 1);
    check_compat("opposite normals", x, z, 3.0f, x, mz, om, beta, 1);
    check_compat("perpendicular normals", x, z, 3.0f, x, xn, om, beta, 1);
    float slightly_back[3] = {0.0f, 0.99f, -0.1f};
    norm3(slightly_back);
    check_compat("normals at 95.7 deg", x, z, 3.0f, y1, slightly_back, om, beta, 1);

    /* Random configurations with dist / s <= 8, n_x . n_y >= 0.3 and beta <= 9, so float rounding
     * of the dot product and of dist / s stays well under 1e-5 after the power and exp. */
    pcg32 rng = rng_for(16u, 0u, 0u, 0u);
    int tested = 0;
    while (tested < 2000) {
        float a[3], b[3], na[3], nb[3];
        for (int k = 0; k < 3; k++) {
            a[k] = 20.0f * pcg32_float(&rng) - 10.0f;
            b[k] = a[k] + 2.0f * pcg32_float(&rng) - 1.0f;
            na[k] = 2.0f * pcg32_float(&rng) - 1.0f;
            nb[k] = na[k] + 1.2f * pcg32_float(&rng) - 0.6f;
        }
        norm3(na);
        norm3(nb);
        float d = 0.5f + 30.0f * pcg32_float(&rng);
        float omega = 0.01f + 0.2f * pcg32_float(&rng);
        float be = 1.0f + 8.0f * pcg32_float(&rng);
        double dist = sqrt(((double)a[0] - b[0]) * ((double)a[0] - b[0]) + ((double)a[1] - b[1]) * ((double)a[1] - b[1]) +
                           ((double)a[2] - b[2]) * ((double)a[2] - b[2]));
        double sc = sqrt((double)omega * d * d / 3.14159265358979323846);
        double dot = (double)na[0] * nb[0] + (double)na[1] * nb[1] + (double)na[2] * nb[2];
        if (!isfinite(na[0]) || !isfinite(nb[0]) || dist / sc > 8.0 || dot < 0.3)
            continue;
        check_compat("random", a, na, d, b, nb, omega, be, 0);
        tested++;
    }
    printf("  compat: %d random configurations within 1e-5 relative\n", tested);
}

/* ---- 4. R2 disk offsets ---------------------------------------------------------------------- */

/* Max relative deviation from uniform over the 16x16 cells of [-1,1]^2 lying fully inside the
 * disk; writes the Pearson statistic and the number of cells. */
static double grid_deviation(const float *xy, int n, double *pearson, int *ncells)
{
    enum { G = 16 };
    double cnt[G * G] = {0};
    for (int i = 0; i < n; i++) {
        int cx = (int)((xy[2 * i] + 1.0f) * 0.5f * G), cy = (int)((xy[2 * i + 1] + 1.0f) * 0.5f * G);
        cx = cx < 0 ? 0 : (cx >= G ? G - 1 : cx);
        cy = cy < 0 ? 0 : (cy >= G ? G - 1 : cy);
        cnt[cy * G + cx] += 1.0;
    }
    const double h = 2.0 / G, expect = n * h * h / 3.14159265358979323846;
    double maxdev = 0.0;
    *pearson = 0.0;
    *ncells = 0;
    for (int cy = 0; cy < G; cy++)
        for (int cx = 0; cx < G; cx++) {
            double x0 = -1.0 + cx * h, y0 = -1.0 + cy * h;
            double fx = fmax(fabs(x0), fabs(x0 + h)), fy = fmax(fabs(y0), fabs(y0 + h));
            if (fx * fx + fy * fy > 1.0)
                continue; /* farthest corner outside the disk */
            double dev = fabs(cnt[cy * G + cx] - expect) / expect;
            if (dev > maxdev)
                maxdev = dev;
            *pearson += (cnt[cy * G + cx] - expect) * (cnt[cy * G + cx] - expect) / expect;
            (*ncells)++;
        }
    return maxdev;
}

static void test_r2_disk(void)
{
    static float xy[2 * R2_DISK_OFFSETS], head[2 * 100], rnd[2 * R2_DISK_OFFSETS];
    const int n = R2_DISK_OFFSETS;
    r2_disk_offsets(n, xy);
    r2_disk_offsets(100, head);
    EXPECT(memcmp(head, xy, sizeof head) == 0, "r2_disk_offsets(100) is a prefix of r2_disk_offsets(8192)");

    int outside = 0, nonfinite = 0, formula = 0;
    const double g = 1.32471795724474602596;
    for (int i = 0; i < n; i++) {
        float x = xy[2 * i], y = xy[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            nonfinite++;
        if ((double)x * x + (double)y * y > 1.0 + 1e-6)
            outside++;
        /* lowdisc.h's definition: frac(0.5 + i / g), frac(0.5 + i / g^2) through the concentric map */
        double u = 0.5 + i / g, v = 0.5 + i / (g * g);
        u -= floor(u);
        v -= floor(v);
        float ex, ey;
        warp_concentric_disk((float)u, (float)v, &ex, &ey);
        if (fabsf(ex - x) > 1e-6f || fabsf(ey - y) > 1e-6f)
            formula++;
    }
    EXPECT(nonfinite == 0, "%d non-finite offsets", nonfinite);
    EXPECT(outside == 0, "%d offsets outside the unit disk", outside);
    EXPECT(formula == 0, "%d offsets differ from the R2 + concentric-map definition", formula);

    pcg32 rng = rng_for(17u, 0u, 0u, 0u);
    for (int i = 0; i < n; i++)
        warp_concentric_disk(pcg32_float(&rng), pcg32_float(&rng), &rnd[2 * i], &rnd[2 * i + 1]);

    static const double radii[4] = {0.25, 0.5, 0.75, 0.9};
    for (int k = 0; k < 4; k++) {
        double r2 = radii[k] * radii[k];
        int in = 0, in_rnd = 0;
        for (int i = 0; i < n; i++) {
            in += (double)xy[2 * i] * xy[2 * i] + (double)xy[2 * i + 1] * xy[2 * i + 1] < r2;
            in_rnd += (double)rnd[2 * i] * rnd[2 * i] + (double)rnd[2 * i + 1] * rnd[2 * i + 1] < r2;
        }
        double f = (double)in / n, fr = (double)in_rnd / n;
        printf("  R2 disk: fraction inside r = %.2f: %.5f (r^2 = %.5f, error %+.5f; random points %+.5f)\n",
               radii[k], f, r2, f - r2, fr - r2);
        EXPECT(fabs(f - r2) <= 0.01, "fraction inside r = %.2f: %.5f vs %.5f", radii[k], f, r2);
    }

    double pearson, pearson_rnd;
    int cells, cells_rnd;
    double dev = grid_deviation(xy, n, &pearson, &cells);
    double dev_rnd = grid_deviation(rnd, n, &pearson_rnd, &cells_rnd);
    printf("  R2 disk: %d interior 16x16 cells (%.1f expected each): max relative deviation %.3f, Pearson "
           "%.1f; random points: %.3f, Pearson %.1f\n",
           cells, n * (2.0 / 16) * (2.0 / 16) / 3.14159265358979323846, dev, pearson, dev_rnd, pearson_rnd);
    EXPECT(dev < 0.3, "R2 disk grid max relative deviation %.3f >= 0.3", dev);
    /* Low discrepancy: the cell counts are far less dispersed than Poisson (Pearson ~ cells). */
    EXPECT(pearson < 0.5 * cells, "R2 disk grid Pearson %.1f not below half its %d cells", pearson, cells);
}

int main(void)
{
    alpha_i = chi2_sidak(FAMILY_ALPHA, NUM_TESTS);
    test_degenerate();
    test_chao();
    test_aes_pairs();
    test_aes_triples();
    test_compat();
    test_r2_disk();
    return test_finish();
}
