/* png.c: 8-bit PNG output through libpng (png.h): tone-mapped sRGB and false colour for signed images.
 * Must never depend on scenes, render code or anything that aborts on bad input. */
#include "io/png.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "io/io_msg.h"

#define PNG_PATH_MAX 4096

struct png_err {
    char text[256];
};

static void png_error_store(png_structp png, png_const_charp text)
{
    struct png_err *e = png_get_error_ptr(png);
    if (e)
        snprintf(e->text, sizeof e->text, "%s", text ? text : "libpng error");
    png_longjmp(png, 1);
}

static void png_warning_ignore(png_structp png, png_const_charp text)
{
    (void)png;
    (void)text;
}

/* sRGB opto-electronic transfer function (IEC 61966-2-1) on a linear value in [0, 1]. */
static float srgb_oetf(float v)
{
    return v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

static unsigned char png_encode_value(float v, float scale)
{
    float x = v * scale;
    if (!(x > 0.0f)) /* NaN and negatives */
        return 0;
    if (x >= 1.0f)
        return 255;
    float s = srgb_oetf(x);
    long q = lrintf(s * 255.0f);
    if (q < 0)
        q = 0;
    if (q > 255)
        q = 255;
    return (unsigned char)q;
}

/* Writes the whole image to an already open file; returns 0 or -1 with err filled. */
static int png_write_stream(FILE *f, const unsigned char *pixels, int w, int h, struct png_err *err)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, png_error_store,
                                              png_warning_ignore);
    if (!png) {
        snprintf(err->text, sizeof err->text, "cannot create libpng writer");
        return -1;
    }
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        snprintf(err->text, sizeof err->text, "cannot create libpng info");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return -1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    /* zlib level 1: previews, written every frame; 23 instead of 26 ms at 512x512 for 0.6 % more
     * bytes (docs/BENCHMARKS.md, "Output cost"; the rest is the sRGB conversion). */
    png_set_compression_level(png, 1);
    png_write_info(png, info);
    for (int y = 0; y < h; y++)
        png_write_row(png, pixels + (size_t)y * (size_t)w * 3);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

/* Writes 8-bit RGB pixels (freed here) to path through a temporary file and a rename. */
static int png_write_pixels(const char *path, unsigned char *pixels, int w, int h, char *msg)
{
    char tmp[PNG_PATH_MAX + 32];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "wb", msg);
    if (!f) {
        free(pixels);
        return -1;
    }
    struct png_err err;
    err.text[0] = '\0';
    int status = png_write_stream(f, pixels, w, h, &err);
    free(pixels);
    int close_failed = fclose(f) != 0;
    if (status != 0 || close_failed) {
        if (status != 0)
            io_msg(msg, "%s: PNG write failed: %s", path, err.text);
        else
            io_msg(msg, "%s: cannot finish writing %.200s: %s", path, tmp,
                    strerror(errno));
        remove(tmp);
        return -1;
    }
    return io_commit(tmp, path, msg);
}

/* Checks the arguments every PNG writer shares; returns 0 or -1 with msg. */
static int png_check_args(const char *path, const float *rgb, int w, int h, char *msg)
{
    if (!rgb || w <= 0 || h <= 0 || w > 65536 || h > 65536) {
        io_msg(msg, "%s: cannot write PNG of invalid size %dx%d", path, w, h);
        return -1;
    }
    if (strlen(path) >= PNG_PATH_MAX) {
        io_msg(msg, "%.200s...: output path is too long", path);
        return -1;
    }
    return 0;
}

int png_write_srgb(const char *path, const float *rgb, int w, int h, float exposure, char *msg)
{
    if (png_check_args(path, rgb, w, h, msg) != 0)
        return -1;
    size_t n = (size_t)w * (size_t)h * 3;
    unsigned char *pixels = malloc(n);
    if (!pixels) {
        io_msg(msg, "%s: out of memory for %dx%d PNG", path, w, h);
        return -1;
    }
    encode_srgb8(rgb, n, exposure, pixels);
    return png_write_pixels(path, pixels, w, h, msg);
}

int png_write_rgb8(const char *path, const unsigned char *rgb8, int w, int h, char *msg)
{
    if (!path || !rgb8 || w <= 0 || h <= 0 || w > 65536 || h > 65536) {
        io_msg(msg, "%s: bad PNG arguments", path ? path : "(null)");
        return -1;
    }
    size_t n = 3 * (size_t)w * (size_t)h;
    unsigned char *pixels = malloc(n);
    if (!pixels) {
        io_msg(msg, "%s: out of memory", path);
        return -1;
    }
    memcpy(pixels, rgb8, n);
    return png_write_pixels(path, pixels, w, h, msg);
}

