/* test_gradient_toy.c: the toy of 002 Figure 3 as a statistical test of the gradient arithmetic
 * (restir/grad.h: paired-pixel integrand, balance weight Eq. 13, positivized targets) driven by
 * the project's RIS / GRIS bookkeeping (restir/reservoir.h, restir/mis.h). Must never depend on
 * Embree, files or the renderer.
 *
 * The toy. Two "pixels" on Omega = [-2, 2], pixel a = 1 (paired part k = 0) and pixel b = 2 (k = 1),
 * RGB with channels that differ in the two bumps:
 *   f_1(x) = P(x) (1, 1, 1) + B_1(x) c_1,   f_2(x) = P(x) (1, 1, 1) + B_2(x) c_2,
 *   P   = 1.0 exp(-x^2 / (2 0.30^2))          the shared peak: f_1 = f_2 near the origin,
 *   B_1 = 0.5 exp(-(x + 1.2)^2 / (2 0.15^2)),  c_1 = (1.0, 0.6, 0.3), only in pixel 1,
 *   B_2 = 0.4 exp(-(x - 1.3)^2 / (2 0.12^2)),  c_2 = (0.3, 0.7, 1.0), only in pixel 2,
 * so f_2 - f_1 = B_2 c_2 - B_1 c_1 and the exact gradient d = int (f_2 - f_1) comes from erf. The
 * inner shift is T = identity on [-2, 2] (|T'| = 1): the paired domain is
 * X = ([-2,2] x {0}) u ([-2,2] x {1}) and, in the project's forward convention (d = F_2 - F_1),
 *   h(x, 0) = restir_grad_pair_integrand(0, f_1(x), f_2(x)) = -omega_12(x) (f_1 - f_2)(x),
 *   h(x, 1) = restir_grad_pair_integrand(1, f_2(x), f_1(x)) = +omega_21(x) (f_2 - f_1)(x),
 * with int_X h = d because omega_12 + omega_21 = 1 (Eq. 13 with T = identity).
 *
 * Estimators (all candidates uniform on [-2, 2], source pdf 1/4):
 *  - Gradient after ReSTIR (002 Sec. 4.1, Eq. 10-13): RIS per pixel with M candidates and target
 *    luminance(f_i) gives (Y_i, W_i); the one-sided differences D'_12 = omega_12 (f_1 - f_2)(Y_1) W_1,
 *    D'_21 = omega_21 (f_2 - f_1)(Y_2) W_2 (restir_grad_one_sided), combined by Eq. 12 in the
 *    forward convention: d = D'_21 - D'_12. 2M integrand evaluations of each f.
 *  - Gradient with ReSTIR (002 Sec. 4.2, Eq. 14-20): M paired candidates, M/2 uniform on each part
 *    k (also 2M evaluations of the f's: each candidate needs f_1 and f_2). Resampling MIS weights:
 *    the generalized balance heuristic over the M candidate sources, m_l(x, k) = p_l(x, k) /
 *    sum_j p_j(x, k). A part-k source has density 1/4 on part k and 0 on the other part (the parts
 *    are disjoint), so only the M/2 sources of y's own part can produce y and m = 1/(M/2) = 2/M on
 *    them. Target restir_grad_target(ABS) (Eq. 19); estimate restir_grad_part(ABS)(h(Y)) W.
 *    Positivized (Eq. 23-26): POS and NEG reservoirs fed the same candidates, estimate
 *    part(POS)(h(Y+)) W+ - part(NEG)(h(Y-)) W-.
 *  - 2-step chain: two independent such reservoirs (M_A = 8, M_B = 24 candidates) merged by one GRIS
 *    step (Eq. 20) with identity outer shift (|dT* / d(x,k)| = 1) and balance MIS with confidences
 *    8 and 24 (restir_mis_weights), for ABS and, within each sign, for POS and NEG.
 *
 * Checks: (1) every estimator is unbiased for d, per channel, |z| < 4.5 over TRIALS independent
 * runs (33 such checks: family-wise false-alarm rate ~2e-4 for a correct implementation);
 * (2) the selected (x, k) of the ABS and POS reservoirs at M = 64 follow their RIS selection law,
 * chi-square p > 1e-4. With M = 64 that law is not yet |h| / int|h| (resp. max(h,0)): finite-M RIS
 * selects with density p_hat(y) E[1 / (w(y) + S)], S the sum of the other candidates' weights,
 * which deviates from p_hat / int p_hat by O(1 / M) times the peak-to-mean ratio of p_hat / p,
 * a few percent in total variation here, which 200k samples resolve easily. The test computes
 * that exact law by quadrature (E[1/(a+S)] = int_0^inf e^{-ta} E[e^{-tS}] dt, E[e^{-tS}] a product
 * of per-part Laplace transforms) and tests against it; the p-value against the asymptotic law
 * p_hat / int p_hat is printed, and the law's distance to it must shrink ~1/M (M = 64 -> 1024).
 * (3) at equal M Gradient with ReSTIR has lower variance than Gradient after ReSTIR (every channel,
 * M = 16 and M = 64), and a wrong resampling MIS weight (1/M on every candidate, i.e. 1/2 for each
 * of the two disjoint part strategies as if they overlapped) is detected as biased by the same
 * z-test, at the value the error predicts; with an unequal split (12 + 4 candidates) the correct
 * per-part weights stay unbiased while 1/M gives (12/16) int h(., 0) + (4/16) int h(., 1). */
