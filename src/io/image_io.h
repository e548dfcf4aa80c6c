/* image_io.h: reading and writing RGB float images as OpenEXR (half or float channels, via the
 * OpenEXR C API) and tone-mapped 8-bit sRGB PNG. Writers write a temporary file and rename it,
 * so a failure never leaves a half-written output. Must never depend on render code. */
#ifndef RESTIR_IO_IMAGE_IO_H
#define RESTIR_IO_IMAGE_IO_H

/* Writes interleaved RGB floats (w*h*3) as a 32-bit float EXR with channels R, G, B.
 * Returns 0, or -1 with msg (RESTIR_MSG_LEN) naming the file and the problem. */
int exr_write_rgb(const char *path, const float *rgb, int w, int h, char *msg);
/* Reads R, G, B channels (half or float) into a newly malloc'ed interleaved buffer.
 * Returns 0, or -1 with msg naming the file and the problem (missing, not EXR, no RGB, ...). */
int exr_read_rgb(const char *path, float **rgb, int *w, int *h, char *msg);
/* Writes an 8-bit sRGB PNG of rgb * 2^exposure, clamped. Returns 0 or -1 with msg. */
int png_write_srgb(const char *path, const float *rgb, int w, int h, float exposure, char *msg);

/* Temporary sibling name for atomic writes: "<path>.tmp-<pid>". */
void io_temp_path(const char *path, char *tmp, unsigned long tmp_len);
/* Renames tmp over path; returns 0, or -1 with msg (and removes tmp). */
int io_commit(const char *tmp, const char *path, char *msg);

#endif
