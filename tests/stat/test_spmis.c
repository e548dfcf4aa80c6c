/* test_spmis.c: stochastic pairwise MIS (004 Eq. 14-19, Algorithm 2) over one reuse cell: unbiased GRIS,
 * E[m~] = m^pw, wrong draw factors detected. Must never depend on Embree, files or the renderer.
 *
 * Setup. Target domain Omega_0 = [0,1), integrand f_0(y) = 0.25 + sin^2(pi y) + a tent spike of
 * height 6 and half-width 0.03 at y = 0.8; int f_0 = 0.25 + 0.5 + 0.18 = 0.93. Domain 0 is the
 * canonical one (identity shift, 004 Sec. 2.3.3); its target p_hat = p_hat_0 = 0.35 + sin^2(pi y)
 * ignores the spike (so p_hat != f_0 and the WRS pick matters) and is > 0 on [0,1); it samples
 * p_0(y) = 1.5 - y, so it alone covers supp f_0. M = 8 non-canonical domains Omega_i = [0,1), each
 * with a source target p_hat_i (zero on [zero_lo, zero_hi)), a linear density p_i, a confidence
 * c_i and a shift T_i: Omega_i -> Omega_0 (affine a x + b or quadratic a x^2 + b), undefined on a
 * failure interval and wherever T_i(x) leaves [0,1):
 *   i  p_hat_i(x)                       zero on      p_i          T_i(x)          fails on     c_i
 *   1  0.2 + 3 x^2                      -            0.5 + x      0.6 x + 0.4     [0.6, 0.75)   1
 *   2  1.3 - x                          [.55, .65)   1.2 - 0.4 x  1.5 x^2 - 0.2   [0.8, 0.84)   2
 *   3  0.05 + exp(-((x - .35)/.15)^2)   -            0.75 + 0.5 x 1.6 x - 0.3     [0.64, 0.72)  3
 *   4  0.5 + x                          [.55, 1)     0.4 + 1.2 x  0.8 x + 0.15    [0.1, 0.2)    1
 *   5  0.4 + 4 x (1 - x)                -            1.3 - 0.6 x  0.9 x^2 + 0.05  [0.3, 0.38)   4
 *   6  1.5 - x^2                        [0, .45)     0.6 + 0.8 x  1.2 x - 0.1     [0.7, 0.78)   2
 *   7  0.1 + 2 x                        -            0.8 + 0.4 x  0.5 x^2 + 0.45  [0.9, 1)      1
 *   8  0.2 + exp(-(x - .7)^2 / .02)     [0, .6)      1            0.7 x + 0.05    [0.85, 0.9)   3
 * and c_0 = 2, so c_sigma = 17 (004 Eq. 12). |dT_i/dx| is never 1; only domain 7 reaches the
 * spike; y = 0.5 is reachable from all nine. Every input (X_i, W_i) is a 3-candidate RIS from p_i
 * towards p_hat_i (W = sum w / p_hat_i(X), a genuine UCW; W = 0 when no candidate contributes,
 * about 21% of the inputs of domains 4 and 8, 4% of domain 6: 5.9% of all neighbor inputs).
 *
 * One merge (Algorithm 2). The nine domains are the nine pixels of ONE cell (a 9 x 1 image, one
 * tile, one key) rebuilt every trial by restir_cells_build with conf[i] = c_i and the Eq. 17
 * weight[i] = c_i p_hat_i(X_i) W_i, so the neighbor selection probabilities
 * P(i) = weight_i / sum_{j != 0} weight_j depend on the samples. With the confidences scaled by
 * s = N / M or 1 (Sec. 4.3), k = (c_0, s c_sigma):
 *   m~_c = c_c / (c_S + c_c) + sum over N_c uniform draws i of (M / N_c) beta_i(X_0)   (Eq. 18-19)
 *   w~_c = m~_c p_hat(X_0) W_0,
 *   for each of N draws z ~ P (Eq. 17), Y = T_z(X_z) where defined:
 *   w~_z = m_z^pw(Y) / (N P(z)) p_hat(Y) W_z |dT_z/dx|                               (Eq. 14, 16)
 * N_c = 0 / N = 0 ("M") enumerate the cell (factor 1: deterministic pairwise, Eq. 11). The WRS
 * over the w~ picks Y; W_Y = sum w~ / p_hat(Y) (Eq. 7) and f_0(Y) W_Y estimates 0.93 (App. A).
 * Rows: N in {1, 3, M} x N_c in {1, M} x adjustment on / off (N = M: scale 1, once), plus N = 3,
 * N_c = 1 with the confidence-proportional canonical pick P_c(i) = c_i / c_S; |z| < 4.5, |rel| < 1%.
 * Negative controls: factor 1 instead of 1 / (N P(z)) (pick by contribution, plain m^pw) and
 * factor M / N (pretend the Eq. 17 pick were uniform) must give |z| > 6.
 * Fixed inputs (004 Eq. 13, App. B): for one hand-picked set (two W = 0, one failing shift) the
 * mean over 2e5 draw sets of m~_c and of sum_{draws at i} m~_i must match m_c^pw and m_i^pw
 * (|z| < 5; exact to 1e-5 when enumerated), draws must hit i with frequency P(i) (P_c(i)), never
 * the canonical nor a non-contributing pixel, and the pairwise weights must sum to 1 (Eq. 8) at
 * y = 0.5 (reached by all), 0.8 and 0.02, for scales 1, 3/8, 1/8. The canonical sits at pixel 0,
 * 4 or 8 of the cell (first, middle, last Eq. 17 slot) or holds W_0 = 0, so the exclusion of the
 * canonical from the draws is exercised at every position. */
