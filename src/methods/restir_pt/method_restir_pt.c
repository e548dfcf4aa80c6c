/* method_restir_pt.c: `restir-pt` (ReSTIR PT, Lin et al. 2022; 004 Sec. 2: path resampling, temporal
 * and spatial path reuse by GRIS with shift mappings, sub-pixel reservoirs) and `area-restir` (002
 * B.3: the same with 1 initial candidate and 2 spatial neighbors). */
#include "methods/restir_pt/method_restir_pt.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "render/boiling_filter.h"
#include "render/nonfinite.h"
#include "render/reuse_cells.h"
#include "render/spatial_select.h"

void restir_pt_state_init(struct restir_pt_state *t, const struct renderer *r)
{
    const struct render_params *p = &r->p;
    const size_t n = (size_t)p->width * (size_t)p->height;
    memset(t, 0, sizeof(*t));
    screen_history_init(&t->h, p, 0, 1);
    t->work = xcalloc(n, sizeof(struct pt_reservoir));
    t->hist[0] = xcalloc(n, sizeof(struct pt_reservoir));
    t->hist[1] = xcalloc(n, sizeof(struct pt_reservoir));
    t->emission = xcalloc(n, sizeof(vec3));
    t->temporal_flags = xcalloc(n, 1);
    if (p->reuse.temporal_reuse != TEMPORAL_BACKPROJECT) {
        t->splat = xmalloc(sizeof(*t->splat));
        pt_splat_buffers_init(t->splat, p->width, p->height, pt_splat_steps(p));
    }
    t->scene_diagonal = scene_diagonal(r->scene);
    struct shift_params sp; /* for the roughness table only: no camera needed */
    pt_shift_params(p, t->scene_diagonal, v3s(0.0f), &sp);
    t->material_rough = xcalloc((size_t)r->scene->num_materials + 1, 1);
    path_shift_rough_table(r->scene, &sp, t->material_rough);
}

void restir_pt_state_fini(struct restir_pt_state *t)
{
    screen_history_fini(&t->h);
    free(t->work);
    free(t->hist[0]);
    free(t->hist[1]);
    free(t->emission);
    free(t->temporal_flags);
    if (t->splat) {
        pt_splat_buffers_fini(t->splat);
        free(t->splat);
    }
    free(t->material_rough);
    free(t->boil);
    memset(t, 0, sizeof(*t));
}

/* pt.boiling_filter (BIASED): the temporal pass's outliers by target x W, per 8 x 8 group, emptied. */
static void pt_boiling_filter(struct restir_pt_state *t, const struct gbuffer *g, const struct render_params *p)
{
    const size_t n = (size_t)g->width * (size_t)g->height;
    if (!t->boil)
        t->boil = xmalloc(sizeof(float) * n);
    for (size_t i = 0; i < n; i++)
        t->boil[i] = pt_reservoir_has_sample(&t->work[i]) ? t->work[i].target * t->work[i].W : 0.0f;
    if (boiling_filter_mark(t->boil, g->width, g->height, restir_pt_boiling_of(p)->strength) == 0)
        return;
    for (size_t i = 0; i < n; i++)
        if (t->boil[i] < 0.0f)
            pt_reservoir_clear(&t->work[i], t->work[i].c);
}

