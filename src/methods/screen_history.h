/* screen_history.h: the screen-space state that the ReSTIR methods share between frames: ping-pong
 * G-buffers, each pixel's history age, the spatial selection pass's output and R2 disk offsets, and
 * spatial.reuse=spmis's cells. Each method that reuses over the screen embeds one; it holds no
 * reservoirs. Must never read or write files. */
#ifndef RESTIR_METHODS_SCREEN_HISTORY_H
#define RESTIR_METHODS_SCREEN_HISTORY_H

#include "methods/renderer.h"
#include "render/gbuffer.h"
#include "render/params.h"

struct screen_history {
    struct gbuffer gb[2];
    int cur;                   /* index of the current G-buffer / history */
    int has_history;
    int *neighbors;            /* selection pass output: spatial neighbors per pixel */
    int neighbors_per_pixel;   /* render_params_spatial_neighbors(p, path_reuse) */
    const float *disk_offsets; /* R2 disk offsets of compat selection (R2_DISK_OFFSETS x 2; r2_disk_table) */
    struct spmis_frame *spmis; /* spatial.reuse=spmis: cells and per-pixel scratch */
    unsigned char *age[2];     /* per pixel: frames its surface has been in view (history chain
                                  length by G-buffer validation, capped at 255); ping-pong */
};

/* Allocates for p's resolution; with_shading keeps each pixel's shading point in the G-buffers
 * (what the DI passes read); path_reuse picks the default neighbor count (ReSTIR PT's 3). */
void screen_history_init(struct screen_history *h, const struct render_params *p, int with_shading, int path_reuse);
void screen_history_fini(struct screen_history *h);
/* The current frame's G-buffer and the previous frame's. */
static inline struct gbuffer *screen_history_gbuffer(struct screen_history *h) { return &h->gb[h->cur]; }
static inline struct gbuffer *screen_history_prev_gbuffer(struct screen_history *h) { return &h->gb[1 - h->cur]; }
/* After a frame: follows each pixel's history chain by the same G-buffer validation as temporal
 * reuse, then flips the ping-pong index and marks history available. */
void screen_history_end_frame(struct screen_history *h, const struct render_params *p);
/* Valid pixels of the current G-buffer. */
long long screen_history_count_valid(const struct screen_history *h);
/* Fills the history part of *out (the last frame's G-buffer, ages, neighbors, cells): call after
 * screen_history_end_frame. */
void screen_history_inspect(const struct screen_history *h, struct renderer_inspect *out);

#endif
