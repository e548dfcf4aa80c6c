/* test_mis.c: unit tests of resampling MIS weights: partition of unity (004 Eq. 8), zero
 * denominators, entries each mode reads, name parsing. Must never depend on Embree or files. */
#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "restir/mis.h"
#include "test_util.h"

#define MAXN 16

/* Evaluates every domain's weight at ONE common point y: with Y_j = y for all j, column j of the
 * target matrix is the same vector q[k] = p_hat_{<-k}(y), so m[j] = m_j(y) for every j and the
 * weights of all domains at y can be summed to check 004 Eq. 8. */
static double weights_at_common_y(enum restir_mis mode, int n, const float *c, const float *q,
                                  float *m)
{
    float p[MAXN * MAXN] = {0};
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            p[k * n + j] = q[k];
    restir_mis_weights(mode, n, c, p, m);
    double sum = 0.0;
    for (int j = 0; j < n; j++)
        sum += m[j];
    return sum;
}

static void test_partition_of_unity(void)
{
    pcg32 rng = pcg32_make(12345u, 7u);
    int bad_bal = 0, bad_pw = 0, bad_uni = 0, bad_range = 0, bad_unreach = 0;
    for (int trial = 0; trial < 20000; trial++) {
        int n = 1 + (int)(pcg32_next(&rng) % MAXN);
        float c[MAXN], q[MAXN], m[MAXN];
        for (int k = 0; k < n; k++) {
            c[k] = 0.5f + 30.0f * pcg32_float(&rng);
            if (pcg32_float(&rng) < 0.2f)
                c[k] = (float)(1 + pcg32_next(&rng) % 20); /* integer confidences 1..20 */
            /* about a third of the domains cannot produce y (shift failed / zero target) */
            q[k] = pcg32_float(&rng) < 0.35f ? 0.0f : 1e-3f + 5.0f * pcg32_float(&rng);
        }
        q[0] = 1e-3f + 5.0f * pcg32_float(&rng); /* y in supp p_hat (canonical target > 0) */
        double s;
        s = weights_at_common_y(RESTIR_MIS_BALANCE, n, c, q, m);
        if (fabs(s - 1.0) > 1e-5)
            bad_bal++;
        for (int j = 0; j < n; j++) {
            if (!(m[j] >= 0.0f && m[j] <= 1.0f + 1e-6f))
                bad_range++;
            if (q[j] == 0.0f && m[j] != 0.0f)
                bad_unreach++; /* Eq. 8: m_i(y) = 0 when y cannot come from domain i */
        }
        s = weights_at_common_y(RESTIR_MIS_PAIRWISE, n, c, q, m);
        if (fabs(s - 1.0) > 1e-5)
            bad_pw++;
        for (int j = 0; j < n; j++) {
            if (!(m[j] >= 0.0f && m[j] <= 1.0f + 1e-6f))
                bad_range++;
            if (q[j] == 0.0f && m[j] != 0.0f)
                bad_unreach++;
        }
        s = weights_at_common_y(RESTIR_MIS_UNIFORM, n, c, q, m);
        if (fabs(s - 1.0) > 1e-5)
            bad_uni++;
    }
    EXPECT(bad_bal == 0, "balance weights not summing to 1 in %d cases", bad_bal);
    EXPECT(bad_pw == 0, "pairwise weights not summing to 1 in %d cases", bad_pw);
    EXPECT(bad_uni == 0, "1/M weights not summing to 1 in %d cases", bad_uni);
    EXPECT(bad_range == 0, "%d weights outside [0,1]", bad_range);
    EXPECT(bad_unreach == 0, "%d nonzero weights for domains that cannot produce y", bad_unreach);
}