#include <math.h>
#include <stdio.h>

#include "accum.h"
#include "chi2_util.h"
#include "core/rng.h"
#include "restir/mis.h"
#include "restir/grad.h"
#include "restir/gris.h"
#include "test_util.h"

#define TOY_PI 3.14159265358979323846
#define TRIALS 200000
#define Z_MAX 4.5
#define Z_POWER 6.0 /* a deliberately wrong estimator must sit at least this many sigma off */
#define P_MIN 1e-4
#define M_EQ 16
#define M_BIG 64
#define SRC_PDF 0.25 /* uniform source density on [-2, 2] (and on each part of X) */

/* ---------------- the toy ---------------- */

struct gauss {
    double a, mu, s;
};
static const struct gauss PEAK = {1.0, 0.0, 0.30};
static const struct gauss BUMP1 = {0.5, -1.2, 0.15};
static const struct gauss BUMP2 = {0.4, 1.3, 0.12};
static const double COL1[3] = {1.0, 0.6, 0.3};
static const double COL2[3] = {0.3, 0.7, 1.0};
static const char *const CH[3] = {"R", "G", "B"};

static double gauss_eval(const struct gauss *g, double x)
{
    double d = (x - g->mu) / g->s;
    return g->a * exp(-0.5 * d * d);
}

/* int_{-2}^{2} g = a s sqrt(pi/2) [erf((2 - mu) / (s sqrt 2)) - erf((-2 - mu) / (s sqrt 2))]. */
static double gauss_int(const struct gauss *g)
{
    double r = g->s * sqrt(2.0);
    return g->a * g->s * sqrt(0.5 * TOY_PI) * (erf((2.0 - g->mu) / r) - erf((-2.0 - g->mu) / r));
}

/* f of pixel pix (0: f_1, 1: f_2) at x, as the float triple the library reads. */
static void toy_f(int pix, double x, float f[3])
{
    double p = gauss_eval(&PEAK, x);
    double b = gauss_eval(pix ? &BUMP2 : &BUMP1, x);
    const double *col = pix ? COL2 : COL1;
    for (int c = 0; c < 3; c++)
        f[c] = (float)(p + b * col[c]);
}

/* d = int (f_2 - f_1) = c_2 int B_2 - c_1 int B_1 (the peak cancels). */
static void exact_gradient(double d[3])
{
    for (int c = 0; c < 3; c++)
        d[c] = COL2[c] * gauss_int(&BUMP2) - COL1[c] * gauss_int(&BUMP1);
}

/* h(x, k) with T = identity, |T'| = 1: the own pixel of part k is f_{k+1}, the other f_{2-k}. */
static void pair_h(int k, double x, float h[3])
{
    float f1[3], f2[3];
    toy_f(0, x, f1);
    toy_f(1, x, f2);
    if (k == 0)
        restir_grad_pair_integrand(0, f1, f2, h);
    else
        restir_grad_pair_integrand(1, f2, f1, h);
}

