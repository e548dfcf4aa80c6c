/* env_light.c: environment importance sampling by CDF inversion of a piecewise-constant 2-D
 * distribution over the map's texels (the scheme of Pharr, Jakob and Humphreys, "Physically Based
 * Rendering", 3rd ed., Sec. 13.6.7 for the 2-D distribution and Sec. 14.2.4 for its use with
 * infinite lights), and uniform sphere sampling for a constant environment.
 * Must never depend on render passes or the ray tracer. */
#include "scene/env_light.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/sampling.h"

#define ENV_PI_D 3.14159265358979323846
/* Directions with sin(theta) at most this (within 1e-9 rad of a pole) get density 0. The density
 * there grows like 1 / sin(theta), so some cut-off is needed to keep it finite (and it is: at most
 * 2^27 / (2 pi^2) / 1e-9 < 1e16); env_sample never returns such a direction (see there), so sampler
 * and density agree. The cap cut out spans v < 1e-9 / pi, a fraction height * 1e-9 / pi (below
 * 3e-6 at the largest height) of the polar texels' probability, which env_sample moves inward. */
#define ENV_MIN_SIN 1e-9f

/* u clamped into [0, 1): the largest float below 1 at the top, NaN to 0. */
static float clamp_unit(float u)
{
    const float below_one = 0x1.fffffep-1f;
    return u >= 0.0f ? (u < below_one ? u : below_one) : 0.0f;
}

/* Weight of texel (x, y): its luminance less `lum_floor` times the sine at its row's centre, which is
 * proportional to the texel's solid angle. Non-finite or negative luminance (impossible for a
 * validated map) and luminance at or below the floor count as 0, so the CDFs stay well formed
 * whatever the caller filled in. */
static double texel_weight(const struct environment *env, int x, int y, double sin_centre, double lum_floor)
{
    double l = v3_luminance(environment_texel(env, x, y));
    return l > lum_floor && l < INFINITY ? (l - lum_floor) * sin_centre : 0.0;
}

static double row_sin(int y, int height) { return sin(ENV_PI_D * ((double)y + 0.5) / (double)height); }

/* Fills row y's conditional CDF (width + 1 values) and returns the row's total weight. Running sums
 * are kept in double: a zero-weight texel repeats the previous value exactly (so it is never
 * chosen), and the last value is exactly 1. A row of zero weight gets a uniform CDF, never used. */
static double build_row(struct env_sampler *s, int y)
{
    const int w = s->width;
    const double sc = row_sin(y, s->height);
    double sum = 0.0;
    for (int x = 0; x < w; x++)
        sum += texel_weight(s->env, x, y, sc, s->lum_floor);
    float *cdf = s->conditional + (size_t)y * (size_t)(w + 1);
    double run = 0.0;
    cdf[0] = 0.0f;
    for (int x = 0; x < w; x++) {
        run += texel_weight(s->env, x, y, sc, s->lum_floor);
        cdf[x + 1] = sum > 0.0 ? (float)(run / sum) : (float)(x + 1) / (float)w;
    }
    cdf[w] = 1.0f;
    return sum;
}

/* The marginal CDF over rows from their totals; returns the grand total. */
static double build_marginal(struct env_sampler *s, const double *row_total)
{
    double sum = 0.0, run = 0.0;
    for (int y = 0; y < s->height; y++)
        sum += row_total[y];
    s->marginal[0] = 0.0f;
    for (int y = 0; y < s->height; y++) {
        run += row_total[y];
        s->marginal[y + 1] = sum > 0.0 ? (float)(run / sum) : (float)(y + 1) / (float)s->height;
    }
    s->marginal[s->height] = 1.0f;
    return sum;
}

/* Solid angle of a texel of row y of a width x height map: (2 pi / width) (cos theta_top -
 * cos theta_bottom). */
static double texel_solid_angle(int y, int width, int height)
{
    return 2.0 * ENV_PI_D / (double)width * (cos(ENV_PI_D * y / height) - cos(ENV_PI_D * (y + 1) / height));
}

/* Per-texel density factor P(texel) * width * height / (2 pi^2), and the exact luminance integral of
 * the piecewise-constant map: texel luminance times its solid angle (2 pi / width) (cos theta_top -
 * cos theta_bottom). */
static void build_density(struct env_sampler *s)
{
    const int w = s->width, h = s->height;
    const double scale = s->total > 0.0 ? (double)w * (double)h / (2.0 * ENV_PI_D * ENV_PI_D * s->total) : 0.0;
    double integral = 0.0;
    for (int y = 0; y < h; y++) {
        const double sc = row_sin(y, h);
        const double band = texel_solid_angle(y, w, h);
        for (int x = 0; x < w; x++) {
            const double weight = texel_weight(s->env, x, y, sc, s->lum_floor);
            s->density[(size_t)y * (size_t)w + (size_t)x] = (float)(weight * scale);
            integral += v3_luminance(environment_texel(s->env, x, y)) * band;
        }
    }
    s->luminance_integral = integral * (double)s->env->intensity;
}

