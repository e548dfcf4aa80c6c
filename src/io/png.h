/* png.h: 8-bit PNG output: tone-mapped sRGB, false colour of signed images, heat maps.
 * Must never depend on scenes or render code. */
#ifndef RESTIR_IO_PNG_H
#define RESTIR_IO_PNG_H

#include <stddef.h>

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
/* The 8-bit RGB of png_write_signed's false colour for npix pixels of rgb (what the viewer shows of a
 * signed image), with its scale rule. Returns 0, or -1 when out of memory (out untouched). */
int encode_signed8(const float *rgb, size_t npix, float scale, unsigned char *out);

/* The heat-map colour of t in [0, 1] (clamped; NaN is black): black, violet, red, orange,
 * pale yellow at HEAT_STOPS evenly spaced stops, linear between them. */
#define HEAT_STOPS 5
extern const unsigned char heat_stops[HEAT_STOPS][3];
void heat_color(float t, unsigned char rgb[3]);
/* Writes values (one float per pixel) as an 8-bit PNG through heat_color(v / vmax). */
int png_write_heatmap(const char *path, const float *values, int w, int h, float vmax, char *msg);

#endif