static double uniform_x(pcg32 *rng) { return -2.0 + 4.0 * (double)pcg32_float(rng); }

/* Simpson quadrature of restir_grad_part(s, h(., k)) over [-2, 2], per channel. */
#define NQ 40000
static void quad_part(enum restir_grad_sign s, int k, double out[3])
{
    double acc[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i <= NQ; i++) {
        float h[3], v[3];
        pair_h(k, -2.0 + 4.0 * i / NQ, h);
        restir_grad_part(s, h, v);
        double wgt = (i == 0 || i == NQ) ? 1.0 : (i & 1) ? 4.0 : 2.0;
        for (int c = 0; c < 3; c++)
            acc[c] += wgt * v[c];
    }
    for (int c = 0; c < 3; c++)
        out[c] = acc[c] * (4.0 / NQ) / 3.0;
}

/* ---------------- checks ---------------- */

struct acc3 {
    struct accum c[3];
};

static void acc3_add(struct acc3 *a, const double v[3])
{
    for (int c = 0; c < 3; c++)
        acc_add(&a->c[c], v[c]);
}

static double acc_var(const struct accum *a)
{
    double s = acc_sigma(a);
    return s * s * (double)a->n;
}

static void expect_unbiased(const struct acc3 *a, const double exact[3], const char *what)
{
    for (int c = 0; c < 3; c++) {
        double m = acc_mean(&a->c[c]), s = acc_sigma(&a->c[c]);
        double z = (m - exact[c]) / s;
        printf("  %-40s %s mean %+.6f exact %+.6f sigma %.6f z %+.2f\n", what, CH[c], m, exact[c], s, z);
        EXPECT(fabs(z) < Z_MAX, "%s %s: z = %.2f", what, CH[c], z);
    }
}

/* A wrong estimator: at least Z_POWER sigma from the truth (the unbiasedness test catches it) and
 * within Z_MAX of the value the error predicts (the test sees the error it was built for). */
static void expect_detected(const struct acc3 *a, const double exact[3], const double predicted[3],
                            const char *what)
{
    for (int c = 0; c < 3; c++) {
        double m = acc_mean(&a->c[c]), s = acc_sigma(&a->c[c]);
        double z = (m - exact[c]) / s, zp = (m - predicted[c]) / s;
        printf("  %-40s %s mean %+.6f exact %+.6f predicted %+.6f: z vs exact %+.1f, vs predicted %+.2f\n",
               what, CH[c], m, exact[c], predicted[c], z, zp);
        EXPECT(fabs(z) > Z_POWER, "%s %s: bias only %.2f sigma, the test has no power", what, CH[c], z);
        EXPECT(fabs(zp) < Z_MAX, "%s %s: z vs predicted biased value = %.2f", what, CH[c], zp);
    }
}

/* ---------------- Gradient after ReSTIR (002 Sec. 4.1) ---------------- */

/* RIS in one pixel (Eq. 10): M uniform candidates, target luminance(f_pix), m = 1/M. Returns Y. */
static double ris_pixel(pcg32 *rng, int pix, int M, float *W)
{
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double y = 0.0;
    float py = 0.0f;
    for (int i = 0; i < M; i++) {
        double x = uniform_x(rng);
        float f[3];
        toy_f(pix, x, f);
        float p = restir_grad_luminance(f);
        if (restir_reservoir_offer(&r, (float)(p / ((double)M * SRC_PDF)), pcg32_float(rng))) {
            y = x;
            py = p;
        }
    }
    *W = restir_gris_contribution_weight(&r, py);
    return y;
}

/* d = D'_21 - D'_12 (Eq. 11-12, forward convention), T = identity. */
static void after_estimate(pcg32 *rng, int M, double d[3])
{
    float W1, W2, f1[3], f2[3], d12[3], d21[3];
    double y1 = ris_pixel(rng, 0, M, &W1);
    toy_f(0, y1, f1);
    toy_f(1, y1, f2);
    restir_grad_one_sided(f1, f2, d12);
    double y2 = ris_pixel(rng, 1, M, &W2);
    toy_f(0, y2, f1);
    toy_f(1, y2, f2);
    restir_grad_one_sided(f2, f1, d21);
    for (int c = 0; c < 3; c++)
        d[c] = (double)d21[c] * (double)W2 - (double)d12[c] * (double)W1;
}

