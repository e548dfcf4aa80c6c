/* test_splat_mis.c: the resampling MIS of reservoir splatting combined with backprojection
 * (temporal.reuse=both, docs/RESTIR_PT.md) on a 1-D domain where every density is known.
 *
 * Model: pixels [j, j+1), j = 0..P-1. The previous frame holds in every pixel q an independent RIS
 * reservoir: X_q from M_q = 1 + q % 3 uniform candidates with target p_prev, its unbiased
 * contribution weight W_q, confidence c_q = M_q. Camera motion is the bijection
 * T(x) = a x + b + e sin(x) (the primary hit projected into the new camera), |T'| its Jacobian.
 * The current pixel p integrates I_p = int_p f. Techniques proposing paths to p:
 *  - canonical: Y_0 by RIS from 2 uniform candidates with target f, confidence c_0 = 1;
 *  - splat: every previous X_q with T(X_q) in p, with W_q and |T'(X_q)|; a path y can come only
 *    from q*(y) = floor(T^{-1}(y)), with density p_hat_s(y) = p_prev(T^{-1} y) / |T'(T^{-1} y)|;
 *  - backprojection: the previous pixel q_b = floor(T^{-1}(p + 1/2)) shifted by the translation
 *    S(x) = x + p - q_b (|S'| = 1), density p_hat_b(y) = p_prev(S^{-1} y).
 * Balance weights (004 Eq. 9) with c_s = c_{q*(y)} / 2, c_b = c_{q_b} / 2; resampling weights
 * w = m f W |J| (004 Eq. 6); the GRIS estimate is f(Y) W_Y = sum of w (004 Eq. 7).
 * Checks: the three weights sum to 1; the splat technique alone, sum over landed q of
 * f(T X_q) W_q |T'(X_q)|, estimates I_p (the proposal density it assigns is right); the merged
 * estimator is unbiased for two pixels; and it has power: leaving the splat's Jacobian out of its
 * resampling weight, or 1/M weights, are caught. Deterministic seeds. */
#include <math.h>
#include <stdio.h>

#include "core/rng.h"
#include "restir/reservoir.h"
#include "test_util.h"

#define P 8
#define TRIALS 400000

static const double A = 1.15, B = -0.4, E = 0.05;

static double f(double y) { return 1.0 + y / 4.0 + 0.3 * cos(5.0 * y); }
static double p_prev(double x) { return 1.0 + 0.5 * sin(3.0 * x); }
static double T(double x) { return A * x + B + E * sin(x); }
static double dT(double x) { return A + E * cos(x); }

static double T_inverse(double y)
{
    double x = (y - B) / A;
    for (int k = 0; k < 6; k++) /* Newton: quadratic, |T' - A| <= E */
        x -= (T(x) - y) / dT(x);
    return x;
}

static double integral(double lo, double hi)
{
    const int n = 20000;
    double s = 0.0, h = (hi - lo) / n;
    for (int k = 0; k < n; k++)
        s += f(lo + (k + 0.5) * h);
    return s * h;
}

/* RIS in [lo, lo + 1) from m uniform candidates with target g: the sample and its W. */
static double ris(pcg32 *rng, double lo, int m, double (*g)(double), double *W)
{
    struct restir_wrs wrs;
    restir_wrs_init(&wrs);
    double chosen = lo;
    for (int k = 0; k < m; k++) {
        double x = lo + pcg32_float(rng);
        if (restir_wrs_offer(&wrs, (float)(g(x) / m), pcg32_float(rng)))
            chosen = x;
    }
    *W = restir_gris_contribution_weight(&wrs, (float)g(chosen));
    return chosen;
}

enum mode { EXACT, NO_SPLAT_JACOBIAN, UNIFORM };

struct terms {
    double c0, cb;
    int p, qb;
    const double *c_prev;
};

/* c_t p_hat_t(y) of the three techniques at y. */
static void technique_terms(const struct terms *t, double y, double out[3])
{
    double xs = T_inverse(y);
    int qs = (int)floor(xs);
    out[0] = t->c0 * f(y);
    out[1] = qs >= 0 && qs < P ? 0.5 * t->c_prev[qs] * p_prev(xs) / dT(xs) : 0.0;
    out[2] = t->cb * p_prev(y - (t->p - t->qb));
}

struct estimate {
    double merged, splat_only;
};

