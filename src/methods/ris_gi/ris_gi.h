/* ris_gi.h: `ris-gi`, the no-reuse RIS baseline of ReSTIR GI (Ouyang et al. 2021), as ris-di is ReSTIR
 * DI's: at each primary hit x1, K directions drawn from x1's BSDF, each traced to its secondary vertex
 * x2 and the radiance of its path suffix (the path walk from x2), one kept by RIS with target
 * p_hat = luminance of f = f_r cos Lr and contribution weight W = (1/K) sum_k p_hat_k / p_k / p_hat(Y);
 * plus x1's emission and its paths of length 2, as pt. Unbiased: p_k > 0 wherever f_r cos > 0, and p_hat > 0
 * wherever f > 0. No state between frames. */
#ifndef RESTIR_METHODS_RIS_GI_RIS_GI_H
#define RESTIR_METHODS_RIS_GI_RIS_GI_H

#include "render/params.h"
#include "scene/camera.h"
#include "scene/scene.h"

/* The method's own setting, risgi.candidates. */
struct ris_gi_settings {
    int candidates; /* K: BSDF directions resampled per primary hit */
};
extern struct param_block ris_gi_block;
static inline const struct ris_gi_settings *ris_gi_settings_of(const struct render_params *p)
{
    return param_block_in(p, &ris_gi_block);
}

/* The random stream of a pixel's paths (rng_stream_id). */
#define RIS_GI_STREAM "ris-gi.paths"

/* Renders frame `frame` seen through view into rgb (3 floats per pixel), p->spp paths per pixel, each
 * from its own primary ray (pt's: jitter, lens and shutter). Returns the rays traced. Threads: OpenMP
 * over tiles. */
long long ris_gi_pass(const struct scene *s, const struct camera_view *view, const struct render_params *p, int frame,
                      float *rgb);

#endif
