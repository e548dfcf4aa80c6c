/* view_debug.h: the viewer's debug views of the renderer's last frame, as 8-bit RGB: reservoir
 * confidence (c over the cap), temporal acceptance (how many frames a pixel's surface has been
 * validated in view: black where history was rejected this frame), selected spatial neighbors (of
 * M), spmis reuse cells (one colour per cell a pixel belongs to; black: no cell) and temporal
 * candidates per technique (path reservoirs' TEMPORAL_* flags, pt_splat.h: black none, dark red
 * received but none accepted, green backprojection accepted, blue splat accepted, cyan both), then
 * one view per output the method declares (method.h: radiance and debug outputs in sRGB, signed ones
 * in png_write_signed's false colour). Must never depend on SDL. */
#ifndef RESTIR_VIEW_VIEW_DEBUG_H
#define RESTIR_VIEW_VIEW_DEBUG_H

#include "methods/renderer.h"

enum view_mode {
    VIEW_IMAGE = 0,
    VIEW_CONFIDENCE,
    VIEW_ACCEPTANCE,
    VIEW_NEIGHBORS,
    VIEW_CELLS,
    VIEW_TEMPORAL_CANDIDATES,
    VIEW_MODES
};

extern const char *const view_mode_names[VIEW_MODES];

/* The views V cycles through with r's method: the VIEW_MODES above, then VIEW_MODES + k for its
 * output k (struct method.outputs). */
int view_count(const struct renderer *r);
/* View mode's name (an output's own name); "image" for a mode out of range. */
const char *view_name(const struct renderer *r, int mode);
/* Writes mode's picture into rgb8 (3 bytes per pixel). Returns 1, or 0 when the method has no
 * such data this frame (no reservoirs, no selection pass, no reuse cells, no path reservoirs'
 * temporal flags, no such output with these settings, a mode out of range): rgb8 then holds the image. */
int view_debug_rgb8(const struct renderer *r, int mode, unsigned char *rgb8);

#endif
