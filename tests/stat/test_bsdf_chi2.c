/* test_bsdf_chi2.c: statistical tests of the BSDF: chi-square fit of bsdf_sample against
 * bsdf_pdf, sample/pdf/eval consistency, pdf normalization and energy conservation.
 * Must never depend on the ray tracer or on render passes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "chi2_util.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "shading/bsdf.h"
#include "test_util.h"

#define TWO_PI 6.283185307179586
#define N_MU 10     /* cos(theta) cells */
#define N_PHI 20    /* phi cells */
#define N_CELLS (N_MU * N_PHI + 1) /* + one cell for failed samples (no direction) */
#define N_SAMPLES 1000000
#define FAMILY_ALPHA 0.01

/* The density being integrated: either the true bsdf_pdf or, for the power self-check, a
 * deliberately wrong one (the true pdf times cos(theta_i), renormalized by the caller). */
struct pdf_ctx {
    const struct bsdf *b;
    vec3 n, wo;
    frame fr;
    int times_cos;
    double mirror_theta, mirror_phi; /* wo mirrored about n, in the binning frame */
};

#define M_PI_2_LOCAL 1.5707963267948966

static struct pdf_ctx make_ctx(const struct bsdf *b, vec3 n, vec3 wo, int times_cos)
{
    struct pdf_ctx c;
    c.b = b;
    c.n = n;
    c.wo = wo;
    c.fr = frame_from_normal(n);
    c.times_cos = times_cos;
    vec3 l = frame_to_local(&c.fr, wo);
    c.mirror_theta = acos(fmin(fmax((double)l.z, -1.0), 1.0));
    c.mirror_phi = atan2(-(double)l.y, -(double)l.x);
    if (c.mirror_phi < 0.0)
        c.mirror_phi += TWO_PI;
    return c;
}

/* The integrand in (theta, phi): pdf * sin(theta), since dw = sin(theta) dtheta dphi. Working
 * in theta rather than cos(theta) keeps a near-mirror lobe about alpha wide in both variables
 * even at the pole, where it would be only ~alpha^2 wide in cos(theta). */
static double pdf_at(const struct pdf_ctx *c, double theta, double phi)
{
    double s = sin(theta), mu = cos(theta);
    vec3 l = v3((float)(s * cos(phi)), (float)(s * sin(phi)), (float)mu);
    vec3 w = frame_to_world(&c->fr, l);
    double p = bsdf_pdf(c->b, c->n, c->wo, w);
    return (c->times_cos ? p * mu : p) * s;
}

/* 3-point Gauss-Legendre product rule on a (theta, phi) rectangle. Interior nodes only, so the
 * horizon (where bsdf_pdf drops to 0 by convention) is never evaluated. */
