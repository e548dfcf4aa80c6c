/* screen_history.c: the ReSTIR methods' shared screen-space state (screen_history.h). */
#include "methods/screen_history.h"

#include <string.h>

#include "core/check.h"
#include "core/lowdisc.h"
#include "render/reuse_cells.h"
#include "render/spatial_select.h"

void screen_history_init(struct screen_history *h, const struct render_params *p, int with_shading, int path_reuse)
{
    memset(h, 0, sizeof(*h));
    size_t n = (size_t)p->width * (size_t)p->height;
    gbuffer_init(&h->gb[0], p->width, p->height, with_shading);
    gbuffer_init(&h->gb[1], p->width, p->height, with_shading);
    h->neighbors = xcalloc(n * SPATIAL_MAX_NEIGHBORS, sizeof(int));
    h->neighbors_per_pixel = render_params_spatial_neighbors(p, path_reuse);
    h->disk_offsets = r2_disk_table();
    h->age[0] = xcalloc(n, 1);
    h->age[1] = xcalloc(n, 1);
    if (p->reuse.spatial && p->reuse.spatial_reuse == REUSE_SPMIS) {
        h->spmis = xmalloc(sizeof(*h->spmis));
        spmis_frame_init(h->spmis, p);
    }
}

void screen_history_fini(struct screen_history *h)
{
    gbuffer_fini(&h->gb[0]);
    gbuffer_fini(&h->gb[1]);
    free(h->neighbors);
    if (h->spmis) {
        spmis_frame_fini(h->spmis);
        free(h->spmis);
    }
    free(h->age[0]);
    free(h->age[1]);
    memset(h, 0, sizeof(*h));
}

long long screen_history_count_valid(const struct screen_history *h)
{
    const struct gbuffer *g = &h->gb[h->cur];
    long long valid = 0;
    for (int i = 0; i < g->width * g->height; i++)
        valid += g->valid[i];
    return valid;
}

void screen_history_end_frame(struct screen_history *h, const struct render_params *p)
{
    const struct gbuffer *g = &h->gb[h->cur], *prev_g = &h->gb[1 - h->cur];
    const unsigned char *prev = h->age[1 - h->cur];
    unsigned char *age = h->age[h->cur];
    const int n = g->width * g->height, has_history = h->has_history;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        int q =
            has_history ? gbuffer_history_pixel(g, i, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane) : -1;
        age[i] = q < 0 ? 0 : (unsigned char)(prev[q] < 255 ? prev[q] + 1 : 255);
    }
    h->cur = 1 - h->cur;
    h->has_history = 1;
}

void screen_history_inspect(const struct screen_history *h, struct renderer_inspect *out)
{
    const int last = 1 - h->cur; /* the ping-pong index flipped after the frame */
    out->gbuffer = &h->gb[last];
    out->age = h->age[last];
    out->neighbors = h->neighbors;
    out->neighbors_per_pixel = h->neighbors_per_pixel;
    out->spmis = h->spmis;
}