void encode_srgb8(const float *rgb, size_t n, float exposure, unsigned char *out)
{
    float scale = exp2f(isfinite(exposure) ? exposure : 0.0f);
    for (size_t i = 0; i < n; i++)
        out[i] = png_encode_value(rgb[i], scale);
}

static float png_luminance(const float *p)
{
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

static int png_cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The automatic scale of png_write_signed (see png.h): 1 / the 99th percentile (nearest
 * rank) of the finite |lum|, else 1 / their maximum, else 1. Returns -1 when out of memory. */
static int png_signed_auto_scale(const float *rgb, size_t npix, float *scale)
{
    float *mag = malloc(npix * sizeof(float));
    if (!mag)
        return -1;
    size_t m = 0;
    for (size_t i = 0; i < npix; i++) {
        float l = fabsf(png_luminance(rgb + 3 * i));
        if (isfinite(l))
            mag[m++] = l;
    }
    float ref = 0.0f;
    if (m > 0) {
        qsort(mag, m, sizeof(float), png_cmp_float);
        size_t rank = (size_t)ceil(0.99 * (double)m); /* 1-based nearest rank, 1..m */
        ref = mag[rank > 0 ? rank - 1 : 0];
        if (!(ref > 0.0f))
            ref = mag[m - 1];
    }
    free(mag);
    double s = ref > 0.0f ? 1.0 / (double)ref : 1.0;
    *scale = s > (double)FLT_MAX ? FLT_MAX : (float)s;
    return 0;
}

/* Encodes one signed luminance on the diverging map: black at zero, red-orange above, blue
 * below; t is the display value |lum| * scale clamped to [0, 1] and raised to 1/2.2. */
static void png_encode_signed(float lum, float scale, unsigned char *out)
{
    out[0] = out[1] = out[2] = 0;
    if (isnan(lum) || lum == 0.0f)
        return;
    float x = fabsf(lum) * scale;
    float t = x >= 1.0f ? 1.0f : powf(x, 1.0f / 2.2f);
    if (!(t > 0.0f))
        return;
    unsigned char hi = (unsigned char)lrintf(t * 255.0f);
    unsigned char mid = (unsigned char)lrintf(0.5f * t * t * 255.0f);
    out[1] = mid;
    if (lum > 0.0f)
        out[0] = hi;
    else
        out[2] = hi;
}

int encode_signed8(const float *rgb, size_t npix, float scale, unsigned char *out)
{
    if ((!(scale > 0.0f) || !isfinite(scale)) && png_signed_auto_scale(rgb, npix, &scale) != 0)
        return -1;
    for (size_t i = 0; i < npix; i++)
        png_encode_signed(png_luminance(rgb + 3 * i), scale, out + 3 * i);
    return 0;
}

int png_write_signed(const char *path, const float *rgb, int w, int h, float scale, char *msg)
{
    if (png_check_args(path, rgb, w, h, msg) != 0)
        return -1;
    size_t npix = (size_t)w * (size_t)h;
    unsigned char *pixels = malloc(npix * 3);
    if (!pixels || encode_signed8(rgb, npix, scale, pixels) != 0) {
        free(pixels);
        io_msg(msg, "%s: out of memory for %dx%d PNG", path, w, h);
        return -1;
    }
    return png_write_pixels(path, pixels, w, h, msg);
}

const unsigned char heat_stops[HEAT_STOPS][3] = {{0, 0, 0}, {90, 20, 130}, {215, 40, 60}, {250, 150, 30}, {255, 250, 190}};

void heat_color(float t, unsigned char rgb[3])
{
    if (!(t == t)) { /* NaN */
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    float x = t * (float)(HEAT_STOPS - 1);
    int k = (int)x < HEAT_STOPS - 1 ? (int)x : HEAT_STOPS - 2;
    float a = x - (float)k;
    for (int c = 0; c < 3; c++)
        rgb[c] = (unsigned char)((1.0f - a) * heat_stops[k][c] + a * heat_stops[k + 1][c] + 0.5f);
}

int png_write_heatmap(const char *path, const float *values, int w, int h, float vmax, char *msg)
{
    if (png_check_args(path, values, w, h, msg) != 0)
        return -1;
    const float inv = vmax > 0.0f && isfinite(vmax) ? 1.0f / vmax : 1.0f;
    size_t n = (size_t)w * (size_t)h;
    unsigned char *pixels = malloc(3 * n);
    if (!pixels) {
        io_msg(msg, "%s: out of memory", path);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        heat_color(values[i] * inv, pixels + 3 * i);
    return png_write_pixels(path, pixels, w, h, msg);
}
