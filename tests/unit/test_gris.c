/* test_gris.c: restir_gris_resample (restir/gris.h), the resampling step every merge ends in:
 *  - it chooses sample j with probability w_j / sum w, w_j = m_j P[j] W[j] J[j] (a chi-square test
 *    over 200000 draws of u, with the MIS weights of each mode from restir_mis_weights);
 *  - a sample with J <= 0 (did not shift in) is never chosen, whatever its other entries;
 *  - W_Y = sum w / P[chosen] (004 Eq. 7), and -1 with W_Y = 0 when no weight is positive. */
#include <math.h>

#include "core/rng.h"
#include "restir/gris.h"
#include "test_util.h"

static void check_mode(enum restir_mis mode)
{
    enum { N = 4 };
    const float c[N] = {4.0f, 1.0f, 2.0f, 3.0f};
    /* P[k * N + j] = p_hat_{<-k}(Y_j): row 0 the canonical domain's targets */
    float P[N * N];
    for (int k = 0; k < N; k++)
        for (int j = 0; j < N; j++)
            P[k * N + j] = 0.5f + 0.25f * (float)((k + 2 * j) % 5);
    const float W[N] = {1.5f, 0.7f, 2.0f, 9.0f}, J[N] = {1.0f, 0.8f, 1.3f, 0.0f};
    float m[N];
    restir_mis_weights(mode, N, c, P, m);
    double w[N], sum = 0.0;
    for (int j = 0; j < N; j++) {
        w[j] = J[j] > 0.0f ? (double)m[j] * P[j] * W[j] * J[j] : 0.0;
        sum += w[j];
    }
    long count[N] = {0};
    const long draws = 200000;
    pcg32 rng = pcg32_make(7, 11);
    for (long t = 0; t < draws; t++) {
        float u[N], W_Y;
        for (int j = 0; j < N; j++)
            u[j] = pcg32_float(&rng);
        const int chosen = restir_gris_resample(mode, N, c, P, W, J, u, &W_Y);
        EXPECT(chosen >= 0 && chosen < N - 1, "%s: chose %d (sample 3 did not shift in)", restir_mis_name(mode), chosen);
        if (chosen < 0 || chosen >= N)
            continue;
        count[chosen]++;
        if (t < 1000)
            EXPECT(fabs(W_Y - sum / P[chosen]) <= 1e-5 * (sum / P[chosen]), "%s: W_Y %g, expected %g",
                   restir_mis_name(mode), W_Y, sum / P[chosen]);
    }
    double chi2 = 0.0;
    for (int j = 0; j < N - 1; j++) {
        const double e = draws * w[j] / sum;
        chi2 += (count[j] - e) * (count[j] - e) / e;
    }
    /* 2 degrees of freedom: P(chi2 > 18.4) = 1e-4 */
    EXPECT(chi2 < 18.4, "%s: chi-square %.2f of the choice frequencies", restir_mis_name(mode), chi2);
    printf("%s: choices %ld %ld %ld %ld of %ld, chi-square %.2f (2 dof)\n", restir_mis_name(mode), count[0], count[1],
           count[2], count[3], draws, chi2);
}

int main(void)
{
    check_mode(RESTIR_MIS_UNIFORM);
    check_mode(RESTIR_MIS_BALANCE);
    check_mode(RESTIR_MIS_PAIRWISE);
    const float c[2] = {1.0f, 1.0f}, P[4] = {0.0f, 0.0f, 0.0f, 0.0f}, W[2] = {1.0f, 1.0f}, J[2] = {1.0f, 1.0f};
    const float u[2] = {0.5f, 0.5f};
    float W_Y = 1.0f;
    EXPECT(restir_gris_resample(RESTIR_MIS_PAIRWISE, 2, c, P, W, J, u, &W_Y) == -1 && W_Y == 0.0f,
           "zero targets: nothing chosen, W_Y = 0");
    return test_finish();
}
