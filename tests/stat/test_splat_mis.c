/* test_splat_mis.c: the resampling MIS of reservoir splatting combined with backprojection
 * (temporal.reuse=both, docs/RESTIR_PT.md) on a 1-D domain where every density is known.
 *
 * Model: a 1-D image of pixels [j, j+1), j = 0..P-1 (P = 8). The previous frame holds in every
 * pixel q an independent RIS reservoir: X_q in [q, q+1) from M_q = 1 + q % 3 uniform candidates
 * with target p_prev(x) = 1 + 0.5 sin(3x), its unbiased contribution weight W_q = (sum of RIS
 * weights) / p_prev(X_q) (restir_reservoir + restir_gris_contribution_weight), confidence c_q = M_q.
 * Camera motion is the monotone bijection T(x) = a x + b + e sin(x), a = 1.15, b = -0.4, e = 0.05
 * (a primary hit projected into the new camera), |T'(x)| = a + e cos(x) its Jacobian. The current
 * pixel p (p = 3 and p = 5) integrates I_p = int_p^{p+1} f(y) dy, f(y) = 1 + y/4 + 0.3 cos(5y),
 * with target p_hat = f. Techniques proposing samples to p:
 *  - canonical: Y_0 by RIS from 2 uniform candidates in [p, p+1) with target f, W_0, c_0 = 1;
 *  - splat: every previous X_q with T(X_q) in [p, p+1) gives Y = T(X_q) with W_q and |J| =
 *    |T'(X_q)|; a sample y can come only from q*(y) = floor(T^{-1}(y)) (T^{-1} by Newton), whose
 *    density in the current domain (004 Eq. 10) is p_hat_s(y) = p_prev(T^{-1} y) / |T'(T^{-1} y)|;
 *  - backprojection: the previous pixel q_b = floor(T^{-1}(p + 1/2)) (the pixel centre's motion
 *    vector) shifted by the translation S(x) = x + p - q_b (|S'| = 1), covering all of [p, p+1),
 *    with p_hat_b(y) = p_prev(S^{-1} y).
 * Balance weights (004 Eq. 9) with c_s = c_{q*(y)} / 2, c_b = c_{q_b} / 2:
 *    m_t(y) = c_t p_hat_t(y) / (c_0 f(y) + c_s p_hat_s(y) + c_b p_hat_b(y)).
 * Every candidate (canonical, every landed splat, backprojection) gets the resampling weight
 * w = m_t(Y) f(Y) W |J| (004 Eq. 6); one is selected by restir_reservoir, W_sel = sum w / f(Y_sel)
 * (004 Eq. 7), and the estimate is F = f(Y_sel) W_sel. Fresh previous reservoirs every trial.
 *
 * Checks: (1) the three weights sum to 1 at many y; (2) the splat technique's proposal density:
 * the splat technique alone, sum over landed q of f(T X_q) W_q |T'(X_q)|, estimates I_p (T is a
 * bijection, so it covers all of [p, p+1)); (3) F is unbiased for p = 3 and p = 5; (4) power, all
 * at |z| > 6: (a) the splat's Jacobian left out of p_hat_s for the splat candidates, i.e. the
 * cached previous target used without the forward Jacobian while the canonical and backprojected
 * candidates evaluate p_hat_s by the inverse splat correctly (the two code paths of pt_splat.c).
 * Leaving |T'| out consistently everywhere would NOT be a bias: the m_t would still sum to 1 (004
 * Eq. 8), it is only another MIS weight, so the mistake is caught only where it breaks the
 * partition of unity, as here; (b) the Jacobian left out of the splat's resampling weight w;
 * (c) 1/M weights, m_t = c_t / sum of the confidences of the candidates offered. Detected at the
 * brief's a = 1.15 without changing the model. Deterministic seeds. */
#include <math.h>
#include <stdio.h>

#include "accum.h"
#include "core/rng.h"
#include "restir/gris.h"
#include "test_util.h"

#define P 8
#define TRIALS 400000
#define Z_MAX 4.5    /* unbiased checks */
#define Z_POWER 6.0  /* mutations must be detected beyond this */

static const double A = 1.15, B = -0.4, E = 0.05;

static double f(double y) { return 1.0 + y / 4.0 + 0.3 * cos(5.0 * y); }
static double p_prev(double x) { return 1.0 + 0.5 * sin(3.0 * x); }
static double T(double x) { return A * x + B + E * sin(x); }
static double dT(double x) { return A + E * cos(x); }

static double T_inverse(double y)
{
    double x = (y - B) / A; /* within E / (A - E) < 0.05 of the root */
    for (int k = 0; k < 4; k++) /* Newton, quadratic: 0.05 -> 1e-4 -> 1e-9 -> round-off */
        x -= (T(x) - y) / dT(x);
    return x;
}

/* I_p by a fine midpoint rule. */
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
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    double chosen = lo;
    for (int k = 0; k < m; k++) {
        double x = lo + (double)pcg32_float(rng);
        if (restir_reservoir_offer(&wrs, (float)(g(x) / m), pcg32_float(rng)))
            chosen = x;
    }
    *W = (double)restir_gris_contribution_weight(&wrs, (float)g(chosen));
    return chosen;
}

enum mode { EXACT, SPLAT_PHAT_NO_JACOBIAN, SPLAT_W_NO_JACOBIAN, UNIFORM };
enum technique { CANONICAL, SPLAT, BACKPROJECTION };

struct pixel {
    int p, qb;
    double c0, cb;
    const double *c_prev; /* confidences of the previous pixels */
};

