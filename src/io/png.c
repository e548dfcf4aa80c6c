/* png.c: tone-mapped 8-bit sRGB PNG output (exposure, clamp, sRGB transfer) through libpng.
 * Must never depend on scenes, render code or anything that aborts on bad input. */
#include "io/image_io.h"

#include "core/check.h"

#include <png.h>

#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Formats a message into msg (RESTIR_MSG_LEN bytes, may be NULL), truncating long paths. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void set_msg(char *msg, const char *fmt, ...)
{
    if (!msg)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, RESTIR_MSG_LEN, fmt, ap);
    va_end(ap);
}

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
    png_write_info(png, info);
    for (int y = 0; y < h; y++)
        png_write_row(png, pixels + (size_t)y * (size_t)w * 3);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;
}

int png_write_srgb(const char *path, const float *rgb, int w, int h, float exposure, char *msg)
{
    if (!rgb || w <= 0 || h <= 0 || w > 65536 || h > 65536) {
        set_msg(msg, "%s: cannot write PNG of invalid size %dx%d", path, w, h);
        return -1;
    }
    if (strlen(path) >= PNG_PATH_MAX) {
        set_msg(msg, "%.200s...: output path is too long", path);
        return -1;
    }
    float scale = exp2f(isfinite(exposure) ? exposure : 0.0f);
    size_t n = (size_t)w * (size_t)h * 3;
    unsigned char *pixels = malloc(n);
    if (!pixels) {
        set_msg(msg, "%s: out of memory for %dx%d PNG", path, w, h);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        pixels[i] = png_encode_value(rgb[i], scale);

    char tmp[PNG_PATH_MAX + 32];
    io_temp_path(path, tmp, sizeof tmp);
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        set_msg(msg, "%s: cannot create temporary file %.200s: %s", path, tmp, strerror(errno));
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
            set_msg(msg, "%s: PNG write failed: %s", path, err.text);
        else
            set_msg(msg, "%s: cannot finish writing %.200s: %s", path, tmp,
                     strerror(errno));
        remove(tmp);
        return -1;
    }
    return io_commit(tmp, path, msg);
}