static struct estimate trial(pcg32 *rng, int p, enum mode mode)
{
    double X[P], W[P], c[P];
    for (int q = 0; q < P; q++) {
        c[q] = 1 + q % 3;
        X[q] = ris(rng, q, (int)c[q], p_prev, &W[q]);
    }
    struct terms t = {1.0, 0.0, p, (int)floor(T_inverse(p + 0.5)), c};
    t.cb = 0.5 * c[t.qb];
    double W0, y0 = ris(rng, p, 2, f, &W0);
    /* candidates: (sample in p, technique, W, |J|, its confidence) */
    double ys[P + 2], Ws[P + 2], Js[P + 2], cs[P + 2];
    int tech[P + 2], n = 0;
    ys[n] = y0, Ws[n] = W0, Js[n] = 1.0, tech[n] = 0, cs[n++] = t.c0;
    struct estimate est = {0.0, 0.0};
    for (int q = 0; q < P; q++) {
        double y = T(X[q]);
        if (y >= p && y < p + 1) {
            est.splat_only += f(y) * W[q] * dT(X[q]);
            ys[n] = y, Ws[n] = W[q], Js[n] = mode == NO_SPLAT_JACOBIAN ? 1.0 : dT(X[q]), tech[n] = 1;
            cs[n++] = 0.5 * c[q];
        }
    }
    ys[n] = X[t.qb] + (p - t.qb), Ws[n] = W[t.qb], Js[n] = 1.0, tech[n] = 2, cs[n++] = t.cb;
    double c_sum = 0.0;
    for (int k = 0; k < n; k++)
        c_sum += cs[k];
    for (int k = 0; k < n; k++) {
        double m;
        if (mode == UNIFORM) {
            m = cs[k] / c_sum;
        } else {
            double term[3];
            technique_terms(&t, ys[k], term);
            m = term[tech[k]] / (term[0] + term[1] + term[2]);
        }
        est.merged += m * f(ys[k]) * Ws[k] * Js[k];
    }
    return est;
}

/* Mean and standard error of TRIALS estimates; returns z against the integral. */
static double run(int p, enum mode mode, int splat_only, uint64_t seed)
{
    pcg32 rng = pcg32_make(seed, 17);
    double s = 0.0, s2 = 0.0;
    for (int k = 0; k < TRIALS; k++) {
        struct estimate e = trial(&rng, p, mode);
        double v = splat_only ? e.splat_only : e.merged;
        s += v;
        s2 += v * v;
    }
    double mean = s / TRIALS, var = (s2 / TRIALS - mean * mean) / (TRIALS - 1), I = integral(p, p + 1);
    double z = (mean - I) / sqrt(var);
    printf("pixel %d, %s%s: mean %.6f, integral %.6f, z %.2f\n", p, splat_only ? "splat alone" : "merged",
           mode == EXACT ? "" : (mode == UNIFORM ? " with 1/M" : " without the splat Jacobian"), mean, I, z);
    return z;
}

int main(void)
{
    /* partition of unity at many y */
    const double c[P] = {1, 2, 3, 1, 2, 3, 1, 2};
    double worst = 0.0;
    for (int p = 2; p <= 5; p++) {
        int qb = (int)floor(T_inverse(p + 0.5));
        struct terms t = {1.0, 0.5 * c[qb], p, qb, c};
        for (int k = 0; k < 100; k++) {
            double y = p + (k + 0.5) / 100.0, term[3];
            technique_terms(&t, y, term);
            double s = 0.0;
            for (int j = 0; j < 3; j++)
                s += term[j] / (term[0] + term[1] + term[2]);
            worst = fmax(worst, fabs(s - 1.0));
        }
    }
    EXPECT(worst < 1e-6, "balance weights sum to 1 (worst %.2g)", worst);
    for (int p = 3; p <= 5; p += 2) {
        EXPECT(fabs(run(p, EXACT, 1, 100 + p)) < 4.5, "pixel %d: the splat technique's proposal density", p);
        EXPECT(fabs(run(p, EXACT, 0, 200 + p)) < 4.5, "pixel %d: the merged estimator is unbiased", p);
    }
    EXPECT(fabs(run(3, NO_SPLAT_JACOBIAN, 0, 303)) > 6.0, "a missing splat Jacobian is caught");
    EXPECT(fabs(run(3, UNIFORM, 0, 403)) > 6.0, "1/M weights are caught");
    return test_finish();
}