static double gl3(const struct pdf_ctx *c, double t0, double t1, double p0, double p1)
{
    static const double x[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double ht = 0.5 * (t1 - t0), ct = 0.5 * (t1 + t0);
    double hp = 0.5 * (p1 - p0), cp = 0.5 * (p1 + p0);
    double sum = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            sum += w[i] * w[j] * pdf_at(c, ct + ht * x[i], cp + hp * x[j]);
    return sum * ht * hp;
}

/* Whether a (theta, phi) rectangle is within a few alpha of the mirror direction, where the
 * specular lobe concentrates; the angular distance is approximated in (theta, sin(theta) phi). */
static int near_mirror(const struct pdf_ctx *c, double t0, double t1, double p0, double p1)
{
    double margin = 8.0 * c->b->alpha;
    double dt = c->mirror_theta < t0 ? t0 - c->mirror_theta : (c->mirror_theta > t1 ? c->mirror_theta - t1 : 0.0);
    double dp = 0.0;
    if (c->mirror_phi < p0 || c->mirror_phi > p1) {
        double a = fabs(c->mirror_phi - p0), b = fabs(c->mirror_phi - p1);
        a = fmin(a, TWO_PI - a);
        b = fmin(b, TWO_PI - b);
        dp = fmin(a, b) * sin(fmin(t0, M_PI_2_LOCAL));
    }
    return dt * dt + dp * dp < margin * margin;
}

/* Adaptive quadrature: split in four until the children agree with the parent. Near the mirror
 * direction the split is forced until the node spacing is below alpha, so that a near-mirror
 * peak (about alpha radians wide) cannot hide between nodes, where parent and children would
 * agree on 0. */
static double integrate(const struct pdf_ctx *c, double t0, double t1, double p0, double p1, double whole,
                        int depth, double tol)
{
    double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
    double q[4] = {gl3(c, t0, tm, p0, pm), gl3(c, tm, t1, p0, pm), gl3(c, t0, tm, pm, p1),
                   gl3(c, tm, t1, pm, p1)};
    double sum = q[0] + q[1] + q[2] + q[3];
    double spacing = fmax(t1 - t0, (p1 - p0) * sin(t1)) / 6.0; /* node spacing of the children */
    int forced = spacing > 0.5 * c->b->alpha && near_mirror(c, t0, t1, p0, p1);
    if (depth >= 12 || (!forced && depth >= 1 && fabs(sum - whole) <= tol))
        return sum;
    double t = 0.5 * tol;
    return integrate(c, t0, tm, p0, pm, q[0], depth + 1, t) + integrate(c, tm, t1, p0, pm, q[1], depth + 1, t) +
           integrate(c, t0, tm, pm, p1, q[2], depth + 1, t) + integrate(c, tm, t1, pm, p1, q[3], depth + 1, t);
}

/* Probability of each (cos theta, phi) cell; returns the total (the pdf's integral over the
 * hemisphere). */
static double cell_probabilities(const struct pdf_ctx *c, double *prob)
{
    double total = 0.0;
    for (int i = 0; i < N_MU; i++) {
        double t0 = acos((double)(i + 1) / N_MU), t1 = acos((double)i / N_MU);
        for (int j = 0; j < N_PHI; j++) {
            double p0 = TWO_PI * j / N_PHI, p1 = TWO_PI * (j + 1) / N_PHI;
            double p = integrate(c, t0, t1, p0, p1, gl3(c, t0, t1, p0, p1), 0, 1e-7);
            prob[i * N_PHI + j] = p;
            total += p;
        }
    }
    return total;
}

static int cell_of(const frame *fr, vec3 wi)
{
    vec3 l = frame_to_local(fr, wi);
    double mu = fmin(fmax((double)l.z, 0.0), 1.0);
    double phi = atan2((double)l.y, (double)l.x);
    if (phi < 0.0)
        phi += TWO_PI;
    int i = (int)(mu * N_MU), j = (int)(phi / TWO_PI * N_PHI);
    i = i < 0 ? 0 : (i >= N_MU ? N_MU - 1 : i);
    j = j < 0 ? 0 : (j >= N_PHI ? N_PHI - 1 : j);
    return i * N_PHI + j;
}

struct case_desc {
    const char *name;
    struct bsdf b;
    int white_diffuse; /* albedo must be exactly 1 */
};

struct sample_stats {
    double observed[N_CELLS];
    double albedo[3];
    long failed;
    long bad_pdf, bad_eval, bad_dir;
    double max_pdf_rel;
};

/* Draws N_SAMPLES directions and bins them; checks (b) consistency and accumulates (d). */
static void run_samples(const struct bsdf *b, vec3 n, vec3 wo, uint64_t seed, struct sample_stats *st)
{
    memset(st, 0, sizeof *st);
    frame fr = frame_from_normal(n);
    pcg32 r = pcg32_make(seed, 0x9e37u);
    for (int s = 0; s < N_SAMPLES; s++) {
        float u0 = pcg32_float(&r), u1 = pcg32_float(&r), u2 = pcg32_float(&r);
        vec3 wi, f;
        float pdf;
        if (!bsdf_sample(b, n, wo, u0, u1, u2, &wi, &pdf, &f)) {
            st->failed++;
            st->observed[N_CELLS - 1] += 1.0;
            continue;
        }
        st->observed[cell_of(&fr, wi)] += 1.0;
        float cos_i = v3_dot(n, wi);
        if (!(cos_i > 0.0f) || fabsf(v3_length(wi) - 1.0f) > 1e-4f)
            st->bad_dir++;
        if ((s & 3) == 0) {
            float p2 = bsdf_pdf(b, n, wo, wi);
            double rel = fabs((double)p2 - pdf) / fmax((double)pdf, 1e-30);
            if (!(pdf > 0.0f) || !isfinite(pdf) || rel > 1e-4)
                st->bad_pdf++;
            if (rel > st->max_pdf_rel)
                st->max_pdf_rel = rel;
            vec3 f2 = bsdf_eval(b, n, wo, wi);
            vec3 d = v3_sub(f2, f);
            if (fabsf(d.x) > 1e-4f * fabsf(f.x) + 1e-12f || fabsf(d.y) > 1e-4f * fabsf(f.y) + 1e-12f ||
                fabsf(d.z) > 1e-4f * fabsf(f.z) + 1e-12f)
                st->bad_eval++;
        }
        /* Directional albedo estimator f cos / pdf (Veach 1997); failed samples contribute 0. */
        double w = cos_i / (double)pdf;
        st->albedo[0] += f.x * w;
        st->albedo[1] += f.y * w;
        st->albedo[2] += f.z * w;
    }
    for (int k = 0; k < 3; k++)
        st->albedo[k] /= N_SAMPLES;
}

/* Chi-square p-value of the binned samples against a density context. */
static double chi2_against(const struct pdf_ctx *c, const double *observed, double *integral_out, int *dof_out)
{
    double prob[N_CELLS];
    double total = cell_probabilities(c, prob);
    if (c->times_cos) {
        /* The wrong density is renormalized over the hemisphere; failure mass kept as sampled. */
        double fail = observed[N_CELLS - 1] / N_SAMPLES;
        for (int i = 0; i < N_CELLS - 1; i++)
            prob[i] *= (1.0 - fail) / total;
        total = 1.0 - fail;
    }
    prob[N_CELLS - 1] = fmax(0.0, 1.0 - total);
    double expected[N_CELLS];
    for (int i = 0; i < N_CELLS; i++)
        expected[i] = prob[i] * N_SAMPLES;
    int dof;
    double stat = chi2_pooled(observed, expected, N_CELLS, &dof);
    if (integral_out)
        *integral_out = total;
    if (dof_out)
        *dof_out = dof;
    return chi2_pvalue(stat, dof);
}

static struct bsdf material_bsdf(vec3 base, float metallic, float roughness)
{
    struct material m;
    memset(&m, 0, sizeof m);
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    struct bsdf b;
    bsdf_from_material(&m, &b);
    return b;
}

/* The chi-square machinery itself against closed forms: dof 2 has Q = exp(-x/2) and dof 1 has
 * Q = erfc(sqrt(x/2)). */
static void test_chi2_cdf(void)
{
    const double xs[] = {0.01, 0.5, 1.0, 3.0, 10.0, 40.0};
    for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++) {
        EXPECT(fabs(chi2_pvalue(xs[i], 2) - exp(-0.5 * xs[i])) < 1e-12, "dof 2 at %g", xs[i]);
        EXPECT(fabs(chi2_pvalue(xs[i], 1) - erfc(sqrt(0.5 * xs[i]))) < 1e-12, "dof 1 at %g", xs[i]);
    }
    /* Tabulated 1% critical values (e.g. NIST/SEMATECH e-Handbook, table 1.3.6.7.4). */
    EXPECT_NEAR(chi2_pvalue(23.209, 10), 0.01, 2e-5, "chi2 dof 10 upper 1%");
    EXPECT_NEAR(chi2_pvalue(135.807, 100), 0.01, 2e-5, "chi2 dof 100 upper 1%");
}