#include "accum.h"
#include "core/rng.h"
#include "restir/cells.h"
#include "restir/gris.h"
#include "restir/spmis.h"
#include "synthetic_domains.h"
#include "synthetic_integrand.h"
#include "test_util.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#if defined(_OPENMP)
#include <omp.h>
#endif

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 25

#define NDOM 9                /* canonical pixel 0 + M = 8 neighbors, one cell */
#define M_OTHERS (NDOM - 1)
#define TRIALS 1000000L       /* per unbiased row */
#define TRIALS_BIASED 250000L /* per negative-control row */
#define CHUNKS 16             /* fixed streams per row: results do not depend on the thread count */
#define Z_MAX 4.5             /* unbiased runs: |z| below this */
#define Z_BIASED 6.0          /* negative controls: |z| above this */
#define REL_MAX 0.01          /* unbiased runs: relative error below 1% */
#define RIS_K 3               /* candidates of the inner RIS that makes W a genuine UCW */
#define DRAW_SETS 200000L     /* draw sets of the fixed-input expectation check */
#define Z_DRAWS 5.0           /* fixed-input check: |z| below this */
#define EXACT_TOL 1e-5        /* deterministic identities (enumeration, partition of unity) */
#define CANONICAL 0           /* the canonical pixel of the cell */

/* ---------------- target domain: integrand (synthetic_integrand.h), the canonical target ------ */

/* int_0^1 f_0 = 0.25 + 1/2 + (area of the tent) */
static double f0_integral(void) { return 0.25 + 0.5 + SPIKE_A * SPIKE_H; }

/* p_hat = p_hat_0, the target of the canonical (and target) domain: ignores the spike. */
static double phat0(double y) { return (y < 0.0 || y >= 1.0) ? 0.0 : 0.35 + synthetic_sin2(y); }

/* ---------------- domains -------------------------------------------------------------------- */

static const struct synthetic_domain dom[NDOM] = {
    {SHIFT_IDENTITY, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.5, -1.0},
    {SHIFT_AFFINE, 0.6, 0.4, 0.6, 0.75, 0.0, 0.0, 0.5, 1.0},
    {SHIFT_QUADRATIC, 1.5, -0.2, 0.8, 0.84, 0.55, 0.65, 1.2, -0.4},
    {SHIFT_AFFINE, 1.6, -0.3, 0.64, 0.72, 0.0, 0.0, 0.75, 0.5},
    {SHIFT_AFFINE, 0.8, 0.15, 0.1, 0.2, 0.55, 1.0, 0.4, 1.2},
    {SHIFT_QUADRATIC, 0.9, 0.05, 0.3, 0.38, 0.0, 0.0, 1.3, -0.6},
    {SHIFT_AFFINE, 1.2, -0.1, 0.7, 0.78, 0.0, 0.45, 0.6, 0.8},
    {SHIFT_QUADRATIC, 0.5, 0.45, 0.9, 1.0, 0.0, 0.0, 0.8, 0.4},
    {SHIFT_AFFINE, 0.7, 0.05, 0.85, 0.9, 0.0, 0.6, 1.0, 0.0},
};

/* c_i (c_0 is the canonical confidence); unscaled, as the cells and spmis functions take them. */
static const float conf[NDOM] = {2.0f, 1.0f, 2.0f, 3.0f, 1.0f, 4.0f, 2.0f, 1.0f, 3.0f};

/* Target of domain k in its own coordinates: p_hat_0 for the canonical, p_hat_k for the others. */
static double target_of(int k, double x)
{
    if (k == 0)
        return phat0(x);
    if (synthetic_target_vanishes(&dom[k], x))
        return 0.0;
    switch (k) {
    case 1:
        return 0.2 + 3.0 * x * x;
    case 2:
        return 1.3 - x;
    case 3: {
        double d = (x - 0.35) / 0.15;
        return 0.05 + exp(-d * d);
    }
    case 4:
        return 0.5 + x;
    case 5:
        return 0.4 + 4.0 * x * (1.0 - x);
    case 6:
        return 1.5 - x * x;
    case 7:
        return 0.1 + 2.0 * x;
    default: {
        double d = x - 0.7;
        return 0.2 + exp(-d * d / 0.02);
    }
    }
}

/* 004 Eq. 10: p_hat_{<-k}(y) = [y in T_k(supp X_k)] p_hat_k(T_k^{-1}(y)) |dT_k^{-1}/dy|. With RIS
 * inputs supp X_k = supp p_hat_k, so the bracket is "y in the image of T_k" times p_hat_k > 0. */
static double phat_from(int k, double y)
{
    double x, jac;
    if (!synthetic_shift_inv(&dom[k], y, &x, &jac))
        return 0.0;
    return target_of(k, x) / jac;
}