/* Hand-computed values for a 3-domain merge with distinct samples Y_0, Y_1, Y_2. */
static void test_known_values(void)
{
    const float c[3] = {1.0f, 2.0f, 3.0f};
    /* p[k*3+j] = p_hat_{<-k}(Y_j) */
    const float p[9] = {2.0f, 1.0f, 4.0f, /* k = 0 */
                        1.0f, 3.0f, 0.0f, /* k = 1 */
                        0.5f, 2.0f, 1.0f}; /* k = 2 */
    float m[3];
    restir_mis_weights(RESTIR_MIS_BALANCE, 3, c, p, m);
    /* Eq. 9: m_0 = 1*2 / (1*2 + 2*1 + 3*0.5) ; m_1 = 2*3 / (1*1 + 2*3 + 3*2) ; m_2 = 3*1/(4+0+3) */
    EXPECT_NEAR(m[0], 2.0 / 5.5, 1e-6, "balance m_0");
    EXPECT_NEAR(m[1], 6.0 / 13.0, 1e-6, "balance m_1");
    EXPECT_NEAR(m[2], 3.0 / 7.0, 1e-6, "balance m_2");

    restir_mis_weights(RESTIR_MIS_PAIRWISE, 3, c, p, m);
    /* Eq. 11-12 with c_S = 5, c_0 = 1, c_S + c_0 = 6 */
    double m1 = (5.0 / 6.0) * 2.0 * 3.0 / (5.0 * 3.0 + 1.0 * 1.0);
    double m2 = (5.0 / 6.0) * 3.0 * 1.0 / (5.0 * 1.0 + 1.0 * 4.0);
    double m0 = 1.0 / 6.0 + (2.0 / 6.0) * 1.0 * 2.0 / (5.0 * 1.0 + 1.0 * 2.0) +
                (3.0 / 6.0) * 1.0 * 2.0 / (5.0 * 0.5 + 1.0 * 2.0);
    EXPECT_NEAR(m[0], m0, 1e-6, "pairwise m_0");
    EXPECT_NEAR(m[1], m1, 1e-6, "pairwise m_1");
    EXPECT_NEAR(m[2], m2, 1e-6, "pairwise m_2");

    restir_mis_weights(RESTIR_MIS_UNIFORM, 3, c, p, m);
    EXPECT_NEAR(m[0], 1.0 / 6.0, 1e-7, "1/M m_0");
    EXPECT_NEAR(m[1], 2.0 / 6.0, 1e-7, "1/M m_1");
    EXPECT_NEAR(m[2], 3.0 / 6.0, 1e-7, "1/M m_2");

    /* equal confidences and targets, c_S = 3, c_0 = 1: Eq. 11a gives (3/4) / 4 = 3/16 to each
     * non-canonical, Eq. 11b gives the canonical 1/4 + 3 (1/4)(1/4) = 7/16 (defensive, not 1/M) */
    const float c1[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    float q1[16];
    for (int i = 0; i < 16; i++)
        q1[i] = 0.7f;
    float mm[4];
    restir_mis_weights(RESTIR_MIS_PAIRWISE, 4, c1, q1, mm);
    EXPECT_NEAR(mm[0], 7.0 / 16.0, 1e-6, "pairwise canonical with equal targets");
    for (int j = 1; j < 4; j++)
        EXPECT_NEAR(mm[j], 3.0 / 16.0, 1e-6, "pairwise non-canonical with equal targets");
}

/* Entries a mode does not need must never be read: poison them with NaN. */
static void test_needs_and_unread_entries(void)
{
    enum { N = 5 };
    const float c[N] = {2.0f, 1.0f, 5.0f, 20.0f, 1.0f};
    pcg32 rng = pcg32_make(99u, 3u);
    for (int mode = RESTIR_MIS_UNIFORM; mode <= RESTIR_MIS_PAIRWISE_TILED; mode++) {
        float p[N * N], m[N];
        for (int k = 0; k < N; k++)
            for (int j = 0; j < N; j++)
                p[k * N + j] = restir_mis_needs((enum restir_mis)mode, k, j)
                                   ? 0.1f + pcg32_float(&rng)
                                   : NAN;
        restir_mis_weights((enum restir_mis)mode, N, c, p, m);
        int finite = 1;
        for (int j = 0; j < N; j++)
            finite &= isfinite(m[j]) != 0;
        EXPECT(finite, "mode %s read an entry it declared unneeded",
               restir_mis_name((enum restir_mis)mode));
    }
    int count_pw = 0, count_bal = 0, count_uni = 0;
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++) {
            count_pw += restir_mis_needs(RESTIR_MIS_PAIRWISE, k, j);
            count_bal += restir_mis_needs(RESTIR_MIS_BALANCE, k, j);
            count_uni += restir_mis_needs(RESTIR_MIS_UNIFORM, k, j);
        }
    EXPECT(count_pw == 3 * N - 2, "pairwise needs O(M) entries: %d", count_pw);
    EXPECT(count_bal == N * N, "balance needs all entries: %d", count_bal);
    EXPECT(count_uni == 0, "1/M needs no entries: %d", count_uni);
    const enum restir_mis pw = RESTIR_MIS_PAIRWISE;
    EXPECT(restir_mis_needs(pw, 2, 2) && restir_mis_needs(pw, 0, 3) && restir_mis_needs(pw, 3, 0) &&
               !restir_mis_needs(pw, 1, 2),
           "pairwise needs (j,j), (0,j), (j,0) only");
}

