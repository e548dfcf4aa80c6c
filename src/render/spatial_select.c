/* spatial_select.c: spatial neighbor selection for ReSTIR DI and PT (see spatial_select.h). */
#include "spatial_select.h"

#include "core/sampling.h"
#include "restir/neighbors.h"

int spatial_select_bitterli(const struct render_params *p, const struct gbuffer *g, int x, int y, int tries,
                            pcg32 *rng, int *out)
{
    const int w = g->width, h = g->height, i = y * w + x;
    const float ni[3] = {g->normal[i].x, g->normal[i].y, g->normal[i].z};
    int n = 0;
    for (int k = 0; k < tries; k++) {
        float dx, dy;
        warp_concentric_disk(pcg32_float(rng), pcg32_float(rng), &dx, &dy);
        int nx = x + (int)lrintf(dx * p->spatial_radius), ny = y + (int)lrintf(dy * p->spatial_radius);
        if (nx < 0 || ny < 0 || nx >= w || ny >= h || (nx == x && ny == y))
            continue;
        int j = ny * w + nx;
        const float nj[3] = {g->normal[j].x, g->normal[j].y, g->normal[j].z};
        if (g->valid[j] &&
            restir_bitterli_compatible(ni, nj, g->depth[i], g->depth[j], p->spatial_normal, p->spatial_depth))
            out[n++] = j;
    }
    return n;
}