/* Input (X_k, W_k): RIS_K candidates from p_k resampled towards p_hat_k, W = sum w / p_hat_k(X)
 * (004 Eq. 2 and 7 with m = 1/K). W = 0 when no candidate contributes. */
static void domain_input(pcg32 *rng, int k, double *x, double *W)
{
    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double sel = 0.0;
    for (int i = 0; i < RIS_K; i++) {
        double cand = synthetic_pdf_sample(&dom[k], pcg32_float(rng));
        float w = (float)(target_of(k, cand) / ((double)RIS_K * synthetic_pdf(&dom[k], cand)));
        if (restir_reservoir_offer(&r, w, pcg32_float(rng)))
            sel = cand;
    }
    *x = sel;
    *W = (double)restir_gris_contribution_weight(&r, (float)target_of(k, sel));
}

/* ---------------- the cell ------------------------------------------------------------------- */

static const uint32_t cell_key[NDOM] = {7u, 7u, 7u, 7u, 7u, 7u, 7u, 7u, 7u};
static const unsigned char cell_valid[NDOM] = {1, 1, 1, 1, 1, 1, 1, 1, 1};

/* 004 Eq. 17 weight of each pixel: c_i p_hat_i(X_i) W_i (0 for a non-contributing input). */
static void eq17_weights(const double *x, const double *W, float *weight)
{
    for (int k = 0; k < NDOM; k++)
        weight[k] = W[k] > 0.0 ? (float)((double)conf[k] * target_of(k, x[k]) * W[k]) : 0.0f;
}

/* The one cell of the 9 x 1 image with nine pixels and the expected number of contributing
 * pixels; returns the cell, or -1 when the build does not hold what was given. */
static int checked_cell(const struct restir_cells *cells, const float *weight)
{
    int contributing = 0;
    for (int k = 0; k < NDOM; k++)
        contributing += weight[k] > 0.0f;
    int cell = cells->cell_of[CANONICAL];
    if (cells->n_cells != 1 || cell < 0 || cells->count[cell] != NDOM || cells->contributing[cell] != contributing)
        return -1;
    return cell;
}

/* ---------------- one stochastic pairwise merge (Algorithm 2) --------------------------------- */

/* Factor applied to each neighbor draw: the library's 1 / (N P(z)) (correct), 1 (pick by
 * contribution with plain m^pw) or M / N (pretend the Eq. 17 pick were uniform). */
enum variant { VAR_SPMIS, VAR_FACTOR_ONE, VAR_FACTOR_UNIFORM };

struct config {
    int n;      /* neighbor draws N; 0 = "M": enumerate the contributing pixels */
    int n_c;    /* canonical draws N_c; 0 = "M": enumerate the M pixels */
    int adjust; /* Sec. 4.3 confidence adjustment */
    enum variant var;
    enum restir_spmis_pick pick; /* canonical draws: P_c = 1 / M (paper) or c_i / c_sigma */
};

struct counts {
    long inputs, noncontributing; /* non-canonical inputs, those with W = 0 */
    long draws, failed;           /* neighbor draws, those whose shift is undefined */
    long bad_cells;               /* trials whose cell build did not match its inputs */
};

static double spmis_once(pcg32 *rng, struct restir_cells *cells, const struct config *g, struct counts *cnt)
{
    double x[NDOM], W[NDOM];
    float weight[NDOM];
    for (int k = 0; k < NDOM; k++)
        domain_input(rng, k, &x[k], &W[k]);
    eq17_weights(x, W, weight);
    for (int k = 1; k < NDOM; k++) {
        cnt->inputs++;
        cnt->noncontributing += !(weight[k] > 0.0f);
    }
    /* One tile: the build's omp for has one iteration, serial whatever the nesting. */
    restir_cells_build(cells, cell_key, cell_valid, conf, weight);
    int cell = checked_cell(cells, weight);
    if (cell < 0) {
        cnt->bad_cells++;
        return 0.0;
    }
    const int m = restir_cells_others(cells, cell, CANONICAL);
    const float cs_raw = restir_cells_confidence_others(cells, cell, CANONICAL, conf);
    const float scale = restir_spmis_confidence_scale(g->n > 0 ? g->n : m, m, g->adjust);
    struct restir_spmis_conf k;
    restir_spmis_conf_set(&k, conf[CANONICAL], cs_raw, scale);

    struct restir_reservoir r;
    restir_reservoir_init(&r);
    double ysel = 0.0;
    struct restir_spmis_draws d;
    float u[RESTIR_SPMIS_MAX_DRAWS];

    /* Canonical (Algorithm 2 lines 6-12): Y_c = X_0, identity shift. */
    const double pc0 = phat0(x[CANONICAL]);
    if (pc0 > 0.0) {
        for (int j = 0; j < g->n_c; j++)
            u[j] = pcg32_float(rng);
        restir_spmis_canonical_draws(cells, cell, CANONICAL, g->n_c, g->pick, u, &d);
        double mc = restir_spmis_canonical_share(&k);
        for (int j = 0; j < d.count; j++) {
            int i = d.pixel[j];
            mc += restir_spmis_canonical_term(&k, conf[i], (float)phat_from(i, x[CANONICAL]), (float)pc0,
                                              d.factor[j]);
        }
        double w = mc * pc0 * W[CANONICAL];
        if (restir_reservoir_offer(&r, (float)w, pcg32_float(rng)))
            ysel = x[CANONICAL];
    }

    /* Neighbors (lines 13-18): N draws by Eq. 17, each offered as its own candidate. */
    for (int j = 0; j < g->n; j++)
        u[j] = pcg32_float(rng);
    restir_spmis_neighbor_draws(cells, cell, CANONICAL, g->n, u, &d);
    for (int j = 0; j < d.count; j++) {
        int z = d.pixel[j];
        double y, jac;
        cnt->draws++;
        if (!synthetic_shift_fwd(&dom[z], x[z], &y, &jac)) {
            cnt->failed++;
            continue;
        }
        float factor = d.factor[j];
        if (g->var == VAR_FACTOR_ONE)
            factor = 1.0f;
        else if (g->var == VAR_FACTOR_UNIFORM)
            factor = (float)m / (float)g->n;
        const double pc = phat0(y);
        double w = restir_spmis_noncanonical(&k, conf[z], (float)phat_from(z, y), (float)pc, factor) * pc * W[z] * jac;
        if (restir_reservoir_offer(&r, (float)w, pcg32_float(rng)))
            ysel = y;
    }
    double Wy = (double)restir_gris_contribution_weight(&r, (float)phat0(ysel)); /* Eq. 7 */
    return synthetic_f0(ysel) * Wy;
}