static void test_material_model(void)
{
    struct bsdf b = material_bsdf(v3(0.5f, 0.5f, 0.5f), 0.0f, 0.5f);
    EXPECT_NEAR(b.f0.x, 0.04, 1e-7, "dielectric f0");
    EXPECT_NEAR(b.alpha, 0.25, 1e-7, "alpha = roughness^2");
    EXPECT(b.p_spec >= 0.1f && b.p_spec <= 0.9f, "dielectric p_spec %g in [0.1, 0.9]", b.p_spec);
    EXPECT_NEAR(bsdf_roughness(&b), 1.0, 0.0, "diffuse-dominated roughness");
    b = material_bsdf(v3(0.9f, 0.6f, 0.5f), 1.0f, 0.3f);
    EXPECT(b.p_spec == 1.0f && v3_max_component(b.diffuse) == 0.0f, "metal samples only specular");
    EXPECT_NEAR(bsdf_roughness(&b), 0.09, 1e-7, "metal roughness is its alpha");
    b = material_bsdf(v3(0.9f, 0.6f, 0.5f), 1.0f, 0.0f);
    EXPECT_NEAR(b.alpha, BSDF_MIN_ALPHA, 0.0, "alpha clamp");
    /* Below-surface directions and wo below the surface give zero. */
    vec3 n = v3(0.0f, 0.0f, 1.0f);
    vec3 up = v3_normalize(v3(0.3f, 0.1f, 0.9f)), down = v3_normalize(v3(0.3f, 0.1f, -0.9f));
    b = material_bsdf(v3(0.5f, 0.5f, 0.5f), 0.0f, 0.5f);
    EXPECT(bsdf_pdf(&b, n, up, down) == 0.0f && bsdf_pdf(&b, n, down, up) == 0.0f, "pdf below");
    EXPECT(v3_max_component(bsdf_eval(&b, n, up, down)) == 0.0f, "eval below");
    EXPECT(v3_max_component(bsdf_eval(&b, n, down, up)) == 0.0f, "eval wo below");
    vec3 wi, f;
    float pdf;
    EXPECT(bsdf_sample(&b, n, down, 0.5f, 0.5f, 0.5f, &wi, &pdf, &f) == 0, "sample with wo below");
    /* Reciprocity: f(wo, wi) = f(wi, wo) (the glTF mix is symmetric in wo, wi). */
    vec3 a = bsdf_eval(&b, n, up, v3_normalize(v3(-0.5f, 0.2f, 0.4f)));
    vec3 c = bsdf_eval(&b, n, v3_normalize(v3(-0.5f, 0.2f, 0.4f)), up);
    EXPECT(fabsf(a.x - c.x) <= 1e-6f * a.x, "reciprocity %g vs %g", a.x, c.x);
}

