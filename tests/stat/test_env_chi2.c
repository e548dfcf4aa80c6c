/* test_env_chi2.c: statistical tests of environment sampling (scene/env_light.h) on a synthetic
 * 32x16 map (a bright "sun" block, a gradient, blocks and a row of zero texels, a blue-only texel)
 * and on a constant environment: the density integrates to 1, samples fit it (chi-square over a
 * binning of the sphere that does not line up with the texels), env_pdf agrees with env_sample and
 * with the weights computed here, no sample lands on a black texel, and rotation turns samples.
 * The same for the MIS-compensated distribution (weights above the map's mean only): its density
 * is 0 exactly on the texels at or below the mean, and it has nothing to sample on a constant
 * environment or a constant map.
 * Must never depend on render passes. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chi2_util.h"
#include "core/check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "scene/environment.h"
#include "scene/env_light.h"
#include "test_util.h"

#define W 32
#define H 16
#define N_SAMPLES 1000000
#define NB_PHI 24   /* bins in world azimuth: 15 degrees, against 11.25-degree texels */
#define NB_THETA 12 /* bins in polar angle: 15 degrees, against 11.25-degree texel rows */
#define NBINS (NB_PHI * NB_THETA)
#define THETA_STEPS 64 /* midpoint sub-steps in theta per refined cell (see bin_probabilities) */
#define FAMILY_ALPHA 0.01
#define N_CHI2 4 /* chi-square tests in the family: map, rotated map, constant, compensated map */
#define ROTATION 1.3f
#define PI_D 3.14159265358979323846

/* The synthetic map: a gradient, a 2x2 "sun" of radiance sun_level at columns 5-6, rows 3-4, zero
 * texels in a block (columns 20-23, rows 5-8) and along the whole bottom row, and one texel that
 * is blue only (luminance 0.0722 B: zero in R and G must not make it zero). */
static void make_image(float *rgb, float sun_level)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            float *p = rgb + 3 * (y * W + x);
            p[0] = 0.1f + 0.9f * (float)x / W;
            p[1] = 0.2f + 0.5f * (float)y / H;
            p[2] = 0.3f;
            int sun = x >= 5 && x <= 6 && y >= 3 && y <= 4;
            int black = (x >= 20 && x <= 23 && y >= 5 && y <= 8) || y == H - 1;
            if (sun)
                p[0] = p[1] = p[2] = sun_level;
            if (black)
                p[0] = p[1] = p[2] = 0.0f;
            if (x == 12 && y == 10)
                p[0] = p[1] = 0.0f, p[2] = 2.0f;
        }
}

static double wrap_2pi(double a)
{
    a = fmod(a, 2.0 * PI_D);
    return a < 0.0 ? a + 2.0 * PI_D : a;
}

static vec3 dir_of(double theta, double phi)
{
    return v3((float)(sin(theta) * cos(phi)), (float)cos(theta), (float)(sin(theta) * sin(phi)));
}

/* World polar angle and azimuth of d, computed here in double (independent of the module). */
static void angles_of(vec3 d, double *theta, double *phi)
{
    *theta = atan2(sqrt((double)d.x * d.x + (double)d.z * d.z), (double)d.y);
    *phi = wrap_2pi(atan2((double)d.z, (double)d.x));
}