static void test_zero_denominators(void)
{
    float m[4];
    /* n == 1: only the canonical */
    const float c1[1] = {3.0f};
    const float p1[1] = {0.0f};
    for (int mode = RESTIR_MIS_UNIFORM; mode <= RESTIR_MIS_PAIRWISE; mode++) {
        restir_mis_weights((enum restir_mis)mode, 1, c1, p1, m);
        EXPECT(m[0] == 1.0f, "n == 1 gives m_0 = 1 (%s): %g",
               restir_mis_name((enum restir_mis)mode), (double)m[0]);
    }

    /* Y_1 outside every domain's support: column 1 all zero */
    const float c[3] = {1.0f, 4.0f, 2.0f};
    const float p[9] = {1.0f, 0.0f, 0.5f, /* k = 0 */
                        2.0f, 0.0f, 0.0f, /* k = 1 */
                        0.0f, 0.0f, 3.0f}; /* k = 2 */
    restir_mis_weights(RESTIR_MIS_BALANCE, 3, c, p, m);
    EXPECT(m[1] == 0.0f, "balance with zero denominator gives 0: %g", (double)m[1]);
    EXPECT(isfinite(m[0]) && isfinite(m[2]), "balance finite elsewhere");
    restir_mis_weights(RESTIR_MIS_PAIRWISE, 3, c, p, m);
    EXPECT(m[1] == 0.0f, "pairwise 11a with zero denominator gives 0: %g", (double)m[1]);
    /* Eq. 11b pair term for j = 2 has p_hat_{<-2}(Y_0) = 0: it reduces to c_2/(c_S+c_0) */
    double m0 = 1.0 / 7.0 + (4.0 / 7.0) * 1.0 / (6.0 * 2.0 + 1.0) + (2.0 / 7.0) * 1.0;
    EXPECT_NEAR(m[0], m0, 1e-6, "pairwise m_0 with a non-canonical that cannot reach Y_0");
    EXPECT_NEAR(m[2], (6.0 / 7.0) * 2.0 * 3.0 / (6.0 * 3.0 + 0.5), 1e-6, "pairwise m_2");

    /* canonical sample with p_hat(Y_0) = 0 and a non-canonical that cannot reach Y_0 either:
     * 0/0 pair terms contribute 0, the defensive share c_0/(c_S+c_0) remains, all finite */
    const float pz[4] = {0.0f, 1.0f, 0.0f, 2.0f};
    const float cz[2] = {1.0f, 3.0f};
    restir_mis_weights(RESTIR_MIS_PAIRWISE, 2, cz, pz, m);
    EXPECT(isfinite(m[0]) && isfinite(m[1]), "pairwise finite with p_hat(Y_0) = 0");
    EXPECT_NEAR(m[0], 0.25, 1e-7, "pairwise m_0 with p_hat(Y_0) = 0: only its defensive share");
    EXPECT_NEAR(m[1], 0.75 * 3.0 * 2.0 / (3.0 * 2.0 + 1.0 * 1.0), 1e-6, "pairwise m_1");
    restir_mis_weights(RESTIR_MIS_BALANCE, 2, cz, pz, m);
    EXPECT(m[0] == 0.0f, "balance m_0 with all-zero column is 0: %g", (double)m[0]);

    /* all confidences zero: no NaN */
    const float c0[3] = {0.0f, 0.0f, 0.0f};
    restir_mis_weights(RESTIR_MIS_PAIRWISE, 3, c0, p, m);
    EXPECT(m[0] == 1.0f && m[1] == 0.0f && m[2] == 0.0f, "pairwise zero confidence -> canonical");
    restir_mis_weights(RESTIR_MIS_UNIFORM, 3, c0, p, m);
    EXPECT_NEAR(m[0] + m[1] + m[2], 1.0, 1e-6, "1/M zero confidence still sums to 1");
    restir_mis_weights(RESTIR_MIS_BALANCE, 3, c0, p, m);
    EXPECT(m[0] == 0.0f && m[1] == 0.0f && m[2] == 0.0f, "balance zero confidence -> 0");
}

/* Pairwise MIS over tiling domains: at a point y that the canonical and exactly one other domain r
 * reach (every other p_hat_{<-k}(y) = 0), the weights of 0 and r sum to one and equal the two-domain
 * pairwise weights; where r's target is zero too, the canonical takes everything. */