/* ---------------- statistics and driver ------------------------------------------------------- */

/* trials independent merges over CHUNKS fixed RNG streams (each with its own cells), summed in
 * chunk order, so the result is the same for any thread count. */
static struct accum run(unsigned seed, const struct config *g, long trials, struct counts *cnt)
{
    struct accum part[CHUNKS];
    struct counts pc[CHUNKS];
#if defined(_OPENMP)
#pragma omp parallel for schedule(static)
#endif
    for (int c = 0; c < CHUNKS; c++) {
        pcg32 rng = rng_for(seed, (uint64_t)c, 0x5b15u, 0u);
        struct restir_cells cells;
        struct accum a = {0.0, 0.0, 0};
        struct counts n = {0, 0, 0, 0, 0};
        if (restir_cells_init(&cells, NDOM, 1, 16) != 0) {
            n.bad_cells = trials / CHUNKS;
        } else {
            for (long i = 0; i < trials / CHUNKS; i++)
                acc_add(&a, spmis_once(&rng, &cells, g, &n));
            restir_cells_fini(&cells);
        }
        part[c] = a;
        pc[c] = n;
    }
    struct accum total = {0.0, 0.0, 0};
    memset(cnt, 0, sizeof(*cnt));
    for (int c = 0; c < CHUNKS; c++) {
        acc_merge(&total, &part[c]);
        cnt->inputs += pc[c].inputs;
        cnt->noncontributing += pc[c].noncontributing;
        cnt->draws += pc[c].draws;
        cnt->failed += pc[c].failed;
        cnt->bad_cells += pc[c].bad_cells;
    }
    return total;
}

static const char *count_name(int n, char *buf)
{
    if (n <= 0)
        return "M";
    snprintf(buf, 12, "%d", n);
    return buf;
}

static const char *variant_name(enum variant v)
{
    return v == VAR_SPMIS ? "spmis" : v == VAR_FACTOR_ONE ? "f=1" : "f=M/N";
}

/* Prints one table row and returns z = (mean - exact) / sigma. */
static double row(const struct config *g, const struct accum *a, const struct counts *cnt, double exact)
{
    char b1[12], b2[12];
    double m = acc_mean(a), s = acc_sigma(a), z = (m - exact) / s;
    printf("  %-6s %2s %3s %-4s %3s %10.6f %10.6f %9.6f %+9.2f %+8.3f%% %6.2f%% %6.2f%%\n", variant_name(g->var),
           count_name(g->n, b1), count_name(g->n_c, b2), g->pick == RESTIR_SPMIS_PICK_UNIFORM ? "1/M" : "c_i",
           g->adjust ? "yes" : "no", m, exact, s, z,
           100.0 * (m - exact) / exact, 100.0 * (double)cnt->noncontributing / (double)cnt->inputs,
           cnt->draws > 0 ? 100.0 * (double)cnt->failed / (double)cnt->draws : 0.0);
    return z;
}

/* ---------------- fixed inputs: E over the draws of the stochastic weights (Eq. 13, App. B) --- */

/* Independent double evaluations of 004 Eq. 11a and 11b (all c_i and c_S scaled by s). */
static double ref_pairwise(double s, int i, double p_from, double p_c)
{
    double cs = 0.0;
    for (int j = 1; j < NDOM; j++)
        cs += s * conf[j];
    double cc = conf[0], d = cs * p_from + cc * p_c;
    return d > 0.0 ? cs / (cs + cc) * s * conf[i] * p_from / d : 0.0;
}
static double ref_canonical(double s, double y)
{
    double cs = 0.0;
    for (int j = 1; j < NDOM; j++)
        cs += s * conf[j];
    double cc = conf[0], pc = phat0(y), m = cc / (cs + cc);
    for (int j = 1; j < NDOM; j++) {
        double pf = phat_from(j, y), d = cs * pf + cc * pc;
        m += d > 0.0 ? s * conf[j] / (cs + cc) * cc * pc / d : 0.0;
    }
    return m;
}

