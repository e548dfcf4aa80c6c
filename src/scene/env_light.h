/* env_light.h: importance sampling of directions toward an environment (scene/environment.h):
 * a piecewise-constant 2-D distribution over its texels, or the uniform sphere for a constant one.
 * Must never depend on render passes or the ray tracer. */
#ifndef RESTIR_SCENE_ENV_LIGHT_H
#define RESTIR_SCENE_ENV_LIGHT_H

#include "scene/environment.h"

/* Texel (x, y) of a width x height map gets probability proportional to
 *   w(x, y) = luminance(texel) * sin(theta at the centre of row y)
 * (luminance 0.2126 R + 0.7152 G + 0.0722 B; the sine is the texel's share of the sphere), chosen
 * as a row from the marginal distribution over rows and then a column from that row's conditional
 * distribution; the direction is uniform in (u, v) inside the texel. Its density in solid angle is
 *   pdf(dir) = P(texel) * width * height / (2 pi^2 sin theta(dir)),
 * since d(solid angle) = sin theta dtheta dphi = 2 pi^2 sin theta du dv. It is positive exactly on
 * the texels with radiance > 0 (the lookups share environment_texel_of). */
struct env_sampler {
    const struct environment *env; /* borrowed: must outlive the sampler, and not change */
    int width, height;             /* of the image; 0 for a constant environment */
    float *marginal;               /* height + 1 CDF values over rows, 0 ... 1 */
    float *conditional;            /* height rows of width + 1 CDF values over columns, 0 ... 1 */
    int guide_rows, guide_cols;    /* guide-table cells of the marginal and of each row */
    int *marginal_guide;           /* guide_rows + 1 entries (env_light.c, build_guide) */
    int *conditional_guide;        /* height rows of guide_cols + 1 entries */
    float *density;                /* per texel: P(texel) * width * height / (2 pi^2) */
    double total;                  /* sum of the weights w; 0: nothing to sample */
    double lum_floor;              /* luminance subtracted from every texel's (0, or the compensated
                                      sampler's mean) */
    double luminance_integral;     /* integral of luminance(environment_radiance) over the sphere */
};

/* Builds the distribution of env (intensity does not change it). Returns 0, or -1 when env has no
 * direction of positive luminance; s is then still valid and every sample has pdf 0. */
int env_sampler_init(struct env_sampler *s, const struct environment *env);
/* The MIS-compensated distribution (Karlik et al. 2019, "MIS Compensation: Optimizing Sampling
 * Techniques in Multiple Importance Sampling", Sec. 4; pbrt-v4's image infinite light): texel
 * weights w(x, y) = max(0, luminance - mean) * sin theta, the mean being the map's average
 * luminance over the sphere (solid-angle weighted, exact for the piecewise-constant map; raised by
 * 1e-6 of itself so that a constant map has nothing above it). It
 * samples only where the map is brighter than its mean and has density 0 elsewhere, so it is
 * unbiased ONLY when combined by MIS with a strategy that covers every direction (BSDF sampling in
 * a path walk): that strategy takes the flat part, which it samples better. Returns 0, or -1 when
 * no texel exceeds the mean (a constant map or environment), with s valid and every pdf 0.
 * luminance_integral stays the environment's own. */
int env_sampler_init_compensated(struct env_sampler *s, const struct environment *env);
void env_sampler_fini(struct env_sampler *s);

/* A unit world direction toward the environment from two uniforms in [0, 1) (values outside are
 * clamped): u1 picks the row (polar angle), u2 the column (azimuth) within it, each by inverting
 * its CDF, so the map from (u1, u2) keeps the square's stratification. *pdf_solid_angle is the
 * density, bit-identical to env_pdf of the returned direction; 0 only when there is nothing to
 * sample, which the caller must treat as no sample. */
vec3 env_sample(const struct env_sampler *s, float u1, float u2, float *pdf_solid_angle);
/* Solid-angle density of env_sample producing dir (any nonzero length; 0 for a zero or non-finite
 * one). For a map: 0 on texels of zero luminance, and within 1e-9 radians of the poles (sin theta
 * <= 1e-9, where the density would grow without bound; never sampled). For a constant
 * environment: 1 / (4 pi). */
float env_pdf(const struct env_sampler *s, vec3 dir);
/* Integral over the sphere of the luminance of environment_radiance (intensity included), exact
 * for the piecewise-constant map. Times pi R^2 (R the radius of the scene's bounding sphere) it is
 * the luminous power entering that sphere, for choosing between the environment and emitters. */
double env_luminance_integral(const struct env_sampler *s);

#endif