/* ---------------- Gradient with ReSTIR (002 Sec. 4.2, 4.4) ---------------- */

struct pair_sample {
    double x;
    int k;
    float h[3];
};

/* One reservoir over X for one sign s (ABS: target Eq. 19; POS / NEG: Eq. 25 / 26). */
struct gres {
    enum restir_grad_sign s;
    struct restir_reservoir r;
    struct pair_sample y;
    float W;
};

static void gres_init(struct gres *g, enum restir_grad_sign s)
{
    g->s = s;
    restir_reservoir_init(&g->r);
    g->y.x = 0.0;
    g->y.k = 0;
    g->y.h[0] = g->y.h[1] = g->y.h[2] = 0.0f;
    g->W = 0.0f;
}

static void gres_finish(struct gres *g)
{
    g->W = restir_gris_contribution_weight(&g->r, restir_grad_target(g->s, g->y.h)); /* Eq. 18 */
}

/* Initial resampling: n[k] uniform candidates on part k, each with resampling MIS weight mis[k],
 * offered to all nres reservoirs (002 Sec. 4.4: r+ and r- share the candidates). Eq. 20 with the
 * source pdf in place of 1/W: w = m p_hat(x, k) / (1/4). */
static void gres_candidates(pcg32 *rng, const int n[2], const double mis[2], struct gres *g, int nres)
{
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < n[k]; i++) {
            struct pair_sample c;
            c.k = k;
            c.x = uniform_x(rng);
            pair_h(k, c.x, c.h);
            for (int j = 0; j < nres; j++) {
                double w = mis[k] * (double)restir_grad_target(g[j].s, c.h) / SRC_PDF;
                if (restir_reservoir_offer(&g[j].r, (float)w, pcg32_float(rng)))
                    g[j].y = c;
            }
        }
    }
    for (int j = 0; j < nres; j++)
        gres_finish(&g[j]);
}

/* restir_grad_part(s)(h(Y)) W (Eq. 17); the NEG reservoir's part is max(-h, 0). */
static void gres_value(const struct gres *g, double v[3])
{
    float part[3];
    restir_grad_part(g->s, g->y.h, part);
    for (int c = 0; c < 3; c++)
        v[c] = (double)part[c] * (double)g->W;
}

/* g[0] ABS, g[1] POS, g[2] NEG: the unpositivized and the positivized estimate. */
static void gres_estimates(const struct gres *g, double abs_est[3], double pos_est[3])
{
    double p[3], q[3];
    gres_value(&g[0], abs_est);
    gres_value(&g[1], p);
    gres_value(&g[2], q);
    for (int c = 0; c < 3; c++)
        pos_est[c] = p[c] - q[c];
}

/* One GRIS step (Eq. 20) merging in[0..n) of one sign into out: identity outer shift, so the
 * shifted sample is (x, k) itself, |dT* / d(x,k)| = 1 and p_hat_{<-j} = p_hat for every input;
 * generalized balance MIS with confidences conf. */
static void gres_merge(pcg32 *rng, const struct gres *in, const float *conf, int n, struct gres *out)
{
    float p[4 * 4], m[4];
    enum restir_grad_sign s = in[0].s;
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            p[k * n + j] = restir_grad_target(s, in[j].y.h);
    restir_mis_weights(RESTIR_MIS_BALANCE, n, conf, p, m);
    gres_init(out, s);
    for (int j = 0; j < n; j++) {
        double w = (double)m[j] * (double)p[j * n + j] * (double)in[j].W;
        if (restir_reservoir_offer(&out->r, (float)w, pcg32_float(rng)))
            out->y = in[j].y;
    }
    gres_finish(out);
}

static const enum restir_grad_sign SIGNS[3] = {RESTIR_GRAD_ABS, RESTIR_GRAD_POS, RESTIR_GRAD_NEG};