/* The deterministic pairwise weights through the library (factor 1 over all M). */
static double lib_canonical(const struct restir_spmis_conf *k, double y)
{
    double m = restir_spmis_canonical_share(k);
    for (int j = 1; j < NDOM; j++)
        m += restir_spmis_canonical_term(k, conf[j], (float)phat_from(j, y), (float)phat0(y), 1.0f);
    return m;
}

/* Partition of unity (004 Eq. 8) at y: sum_i m_i^pw(y) + m_c^pw(y), library and reference. */
static void partition(const struct restir_spmis_conf *k, double y, double *lib, double *ref)
{
    *lib = lib_canonical(k, y);
    *ref = ref_canonical((double)k->scale, y);
    for (int j = 1; j < NDOM; j++) {
        *lib += restir_spmis_pairwise(k, conf[j], (float)phat_from(j, y), (float)phat0(y));
        *ref += ref_pairwise((double)k->scale, j, phat_from(j, y), phat0(y));
    }
}

/* Hand-picked inputs: 2 and 4 are non-contributing (X in the zero set of p_hat_i, W = 0), 3
 * contributes but its shift fails (X_3 in [0.64, 0.72)), the others shift; W = 1 / p_i(X). */
static const double fixed_x[NDOM] = {0.3, 0.2, 0.6, 0.68, 0.8, 0.5, 0.55, 0.82, 0.75};

static void fixed_inputs(double *x, double *W)
{
    for (int k = 0; k < NDOM; k++) {
        x[k] = fixed_x[k];
        W[k] = target_of(k, x[k]) > 0.0 ? 1.0 / synthetic_pdf(&dom[k], x[k]) : 0.0;
    }
}

/* Where the domains sit in the 9 x 1 image (domain k at pixel pix[k]), so the canonical pixel's
 * slot among the contributing entries is the first, a middle or the last one, or it does not
 * contribute at all (W_0 = 0): every case of the excluded interval of the Eq. 17 prefix sums. */
struct layout {
    const char *name;
    int pix[NDOM];
    int canonical_w0; /* 0: W_0 forced to 0 (the canonical reservoir holds no contributing sample) */
};
static const struct layout layouts[4] = {
    {"c@0", {0, 1, 2, 3, 4, 5, 6, 7, 8}, 1},
    {"c@4", {4, 0, 1, 2, 3, 5, 6, 7, 8}, 1},
    {"c@8", {8, 0, 1, 2, 3, 4, 5, 6, 7}, 1},
    {"c@4W0", {4, 0, 1, 2, 3, 5, 6, 7, 8}, 0},
};

/* One fixed-input configuration: the cell built from the layout, the deterministic pairwise
 * weights, DRAW_SETS draw sets; prints its row and counts its out-of-bounds checks as one EXPECT. */
