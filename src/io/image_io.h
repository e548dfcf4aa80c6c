/* image_io.h: reading and writing RGB float images as OpenEXR (half or float channels, one or
 * more layers, via the OpenEXR C API), tone-mapped 8-bit sRGB PNG and false-colour PNG of
 * signed images. Writers write a temporary file and rename it, so a failure never leaves a
 * half-written output. Must never depend on render code. */
#ifndef RESTIR_IO_IMAGE_IO_H
#define RESTIR_IO_IMAGE_IO_H

#include <stddef.h>

/* One RGB image of a multi-layer EXR: interleaved floats (w*h*3). name NULL or "" is the default
 * layer, stored as the plain channels R, G, B; any other name is stored as name.R, name.G,
 * name.B, which tev and the OpenEXR tools show as a layer called name. */
struct exr_layer {
    const char *name;
    const float *rgb;
};

/* Writes n layers (1 to 256) of a w x h image as one scanline EXR of 32-bit float channels
 * (RLE compressed, lossless: 5x faster to write than ZIP for 12 % more bytes on rendered frames,
 * docs/BENCHMARKS.md "Output cost"). Layer names must not contain '.' (so neither nested nor empty
 * after a dot), must be at most 200 bytes, and must be unique (at most one default layer);
 * these are checked before any file is created. Returns 0, or -1 with msg (RESTIR_MSG_LEN)
 * naming the file and the problem. */
int exr_write_layers(const char *path, const struct exr_layer *layers, int n, int w, int h,
                     char *msg);
/* A text attribute of an EXR header (OpenEXR type "string"): the name needs a '.' namespace
 * ("restir.samples") so it cannot collide with a standard attribute. */
struct exr_attribute {
    const char *name;
    const char *value;
};
/* exr_write_layers with n_attrs (0 to 64) text attributes in the header, checked (names unique,
 * namespaced, at most 200 bytes; values at most 64 KiB) before any file is created. */
int exr_write_layers_attrs(const char *path, const struct exr_layer *layers, int n,
                           const struct exr_attribute *attrs, int n_attrs, int w, int h, char *msg);
/* Reads text attribute name of path's header into value (len bytes). Returns 0; 1 (value empty)
 * when the header has no such attribute; -1 with msg when the file is unreadable, the attribute is
 * not text or it does not fit. */
int exr_read_attribute(const char *path, const char *name, char *value, size_t len, char *msg);
/* Writes interleaved RGB floats (w*h*3) as a 32-bit float EXR with channels R, G, B: the
 * one-layer case of exr_write_layers. Returns 0, or -1 with msg naming the file and problem. */
int exr_write_rgb(const char *path, const float *rgb, int w, int h, char *msg);
/* Reads the R, G, B channels (half or float) into a newly malloc'ed interleaved buffer; other
 * channels (alpha, named layers such as dx.R) are ignored. Returns 0, or -1 with msg naming the
 * file and the problem (missing, not EXR, no RGB, ...). */
int exr_read_rgb(const char *path, float **rgb, int *w, int *h, char *msg);
/* Reads channels layer.R, layer.G, layer.B (half or float; layer NULL or "" = the default R, G,
 * B, exactly as exr_read_rgb) into a newly malloc'ed interleaved buffer. A missing layer gives
 * -1 with msg naming the file, the layer and the layers the file does have. */
int exr_read_layer(const char *path, const char *layer, float **rgb, int *w, int *h, char *msg);
/* n values of rgb * 2^exposure as 8-bit sRGB, clamped (what PNGs and the viewer show). */
void encode_srgb8(const float *rgb, size_t n, float exposure, unsigned char *out);
/* Writes 8-bit RGB bytes as they are. Returns 0 or -1 with msg. */
int png_write_rgb8(const char *path, const unsigned char *rgb8, int w, int h, char *msg);
/* Writes an 8-bit sRGB PNG of rgb * 2^exposure, clamped. Returns 0 or -1 with msg. */
int png_write_srgb(const char *path, const float *rgb, int w, int h, float exposure, char *msg);
/* Writes a false-colour 8-bit PNG of a signed image (a gradient or a difference): each pixel's
 * luminance lum = 0.2126 R + 0.7152 G + 0.0722 B is shown on a diverging map with black at zero,
 * so sparse gradients stay readable. With t = clamp(|lum| * scale, 0, 1)^(1/2.2), a positive
 * pixel is (t, t^2/2, 0) (dark red to orange at t = 1), a negative one (0, t^2/2, t) (dark blue
 * to sky blue); NaN is black, +-infinity is full colour. scale <= 0 (or not finite) chooses
 * scale = 1 / (99th percentile of the finite |lum|); where that percentile is 0 (fewer than 1%
 * of pixels nonzero), 1 / (largest |lum|); where every lum is 0, 1. Returns 0 or -1 with msg. */
int png_write_signed(const char *path, const float *rgb, int w, int h, float scale, char *msg);

/* The heat-map colour of t in [0, 1] (clamped; NaN is black): black, violet, red, orange,
 * pale yellow at HEAT_STOPS evenly spaced stops, linear between them. */
#define HEAT_STOPS 5
extern const unsigned char heat_stops[HEAT_STOPS][3];
void heat_color(float t, unsigned char rgb[3]);
/* Writes values (one float per pixel) as an 8-bit PNG through heat_color(v / vmax). */
int png_write_heatmap(const char *path, const float *values, int w, int h, float vmax, char *msg);

/* Temporary sibling name for atomic writes: "<path>.tmp-<pid>". */
void io_temp_path(const char *path, char *tmp, unsigned long tmp_len);
/* Removes path's temporaries ("<path>.tmp-<pid>") whose writer process no longer exists, left by a
 * process that was killed mid-write. Returns how many were removed. */
int io_remove_stale_temporaries(const char *path);
/* Renames tmp over path; returns 0, or -1 with msg (and removes tmp). */
int io_commit(const char *tmp, const char *path, char *msg);
/* Creates folder dir and its missing parents (mkdir -p). Returns 0, or -1 with msg naming the
 * folder that could not be made, or dir when it exists but is not a folder. */
int io_make_dirs(const char *dir, char *msg);

#endif