/* Fresh ABS / POS / NEG reservoirs from n[0] + n[1] shared candidates. */
static void gres_run(pcg32 *rng, const int n[2], const double mis[2], struct gres g[3])
{
    for (int j = 0; j < 3; j++)
        gres_init(&g[j], SIGNS[j]);
    gres_candidates(rng, n, mis, g, 3);
}

static void correct_mis(const int n[2], double mis[2])
{
    for (int k = 0; k < 2; k++)
        mis[k] = n[k] > 0 ? 1.0 / n[k] : 0.0; /* balance over the sources that can produce part k */
}

/* ---------------- the exact finite-M RIS selection law ----------------
 * Candidates: n[k] uniform on part k with weights w_k(x) = p_hat(x, k) / (n[k] / 4). The chosen
 * (Y, K) has density p(y, k) = p_hat(y, k) E[1 / (w_k(y) + S_k)], S_k the sum of the weights of the
 * n[k] - 1 other part-k and n[1-k] part-(1-k) candidates, and
 *   E[1 / (a + S_k)] = int_0^inf e^{-t a} phi_k(t)^{n[k]-1} phi_{1-k}(t)^{n[1-k]} dt,
 *   phi_k(t) = E[e^{-t w_k(X)}] = (1/4) int_{-2}^{2} e^{-t w_k(x)} dx.
 * Simpson on NG intervals in x per part and on NT intervals in ln t, t = tau / int p_hat with
 * tau in [1e-7, 1e7]; [0, t_min] adds t_min (integrand 1 there to O(t_min)). */
#define NB 40 /* chi-square bins of x per part */
#define NG 4000 /* x quadrature intervals per part: NG / NB = 100, even */
#define NT 700
static double lg_phat[2][NG + 1], lg_dens[2][NG + 1], lg_phi[2][NT + 1];

static double simpson_w(int i, int n) { return (i == 0 || i == n) ? 1.0 : (i & 1) ? 4.0 : 2.0; }

/* prob[k * NB + b] for the law, asym[] for p_hat / int p_hat. Returns the law's total mass. */
static double selection_law(enum restir_grad_sign s, const int n[2], double *prob, double *asym)
{
    const double dx = 4.0 / NG;
    double total_phat = 0.0;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i <= NG; i++) {
            float h[3];
            pair_h(k, -2.0 + dx * i, h);
            lg_phat[k][i] = restir_grad_target(s, h);
            total_phat += simpson_w(i, NG) * lg_phat[k][i] * dx / 3.0;
        }
    const double lt0 = log(1e-7), lt1 = log(1e7), dl = (lt1 - lt0) / NT;
    for (int k = 0; k < 2; k++)
        for (int j = 0; j <= NT; j++) {
            double t = exp(lt0 + dl * j) / total_phat, acc = 0.0;
            for (int i = 0; i <= NG; i++)
                acc += simpson_w(i, NG) * exp(-t * lg_phat[k][i] / (n[k] * SRC_PDF));
            lg_phi[k][j] = SRC_PDF * acc * dx / 3.0;
        }
    for (int k = 0; k < 2; k++) {
        double L[NT + 1];
        for (int j = 0; j <= NT; j++)
            L[j] = pow(lg_phi[k][j], n[k] - 1) * pow(lg_phi[1 - k][j], n[1 - k]);
        for (int i = 0; i <= NG; i++) {
            double a = lg_phat[k][i] / (n[k] * SRC_PDF);
            double e = exp(lt0) / total_phat; /* the [0, t_min] piece */
            if (a > 0.0)
                for (int j = 0; j <= NT; j++) {
                    double t = exp(lt0 + dl * j) / total_phat;
                    e += simpson_w(j, NT) * exp(-t * a) * L[j] * t * dl / 3.0;
                }
            lg_dens[k][i] = lg_phat[k][i] * e;
        }
    }
    double total = 0.0;
    const int per = NG / NB;
    for (int k = 0; k < 2; k++)
        for (int b = 0; b < NB; b++) {
            double pl = 0.0, pa = 0.0;
            for (int i = 0; i <= per; i++) {
                double wgt = simpson_w(i, per) * dx / 3.0;
                pl += wgt * lg_dens[k][b * per + i];
                pa += wgt * lg_phat[k][b * per + i];
            }
            prob[k * NB + b] = pl;
            asym[k * NB + b] = pa / total_phat;
            total += pl;
        }
    return total;
}