static void check_fixed(const struct layout *lay, int n, int n_c, enum restir_spmis_pick pick, int adjust,
                        unsigned seed)
{
    double x[NDOM], W[NDOM];
    float wdom[NDOM], weight[NDOM], cpx[NDOM];
    int dom_of[NDOM];
    fixed_inputs(x, W);
    if (!lay->canonical_w0)
        W[0] = 0.0;
    eq17_weights(x, W, wdom);
    for (int k = 0; k < NDOM; k++) {
        dom_of[lay->pix[k]] = k;
        weight[lay->pix[k]] = wdom[k];
        cpx[lay->pix[k]] = conf[k];
    }
    const int canon = lay->pix[0];
    struct restir_cells cells;
    if (restir_cells_init(&cells, NDOM, 1, 16) != 0) {
        EXPECT(0, "restir_cells_init(9, 1, 16)");
        return;
    }
    restir_cells_build(&cells, cell_key, cell_valid, cpx, weight);
    int cell = checked_cell(&cells, weight);
    EXPECT(cell >= 0 && cells.cell_of[canon] == cell, "%s: one cell of 9 pixels", lay->name);
    if (cell < 0) {
        restir_cells_fini(&cells);
        return;
    }
    const int m = restir_cells_others(&cells, cell, canon);
    const float cs_raw = restir_cells_confidence_others(&cells, cell, canon, cpx);
    const float scale = restir_spmis_confidence_scale(n > 0 ? n : m, m, adjust);
    struct restir_spmis_conf k;
    restir_spmis_conf_set(&k, conf[0], cs_raw, scale);
    int bad = (m != M_OTHERS) + !(fabs((double)cs_raw - 17.0) < 1e-6);

    /* Deterministic pairwise weights (004 Eq. 11) at the fixed samples, per domain. */
    const double yc = x[0];
    const double mc_pw = lib_canonical(&k, yc);
    double y[NDOM], jac[NDOM], mi_pw[NDOM], prob[NDOM];
    int ok[NDOM];
    double wsum = 0.0;
    for (int i = 1; i < NDOM; i++)
        wsum += wdom[i];
    for (int i = 0; i < NDOM; i++) {
        ok[i] = i != 0 && W[i] > 0.0 && synthetic_shift_fwd(&dom[i], x[i], &y[i], &jac[i]);
        mi_pw[i] = ok[i] ? restir_spmis_pairwise(&k, conf[i], (float)phat_from(i, y[i]), (float)phat0(y[i])) : 0.0;
        prob[i] = i != 0 ? (double)wdom[i] / wsum : 0.0;
    }
    bad += !(fabs(mc_pw - ref_canonical((double)scale, yc)) <= EXACT_TOL);
    for (int i = 1; i < NDOM; i++)
        if (ok[i])
            bad += !(fabs(mi_pw[i] - ref_pairwise((double)scale, i, phat_from(i, y[i]), phat0(y[i]))) <= EXACT_TOL);

    /* Average of the stochastic weights over DRAW_SETS independent draw sets. */
    struct accum mc = {0.0, 0.0, 0}, mi[NDOM];
    long hits[NDOM] = {0}, canon_hits[NDOM] = {0};
    memset(mi, 0, sizeof(mi));
    pcg32 rng = rng_for(seed, 1u, 0x5b15u, 1u);
    struct restir_spmis_draws d;
    float u[RESTIR_SPMIS_MAX_DRAWS];
    long draws = 0, canon_draws = 0, foreign = 0;
    for (long t = 0; t < DRAW_SETS; t++) {
        for (int j = 0; j < n_c; j++)
            u[j] = pcg32_float(&rng);
        restir_spmis_canonical_draws(&cells, cell, canon, n_c, pick, u, &d);
        double v = restir_spmis_canonical_share(&k);
        for (int j = 0; j < d.count; j++) {
            if (d.pixel[j] < 0 || d.pixel[j] >= NDOM) {
                foreign++;
                continue;
            }
            int i = dom_of[d.pixel[j]];
            canon_hits[i]++;
            canon_draws++;
            v += restir_spmis_canonical_term(&k, conf[i], (float)phat_from(i, yc), (float)phat0(yc), d.factor[j]);
        }
        acc_add(&mc, v);

        for (int j = 0; j < n; j++)
            u[j] = pcg32_float(&rng);
        restir_spmis_neighbor_draws(&cells, cell, canon, n, u, &d);
        double s[NDOM] = {0.0};
        for (int j = 0; j < d.count; j++) {
            if (d.pixel[j] < 0 || d.pixel[j] >= NDOM) {
                foreign++;
                continue;
            }
            int i = dom_of[d.pixel[j]];
            hits[i]++;
            draws++;
            if (ok[i])
                s[i] += restir_spmis_noncanonical(&k, conf[i], (float)phat_from(i, y[i]), (float)phat0(y[i]),
                                                  d.factor[j]);
        }
        for (int i = 1; i < NDOM; i++)
            acc_add(&mi[i], s[i]);
    }
    restir_cells_fini(&cells);

    /* Draw counts: exactly n_c (or M) and n (or the contributing others) per set. */
    int contributing_others = 0;
    for (int i = 1; i < NDOM; i++)
        contributing_others += wdom[i] > 0.0f;
    bad += foreign != 0;
    bad += canon_draws != DRAW_SETS * (n_c > 0 ? n_c : M_OTHERS);
    bad += draws != DRAW_SETS * (n > 0 ? n : contributing_others);

    char b1[12], b2[12];
    double zc = acc_sigma(&mc) > 0.0 ? (acc_mean(&mc) - mc_pw) / acc_sigma(&mc) : 0.0;
    double zmax = 0.0, dmax = fabs(acc_mean(&mc) - mc_pw), fz = 0.0;
    if (acc_sigma(&mc) > 0.0)
        bad += !(fabs(zc) < Z_DRAWS);
    else
        bad += !(fabs(acc_mean(&mc) - mc_pw) <= EXACT_TOL);
    for (int i = 1; i < NDOM; i++) {
        double mean = acc_mean(&mi[i]), sg = acc_sigma(&mi[i]), diff = mean - mi_pw[i];
        dmax = fmax(dmax, fabs(diff));
        if (sg > 0.0) {
            zmax = fmax(zmax, fabs(diff / sg));
            bad += !(fabs(diff / sg) < Z_DRAWS);
        } else {
            bad += !(fabs(diff) <= EXACT_TOL);
        }
        /* draw frequencies: P(i) (Eq. 17) for the neighbor draws, P_c(i) for the canonical ones */
        if (n > 0) {
            double p = prob[i], e = (double)draws * p, sd = sqrt((double)draws * p * (1.0 - p));
            if (p > 0.0)
                fz = fmax(fz, fabs((double)hits[i] - e) / sd);
            else
                bad += hits[i] != 0;
        } else {
            bad += hits[i] != (wdom[i] > 0.0f ? DRAW_SETS : 0);
        }
        if (n_c > 0) {
            double p = pick == RESTIR_SPMIS_PICK_UNIFORM ? 1.0 / M_OTHERS : (double)conf[i] / 17.0;
            double e = (double)canon_draws * p, sd = sqrt((double)canon_draws * p * (1.0 - p));
            fz = fmax(fz, fabs((double)canon_hits[i] - e) / sd);
        } else {
            bad += canon_hits[i] != DRAW_SETS;
        }
    }
    bad += hits[0] != 0 || canon_hits[0] != 0; /* the canonical is never its own neighbor */
    bad += !(fz < Z_DRAWS);
    double lib, ref;
    partition(&k, 0.5, &lib, &ref);
    bad += !(fabs(lib - 1.0) <= EXACT_TOL);
    printf("  %-5s %2s %3s %-3s %3s %6.4f %9.6f %9.6f %+7.2f %8.2f %9.2e %6.2f %10.7f %s\n", lay->name,
           count_name(n, b1), count_name(n_c, b2), pick == RESTIR_SPMIS_PICK_UNIFORM ? "1/M" : "c_i",
           adjust ? "yes" : "no", (double)scale, mc_pw, acc_mean(&mc), zc, zmax, dmax, fz, lib, bad ? "FAIL" : "ok");
    EXPECT(bad == 0, "fixed inputs %s N = %d, N_c = %d, pick %d, adjust = %d: %d checks out of bounds", lay->name, n,
           n_c, (int)pick, adjust, bad);
}