static void test_pairwise_tiled(void)
{
    pcg32 rng = pcg32_make(777u, 5u);
    int bad_sum = 0, bad_two = 0, bad_zero = 0;
    for (int trial = 0; trial < 20000; trial++) {
        const int n = 2 + (int)(pcg32_next(&rng) % 4); /* canonical and 1..4 previous pixels */
        const int r = 1 + (int)(pcg32_next(&rng) % (uint32_t)(n - 1));
        float c[MAXN], q[MAXN] = {0}, m[MAXN];
        for (int k = 0; k < n; k++)
            c[k] = 0.5f + 20.0f * pcg32_float(&rng);
        q[0] = 1e-3f + 5.0f * pcg32_float(&rng);
        q[r] = pcg32_float(&rng) < 0.2f ? 0.0f : 1e-3f + 5.0f * pcg32_float(&rng);
        double s = weights_at_common_y(RESTIR_MIS_PAIRWISE_TILED, n, c, q, m);
        if (fabs(s - 1.0) > 1e-5)
            bad_sum++;
        for (int k = 1; k < n; k++)
            bad_zero += k != r && m[k] != 0.0f;
        const float c2[2] = {c[0], c[r]}, q2[2] = {q[0], q[r]};
        float m2[2];
        weights_at_common_y(RESTIR_MIS_PAIRWISE, 2, c2, q2, m2);
        if (fabs((double)m[0] - (double)m2[0]) > 1e-6 || fabs((double)m[r] - (double)m2[1]) > 1e-6)
            bad_two++;
        if (q[r] == 0.0f && m[0] != 1.0f)
            bad_two++;
    }
    EXPECT(bad_sum == 0, "pairwise-tiled weights not summing to 1 in %d cases", bad_sum);
    EXPECT(bad_zero == 0, "pairwise-tiled gave weight to %d domains that cannot reach y", bad_zero);
    EXPECT(bad_two == 0, "pairwise-tiled differs from two-domain pairwise in %d cases", bad_two);
    /* hand-computed: c = (1, 3, 2), Y_0 reached by domain 2 only (p_hat_{<-2}(Y_0) = 4, p_hat(Y_0) = 2);
     * Y_1 with p_hat_{<-1}(Y_1) = 1, p_hat(Y_1) = 3; Y_2 with p_hat_{<-2}(Y_2) = 5, p_hat(Y_2) = 1 */
    const float c[3] = {1.0f, 3.0f, 2.0f};
    const float p[9] = {2.0f, 3.0f, 1.0f, /* k = 0 */
                        0.0f, 1.0f, NAN,  /* k = 1 (entry (1,2) must not be read) */
                        4.0f, NAN, 5.0f}; /* k = 2 */
    float m[3];
    restir_mis_weights(RESTIR_MIS_PAIRWISE_TILED, 3, c, p, m);
    EXPECT_NEAR(m[0], 1.0 / 3.0 + (2.0 / 3.0) * 2.0 / (2.0 * 4.0 + 2.0), 1e-6, "tiled m_0");
    EXPECT_NEAR(m[1], (3.0 / 4.0) * 3.0 / (3.0 + 3.0), 1e-6, "tiled m_1");
    EXPECT_NEAR(m[2], (2.0 / 3.0) * 10.0 / (10.0 + 1.0), 1e-6, "tiled m_2");
}

static void test_parse_name(void)
{
    enum restir_mis mode;
    const char *names[] = {"1/M", "balance", "pairwise"};
    for (int i = 0; i < 3; i++) {
        EXPECT(restir_mis_parse(names[i], &mode) == 0, "parse %s", names[i]);
        EXPECT(strcmp(restir_mis_name(mode), names[i]) == 0, "round trip %s -> %s", names[i],
               restir_mis_name(mode));
    }
    for (int i = RESTIR_MIS_UNIFORM; i <= RESTIR_MIS_PAIRWISE; i++) {
        EXPECT(restir_mis_parse(restir_mis_name((enum restir_mis)i), &mode) == 0 && (int)mode == i,
               "name/parse round trip of mode %d", i);
    }
    EXPECT(restir_mis_parse("uniform", &mode) == 0 && mode == RESTIR_MIS_UNIFORM, "uniform alias");
    EXPECT(restir_mis_parse("Balance", &mode) == -1, "names are case sensitive");
    EXPECT(restir_mis_parse("", &mode) == -1, "empty name rejected");
    EXPECT(restir_mis_parse("talbot", &mode) == -1, "unknown name rejected");
    EXPECT(restir_mis_parse("pairwise-tiled", &mode) == -1, "the tiled mode is not a user's choice");
}

int main(void)
{
    test_partition_of_unity();
    test_known_values();
    test_needs_and_unread_entries();
    test_zero_denominators();
    test_pairwise_tiled();
    test_parse_name();
    return test_finish();
}