static int bin_of(const struct pair_sample *y)
{
    int b = (int)floor((y->x + 2.0) / 4.0 * NB);
    b = b < 0 ? 0 : b >= NB ? NB - 1 : b;
    return y->k * NB + b;
}

/* Chi-square of the selections against the exact law and, printed only, the asymptotic law. */
static void check_selection(const char *what, enum restir_grad_sign s, const int n[2], const double *count,
                            double selected)
{
    double prob[2 * NB], asym[2 * NB];
    double total = selection_law(s, n, prob, asym);
    printf("  %s: law mass %.8f (quadrature self-check)\n", what, total);
    EXPECT(fabs(total - 1.0) < 1e-5, "%s: selection law mass %.8f", what, total);
    for (int i = 0; i < 2 * NB; i++)
        prob[i] /= total;
    int dof, dof_a;
    double p = chi2_counts(count, prob, 2 * NB, selected, &dof);
    double pa = chi2_counts(count, asym, 2 * NB, selected, &dof_a);
    double obs_k1 = 0.0, law_k1 = 0.0, asym_k1 = 0.0, tv = 0.0;
    for (int b = 0; b < NB; b++) {
        obs_k1 += count[NB + b] / selected;
        law_k1 += prob[NB + b];
        asym_k1 += asym[NB + b];
    }
    for (int i = 0; i < 2 * NB; i++)
        tv += 0.5 * fabs(prob[i] - asym[i]);
    printf("  %s: chi2 vs finite-M law p = %.4g (dof %d); vs p_hat/int p_hat p = %.3g (dof %d), "
           "law-to-asymptotic total variation %.4f; P(k=1) observed %.5f law %.5f asymptotic %.5f\n",
           what, p, dof, pa, dof_a, tv, obs_k1, law_k1, asym_k1);
    EXPECT(p > P_MIN, "%s: chi2 p = %.3g against the RIS selection law", what, p);
    /* The law tends to p_hat / int p_hat as O(1/M): 16x the candidates, ~1/16 the distance. */
    const int n_big[2] = {16 * n[0], 16 * n[1]};
    double big_total = selection_law(s, n_big, prob, asym), tv_big = 0.0;
    for (int i = 0; i < 2 * NB; i++)
        tv_big += 0.5 * fabs(prob[i] / big_total - asym[i]);
    printf("  %s: law-to-asymptotic total variation at M = %d: %.5f (%.1fx smaller)\n", what,
           n_big[0] + n_big[1], tv_big, tv / tv_big);
    EXPECT(tv_big < tv / 8.0, "%s: RIS law at M = %d not closer to p_hat / int p_hat (%.5f vs %.5f)", what,
           n_big[0] + n_big[1], tv_big, tv);
}

/* ---------------- the tests ---------------- */

static void print_var(const char *what, const struct acc3 *a)
{
    printf("  variance per run %-34s R %.6f G %.6f B %.6f\n", what, acc_var(&a->c[0]), acc_var(&a->c[1]),
           acc_var(&a->c[2]));
}

static void expect_lower_var(const struct acc3 *lo, const struct acc3 *hi, const char *what)
{
    for (int c = 0; c < 3; c++) {
        double vl = acc_var(&lo->c[c]), vh = acc_var(&hi->c[c]);
        printf("  %-40s %s variance ratio with/after %.4f\n", what, CH[c], vl / vh);
        EXPECT(vl < vh, "%s %s: Gradient with ReSTIR variance %.6g not below after %.6g", what, CH[c], vl, vh);
    }
}

