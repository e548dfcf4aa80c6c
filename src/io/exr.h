/* exr.h: reading and writing RGB float images as OpenEXR (half or float channels, one or more layers,
 * text attributes) via the OpenEXR C API. Must never depend on scenes or render code. */
#ifndef RESTIR_IO_EXR_H
#define RESTIR_IO_EXR_H

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

#endif