static void fixed_input_checks(void)
{
    double x[NDOM], W[NDOM];
    float weight[NDOM];
    fixed_inputs(x, W);
    eq17_weights(x, W, weight);
    EXPECT(weight[2] == 0.0f && weight[4] == 0.0f, "fixed inputs 2 and 4 must be non-contributing");
    double yy, jj;
    EXPECT(weight[3] > 0.0f && !synthetic_shift_fwd(&dom[3], x[3], &yy, &jj),
           "fixed input 3 must contribute and fail to shift");

    /* The same cell built outside any parallel region and inside one (where the build's own
     * omp for is a nested, by default inactive region) must be identical. */
    struct restir_cells cells, inner;
    int ok = restir_cells_init(&cells, NDOM, 1, 16) == 0;
    EXPECT(ok, "restir_cells_init(9, 1, 16)");
    if (!ok)
        return;
    restir_cells_build(&cells, cell_key, cell_valid, conf, weight);
    int cell = checked_cell(&cells, weight);
    EXPECT(cell >= 0, "one cell of 9 pixels, 7 contributing");
    int same = 0, nested = 1;
    if (cell >= 0 && restir_cells_init(&inner, NDOM, 1, 16) == 0) {
#if defined(_OPENMP)
#pragma omp parallel num_threads(2)
        {
#pragma omp single
            {
                restir_cells_build(&inner, cell_key, cell_valid, conf, weight);
#pragma omp parallel
                {
#pragma omp single
                    nested = omp_get_num_threads();
                }
            }
        }
#else
        restir_cells_build(&inner, cell_key, cell_valid, conf, weight);
#endif
        same = inner.n_cells == cells.n_cells && memcmp(inner.entry, cells.entry, sizeof(int) * NDOM) == 0 &&
               memcmp(inner.cdf, cells.cdf, sizeof(double) * NDOM) == 0 &&
               memcmp(inner.conf_cdf, cells.conf_cdf, sizeof(double) * NDOM) == 0 &&
               inner.contributing[cell] == cells.contributing[cell] && inner.conf_sum[cell] == cells.conf_sum[cell];
        restir_cells_fini(&inner);
    }
    restir_cells_fini(&cells);
    EXPECT(same, "cells built inside a parallel region equal the serial build");
    printf("cells build inside a parallel region: nested team of %d thread(s), same cell: %s\n", nested,
           same ? "yes" : "no");

    /* Partition of unity (004 Eq. 8): y = 0.5 reachable by all nine domains; y = 0.8 (spike) only
     * by 0 and 7; y = 0.02 only by the canonical. */
    for (int j = 1; j < NDOM; j++)
        EXPECT(phat_from(j, 0.5) > 0.0, "y = 0.5 reachable from domain %d", j);
    static const double ys[3] = {0.5, 0.8, 0.02};
    static const float scales[3] = {1.0f, 3.0f / 8.0f, 1.0f / 8.0f};
    for (int si = 0; si < 3; si++) {
        struct restir_spmis_conf k;
        restir_spmis_conf_set(&k, conf[CANONICAL], 17.0f, scales[si]);
        printf("  partition of unity, scale %.4f:", (double)scales[si]);
        for (int yi = 0; yi < 3; yi++) {
            double lib, ref;
            partition(&k, ys[yi], &lib, &ref);
            EXPECT_NEAR(lib, 1.0, EXACT_TOL, "library pairwise weights sum to 1");
            EXPECT_NEAR(ref, 1.0, 1e-12, "reference pairwise weights sum to 1");
            printf("  y = %.2f: sum m^pw = %.8f (ref %.8f)", ys[yi], lib, ref);
        }
        printf("\n");
    }
    EXPECT_NEAR(restir_spmis_confidence_scale(1, 8, 1), 0.125, 1e-7, "scale N = 1");
    EXPECT_NEAR(restir_spmis_confidence_scale(3, 8, 1), 0.375, 1e-7, "scale N = 3");
    EXPECT_NEAR(restir_spmis_confidence_scale(8, 8, 1), 1.0, 0.0, "scale N = M");
    EXPECT_NEAR(restir_spmis_confidence_scale(3, 8, 0), 1.0, 0.0, "scale without adjustment");

    printf("fixed inputs, %ld draw sets: E[m~_c] = m_c^pw, E[sum_{draws at i} m~_i] = m_i^pw, draw "
           "frequencies P(i) and P_c(i)\n",
           DRAW_SETS);
    printf("  %-5s %2s %3s %-3s %3s %6s %9s %9s %7s %8s %9s %6s %10s\n", "cell", "N", "N_c", "P_c", "adj", "scale",
           "m_c^pw", "E m~_c", "z_c", "max|z_i|", "max|diff|", "freq z", "sum m(.5)");
    static const int ns[3] = {1, 3, 0}, ncs[3] = {1, 3, 0};
    unsigned seed = 9100u;
    /* canonical at pixel 0: every combination */
    for (int a = 0; a <= 1; a++)
        for (int ni = 0; ni < 3; ni++)
            for (int ci = 0; ci < 3; ci++)
                for (int pk = 0; pk < (ncs[ci] > 0 ? 2 : 1); pk++)
                    check_fixed(&layouts[0], ns[ni], ncs[ci],
                                pk ? RESTIR_SPMIS_PICK_CONFIDENCE : RESTIR_SPMIS_PICK_UNIFORM, a, seed++);
    /* canonical in the middle, last, or non-contributing: the excluded interval elsewhere */
    for (int li = 1; li < 4; li++)
        for (int ni = 0; ni < 2; ni++)
            for (int pk = 0; pk < 2; pk++)
                check_fixed(&layouts[li], ns[ni], 3, pk ? RESTIR_SPMIS_PICK_CONFIDENCE : RESTIR_SPMIS_PICK_UNIFORM,
                            1, seed++);
}