void restir_pt_frame(struct renderer *r, struct restir_pt_state *t, const struct camera_view *view,
                     struct pt_reservoir *base, restir_pt_after_shade_fn after_shade, void *ctx,
                     struct frame_stats *st)
{
    struct screen_history *h = &t->h;
    const struct render_params *p = &r->p;
    struct gbuffer *g = screen_history_gbuffer(h), *prev_g = screen_history_prev_gbuffer(h);
    struct pt_reservoir *out = t->hist[h->cur], *prev_res = t->hist[1 - h->cur];
    struct pt_frame fr = {r->scene, p, {0}, view, &r->prev_view, r->frame};
    pt_shift_params(p, t->scene_diagonal, view->position, &fr.shift);
    fr.shift.rough = t->material_rough;
    RENDERER_TIMED(st, PASS_GBUFFER,
                   st->rays += gbuffer_pass(g, r->scene, view, h->has_history ? &r->prev_view : NULL, 0, p->seed,
                                            r->frame)); /* pixel centres: see pt_initial_pass */
    const size_t n = (size_t)g->width * (size_t)g->height;
    RENDERER_TIMED(st, PASS_INITIAL, st->rays += pt_initial_pass(&fr, g, t->work, t->emission);
                   st->nonfinite += nonfinite_discard_pt(t->work, n));
    if (base)
        memcpy(base, t->work, sizeof(*out) * n);
    memset(t->temporal_flags, 0, n);
    if (p->reuse.temporal && renderer_history_reusable(r, h->has_history))
        RENDERER_TIMED(st, PASS_TEMPORAL, {
            if (t->splat)
                st->rays += pt_temporal_splat_pass(&fr, g, prev_g, prev_res, t->work, t->splat, t->temporal_flags);
            else
                st->rays += pt_temporal_pass(&fr, g, prev_g, prev_res, t->work, &st->temporal_accepted,
                                             t->temporal_flags);
            st->nonfinite += nonfinite_discard_pt(t->work, n);
            if (restir_pt_boiling_of(p)->filter) /* off for the methods that do not list the block */
                pt_boiling_filter(t, g, p);
        });
    pt_temporal_counts(t->temporal_flags, (int)n, &st->temporal);
    if (t->splat) /* pixels that reused history: a candidate of either technique shifted in */
        st->temporal_accepted = temporal_counts_any_accepted(t->temporal_flags, (int)n);
    if (p->reuse.spatial && h->spmis) {
        struct spmis_frame *f = h->spmis;
        RENDERER_TIMED(st, PASS_CELLS, {
            pt_spmis_weights(&fr, g, t->work, f);
            spmis_cells_pass(f, p, g);
        });
        RENDERER_TIMED(st, PASS_CELL_SEARCH, spmis_search_pass(f, p, g, r->frame));
        RENDERER_TIMED(st, PASS_SPMIS_CANONICAL, st->rays += pt_spmis_canonical_pass(&fr, g, t->work, f));
        RENDERER_TIMED(st, PASS_SPMIS_REUSE, st->rays += pt_spmis_reuse_pass(&fr, g, t->work, f, out);
                       st->nonfinite += nonfinite_discard_pt(out, n));
    } else if (p->reuse.spatial) {
        RENDERER_TIMED(st, PASS_SELECT,
                       st->neighbors_selected =
                           spatial_select_pass(p, 1, g, r->frame, h->disk_offsets, h->neighbors));
        RENDERER_TIMED(st, PASS_SPATIAL, st->rays += pt_spatial_pass(&fr, g, h->neighbors, t->work, out);
                       st->nonfinite += nonfinite_discard_pt(out, n));
    } else {
        memcpy(out, t->work, sizeof(*out) * n);
    }
    RENDERER_TIMED(st, PASS_SHADE, pt_shade_pass(g, out, t->emission, r->image));
    if (after_shade)
        after_shade(r, ctx, t, &fr, out, st);
    if (p->reuse.history_temporal && p->reuse.spatial)
        memcpy(out, t->work, sizeof(*out) * n);
    st->valid_pixels = screen_history_count_valid(h);
    screen_history_end_frame(h, p);
}

static float pt_confidence(const void *reservoirs, int pixel)
{
    return ((const struct pt_reservoir *)reservoirs)[pixel].c;
}

void restir_pt_inspect(const struct restir_pt_state *t, struct renderer_inspect *out)
{
    screen_history_inspect(&t->h, out);
    out->reservoirs = t->hist[1 - t->h.cur];
    out->confidence = pt_confidence;
    out->temporal_flags = t->temporal_flags; /* a single buffer, not ping-pong: the last frame's */
}

void restir_pt_area_defaults(struct render_params *p)
{
    if (p->reuse.spatial_neighbors == 0)
        p->reuse.spatial_neighbors = 2;
}

static void *restir_pt_create(const struct renderer *r)
{
    struct restir_pt_state *t = xmalloc(sizeof(*t));
    restir_pt_state_init(t, r);
    return t;
}

static void restir_pt_destroy(void *state)
{
    restir_pt_state_fini(state);
    free(state);
}

static void restir_pt_render_frame(struct renderer *r, void *state, const struct camera_view *view,
                                   struct frame_stats *st)
{
    restir_pt_frame(r, state, view, NULL, NULL, NULL, st);
}

static void restir_pt_inspect_state(const void *state, struct renderer_inspect *out)
{
    restir_pt_inspect(state, out);
}

#define RESTIR_PT_CAPS (METHOD_HISTORY | METHOD_CAMERA_EFFECTS | METHOD_PATH_RESERVOIRS | METHOD_ANIMATED_EMITTERS)

const struct method method_restir_pt = {
    .name = "restir-pt",
    .description = "ReSTIR PT: path resampling, temporal and spatial path reuse by GRIS with shift mappings "
                   "(hybrid default) and sub-pixel reservoirs",
    .caps = RESTIR_PT_CAPS | METHOD_SELECTION_STUDY,
    .blocks = (const struct param_block *const[]){RESTIR_PT_BLOCKS, &params_block_permutation, &restir_pt_boiling_block,
                                                  NULL},
    .passes = (const char *const[]){RESTIR_PT_PASSES, NULL},
    .variants = "spatial.reuse=spmis spatial.select=compat-binary shift=reconnection temporal.permutation=on pt.boiling_filter=on",
    .viewer_order = 2,
    .create = restir_pt_create,
    .destroy = restir_pt_destroy,
    .render_frame = restir_pt_render_frame,
    .inspect = restir_pt_inspect_state,
};

const struct method method_area_restir = {
    .name = "area-restir",
    .description = "Area ReSTIR (002 B.3): restir-pt with 1 initial candidate and 2 spatial neighbors, "
                   "sub-pixel reservoirs",
    .caps = RESTIR_PT_CAPS,
    .blocks = (const struct param_block *const[]){RESTIR_PT_BLOCKS, &params_block_permutation, &restir_pt_boiling_block,
                                                  NULL},
    .passes = (const char *const[]){RESTIR_PT_PASSES, NULL},
    .defaults = restir_pt_area_defaults,
    .create = restir_pt_create,
    .destroy = restir_pt_destroy,
    .render_frame = restir_pt_render_frame,
    .inspect = restir_pt_inspect_state,
};
