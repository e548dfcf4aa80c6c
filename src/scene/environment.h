/* environment.h: the environment light's data: an equirectangular radiance image (Radiance .hdr or
 * OpenEXR .exr) or one constant colour, checked on load, and its direction <-> image mapping.
 * Must never depend on shading, render code or anything that aborts on bad input. */
#ifndef RESTIR_SCENE_ENVIRONMENT_H
#define RESTIR_SCENE_ENVIRONMENT_H

#include "core/vec3.h"

/* Largest image accepted: per side, and in texels (12 bytes each decoded: 2^27 is 1.5 GiB, the
 * size of a 16384 x 8192 map). Both are checked from the file header, before decoding. */
#define ENVIRONMENT_MAX_SIDE 16384
#define ENVIRONMENT_MAX_TEXELS (1L << 27)

/* Radiance arriving from infinitely far away, seen along world directions.
 *
 * Mapping (equirectangular, "latitude-longitude"): world +y is up. For a direction d (any
 * nonzero length),
 *   theta = atan2(sqrt(d.x^2 + d.z^2), d.y)   in [0, pi]   (= acos(d.y) for unit d; 0 is +y),
 *   phi   = atan2(d.z, d.x) - rotation        wrapped into [0, 2 pi),
 *   u = phi / (2 pi) in [0, 1),  v = theta / pi in [0, 1],
 * and d reads texel column floor(u * width), row floor(v * height) (clamped to the last one):
 * row 0 is the image's top row, around +y; column 0 starts at azimuth phi = 0. So with rotation 0
 * the image's left edge lies along +x, and its columns advance from +x toward +z.
 *
 * rotation turns the whole map about +y, in the sense of increasing phi (from +x toward +z): the
 * texel seen along image direction (x, y, z) at rotation 0 is seen along
 *   (x cos r - z sin r, y, x sin r + z cos r)
 * at rotation r. (For the right-handed convention about +y, that is a turn by -r.)
 *
 * Lookups are NEAREST (the texel containing (u, v)): radiance is piecewise constant over texels,
 * so a piecewise-constant sampling density built from the same texels (scene/env_light.h) is
 * zero exactly where the radiance is zero and positive wherever it is not, with no bilinear
 * footprint that would leak light into a texel the density gives no probability. */
struct environment {
    int width, height;
    float *rgb;     /* width * height * 3 linear RGB, row 0 = top (theta = 0, +y); NULL: constant */
    vec3 constant;  /* radiance everywhere when rgb == NULL */
    float intensity; /* scale applied to every lookup (environment_radiance) */
    float rotation;  /* radians about +y, see above */
};

/* Reads an equirectangular map from path: a Radiance RGBE .hdr (stb_image) or an OpenEXR .exr
 * (scanline, channels R, G, B as half or float; other channels ignored), told apart by content.
 * Refuses, with msg (RESTIR_MSG_LEN) naming key (the caller's name for the setting, such as
 * "environment" or "--env"; NULL reads "environment") and the file: a missing, undecodable,
 * truncated or corrupt file (a damaged .hdr is caught before stb_image, which may never return on
 * one, sees it), an image beyond ENVIRONMENT_MAX_SIDE / ENVIRONMENT_MAX_TEXELS, any texel that is
 * NaN, infinite or negative (naming the first one, x and y), an all-zero image, an intensity that
 * is not finite and non-negative, a rotation that is not finite. Returns 0, or -1 with *env
 * zeroed. */
int environment_load(const char *key, const char *path, float intensity, float rotation,
                     struct environment *env, char *msg);
/* The same from linear RGB texels already in memory (copied; width * height * 3 floats, row 0 at
 * the top); name labels msg the way path does. */
int environment_from_rgb(const char *key, const char *name, const float *rgb, int width, int height,
                         float intensity, float rotation, struct environment *env, char *msg);
/* A constant environment of radiance c * intensity. Refuses (msg naming key) a colour or intensity
 * that is not finite and non-negative. Returns 0, or -1 with *env zeroed. */
int environment_constant(const char *key, vec3 c, float intensity, struct environment *env, char *msg);
void environment_fini(struct environment *env);
/* The sky a mesh file without emitters is lit by (scene_import_file): 64 x 32 texels, a blue
 * zenith fading to a pale horizon over a grey-brown ground, radiance around 1. */
void environment_default_sky(struct environment *env);

/* (u, v) of direction dir as described above. A direction with a NaN reads (0, 0). */
void environment_dir_to_uv(const struct environment *env, vec3 dir, float *u, float *v);
/* The unit world direction of (u, v): the inverse of environment_dir_to_uv. */
vec3 environment_uv_to_dir(const struct environment *env, float u, float v);
/* The texel (column x, row y) that dir reads; (0, 0) for a constant environment. */
void environment_texel_of(const struct environment *env, vec3 dir, int *x, int *y);
/* Stored value of texel (x, y), without intensity (the constant for a constant environment). */
vec3 environment_texel(const struct environment *env, int x, int y);
/* Radiance arriving along dir (pointing away from the receiver, toward the sky): the nearest
 * texel times intensity. */
vec3 environment_radiance(const struct environment *env, vec3 dir);

#endif