int main(void)
{
    test_chi2_cdf();
    test_material_model();

    struct case_desc cases[5];
    memset(cases, 0, sizeof cases);
    cases[0].name = "pure diffuse (white)";
    cases[0].b.diffuse = v3s(1.0f);
    cases[0].b.f0 = v3s(0.0f);
    cases[0].b.alpha = 1.0f;
    cases[0].b.p_spec = 0.0f;
    cases[0].white_diffuse = 1;
    cases[1].name = "dielectric r0.5 (white)";
    cases[1].b = material_bsdf(v3s(1.0f), 0.0f, 0.5f);
    cases[2].name = "metal r0.3";
    cases[2].b = material_bsdf(v3(1.0f, 0.85f, 0.6f), 1.0f, 0.3f);
    cases[3].name = "metal r0.05 (white)";
    cases[3].b = material_bsdf(v3s(1.0f), 1.0f, 0.05f);
    cases[4].name = "mixed m0.5 r0.2 (white)";
    cases[4].b = material_bsdf(v3s(1.0f), 0.5f, 0.2f);
    const float angles_deg[] = {0.0f, 30.0f, 60.0f, 80.0f};
    const int n_cases = 5, n_angles = 4;
    const int num_tests = n_cases * n_angles;
    const double alpha_i = chi2_sidak(FAMILY_ALPHA, num_tests);

    /* A tilted normal exercises the world <-> local frames; wo's azimuth is arbitrary. */
    const vec3 n = v3_normalize(v3(0.3f, -0.2f, 0.9f));
    const frame fr = frame_from_normal(n);
    double min_p = 1.0;
    printf("chi-square: %d tests, per-test alpha %.3g (Sidak, family %.2g)\n", num_tests, alpha_i, FAMILY_ALPHA);
    for (int ci = 0; ci < n_cases; ci++) {
        for (int ai = 0; ai < n_angles; ai++) {
            float th = angles_deg[ai] * RESTIR_PI / 180.0f;
            vec3 wo = frame_to_world(&fr, v3(sinf(th) * cosf(0.7f), sinf(th) * sinf(0.7f), cosf(th)));
            const struct bsdf *b = &cases[ci].b;
            static struct sample_stats st;
            run_samples(b, n, wo, (uint64_t)(ci * 16 + ai + 1), &st);
            struct pdf_ctx c = make_ctx(b, n, wo, 0);
            double integral;
            int dof;
            double p = chi2_against(&c, st.observed, &integral, &dof);
            double fail = (double)st.failed / N_SAMPLES;
            double amax = fmax(st.albedo[0], fmax(st.albedo[1], st.albedo[2]));
            printf("  %-26s wo %4.0f deg: p = %.4f (dof %3d), integral %.5f + failed %.5f = %.5f, "
                   "albedo max %.4f\n",
                   cases[ci].name, angles_deg[ai], p, dof, integral, fail, integral + fail, amax);
            if (p < min_p)
                min_p = p;
            /* (a) goodness of fit */
            EXPECT(p >= alpha_i, "%s wo %g: chi-square p %g < %g", cases[ci].name, angles_deg[ai], p, alpha_i);
            /* (b) sample's pdf/f agree with bsdf_pdf/bsdf_eval; directions valid */
            EXPECT(st.bad_pdf == 0, "%s wo %g: %ld pdf mismatches (max rel %g)", cases[ci].name,
                   angles_deg[ai], st.bad_pdf, st.max_pdf_rel);
            EXPECT(st.bad_eval == 0, "%s wo %g: %ld eval mismatches", cases[ci].name, angles_deg[ai], st.bad_eval);
            EXPECT(st.bad_dir == 0, "%s wo %g: %ld invalid directions", cases[ci].name, angles_deg[ai], st.bad_dir);
            /* (c) the pdf integrates to the probability of producing a direction (binomial
             * error of the failure fraction is <= 5e-4 at 1e6 samples). */
            EXPECT(fabs(integral + fail - 1.0) < 3e-3, "%s wo %g: integral %g + failed %g", cases[ci].name,
                   angles_deg[ai], integral, fail);
            EXPECT(integral <= 1.0 + 1e-3, "%s wo %g: pdf integrates to %g > 1", cases[ci].name, angles_deg[ai],
                   integral);
            /* (d) energy */
            if (cases[ci].white_diffuse)
                EXPECT_NEAR(st.albedo[0], 1.0, 0.01, "white Lambert albedo");
            EXPECT(amax <= 1.01, "%s wo %g: albedo %g > 1", cases[ci].name, angles_deg[ai], amax);
        }
    }
    printf("smallest chi-square p-value %.4f\n", min_p);

    /* Power self-checks: the same machinery must reject wrong densities. */
    {
        float th = 30.0f * RESTIR_PI / 180.0f;
        vec3 wo = frame_to_world(&fr, v3(sinf(th), 0.0f, cosf(th)));
        static struct sample_stats st;
        const struct bsdf *b = &cases[1].b;
        run_samples(b, n, wo, 777u, &st);
        struct pdf_ctx c = make_ctx(b, n, wo, 1);
        double p = chi2_against(&c, st.observed, NULL, NULL);
        printf("power check 1 (pdf * cos, dielectric r0.5): p = %.3g\n", p);
        EXPECT(p < 1e-6, "chi-square must reject the cos-scaled pdf (p = %g)", p);

        /* Subtle error: samples from alpha 10% too large tested against the true pdf. */
        struct bsdf wrong = cases[2].b;
        wrong.alpha *= 1.1f;
        run_samples(&wrong, n, wo, 778u, &st);
        struct pdf_ctx c2 = make_ctx(&cases[2].b, n, wo, 0);
        p = chi2_against(&c2, st.observed, NULL, NULL);
        printf("power check 2 (alpha off by 10%%, metal r0.3): p = %.3g\n", p);
        EXPECT(p < 1e-6, "chi-square must reject samples from a 10%% wider lobe (p = %g)", p);
    }
    return test_finish();
}
