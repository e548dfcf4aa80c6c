/* test_wrs.c: statistical test of streaming weighted reservoir sampling and reservoir merging:
 * selection frequencies match w_i / sum w. Must never depend on Embree, files or the renderer. */
#include <math.h>

#include "core/rng.h"
#include "restir/gris.h"
#include "test_util.h"

#define NCAND 10
#define TRIALS 1000000

/* Varied weights, including ones that must never be selected: zero, NaN, +inf, negative. */
static float cand_weight(int i)
{
    static const float w[NCAND] = {1.0f, 2.5f, 0.0f, 4.0f, 0.0f, 1.5f, 3.0f, 0.8f, 0.0f, -2.0f};
    if (i == 4)
        return NAN;
    if (i == 8)
        return INFINITY;
    return w[i];
}

static double valid_sum(void)
{
    double s = 0.0;
    for (int i = 0; i < NCAND; i++) {
        float w = cand_weight(i);
        if (isfinite(w) && w > 0.0f)
            s += w;
    }
    return s;
}

static void check_frequencies(const long *count, const char *what)
{
    double total = valid_sum();
    for (int i = 0; i < NCAND; i++) {
        float w = cand_weight(i);
        if (!(isfinite(w) && w > 0.0f)) {
            EXPECT(count[i] == 0, "%s: invalid-weight candidate %d selected %ld times", what, i,
                   count[i]);
            continue;
        }
        double expect = (double)w / total;
        double freq = (double)count[i] / TRIALS;
        double sigma = sqrt(expect * (1.0 - expect) / TRIALS);
        printf("  %s cand %d: freq %.5f expected %.5f (%.2f sigma)\n", what, i, freq, expect,
               (freq - expect) / sigma);
        EXPECT(fabs(freq - expect) <= 0.03 * expect, "%s: candidate %d freq %.5f vs %.5f", what, i,
               freq, expect);
    }
}

/* Streaming WRS over one stream of NCAND candidates (Chao 1982, 004 Sec. 2.2). */
static void test_streaming(void)
{
    long count[NCAND] = {0};
    int mismatch = 0, bad_sum = 0, bad_offered = 0;
    pcg32 rng = rng_for(1u, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct restir_reservoir r;
        restir_reservoir_init(&r);
        int kept = -1; /* what the caller stores when offer returns 1 */
        for (int i = 0; i < NCAND; i++)
            if (restir_reservoir_offer(&r, cand_weight(i), pcg32_float(&rng)))
                kept = i;
        if (kept != r.selected)
            mismatch++;
        if (r.selected >= 0)
            count[r.selected]++;
        if (fabs(r.w_sum - valid_sum()) > 1e-5)
            bad_sum++;
        if (r.offered != NCAND)
            bad_offered++;
    }
    EXPECT(mismatch == 0, "returned winner differs from selected index %d times", mismatch);
    EXPECT(bad_sum == 0, "w_sum polluted by invalid weights %d times", bad_sum);
    EXPECT(bad_offered == 0, "offered count wrong %d times", bad_offered);
    check_frequencies(count, "stream");
}

/* Merge tree: 4 independent sub-reservoirs over consecutive slices of the stream, merged
 * ((r0 + r1) + (r2 + r3)); b's stream counts as appended after a's, so indices stay global. */
static void test_merge_tree(void)
{
    static const int start[5] = {0, 3, 5, 8, NCAND};
    long count[NCAND] = {0};
    int mismatch = 0, bad_offered = 0;
    pcg32 rng = rng_for(2u, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct restir_reservoir sub[4];
        int kept[4];
        for (int s = 0; s < 4; s++) {
            restir_reservoir_init(&sub[s]);
            kept[s] = -1;
            for (int i = start[s]; i < start[s + 1]; i++)
                if (restir_reservoir_offer(&sub[s], cand_weight(i), pcg32_float(&rng)))
                    kept[s] = i; /* the caller's stored sample, as a global index */
        }
        int left = kept[0], right = kept[2];
        if (restir_reservoir_merge(&sub[0], &sub[1], pcg32_float(&rng)))
            left = kept[1];
        if (restir_reservoir_merge(&sub[2], &sub[3], pcg32_float(&rng)))
            right = kept[3];
        int final = left;
        if (restir_reservoir_merge(&sub[0], &sub[2], pcg32_float(&rng)))
            final = right;
        if (final != sub[0].selected)
            mismatch++;
        if (sub[0].offered != NCAND)
            bad_offered++;
        if (final >= 0)
            count[final]++;
    }
    EXPECT(mismatch == 0, "merged selection index differs from stored sample %d times", mismatch);
    EXPECT(bad_offered == 0, "merged offered count wrong %d times", bad_offered);
    check_frequencies(count, "merge");
}

static void test_edge_cases(void)
{
    struct restir_reservoir r, e;
    restir_reservoir_init(&r);
    EXPECT(r.selected == -1 && r.offered == 0 && r.w_sum == 0.0f, "init");
    EXPECT(restir_gris_contribution_weight(&r, 1.0f) == 0.0f, "W = 0 when nothing selected");
    EXPECT(restir_reservoir_offer(&r, 0.6f, 0.999f) == 1, "a single valid candidate is always taken");
    /* 004 Eq. 7 with one candidate: W = w / p_hat */
    EXPECT_NEAR(restir_gris_contribution_weight(&r, 0.3f), 0.6 / 0.3, 1e-6, "single-candidate W");
    EXPECT(restir_gris_contribution_weight(&r, 0.0f) == 0.0f, "W = 0 when target is 0");
    EXPECT(restir_gris_contribution_weight(&r, -1.0f) == 0.0f, "W = 0 when target is negative");

    /* merging an empty reservoir changes nothing but the offered count */
    restir_reservoir_init(&e);
    e.offered = 3;
    EXPECT(restir_reservoir_merge(&r, &e, 0.0f) == 0, "empty b never wins");
    EXPECT(r.selected == 0 && r.offered == 4 && r.w_sum == 0.6f, "merge of empty b");
    /* merging into an empty reservoir always takes b */
    struct restir_reservoir a;
    restir_reservoir_init(&a);
    a.offered = 2;
    EXPECT(restir_reservoir_merge(&a, &r, 0.999f) == 1, "empty a always takes b");
    EXPECT(a.selected == 2 && a.offered == 6 && a.w_sum == 0.6f, "b's index offset by a.offered");

    EXPECT(restir_gris_confidence_merge(7.0f, 20.0f) == 7.0f, "confidence below cap");
    EXPECT(restir_gris_confidence_merge(27.0f, 20.0f) == 20.0f, "confidence capped");
    EXPECT(restir_gris_confidence_merge(27.0f, 0.0f) == 27.0f, "cap <= 0 means uncapped");
}

int main(void)
{
    test_edge_cases();
    test_streaming();
    test_merge_tree();
    return test_finish();
}