int main(void)
{
    const double exact = f0_integral();
    EXPECT_NEAR(exact, 0.93, 1e-12, "closed-form integral of f_0");

    fixed_input_checks();

    printf("stochastic pairwise MIS in one cell of 1 + %d domains, %ld trials per row (controls %ld), "
           "c = (%g | %g %g %g %g %g %g %g %g)\n",
           M_OTHERS, TRIALS, TRIALS_BIASED, (double)conf[0], (double)conf[1], (double)conf[2], (double)conf[3],
           (double)conf[4], (double)conf[5], (double)conf[6], (double)conf[7], (double)conf[8]);
    printf("  %-6s %2s %3s %-4s %3s %10s %10s %9s %9s %9s %7s %7s\n", "mode", "N", "N_c", "P_c", "adj", "estimate",
           "exact", "sigma", "z", "rel", "W=0", "T fail");

    unsigned seed = 5000u;
    static const int ns[3] = {1, 3, 0}, ncs[2] = {1, 0};
    for (int ni = 0; ni < 3; ni++)
        for (int ci = 0; ci < 2; ci++)
            for (int a = 0; a <= 2; a++) {
                if ((ns[ni] == 0 && a == 1) || (a == 2 && !(ns[ni] == 3 && ncs[ci] == 1)))
                    continue; /* N = M: the adjustment is the identity (scale 1) */
                /* a = 2: the confidence-proportional canonical pick, once (N = 3, N_c = 1) */
                struct config g = {ns[ni], ncs[ci], a != 0, VAR_SPMIS,
                                   a == 2 ? RESTIR_SPMIS_PICK_CONFIDENCE : RESTIR_SPMIS_PICK_UNIFORM};
                struct counts cnt;
                struct accum acc = run(seed++, &g, TRIALS, &cnt);
                double z = row(&g, &acc, &cnt, exact);
                double rel = (acc_mean(&acc) - exact) / exact;
                EXPECT(cnt.bad_cells == 0, "N = %d, N_c = %d, adjust = %d: %ld cell builds did not match", g.n,
                       g.n_c, g.adjust, cnt.bad_cells);
                EXPECT(fabs(z) < Z_MAX, "N = %d, N_c = %d, adjust = %d: z = %.2f", g.n, g.n_c, g.adjust, z);
                EXPECT(fabs(rel) < REL_MAX, "N = %d, N_c = %d, adjust = %d: relative error %.4f", g.n, g.n_c,
                       g.adjust, rel);
            }

    /* Negative controls: wrong neighbor factors must be detected. */
    static const struct config bad[2] = {{1, 1, 0, VAR_FACTOR_ONE, RESTIR_SPMIS_PICK_UNIFORM},
                                         {1, 1, 0, VAR_FACTOR_UNIFORM, RESTIR_SPMIS_PICK_UNIFORM}};
    for (int bi = 0; bi < 2; bi++) {
        struct counts cnt;
        struct accum acc = run(seed++, &bad[bi], TRIALS_BIASED, &cnt);
        double z = row(&bad[bi], &acc, &cnt, exact);
        EXPECT(fabs(z) > Z_BIASED, "%s: bias only %.2f sigma, the test has no power", variant_name(bad[bi].var), z);
    }
    return test_finish();
}
