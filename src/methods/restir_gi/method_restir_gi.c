/* method_restir_gi.c: `restir-gi`, ReSTIR GI (Ouyang et al. 2021) written as GRIS (render/restir_gi.h):
 * per pixel one secondary vertex x2 with its path suffix, reused temporally and spatially by
 * reconnecting the pixel's shading point to x2, plus the direct light at the shading point traced
 * every frame. gi.radiance=reevaluate (default) traces x2's outgoing radiance again toward every
 * shading point that reuses it and is unbiased; gi.radiance=stored keeps the radiance x2 sent
 * toward the pixel that traced it (the paper's form; BIASED where x2 is glossy). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/screen_history.h"
#include "methods/restir_gi/restir_gi.h"
#include "render/spatial_select.h"
#include "methods/restir_gi/gi_settings.h"
#include "render/boiling_filter.h"

struct restir_gi_state {
    struct screen_history h;
    struct gi_reservoir *work;    /* initial, then temporal outputs */
    struct gi_reservoir *hist[2]; /* spatial outputs: this frame's and the previous frame's */
    struct path_vertex *x1[2];    /* each pixel's shading point: this frame's and the previous one's */
    vec3 *base;                   /* emission seen directly plus direct light at x1 */
    float *boil;                  /* gi.boiling_filter's weights (allocated by its first frame) */
};

static void *restir_gi_create(const struct renderer *r)
{
    const struct render_params *p = &r->p;
    const size_t n = (size_t)p->width * (size_t)p->height;
    struct restir_gi_state *t = xcalloc(1, sizeof(*t));
    screen_history_init(&t->h, p, 0, 1);
    t->work = xcalloc(n, sizeof(struct gi_reservoir));
    for (int k = 0; k < 2; k++) {
        t->hist[k] = xcalloc(n, sizeof(struct gi_reservoir));
        t->x1[k] = xcalloc(n, sizeof(struct path_vertex));
    }
    t->base = xcalloc(n, sizeof(vec3));
    return t;
}

static void restir_gi_destroy(void *state)
{
    struct restir_gi_state *t = state;
    screen_history_fini(&t->h);
    free(t->work);
    for (int k = 0; k < 2; k++) {
        free(t->hist[k]);
        free(t->x1[k]);
    }
    free(t->base);
    free(t->boil);
    free(t);
}

/* gi.boiling_filter (BIASED): the temporal pass's outliers by target x W, per 8 x 8 group, emptied. */
static void gi_boiling_filter(struct restir_gi_state *t, const struct gbuffer *g, const struct render_params *p)
{
    const size_t n = (size_t)g->width * (size_t)g->height;
    if (!t->boil)
        t->boil = xmalloc(sizeof(float) * n);
    for (size_t i = 0; i < n; i++)
        t->boil[i] = gi_reservoir_has_sample(&t->work[i]) ? t->work[i].target * t->work[i].W : 0.0f;
    if (boiling_filter_mark(t->boil, g->width, g->height, gi_settings_of(p)->boiling_strength) == 0)
        return;
    for (size_t i = 0; i < n; i++)
        if (t->boil[i] < 0.0f)
            gi_reservoir_clear(&t->work[i], t->work[i].c);
}

static void restir_gi_render_frame(struct renderer *r, void *state, const struct camera_view *view,
                                   struct frame_stats *st)
{
    struct restir_gi_state *t = state;
    struct screen_history *h = &t->h;
    const struct render_params *p = &r->p;
    const int cur = h->cur;
    struct gbuffer *g = screen_history_gbuffer(h), *prev_g = screen_history_prev_gbuffer(h);
    struct gi_reservoir *out = t->hist[cur];
    const size_t n = (size_t)g->width * (size_t)g->height;
    const struct gi_frame fr = {r->scene, p, view, r->frame};
    /* The G-buffer's jitter is drawn from its own streams, independent of the samples, so history
     * and neighbor selection, which read only G-buffers, cannot bias the merges. */
    RENDERER_TIMED(st, PASS_GBUFFER,
                   st->rays += gbuffer_pass(g, r->scene, view, h->has_history ? &r->prev_view : NULL, p->jitter,
                                            p->seed, r->frame));
    RENDERER_TIMED(st, PASS_INITIAL, st->rays += gi_initial_pass(&fr, g, t->x1[cur], t->base, t->work);
                   st->nonfinite += gi_nonfinite_discard(t->work, n));
    if (p->reuse.temporal && renderer_history_reusable(r, h->has_history))
        RENDERER_TIMED(st, PASS_TEMPORAL,
                       st->rays += gi_temporal_pass(&fr, g, prev_g, t->x1[cur], t->x1[1 - cur], t->hist[1 - cur],
                                                    t->work, &st->temporal_accepted);
                       st->nonfinite += gi_nonfinite_discard(t->work, n);
                       if (gi_settings_of(p)->boiling_filter) gi_boiling_filter(t, g, p));
    if (p->reuse.spatial) {
        RENDERER_TIMED(st, PASS_SELECT,
                       st->neighbors_selected = spatial_select_pass(p, 1, g, r->frame, h->disk_offsets, h->neighbors));
        RENDERER_TIMED(st, PASS_SPATIAL, st->rays += gi_spatial_pass(&fr, g, h->neighbors, t->x1[cur], t->work, out);
                       st->nonfinite += gi_nonfinite_discard(out, n));
    } else {
        memcpy(out, t->work, sizeof(*out) * n);
    }
    RENDERER_TIMED(st, PASS_SHADE, gi_shade_pass(g, t->base, out, r->image));
    if (p->reuse.history_temporal && p->reuse.spatial)
        memcpy(out, t->work, sizeof(*out) * n);
    st->valid_pixels = screen_history_count_valid(h);
    screen_history_end_frame(h, p);
}

static float gi_confidence(const void *reservoirs, int pixel)
{
    return ((const struct gi_reservoir *)reservoirs)[pixel].c;
}

static void restir_gi_inspect(const void *state, struct renderer_inspect *out)
{
    const struct restir_gi_state *t = state;
    screen_history_inspect(&t->h, out);
    out->reservoirs = t->hist[1 - t->h.cur];
    out->confidence = gi_confidence;
}

/* Reuse cells (spatial.reuse=spmis) are not built for GI reservoirs. */
static int restir_gi_check(const struct render_params *p, const struct scene *s, char *msg)
{
    (void)s;
    if (p->reuse.spatial && p->reuse.spatial_reuse != REUSE_STANDARD) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "spatial.reuse=spmis: restir-gi reuses from the selection pass only (spatial.reuse=standard)");
        return -1;
    }
    return 0;
}

const struct method method_restir_gi = {
    .name = "restir-gi",
    .description = "ReSTIR GI (Ouyang et al. 2021) as GRIS: one secondary vertex per pixel with its path suffix, "
                   "temporal and spatial reuse by reconnection; gi.radiance=reevaluate (unbiased) or stored",
    .caps = METHOD_HISTORY | METHOD_ANIMATED_EMITTERS,
    .blocks = (const struct param_block *const[]){&params_block_depth, &params_block_roulette, &params_block_lights,
                                                  &params_block_reuse, &gi_block, NULL},
    .passes = (const char *const[]){"gbuffer", "initial", "temporal", "select", "spatial", "shade", NULL},
    .check = restir_gi_check,
    .create = restir_gi_create,
    .destroy = restir_gi_destroy,
    .render_frame = restir_gi_render_frame,
    .inspect = restir_gi_inspect,
};
