/* view_debug.h: the viewer's debug views of the renderer's last frame, as 8-bit RGB: reservoir
 * confidence (c over the cap), temporal acceptance (how many frames a pixel's surface has been
 * validated in view: black where history was rejected this frame), selected spatial neighbors (of
 * M), spmis reuse cells (one colour per cell a pixel belongs to; black: no cell) and temporal
 * candidates per technique (path reservoirs' TEMPORAL_* flags, pt_splat.h: black none, dark red
 * received but none accepted, green backprojection accepted, blue splat accepted, cyan both).
 * Must never depend on SDL. */
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

/* Writes mode's picture into rgb8 (3 bytes per pixel). Returns 1, or 0 when the method has no
 * such data this frame (no reservoirs, no selection pass, no reuse cells, no path reservoirs'
 * temporal flags): rgb8 then holds the image. */
int view_debug_rgb8(const struct renderer *r, enum view_mode mode, unsigned char *rgb8);

#endif
