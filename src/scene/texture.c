/* texture.c: texture decoding (stb_image, the Debian libstb build) and bilinear lookup.
 * Must never depend on materials or render code. */
#include "scene/texture.h"

#include <math.h>
#include <stb/stb_image.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

/* Largest texture accepted: per side, and in texels (12 bytes each decoded: 2^26 is 768 MB). Both
 * are checked from the image header, before anything is decoded. */
#define TEXTURE_MAX_SIDE 32768
#define TEXTURE_MAX_TEXELS (1L << 26)

/* sRGB transfer function, inverse (IEC 61966-2-1). */
static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* t->alpha from 8-bit texels (byte offset alpha_at of `channels`), kept only when some texel is
 * not opaque. */
static void alpha_from_bytes(const unsigned char *px, int w, int h, int channels, int alpha_at, struct texture *t)
{
    const size_t n = (size_t)w * (size_t)h;
    size_t i = 0;
    while (i < n && px[(size_t)channels * i + (size_t)alpha_at] == 255)
        i++;
    if (i == n)
        return;
    t->alpha = xmalloc(sizeof(float) * n);
    for (i = 0; i < n; i++)
        t->alpha[i] = (float)px[(size_t)channels * i + (size_t)alpha_at] / 255.0f;
}

/* Fills t from 8-bit texels with `channels` bytes each at the given byte offsets of R, G, B. */
static void from_bytes(const unsigned char *px, int w, int h, int channels, const int rgb_at[3], int srgb,
                       struct texture *t)
{
    float table[256];
    for (int i = 0; i < 256; i++)
        table[i] = srgb ? srgb_to_linear((float)i / 255.0f) : (float)i / 255.0f;
    t->width = w;
    t->height = h;
    t->rgb = xmalloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        for (int c = 0; c < 3; c++)
            t->rgb[3 * i + c] = table[px[(size_t)channels * i + (size_t)rgb_at[c]]];
}

static const char *failure_reason(void)
{
    const char *why = stbi_failure_reason();
    return why ? why : "unknown reason";
}

/* The header's verdict, before decoding: 0, or -1 with msg (unreadable, HDR, too large). */
static int check_header(int ok, int w, int h, int hdr, const char *name, char *msg)
{
    if (!ok) {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: cannot read the image: %s", name, failure_reason());
        return -1;
    }
    if (hdr) { /* stb would tone-map it to 8 bits: refuse rather than change the data */
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: HDR images are not supported (8-bit PNG, JPEG, TGA, BMP)", name);
        return -1;
    }
    if (w < 1 || h < 1 || w > TEXTURE_MAX_SIDE || h > TEXTURE_MAX_SIDE || (long)w * (long)h > TEXTURE_MAX_TEXELS) {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: %dx%d is out of range (1..%d per side, %ld texels)", name, w, h,
                 TEXTURE_MAX_SIDE, TEXTURE_MAX_TEXELS);
        return -1;
    }
    return 0;
}

static int decoded(unsigned char *px, int w, int h, int channels, int srgb, const char *name, struct texture *t,
                   char *msg)
{
    if (!px) {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: cannot decode: %s", name, failure_reason());
        return -1;
    }
    /* grey and grey-alpha images replicate their one channel; alpha is the last of 2 or 4 */
    const int grey[3] = {0, 0, 0}, colour[3] = {0, 1, 2};
    from_bytes(px, w, h, channels, channels < 3 ? grey : colour, srgb, t);
    t->alpha = NULL;
    if (channels == 2 || channels == 4)
        alpha_from_bytes(px, w, h, channels, channels - 1, t);
    stbi_image_free(px);
    return 0;
}

int texture_load_file(const char *path, int srgb, struct texture *t, char *msg)
{
    memset(t, 0, sizeof(*t));
    int w = 0, h = 0, n = 0;
    const int ok = stbi_info(path, &w, &h, &n); /* before w and h are read below */
    if (check_header(ok, w, h, stbi_is_hdr(path), path, msg) != 0)
        return -1;
    unsigned char *px = stbi_load(path, &w, &h, &n, 0);
    return decoded(px, w, h, n, srgb, path, t, msg);
}

