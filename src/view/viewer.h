/* viewer.h: `restir view`, an SDL2 window that renders frame after frame with one method while the
 * camera moves (mouse drag turns, W A S D move, Q E down and up), so motion goes through the real
 * motion vectors and temporal reuse. Keys: M next method, T temporal reuse, Y spatial reuse,
 * N neighbor selection, P stochastic pairwise MIS (spmis), V the next debug view (view_debug.h:
 * confidence, temporal acceptance, selected neighbors, reuse cells, temporal candidates per
 * technique), O the denoised frame or the raw one (turning SVGF on the first time), I the next
 * denoiser (svgf, atrous), K screenshot (EXR and PNG, the denoised frame too), C save the camera path
 * since the last change of method
 * or settings (a camera file `render --camera FILE` replays frame for frame), escape quits. The
 * window title shows the method, its settings and the per-pass milliseconds. The only SDL2 user. */
#ifndef RESTIR_VIEW_VIEWER_H
#define RESTIR_VIEW_VIEWER_H

#include "methods/renderer.h"
#include "scene/scene.h"

struct view_options {
    const struct scene *scene;
    const struct method *method;
    struct render_params params;
    const char *script;  /* timed input (view_script.h), or NULL */
    const char *out_dir; /* screenshots, camera files and the last frame */
    /* The command's checks of a method and its parameters on this scene, run before every restart
     * (M, T, Y, N, P, O, I): 0, or nonzero with msg (RESTIR_MSG_LEN bytes), and the viewer keeps what
     * runs. NULL: none. */
    int (*check)(void *ctx, const struct method *m, const struct render_params *p, char *msg);
    void *check_ctx;
};

/* Runs the viewer until escape, the window is closed or the script quits; on leaving it writes
 * out_dir/last_frame.exr and .png. Returns 0, 1 with msg when there is no display or an output
 * cannot be written, 2 with msg for a bad script. */
int view_run(const struct view_options *o, char *msg);

/* The method the M key switches to after m: the registry's methods with viewer_order > 0, in that
 * order, wrapping around; m NULL or not in the cycle: the first. */
const struct method *view_method_after(const struct method *m);
/* The cycle's method names, ", "-separated, into out (n bytes). */
void view_method_cycle_names(char *out, size_t n);

#endif