/* Guide table of a CDF (Chen and Asau 1974, "On generating random variates from an empirical
 * distribution", AIIE Transactions 6(2)): guide[k], k = 0 ... g, is the last entry i < n with
 * cdf[i] <= k / g, so the entry holding u lies between guide[k] and guide[k + 1] for
 * k = floor(u g). It only narrows the search of invert_cdf (a bisection over a whole row of a big
 * map costs one cache miss per step); the entry found, and so the distribution, is unchanged. */
static void build_guide(const float *cdf, int n, int g, int *guide)
{
    int i = 0;
    for (int k = 0; k <= g; k++) {
        const float t = (float)k / (float)g;
        while (i + 1 < n && cdf[i + 1] <= t)
            i++;
        guide[k] = i;
    }
}

/* Guide cells per CDF: one per four entries, a few cache lines of search at most on average. */
static int guide_size(int n) { return (n + 3) / 4; }

static int sampler_build(struct env_sampler *s, const struct environment *env, double lum_floor)
{
    memset(s, 0, sizeof *s);
    s->env = env;
    s->lum_floor = lum_floor;
    if (!env->rgb) {
        double l = v3_luminance(env->constant);
        s->total = l > 0.0 && l < INFINITY ? l : 0.0;
        s->luminance_integral = 4.0 * ENV_PI_D * s->total * (double)env->intensity;
        return s->total > 0.0 ? 0 : -1;
    }
    s->width = env->width;
    s->height = env->height;
    s->guide_rows = guide_size(env->height);
    s->guide_cols = guide_size(env->width);
    const size_t w = (size_t)env->width, h = (size_t)env->height, gc = (size_t)s->guide_cols + 1;
    s->marginal = xmalloc(sizeof(float) * (h + 1));
    s->conditional = xmalloc(sizeof(float) * h * (w + 1));
    s->marginal_guide = xmalloc(sizeof(int) * ((size_t)s->guide_rows + 1));
    s->conditional_guide = xmalloc(sizeof(int) * h * gc);
    s->density = xmalloc(sizeof(float) * h * w);
    double *row_total = xmalloc(sizeof(double) * h);
    for (int y = 0; y < s->height; y++) {
        row_total[y] = build_row(s, y);
        build_guide(s->conditional + (size_t)y * (w + 1), s->width, s->guide_cols, s->conditional_guide + y * gc);
    }
    s->total = build_marginal(s, row_total);
    build_guide(s->marginal, s->height, s->guide_rows, s->marginal_guide);
    free(row_total);
    build_density(s);
    return s->total > 0.0 ? 0 : -1;
}

int env_sampler_init(struct env_sampler *s, const struct environment *env) { return sampler_build(s, env, 0.0); }

/* The map's mean luminance over the sphere (without intensity, as the texel weights). */
static double map_mean_luminance(const struct environment *env)
{
    double sum = 0.0;
    for (int y = 0; y < env->height; y++) {
        const double band = texel_solid_angle(y, env->width, env->height);
        for (int x = 0; x < env->width; x++) {
            const double l = v3_luminance(environment_texel(env, x, y));
            sum += l > 0.0 && l < INFINITY ? l * band : 0.0;
        }
    }
    return sum / (4.0 * ENV_PI_D);
}

int env_sampler_init_compensated(struct env_sampler *s, const struct environment *env)
{
    if (!env->rgb) { /* a constant environment: nothing above its mean */
        const int rc = sampler_build(s, env, 0.0); /* keeps its luminance integral */
        s->total = 0.0;
        return rc == 0 ? -1 : rc;
    }
    /* 1e-6 above the mean, so that rounding in the mean cannot leave a constant map a distribution
     * of rounding residues (any floor keeps the combination unbiased; this one samples nothing there) */
    return sampler_build(s, env, map_mean_luminance(env) * (1.0 + 1e-6));
}

void env_sampler_fini(struct env_sampler *s)
{
    free(s->marginal);
    free(s->conditional);
    free(s->marginal_guide);
    free(s->conditional_guide);
    free(s->density);
    memset(s, 0, sizeof *s);
}

/* The entry i in [0, n) with cdf[i] <= u < cdf[i + 1] (cdf[0] = 0, cdf[n] = 1, u in [0, 1)), and
 * where u falls inside it, in [0, 1): bisection between the bounds the guide table (g cells) gives,
 * checked so that float rounding of k / g can only widen the search. Entries of zero width cannot
 * satisfy both inequalities, so they are never returned. */