static void test_exact(const double exact[3])
{
    double i0[3], i1[3];
    quad_part(RESTIR_GRAD_ABS, 0, i0);
    quad_part(RESTIR_GRAD_ABS, 1, i1);
    printf("exact d = int (f_2 - f_1): R %+.6f G %+.6f B %+.6f (erf); quadrature of int_X h: R %+.6f G "
           "%+.6f B %+.6f\n",
           exact[0], exact[1], exact[2], i0[0] + i1[0], i0[1] + i1[1], i0[2] + i1[2]);
    for (int c = 0; c < 3; c++)
        EXPECT_NEAR(i0[c] + i1[c], exact[c], 1e-5, "int_X h = d (omega_12 + omega_21 = 1)");
}

/* (1) + (3): unbiasedness and variance at M = m_eq, the positivized variant and the chain. */
static void test_equal_m(const double exact[3], int m_eq, unsigned seed)
{
    char name[96];
    printf("M = %d (after: %d candidates per pixel; with: %d + %d paired candidates)\n", m_eq, m_eq, m_eq / 2,
           m_eq / 2);
    struct acc3 after = {0}, with_abs = {0}, with_pos = {0};
    pcg32 rng = rng_for(seed, 0u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        double d[3];
        after_estimate(&rng, m_eq, d);
        acc3_add(&after, d);
    }
    rng = rng_for(seed, 1u, 0u, 0u);
    const int n[2] = {m_eq / 2, m_eq / 2};
    double mis[2];
    correct_mis(n, mis);
    for (long t = 0; t < TRIALS; t++) {
        struct gres g[3];
        double a[3], p[3];
        gres_run(&rng, n, mis, g);
        gres_estimates(g, a, p);
        acc3_add(&with_abs, a);
        acc3_add(&with_pos, p);
    }
    snprintf(name, sizeof name, "after ReSTIR M=%d", m_eq);
    expect_unbiased(&after, exact, name);
    snprintf(name, sizeof name, "with ReSTIR |h| M=%d", m_eq);
    expect_unbiased(&with_abs, exact, name);
    snprintf(name, sizeof name, "with ReSTIR positivized M=%d", m_eq);
    expect_unbiased(&with_pos, exact, name);
    snprintf(name, sizeof name, "after ReSTIR M=%d", m_eq);
    print_var(name, &after);
    snprintf(name, sizeof name, "with ReSTIR |h| M=%d", m_eq);
    print_var(name, &with_abs);
    snprintf(name, sizeof name, "with ReSTIR positivized M=%d", m_eq);
    print_var(name, &with_pos);
    snprintf(name, sizeof name, "|h| vs after, M=%d", m_eq);
    expect_lower_var(&with_abs, &after, name);
    snprintf(name, sizeof name, "positivized vs after, M=%d", m_eq);
    expect_lower_var(&with_pos, &after, name);
}

static void test_chain(const double exact[3])
{
    const int na[2] = {4, 4}, nb[2] = {12, 12};
    const float conf[2] = {8.0f, 24.0f};
    double ma[2], mb[2];
    correct_mis(na, ma);
    correct_mis(nb, mb);
    struct acc3 c_abs = {0}, c_pos = {0};
    pcg32 rng = rng_for(7u, 2u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct gres ga[3], gb[3], out[3];
        gres_run(&rng, na, ma, ga);
        gres_run(&rng, nb, mb, gb);
        for (int j = 0; j < 3; j++) {
            struct gres in[2] = {ga[j], gb[j]}; /* within-sign reuse (002 Sec. 4.4) */
            gres_merge(&rng, in, conf, 2, &out[j]);
        }
        double a[3], p[3];
        gres_estimates(out, a, p);
        acc3_add(&c_abs, a);
        acc3_add(&c_pos, p);
    }
    printf("2-step chain: GRIS merge of M=8 and M=24 reservoirs, identity outer shift, balance c=(8,24)\n");
    expect_unbiased(&c_abs, exact, "chain |h|");
    expect_unbiased(&c_pos, exact, "chain positivized");
    print_var("chain |h| (32 candidates)", &c_abs);
    print_var("chain positivized (32 candidates)", &c_pos);
}

