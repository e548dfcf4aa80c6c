/* spatial_select.h: which pixels spatial reuse merges into a pixel. Selection reads only the
 * G-buffer, never samples or weights, so GRIS stays unbiased (000 Sec. 3.5).
 * Must never depend on reservoirs. */
#ifndef RESTIR_RENDER_SPATIAL_SELECT_H
#define RESTIR_RENDER_SPATIAL_SELECT_H

#include "core/rng.h"
#include "gbuffer.h"
#include "params.h"

/* Bitterli et al. 2020: `tries` pixels uniform in the disk of radius p->spatial_radius around
 * (x, y), each kept when it is valid, not (x, y) and passes 000 Eq. 7. Writes the kept pixel
 * indices to out and returns how many. */
int spatial_select_bitterli(const struct render_params *p, const struct gbuffer *g, int x, int y, int tries,
                            pcg32 *rng, int *out);

#endif