static int bin_of(double theta, double phi)
{
    int i = (int)(phi / (2.0 * PI_D) * NB_PHI), j = (int)(theta / PI_D * NB_THETA);
    i = i < 0 ? 0 : (i >= NB_PHI ? NB_PHI - 1 : i);
    j = j < 0 ? 0 : (j >= NB_THETA ? NB_THETA - 1 : j);
    return j * NB_PHI + i;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorted breakpoints: n equal steps over [0, span] plus m texel edges offset by `offset` (wrapped). */
static int breakpoints(double *out, int n, int m, double span, double offset)
{
    int k = 0;
    for (int i = 0; i <= n; i++)
        out[k++] = span * i / n;
    for (int j = 0; j < m; j++)
        out[k++] = offset >= 0.0 ? wrap_2pi(span * j / m + offset) : span * j / m;
    qsort(out, (size_t)k, sizeof(double), cmp_double);
    return k;
}

/* Probability of each bin under env_pdf. The sphere is cut at every bin edge and every texel edge
 * (in world azimuth, so after rotation), so each refined cell lies inside one bin and one texel.
 * There pdf * sin(theta) is constant in (theta, phi) for a map (the density is the texel's factor
 * over sin theta), so a midpoint rule in (theta, phi) is exact up to float rounding; for the
 * constant environment pdf is constant and the THETA_STEPS midpoint sub-steps integrate sin(theta)
 * with relative error at most h^2 / 24 = 7e-7 (h <= pi / 768). The total is the density's integral. */
static double bin_probabilities(const struct env_sampler *s, const struct environment *env, double *prob)
{
    double phis[NB_PHI + W + 1], thetas[NB_THETA + H + 1];
    int n_phi = breakpoints(phis, NB_PHI, env->rgb ? W : 0, 2.0 * PI_D, env->rotation);
    int n_theta = breakpoints(thetas, NB_THETA, env->rgb ? H : 0, PI_D, -1.0);
    double total = 0.0;
    memset(prob, 0, sizeof(double) * NBINS);
    for (int a = 0; a + 1 < n_phi; a++) {
        double p0 = phis[a], p1 = phis[a + 1];
        if (p1 - p0 < 1e-9)
            continue;
        for (int b = 0; b + 1 < n_theta; b++) {
            double t0 = thetas[b], t1 = thetas[b + 1], dt = (t1 - t0) / THETA_STEPS;
            if (t1 - t0 < 1e-9)
                continue;
            for (int k = 0; k < THETA_STEPS; k++) {
                double tm = t0 + (k + 0.5) * dt, pm = 0.5 * (p0 + p1);
                double mass = (double)env_pdf(s, dir_of(tm, pm)) * sin(tm) * dt * (p1 - p0);
                prob[bin_of(tm, pm)] += mass;
                total += mass;
            }
        }
    }
    return total;
}

/* Monte Carlo check of a sphere integral with uniform directions: mean of 4 pi f, its standard error. */
static void uniform_mc(const struct env_sampler *s, const struct environment *env, int luminance, double *mean,
                       double *stderr_out)
{
    pcg32 r = pcg32_make(7u, 3u);
    double sum = 0.0, sum2 = 0.0;
    const int n = 1000000;
    for (int k = 0; k < n; k++) {
        double z = 1.0 - 2.0 * pcg32_float(&r), phi = 2.0 * PI_D * pcg32_float(&r);
        vec3 d = dir_of(acos(z), phi);
        double f = luminance ? v3_luminance(environment_radiance(env, d)) : env_pdf(s, d);
        sum += 4.0 * PI_D * f;
        sum2 += 16.0 * PI_D * PI_D * f * f;
    }
    *mean = sum / n;
    *stderr_out = sqrt((sum2 / n - *mean * *mean) / n);
}

/* (a): the density integrates to 1, exactly by the refined quadrature (tolerance 1e-5: float
 * densities, each within ~1e-7 relative, summed in double, plus the 7e-7 theta sub-step error of
 * the constant case) and, independently of the texel layout, by uniform Monte Carlo (within 5
 * standard errors, plus 1e-6 for the float rounding of a constant density, whose estimate has no
 * variance). The luminance integral is checked the same way. */
static void check_integrals(const struct env_sampler *s, const struct environment *env, const char *name)
{
    double prob[NBINS], mean, se;
    double total = bin_probabilities(s, env, prob);
    printf("%s: integral of env_pdf over the sphere, refined quadrature: %.9f (error %.2e)\n", name, total,
           total - 1.0);
    EXPECT_NEAR(total, 1.0, 1e-5, "density integral (quadrature)");
    uniform_mc(s, env, 0, &mean, &se);
    printf("%s: integral of env_pdf, uniform Monte Carlo: %.5f +- %.5f\n", name, mean, se);
    EXPECT(fabs(mean - 1.0) <= 5.0 * se + 1e-6, "%s: density integral (Monte Carlo) %g +- %g", name, mean, se);
    uniform_mc(s, env, 1, &mean, &se);
    double want = env_luminance_integral(s);
    printf("%s: luminance integral %.6f, uniform Monte Carlo %.6f +- %.6f\n", name, want, mean, se);
    EXPECT(fabs(mean - want) <= 5.0 * se + 1e-6 * want, "%s: luminance integral %g vs Monte Carlo %g +- %g", name,
           want, mean, se);
}

static double own_luminance(const float *rgb, int x, int y)
{
    const float *p = rgb + 3 * (y * W + x);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/* Weight of the texel containing d, computed here from the image: (luminance - lum_floor, at least 0)
 * * sin(row centre); lum_floor 0 for the map's own distribution. */
static double own_weight(const float *rgb, int x, int y, double lum_floor)
{
    double l = own_luminance(rgb, x, y);
    return (l > lum_floor ? l - lum_floor : 0.0) * sin(PI_D * (y + 0.5) / H);
}

/* The compensated sampler's lum_floor, computed here: the map's mean luminance over the sphere (each
 * texel's exact solid angle), raised by 1e-6 of itself as env_light.h says. */
static double own_floor(const float *rgb)
{
    double sum = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            sum += own_luminance(rgb, x, y) * 2.0 * PI_D / W * (cos(PI_D * y / H) - cos(PI_D * (y + 1) / H));
    return sum / (4.0 * PI_D) * (1.0 + 1e-6);
}

struct sample_stats {
    long pdf_mismatch, pdf_nonpositive, black, weight_mismatch, not_unit;
    double observed[NBINS];
};

/* Draws N_SAMPLES directions, bins them and checks each: (c) the returned pdf equals env_pdf and
 * pdf * 2 pi^2 sin(theta) / (W H) equals this file's own weight / total (relative 1e-4, skipping
 * the rare directions within 1e-5 of a texel edge, where the two mappings may round differently);
 * (d) the direction's radiance is not black. */
static void draw(const struct env_sampler *s, const struct environment *env, const float *rgb, double lum_floor,
                 double weight_total, uint64_t seed, struct sample_stats *st)
{
    memset(st, 0, sizeof *st);
    pcg32 r = pcg32_make(seed, 1u);
    for (int k = 0; k < N_SAMPLES; k++) {
        float pdf;
        vec3 d = env_sample(s, pcg32_float(&r), pcg32_float(&r), &pdf);
        double theta, phi;
        angles_of(d, &theta, &phi);
        st->observed[bin_of(theta, phi)] += 1.0;
        st->pdf_mismatch += pdf != env_pdf(s, d);
        st->pdf_nonpositive += !(pdf > 0.0f) || !isfinite(pdf);
        st->black += !(v3_luminance(environment_radiance(env, d)) > 0.0f);
        st->not_unit += fabsf(v3_length(d) - 1.0f) > 1e-5f;
        if (!rgb)
            continue;
        double u = wrap_2pi(phi - env->rotation) / (2.0 * PI_D) * W, v = theta / PI_D * H;
        int x = (int)u, y = (int)v;
        if (fabs(u - floor(u + 0.5)) < 1e-5 || fabs(v - floor(v + 0.5)) < 1e-5 || x >= W || y >= H)
            continue;
        double want = own_weight(rgb, x, y, lum_floor) / weight_total;
        double got = pdf * 2.0 * PI_D * PI_D * sin(theta) / (W * H);
        st->weight_mismatch += fabs(got - want) > 1e-4 * want;
    }
}

/* Runs draw, the per-sample checks and the chi-square test; returns the bin probabilities. */
static void check_sampling(const struct env_sampler *s, const struct environment *env, const float *rgb,
                           double lum_floor, const char *name, uint64_t seed, struct sample_stats *st)
{
    double weight_total = 0.0, prob[NBINS];
    for (int y = 0; rgb && y < H; y++)
        for (int x = 0; x < W; x++)
            weight_total += own_weight(rgb, x, y, lum_floor);
    draw(s, env, rgb, lum_floor, weight_total, seed, st);
    EXPECT(st->pdf_mismatch == 0, "%s: %ld samples whose pdf differs from env_pdf", name, st->pdf_mismatch);
    EXPECT(st->pdf_nonpositive == 0, "%s: %ld samples with pdf <= 0 or not finite", name, st->pdf_nonpositive);
    EXPECT(st->black == 0, "%s: %ld samples on zero-radiance texels", name, st->black);
    EXPECT(st->weight_mismatch == 0, "%s: %ld samples whose pdf is not the texel weight / total", name,
           st->weight_mismatch);
    EXPECT(st->not_unit == 0, "%s: %ld samples not of unit length", name, st->not_unit);
    bin_probabilities(s, env, prob);
    int dof;
    double p = chi2_counts(st->observed, prob, NBINS, N_SAMPLES, &dof);
    const double alpha = chi2_sidak(FAMILY_ALPHA, N_CHI2);
    printf("%s: chi-square over %dx%d (phi x theta) bins, %d samples: p = %.4f (dof %d, alpha %.4f)\n", name,
           NB_PHI, NB_THETA, N_SAMPLES, p, dof, alpha);
    EXPECT(p >= alpha, "%s: chi-square p %g < %g", name, p, alpha);
}

/* The same histogram must reject the density of a map whose sun is 3 % dimmer: the test has power. */
static void check_power(const struct sample_stats *st)
{
    float rgb[W * H * 3];
    make_image(rgb, 40.0f * 0.97f);
    struct environment env;
    struct env_sampler s;
    char msg[RESTIR_MSG_LEN];
    EXPECT(environment_from_rgb("test", "dim sun", rgb, W, H, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    env_sampler_init(&s, &env);
    double prob[NBINS];
    bin_probabilities(&s, &env, prob);
    int dof;
    double p = chi2_counts(st->observed, prob, NBINS, N_SAMPLES, &dof);
    printf("power check (sun 3%% dimmer): p = %.3g\n", p);
    EXPECT(p < 1e-6, "chi-square must reject a 3%% dimmer sun (p = %g)", p);
    env_sampler_fini(&s);
    environment_fini(&env);
}

/* (e): the same uniforms through the rotated map give the directions turned by the rotation (phi
 * increased, environment.h), with the same density and radiance. A sample moved to its texel centre
 * in one map but not the other (float rounding at an edge, about 1e-7 of samples) may differ. */
static void check_rotation(const struct env_sampler *a, const struct environment *ea, const struct env_sampler *b,
                           const struct environment *eb)
{
    const float c = cosf(eb->rotation), s = sinf(eb->rotation);
    long moved = 0, pdf_bad = 0, radiance_bad = 0;
    pcg32 r = pcg32_make(55u, 9u);
    for (int k = 0; k < N_SAMPLES; k++) {
        float u1 = pcg32_float(&r), u2 = pcg32_float(&r), pa, pb;
        vec3 da = env_sample(a, u1, u2, &pa), db = env_sample(b, u1, u2, &pb);
        vec3 want = v3(da.x * c - da.z * s, da.y, da.x * s + da.z * c);
        if (v3_length(v3_sub(db, want)) > 2e-5f) {
            moved++;
            continue;
        }
        pdf_bad += fabsf(pa - pb) > 1e-4f * pa;
        vec3 la = environment_radiance(ea, da), lb = environment_radiance(eb, db);
        radiance_bad += la.x != lb.x || la.y != lb.y || la.z != lb.z;
    }
    printf("rotation %.2f rad: %ld of %d samples not turned exactly (edge rounding)\n", (double)eb->rotation, moved,
           N_SAMPLES);
    EXPECT(moved <= 10, "%ld samples of the rotated map are not the turned samples", moved);
    EXPECT(pdf_bad == 0, "%ld turned samples with a different pdf", pdf_bad);
    EXPECT(radiance_bad == 0, "%ld turned samples with a different radiance", radiance_bad);
}

/* Poles, extreme and invalid uniforms, and an environment that emits nothing. */
static void check_edges(const struct env_sampler *s)
{
    EXPECT(env_pdf(s, v3(0, 1, 0)) == 0.0f && env_pdf(s, v3(0, -1, 0)) == 0.0f, "density 0 at the poles");
    EXPECT(env_pdf(s, v3(1e-10f, 1, 0)) == 0.0f, "density 0 within 1e-9 of a pole");
    float tiny = env_pdf(s, v3(1e-8f, 1, 0));
    EXPECT(tiny > 0.0f && isfinite(tiny), "finite positive density 1e-8 from the pole: %g", tiny);
    float near_pole = env_pdf(s, v3(1e-4f, 1, 0));
    EXPECT(near_pole > 0.0f && isfinite(near_pole), "finite positive density near the pole: %g", near_pole);
    EXPECT(env_pdf(s, v3(0, 0, 0)) == 0.0f && env_pdf(s, v3(NAN, 0, 1)) == 0.0f, "zero and NaN directions");
    EXPECT(env_pdf(s, v3(0, 0, 5)) == env_pdf(s, v3(0, 0, 1)), "density ignores the direction's length");
    const float us[] = {0.0f, 0x1.fffffep-1f, 1.0f, 2.0f, -1.0f, NAN, 0.5f};
    long bad = 0;
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 7; j++) {
            float pdf;
            vec3 d = env_sample(s, us[i], us[j], &pdf);
            bad += !(pdf > 0.0f) || !isfinite(pdf) || pdf != env_pdf(s, d) || !v3_is_finite(d);
        }
    EXPECT(bad == 0, "%ld extreme uniform pairs give a bad sample", bad);

    float zeros[4 * 2 * 3] = {0};
    struct environment dark = {4, 2, zeros, {0, 0, 0}, 1.0f, 0.0f}; /* filled by hand: bypasses the checks */
    struct env_sampler ds;
    EXPECT(env_sampler_init(&ds, &dark) == -1, "an all-black map has nothing to sample");
    float pdf = 1.0f;
    vec3 d = env_sample(&ds, 0.3f, 0.7f, &pdf);
    EXPECT(pdf == 0.0f && v3_is_finite(d) && env_pdf(&ds, v3(1, 0, 0)) == 0.0f, "black map: pdf 0");
    env_sampler_fini(&ds);
}

static void test_map(void)
{
    float rgb[W * H * 3];
    make_image(rgb, 40.0f);
    char msg[RESTIR_MSG_LEN];
    struct environment env, rot;
    struct env_sampler s, sr;
    EXPECT(environment_from_rgb("test", "synthetic", rgb, W, H, 2.0f, 0.0f, &env, msg) == 0, "%s", msg);
    EXPECT(environment_from_rgb("test", "synthetic", rgb, W, H, 2.0f, ROTATION, &rot, msg) == 0, "%s", msg);
    EXPECT(env_sampler_init(&s, &env) == 0 && env_sampler_init(&sr, &rot) == 0, "samplers build");
    check_integrals(&s, &env, "map");
    check_integrals(&sr, &rot, "rotated map");
    struct sample_stats *st = xmalloc(sizeof *st);
    check_sampling(&sr, &rot, rgb, 0.0, "rotated map", 22u, st);
    check_sampling(&s, &env, rgb, 0.0, "map", 11u, st);
    check_power(st);
    free(st);
    check_rotation(&s, &env, &sr, &rot);
    check_edges(&s);
    env_sampler_fini(&sr);
    env_sampler_fini(&s);
    environment_fini(&rot);
    environment_fini(&env);
}

static void test_constant(void)
{
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    struct env_sampler s;
    EXPECT(environment_constant("test", v3(0.5f, 1.0f, 2.0f), 3.0f, &env, msg) == 0, "%s", msg);
    EXPECT(env_sampler_init(&s, &env) == 0, "constant sampler builds");
    EXPECT(env_pdf(&s, v3(0.3f, -0.2f, 0.9f)) == 1.0f / (4.0f * RESTIR_PI), "uniform density");
    EXPECT_NEAR(env_luminance_integral(&s), 4.0 * PI_D * 3.0 * v3_luminance(v3(0.5f, 1.0f, 2.0f)), 1e-4,
                "constant luminance integral");
    check_integrals(&s, &env, "constant");
    struct sample_stats *st = xmalloc(sizeof *st);
    check_sampling(&s, &env, NULL, 0.0, "constant", 33u, st);
    free(st);
    env_sampler_fini(&s);
    struct env_sampler c;
    EXPECT(env_sampler_init_compensated(&c, &env) == -1, "a constant environment has nothing above its mean");
    float pdf = 1.0f;
    env_sample(&c, 0.3f, 0.6f, &pdf);
    EXPECT(pdf == 0.0f && env_pdf(&c, v3(0.3f, -0.2f, 0.9f)) == 0.0f, "compensated constant: pdf 0");
    EXPECT_NEAR(env_luminance_integral(&c), env_luminance_integral(&s) > 0.0 ? env_luminance_integral(&s) : 4.0 *
                PI_D * 3.0 * v3_luminance(v3(0.5f, 1.0f, 2.0f)), 1e-4, "compensated keeps the luminance integral");
    env_sampler_fini(&c);
    environment_fini(&env);
}

/* The compensated distribution of the synthetic map: everything the map's own passes, with the
 * weights above the mean; density 0 exactly on the texels at or below it; a constant map has none. */
static void test_compensated(void)
{
    float rgb[W * H * 3];
    make_image(rgb, 4.0f); /* a dimmer sun, so that part of the gradient is above the mean too */
    char msg[RESTIR_MSG_LEN];
    struct environment env;
    struct env_sampler s;
    EXPECT(environment_from_rgb("test", "synthetic", rgb, W, H, 2.0f, 0.0f, &env, msg) == 0, "%s", msg);
    EXPECT(env_sampler_init_compensated(&s, &env) == 0, "compensated sampler builds");
    const double lum_floor = own_floor(rgb);
    /* the sampler sums float luminances, this file doubles */
    EXPECT_NEAR(s.lum_floor, lum_floor, 1e-6 * lum_floor, "compensated floor: the mean luminance");
    int above = 0, wrong = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            vec3 centre = environment_uv_to_dir(&env, ((float)x + 0.5f) / W, ((float)y + 0.5f) / H);
            const int bright = own_luminance(rgb, x, y) > lum_floor;
            above += bright;
            wrong += bright != (env_pdf(&s, centre) > 0.0f);
        }
    printf("compensated map: %d of %d texels above the mean %.4f\n", above, W * H, lum_floor);
    EXPECT(wrong == 0, "%d texels whose density is not positive exactly where they exceed the mean", wrong);
    EXPECT(above > 1 && above < W * H / 2, "the test map has a few texels above its mean (%d)", above);
    check_integrals(&s, &env, "compensated map");
    struct sample_stats *st = xmalloc(sizeof *st);
    check_sampling(&s, &env, rgb, lum_floor, "compensated map", 44u, st);
    free(st);
    env_sampler_fini(&s);
    environment_fini(&env);

    for (int k = 0; k < W * H * 3; k++)
        rgb[k] = 0.37f;
    EXPECT(environment_from_rgb("test", "flat", rgb, W, H, 1.0f, 0.0f, &env, msg) == 0, "%s", msg);
    EXPECT(env_sampler_init_compensated(&s, &env) == -1, "a constant map has nothing above its mean");
    env_sampler_fini(&s);
    environment_fini(&env);
}

int main(void)
{
    test_map();
    test_constant();
    test_compensated();
    return test_finish();
}
