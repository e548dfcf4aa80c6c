/* spatial_select.h: the neighbor-selection pass: per pixel, the spatial neighbors that spatial
 * reuse will merge. Selection reads only the G-buffer, never samples or weights, so GRIS stays
 * unbiased (000 Sec. 3.5 and 4.3). Must never depend on reservoirs. */
#ifndef RESTIR_RENDER_SPATIAL_SELECT_H
#define RESTIR_RENDER_SPATIAL_SELECT_H

#include "render/gbuffer.h"
#include "render/params.h"

/* Most neighbors per pixel (the parameter table caps spatial.neighbors at this). */
#define SPATIAL_MAX_NEIGHBORS 5

/* Writes m = render_params_spatial_neighbors(p, path_reuse) entries per pixel to out (pixel
 * indices, -1 for none) by p->reuse.spatial_select:
 *  - bitterli: m pixels uniform in the radius-R disk, each kept when 000 Eq. 7 holds;
 *  - compat: 000 Algorithm 1: K candidates in the disk from the R2 offsets (r2_disk_offsets,
 *    R2_DISK_OFFSETS of them) with a random start, scored by 000 Eq. 14, m distinct ones drawn
 *    by weighted reservoir sampling, stopping early once more than m score above 0.5;
 *  - compat-binary: the same search with 000 Eq. 7 as a 0/1 score (000 Sec. 7.4).
 * Returns the number of neighbors written (not -1). */
long long spatial_select_pass(const struct render_params *p, int path_reuse, const struct gbuffer *g, int frame,
                              const float *disk_offsets, int *out);

#endif