static int invert_cdf(const float *cdf, int n, const int *guide, int g, float u, float *frac)
{
    int k = (int)(u * (float)g);
    k = k < g ? k : g - 1;
    int lo = guide[k], hi = guide[k + 1] + 1;
    if (!(cdf[lo] <= u))
        lo = 0;
    if (!(u < cdf[hi]))
        hi = n;
    while (hi - lo > 1) { /* invariant: cdf[lo] <= u < cdf[hi] */
        int mid = lo + (hi - lo) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    *frac = clamp_unit((u - cdf[lo]) / (cdf[lo + 1] - cdf[lo]));
    return lo;
}

/* Density of dir, known to read texel (x, y): the texel's factor over sin(theta). */
static float texel_pdf(const struct env_sampler *s, int x, int y, vec3 dir)
{
    float r2 = dir.x * dir.x + dir.z * dir.z;
    float sin_theta = sqrtf(r2 / (r2 + dir.y * dir.y));
    if (!(sin_theta > ENV_MIN_SIN)) /* also NaN: a zero or non-finite direction */
        return 0.0f;
    return s->density[(size_t)y * (size_t)s->width + (size_t)x] / sin_theta;
}

/* The direction at fractions (fu, fv) inside texel (x, y), with its density when it reads that
 * texel (0 when rounding put it in a neighbour, or it is at a pole). */
static vec3 point_in_texel(const struct env_sampler *s, int x, int y, float fu, float fv, float *pdf)
{
    vec3 dir = environment_uv_to_dir(s->env, ((float)x + fu) / (float)s->width, ((float)y + fv) / (float)s->height);
    int tx, ty;
    environment_texel_of(s->env, dir, &tx, &ty);
    *pdf = tx == x && ty == y ? texel_pdf(s, x, y, dir) : 0.0f;
    return dir;
}

static float clamp_inside(float f)
{
    const float margin = 1.0f / 1024.0f;
    return f > margin ? (f < 1.0f - margin ? f : 1.0f - margin) : margin;
}

vec3 env_sample(const struct env_sampler *s, float u1, float u2, float *pdf_solid_angle)
{
    u1 = clamp_unit(u1);
    u2 = clamp_unit(u2);
    if (!(s->total > 0.0)) {
        *pdf_solid_angle = 0.0f;
        return v3(0.0f, 1.0f, 0.0f);
    }
    if (!s->env->rgb) { /* uniform over the sphere; the warp's z axis becomes our y */
        vec3 d = warp_uniform_sphere(u1, u2);
        *pdf_solid_angle = 1.0f / (4.0f * RESTIR_PI);
        return v3(d.x, d.z, d.y);
    }
    float fv, fu, pdf;
    const int y = invert_cdf(s->marginal, s->height, s->marginal_guide, s->guide_rows, u1, &fv);
    const size_t row = (size_t)y;
    const int x = invert_cdf(s->conditional + row * (size_t)(s->width + 1), s->width,
                             s->conditional_guide + row * (size_t)(s->guide_cols + 1), s->guide_cols, u2, &fu);
    vec3 dir = point_in_texel(s, x, y, fu, fv, &pdf);
    /* With 24-bit uniforms the place inside the texel is quantized (to 2^-24 / P(entry)), so points
     * exactly on a texel's edge are not rare, and float rounding in the angles moves some of them
     * into the neighbouring texel (3.5e-5 of the samples of a random 2048 x 1024 map); v = 0 is the
     * pole, of no finite density. Those points are moved 1/1024 of a texel inwards (and, should that
     * still fail, to the centre), so every direction returned lies in the texel it was drawn from,
     * with a positive density bit-identical to env_pdf's. */
    if (!(pdf > 0.0f))
        dir = point_in_texel(s, x, y, clamp_inside(fu), clamp_inside(fv), &pdf);
    if (!(pdf > 0.0f))
        dir = point_in_texel(s, x, y, 0.5f, 0.5f, &pdf);
    *pdf_solid_angle = pdf;
    return dir;
}

float env_pdf(const struct env_sampler *s, vec3 dir)
{
    if (!(s->total > 0.0) || !v3_is_finite(dir))
        return 0.0f;
    if (!s->env->rgb)
        return 1.0f / (4.0f * RESTIR_PI);
    int x, y;
    environment_texel_of(s->env, dir, &x, &y);
    return texel_pdf(s, x, y, dir);
}

double env_luminance_integral(const struct env_sampler *s) { return s->luminance_integral; }