/* c_t p_hat_t(y) of the three techniques at y; the splat term without |T'| if !jacobian. */
static void technique_terms(const struct pixel *px, double y, int jacobian, double out[3])
{
    double xs = T_inverse(y);
    int qs = (int)floor(xs);
    out[CANONICAL] = px->c0 * f(y);
    out[SPLAT] = qs >= 0 && qs < P ? 0.5 * px->c_prev[qs] * p_prev(xs) / (jacobian ? dT(xs) : 1.0) : 0.0;
    out[BACKPROJECTION] = px->cb * p_prev(y - (px->p - px->qb));
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
    struct pixel px = {p, (int)floor(T_inverse(p + 0.5)), 1.0, 0.0, c};
    px.cb = 0.5 * c[px.qb];
    /* candidates: sample in [p, p+1), technique, W, |J|, confidence */
    double ys[P + 2], Ws[P + 2], Js[P + 2], cs[P + 2];
    enum technique tech[P + 2];
    int n = 0;
    ys[n] = ris(rng, p, 2, f, &Ws[n]), Js[n] = 1.0, tech[n] = CANONICAL, cs[n++] = px.c0;
    struct estimate est = {0.0, 0.0};
    for (int q = 0; q < P; q++) {
        double y = T(X[q]);
        if (y >= p && y < p + 1) {
            est.splat_only += f(y) * W[q] * dT(X[q]);
            ys[n] = y, Ws[n] = W[q], Js[n] = mode == SPLAT_W_NO_JACOBIAN ? 1.0 : dT(X[q]);
            tech[n] = SPLAT, cs[n++] = 0.5 * c[q];
        }
    }
    ys[n] = X[px.qb] + (p - px.qb), Ws[n] = W[px.qb], Js[n] = 1.0, tech[n] = BACKPROJECTION;
    cs[n++] = px.cb;
    double c_sum = 0.0;
    for (int k = 0; k < n; k++)
        c_sum += cs[k];
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    double y_sel = p;
    for (int k = 0; k < n; k++) {
        double m;
        if (mode == UNIFORM) {
            m = cs[k] / c_sum;
        } else {
            double term[3];
            technique_terms(&px, ys[k], !(mode == SPLAT_PHAT_NO_JACOBIAN && tech[k] == SPLAT), term);
            m = term[tech[k]] / (term[0] + term[1] + term[2]);
        }
        if (restir_reservoir_offer(&wrs, (float)(m * f(ys[k]) * Ws[k] * Js[k]), pcg32_float(rng)))
            y_sel = ys[k];
    }
    est.merged = f(y_sel) * (double)restir_gris_contribution_weight(&wrs, (float)f(y_sel));
    return est;
}

static double z_of(const struct accum *a, double exact, int p, const char *what)
{
    double m = acc_mean(a), s = acc_sigma(a), z = (m - exact) / s;
    printf("  pixel %d %-46s mean %.6f I %.6f sigma %.6f z %+8.2f\n", p, what, m, exact, s, z);
    return z;
}

/* TRIALS estimates of pixel p; z of the merged estimator and of the splat technique alone. */
static void run(int p, enum mode mode, uint64_t seed, double *z_merged, double *z_splat)
{
    static const char *name[] = {"merged, balance", "merged, splat p_hat without |T'|",
                                 "merged, splat w without |T'|", "merged, 1/M"};
    pcg32 rng = pcg32_make(seed, 17u);
    struct accum merged = {0.0, 0.0, 0}, splat = {0.0, 0.0, 0};
    for (long k = 0; k < TRIALS; k++) {
        struct estimate e = trial(&rng, p, mode);
        acc_add(&merged, e.merged);
        acc_add(&splat, e.splat_only);
    }
    double I = integral(p, p + 1);
    if (z_splat)
        *z_splat = z_of(&splat, I, p, "splat technique alone");
    *z_merged = z_of(&merged, I, p, name[mode]);
}

int main(void)
{
    /* (1) partition of unity at many y of several pixels */
    const double c[P] = {1, 2, 3, 1, 2, 3, 1, 2};
    double worst = 0.0;
    for (int p = 1; p <= 6; p++) {
        struct pixel px = {p, (int)floor(T_inverse(p + 0.5)), 1.0, 0.0, c};
        px.cb = 0.5 * c[px.qb];
        for (int k = 0; k < 100; k++) {
            double y = p + (k + 0.5) / 100.0, term[3];
            technique_terms(&px, y, 1, term);
            double s = 0.0;
            for (int j = 0; j < 3; j++)
                s += term[j] / (term[0] + term[1] + term[2]);
            worst = fmax(worst, fabs(s - 1.0));
        }
    }
    printf("  balance weights: worst |sum - 1| = %.2g over 600 y\n", worst);
    EXPECT(worst < 1e-6, "balance weights sum to 1 (worst %.2g)", worst);
    /* (2) splat proposal density and (3) unbiased merged estimator */
    for (int p = 3; p <= 5; p += 2) {
        double zm, zs;
        run(p, EXACT, 100u + (uint64_t)p, &zm, &zs);
        EXPECT(fabs(zs) < Z_MAX, "pixel %d: the splat technique alone, z = %.2f", p, zs);
        EXPECT(fabs(zm) < Z_MAX, "pixel %d: the merged estimator, z = %.2f", p, zm);
    }
    /* (4) power */
    static const struct {
        enum mode mode;
        const char *what;
    } mut[] = {{SPLAT_PHAT_NO_JACOBIAN, "splat p_hat without its Jacobian"},
               {SPLAT_W_NO_JACOBIAN, "splat resampling weight without its Jacobian"},
               {UNIFORM, "1/M weights"}};
    for (unsigned k = 0; k < sizeof mut / sizeof mut[0]; k++) {
        double zm;
        run(3, mut[k].mode, 300u + k, &zm, NULL);
        EXPECT(fabs(zm) > Z_POWER, "%s is caught: z = %.2f", mut[k].what, zm);
    }
    return test_finish();
}