/* (2): selections at M = 64 against the RIS law; also unbiasedness and variance at M = 64. */
static void test_selection(const double exact[3])
{
    const int n[2] = {M_BIG / 2, M_BIG / 2};
    double mis[2];
    correct_mis(n, mis);
    static double cnt_abs[2 * NB], cnt_pos[2 * NB];
    double sel_abs = 0.0, sel_pos = 0.0;
    struct acc3 with_abs = {0}, with_pos = {0}, after = {0};
    pcg32 rng = rng_for(7u, 3u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        struct gres g[3];
        gres_run(&rng, n, mis, g);
        if (g[0].r.selected >= 0) {
            cnt_abs[bin_of(&g[0].y)] += 1.0;
            sel_abs += 1.0;
        }
        if (g[1].r.selected >= 0) {
            cnt_pos[bin_of(&g[1].y)] += 1.0;
            sel_pos += 1.0;
        }
        double a[3], p[3];
        gres_estimates(g, a, p);
        acc3_add(&with_abs, a);
        acc3_add(&with_pos, p);
    }
    rng = rng_for(7u, 4u, 0u, 0u);
    for (long t = 0; t < TRIALS; t++) {
        double d[3];
        after_estimate(&rng, M_BIG, d);
        acc3_add(&after, d);
    }
    printf("M = %d selections (%d + %d paired candidates)\n", M_BIG, n[0], n[1]);
    check_selection("|h| reservoir", RESTIR_GRAD_ABS, n, cnt_abs, sel_abs);
    check_selection("POS reservoir", RESTIR_GRAD_POS, n, cnt_pos, sel_pos);
    expect_unbiased(&after, exact, "after ReSTIR M=64");
    expect_unbiased(&with_abs, exact, "with ReSTIR |h| M=64");
    expect_unbiased(&with_pos, exact, "with ReSTIR positivized M=64");
    print_var("after ReSTIR M=64", &after);
    print_var("with ReSTIR |h| M=64", &with_abs);
    print_var("with ReSTIR positivized M=64", &with_pos);
    expect_lower_var(&with_abs, &after, "|h| vs after, M=64");
}

/* (3): the disjoint-part correction of the resampling MIS weights, and what omitting it does. */
static void test_wrong_mis(const double exact[3])
{
    double i0[3], i1[3];
    quad_part(RESTIR_GRAD_ABS, 0, i0);
    quad_part(RESTIR_GRAD_ABS, 1, i1);
    static const int splits[2][2] = {{M_EQ / 2, M_EQ / 2}, {12, 4}};
    for (int sp = 0; sp < 2; sp++) {
        const int *n = splits[sp];
        double good[2], bad[2] = {1.0 / M_EQ, 1.0 / M_EQ};
        correct_mis(n, good);
        struct acc3 a_good = {0}, a_bad = {0};
        pcg32 rng = rng_for(7u, 5u, (uint64_t)sp, 0u);
        for (long t = 0; t < TRIALS; t++) {
            struct gres g;
            double v[3];
            gres_init(&g, RESTIR_GRAD_ABS);
            gres_candidates(&rng, n, bad, &g, 1);
            gres_value(&g, v);
            acc3_add(&a_bad, v);
            if (sp == 1) { /* the equal split's correct weights are checked in test_equal_m */
                gres_init(&g, RESTIR_GRAD_ABS);
                gres_candidates(&rng, n, good, &g, 1);
                gres_value(&g, v);
                acc3_add(&a_good, v);
            }
        }
        /* 1/M on n[k] part-k sources: the part-k integral gets weight n[k] / M instead of 1 */
        double predicted[3];
        for (int c = 0; c < 3; c++)
            predicted[c] = (n[0] * i0[c] + n[1] * i1[c]) / M_EQ;
        char name[96];
        printf("resampling MIS on %d + %d candidates\n", n[0], n[1]);
        if (sp == 1) {
            snprintf(name, sizeof name, "balance 1/%d, 1/%d (correct)", n[0], n[1]);
            expect_unbiased(&a_good, exact, name);
        }
        snprintf(name, sizeof name, "1/M uncorrected (%d+%d)", n[0], n[1]);
        expect_detected(&a_bad, exact, predicted, name);
    }
}

int main(void)
{
    double exact[3];
    exact_gradient(exact);
    test_exact(exact);
    test_equal_m(exact, M_EQ, 7u);
    test_chain(exact);
    test_selection(exact);
    test_wrong_mis(exact);
    return test_finish();
}