int texture_load_memory(const unsigned char *data, int len, int srgb, const char *name, struct texture *t, char *msg)
{
    memset(t, 0, sizeof(*t));
    int w = 0, h = 0, n = 0;
    if (len <= 0) {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: no image data", name);
        return -1;
    }
    const int ok = stbi_info_from_memory(data, len, &w, &h, &n);
    if (check_header(ok, w, h, stbi_is_hdr_from_memory(data, len), name, msg) != 0)
        return -1;
    unsigned char *px = stbi_load_from_memory(data, len, &w, &h, &n, 0);
    return decoded(px, w, h, n, srgb, name, t, msg);
}

void texture_from_bgra8(const unsigned char *bgra, int width, int height, int srgb, struct texture *t)
{
    const int order[3] = {2, 1, 0};
    from_bytes(bgra, width, height, 4, order, srgb, t);
    t->alpha = NULL;
    alpha_from_bytes(bgra, width, height, 4, 3, t);
}

void texture_fini(struct texture *t)
{
    free(t->rgb);
    free(t->alpha);
    memset(t, 0, sizeof(*t));
}

static vec3 texel(const struct texture *t, size_t i)
{
    const float *p = t->rgb + 3 * i;
    return v3(p[0], p[1], p[2]);
}

/* Wraps i into [0, n). */
static int wrap(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

/* The four texels around (u, v) and the bilinear weights between them. */
struct bilinear {
    size_t i00, i10, i01, i11;
    float ax, ay;
};

/* Texel index i of n under a wrap mode: repeat (the unit-square fraction was taken before),
 * clamp to the edge, or mirrored repeat (period 2n: 0 .. n-1, n-1 .. 0). */
static int wrap_mode(int i, int n, int mode)
{
    if (mode == 1)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    if (mode == 2) {
        int r = wrap(i, 2 * n);
        return r < n ? r : 2 * n - 1 - r;
    }
    return wrap(i, n);
}

static struct bilinear bilinear_wrap(const struct texture *t, float u, float v, int wu, int wv)
{
    struct bilinear b = {0, 0, 0, 0, 0.0f, 0.0f};
    /* clamp and mirror index with u as is: keep it where int conversion is defined */
    if (!isfinite(u) || !isfinite(v) || (wu && fabsf(u) > 1e6f) || (wv && fabsf(v) > 1e6f))
        return b;
    /* texel centres at (i + 0.5) / width; v = 0 is the bottom row, i.e. image row height - 1.
     * Repeat takes the fraction first, exactly as before wrap modes existed. */
    float fx = (wu ? u : u - floorf(u)) * (float)t->width - 0.5f;
    float fy = (1.0f - (wv ? v : v - floorf(v))) * (float)t->height - 0.5f;
    float x0f = floorf(fx), y0f = floorf(fy);
    b.ax = fx - x0f;
    b.ay = fy - y0f;
    int x0 = wrap_mode((int)x0f, t->width, wu), y0 = wrap_mode((int)y0f, t->height, wv);
    int x1 = wrap_mode((int)x0f + 1, t->width, wu), y1 = wrap_mode((int)y0f + 1, t->height, wv);
    const size_t w = (size_t)t->width;
    b.i00 = (size_t)y0 * w + (size_t)x0;
    b.i10 = (size_t)y0 * w + (size_t)x1;
    b.i01 = (size_t)y1 * w + (size_t)x0;
    b.i11 = (size_t)y1 * w + (size_t)x1;
    return b;
}

vec3 texture_sample(const struct texture *t, float u, float v) { return texture_sample_wrap(t, u, v, 0, 0); }

vec3 texture_sample_wrap(const struct texture *t, float u, float v, int wrap_u, int wrap_v)
{
    const struct bilinear b = bilinear_wrap(t, u, v, wrap_u, wrap_v);
    vec3 top = v3_lerp(texel(t, b.i00), texel(t, b.i10), b.ax);
    vec3 bottom = v3_lerp(texel(t, b.i01), texel(t, b.i11), b.ax);
    return v3_lerp(top, bottom, b.ay);
}

float texture_sample_alpha(const struct texture *t, float u, float v)
{
    return texture_sample_alpha_wrap(t, u, v, 0, 0);
}

float texture_sample_alpha_wrap(const struct texture *t, float u, float v, int wrap_u, int wrap_v)
{
    if (!t->alpha)
        return 1.0f;
    const struct bilinear b = bilinear_wrap(t, u, v, wrap_u, wrap_v);
    const float *a = t->alpha;
    float top = a[b.i00] + (a[b.i10] - a[b.i00]) * b.ax, bottom = a[b.i01] + (a[b.i11] - a[b.i01]) * b.ax;
    return top + (bottom - top) * b.ay;
}
