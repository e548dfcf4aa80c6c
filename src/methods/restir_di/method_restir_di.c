/* method_restir_di.c: `restir-di` (ReSTIR DI, Bitterli et al. 2020 / 001: initial RIS, temporal and
 * spatial reuse by GRIS) and `ris-di` (the same initial RIS without reuse, 001's baseline), as
 * passes over DI reservoirs and the shared screen history. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/screen_history.h"
#include "methods/restir_di/di_gradient.h"
#include "methods/restir_di/di_sample.h"
#include "methods/restir_di/light_pool.h"
#include "methods/restir_di/regir.h"
#include "render/boiling_filter.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"
#include "scene/scene_rt.h"
#include "shading/lights.h"
#include "render/nonfinite.h"
#include "methods/restir_di/restir_di.h"
#include "render/reuse_cells.h"
#include "render/spatial_select.h"
#include "methods/restir_di/di_settings.h"

struct restir_di_state {
    struct screen_history h;
    struct di_reservoir *work;    /* initial, then temporal outputs */
    struct di_reservoir *hist[2]; /* spatial outputs: this frame's and the previous frame's */
    struct light_pool lights;     /* this frame's light candidates (initial RIS, di.initial=pool) */
    struct regir_grid *regir;     /* or this frame's grid of light reservoirs (di.initial=regir) */
    float *boil;                  /* di.boiling_filter's weights (allocated by its first frame) */
    float *grad, *grad_tmp;       /* denoise.svgf.temporal_gradient: lambda per pixel, and its scratch */
};

static void *restir_di_create(const struct renderer *r)
{
    const struct render_params *p = &r->p;
    const size_t n = (size_t)p->width * (size_t)p->height;
    struct restir_di_state *d = xcalloc(1, sizeof(*d));
    screen_history_init(&d->h, p, 1, 0); /* the DI passes read the shading points */
    d->work = xcalloc(n, sizeof(struct di_reservoir));
    d->hist[0] = xcalloc(n, sizeof(struct di_reservoir));
    d->hist[1] = xcalloc(n, sizeof(struct di_reservoir));
    const struct di_settings *ds = di_settings_of(p);
    if (di_initial_uses_regir(ds->initial, r->scene->num_emitters)) {
        d->regir = xmalloc(sizeof(*d->regir));
        regir_init(d->regir, r->scene, ds);
    }
    if (!d->regir || ds->initial == DI_INITIAL_AUTO) /* auto takes the pool where the grid does not pay */
        light_pool_init(&d->lights, ds->light_candidates);
    return d;
}

static void restir_di_destroy(void *state)
{
    struct restir_di_state *d = state;
    screen_history_fini(&d->h);
    light_pool_fini(&d->lights);
    if (d->regir)
        regir_fini(d->regir);
    free(d->regir);
    free(d->work);
    free(d->hist[0]);
    free(d->hist[1]);
    free(d->boil);
    free(d->grad);
    free(d->grad_tmp);
    free(d);
}

/* Animated emitters: the previous frame's samples carry this frame's radiance into the temporal
 * pass, where the current domain evaluates them, while their cached targets stay the previous
 * frame's (the previous domain's p_hat at its own sample); the temporal merge evaluates the previous
 * domain's target at the current sample with that emitter's previous strength (merge_begin's
 * prev_scale). Every domain then measures with its own frame's lights, as GRIS requires: exact across
 * a switch (render.animated_unbiased). The chosen sample leaves with this frame's radiance and target. */
static void di_relight(const struct scene *s, struct di_reservoir *prev, size_t n)
{
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        struct di_sample *y = &prev[i].y;
        if (y->tri < 0 || y->tri == DI_ENV_TRI) /* the environment does not change */
            continue;
        struct light_sample ls;
        lights_point(s, y->tri, y->b1, y->b2, &ls);
        y->Le = ls.Le;
        y->p = ls.p; /* where the emitter is now: a light sample is its triangle and barycentrics, */
        y->n = ls.n; /* which a rigid motion maps to the same point of the moved triangle (Jacobian 1) */
    }
}

/* di.boiling_filter (BIASED): the temporal pass's outliers by target x W (the pixel's unshadowed estimate:
 * W alone is per area for a light point, per solid angle for the sky, and grows with distance), per 8 x 8
 * group, emptied. */
static void di_boiling_filter(struct restir_di_state *d, const struct gbuffer *g, const struct render_params *p)
{
    const size_t n = (size_t)g->width * (size_t)g->height;
    if (!d->boil)
        d->boil = xmalloc(sizeof(float) * n);
    for (size_t i = 0; i < n; i++)
        d->boil[i] = d->work[i].y.tri >= 0 ? d->work[i].target * d->work[i].W : 0.0f; /* DI_ENV_TRI too */
    if (boiling_filter_mark(d->boil, g->width, g->height, di_reuse_settings_of(p)->boiling_strength) == 0)
        return;
    for (size_t i = 0; i < n; i++)
        if (d->boil[i] < 0.0f)
            di_reservoir_clear(&d->work[i], d->work[i].c);
}

static void restir_di_render_frame(struct renderer *r, void *state, const struct camera_view *view,
                                   struct frame_stats *st)
{
    struct restir_di_state *d = state;
    struct screen_history *h = &d->h;
    const struct scene *s = r->scene;
    const struct render_params *p = &r->p;
    struct gbuffer *g = screen_history_gbuffer(h), *prev_g = screen_history_prev_gbuffer(h);
    struct di_reservoir *out = d->hist[h->cur], *prev_res = d->hist[1 - h->cur];
    const int frame = r->frame;
    const size_t n = (size_t)g->width * (size_t)g->height;
    RENDERER_TIMED(st, PASS_GBUFFER,
                   st->rays += gbuffer_pass(g, s, view, h->has_history ? &r->prev_view : NULL, p->jitter, p->seed,
                                            frame));
    RENDERER_TIMED(st, PASS_INITIAL, {
        const struct di_settings *ds = di_settings_of(p);
        const struct regir_grid *rg = NULL;
        if (d->regir) {
            regir_build(d->regir, g, ds);
            if (ds->initial == DI_INITIAL_REGIR || regir_fill_share(d->regir, ds) <= DI_AUTO_REGIR_MAX_FILL_SHARE) {
                regir_fill(d->regir, s, ds, p->seed, frame);
                rg = d->regir;
            }
        }
        if (!rg && ds->initial != DI_INITIAL_BVH) /* bvh: each pixel draws its own */
            light_pool_fill(&d->lights, s, p->seed, frame);
        st->rays += di_initial_pass(s, &d->lights, rg, p, frame, g, d->work);
        st->nonfinite += nonfinite_discard_di(d->work, n);
    });
    const int confidence = di_reuse_settings_of(p)->gradient_confidence;
    if ((p->denoise.method == DENOISE_SVGF && p->denoise.svgf_temporal_gradient) || confidence) { /* A-SVGF */
        if (!d->grad) {
            d->grad = xmalloc(sizeof(float) * n);
            d->grad_tmp = xmalloc(4 * sizeof(float) * n);
        }
        di_temporal_gradient(s, g, prev_g, d->work, h->has_history ? prev_res : NULL, frame, d->grad, d->grad_tmp);
    }
    /* emitters that moved: the previous frame's targets need its geometry (scene_occluded_previous_batch) */
    const int moved = r->lights_moved;
    const int keep = !moved || (scene_can_trace_previous(s) && di_reuse_settings_of(p)->moved_confidence > 0.0f);
    if (p->reuse.temporal && h->has_history && keep)
        RENDERER_TIMED(st, PASS_TEMPORAL, if (scene_is_animated(s)) di_relight(s, prev_res, n);
                       if (moved) scene_motion_pose_previous(s, (float)r->prev_frame);
                       st->temporal_accepted =
                           di_temporal_pass(s, p, frame, (float)r->prev_frame, moved, g, prev_g, prev_res,
                                            confidence ? d->grad : NULL, d->work, &st->rays);
                       st->nonfinite += nonfinite_discard_di(d->work, n);
                       if (di_reuse_settings_of(p)->boiling_filter) di_boiling_filter(d, g, p));
    if (p->reuse.spatial && h->spmis) {
        struct spmis_frame *f = h->spmis;
        RENDERER_TIMED(st, PASS_CELLS, {
            di_spmis_weights(p, g, d->work, f);
            spmis_cells_pass(f, p, g);
        });
        RENDERER_TIMED(st, PASS_CELL_SEARCH, spmis_search_pass(f, p, g, frame));
        RENDERER_TIMED(st, PASS_SPMIS_CANONICAL, st->rays += di_spmis_canonical_pass(s, p, frame, g, d->work, f));
        RENDERER_TIMED(st, PASS_SPMIS_REUSE, st->rays += di_spmis_reuse_pass(s, p, frame, g, d->work, f, out);
                       st->nonfinite += nonfinite_discard_di(out, n));
    } else if (p->reuse.spatial) {
        RENDERER_TIMED(st, PASS_SELECT,
                       st->neighbors_selected =
                           spatial_select_pass(p, 0, g, frame, h->disk_offsets, h->neighbors));
        RENDERER_TIMED(st, PASS_SPATIAL, st->rays += di_spatial_pass(s, p, frame, g, h->neighbors, d->work, out);
                       st->nonfinite += nonfinite_discard_di(out, n));
    } else {
        memcpy(out, d->work, sizeof(*out) * n);
    }
    RENDERER_TIMED(st, PASS_SHADE, st->rays += di_shade_pass(s, p, g, out, r->image));
    if (p->reuse.history_temporal && p->reuse.spatial)
        memcpy(out, d->work, sizeof(*out) * n);
    st->valid_pixels = screen_history_count_valid(h);
    screen_history_end_frame(h, p);
}

static float di_confidence(const void *reservoirs, int pixel)
{
    return ((const struct di_reservoir *)reservoirs)[pixel].c;
}

static void restir_di_inspect(const void *state, struct renderer_inspect *out)
{
    const struct restir_di_state *d = state;
    screen_history_inspect(&d->h, out);
    out->reservoirs = d->hist[1 - d->h.cur];
    out->temporal_gradient = d->grad;
    out->confidence = di_confidence;
}

/* ReGIR's cells hold emitter samples: a scene without emitters has nothing to put in them. */
static int restir_di_check(const struct render_params *p, const struct scene *s, char *msg)
{
    if (s && di_settings_of(p)->initial == DI_INITIAL_REGIR && s->num_emitters < 1) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "di.initial=regir: the scene has no emissive triangles for the light grid's cells to hold "
                 "(use di.initial=pool)");
        return -1;
    }
    return 0;
}

/* 001's no-reuse baseline: the initial RIS alone. */
static void ris_di_defaults(struct render_params *p)
{
    p->reuse.temporal = 0;
    p->reuse.spatial = 0;
}

/* Reuse, neighbor selection and SPMIS, and the DI candidates. */
#define RESTIR_DI_BLOCKS                                                                                          \
    &di_block, &di_reuse_block, &params_block_reuse, &params_block_permutation, &params_block_spmis,              \
        &params_block_depth

/* The passes restir_di_render_frame times (struct method.passes). */
static const char *const restir_di_passes[] = {"gbuffer", "initial",     "temporal",        "select",      "spatial",
                                               "cells",   "cell_search", "spmis_canonical", "spmis_reuse", "shade",
                                               NULL};

const struct method method_restir_di = {
    .name = "restir-di",
    .description = "ReSTIR DI: initial RIS, temporal and spatial reuse by GRIS (pairwise MIS default)",
    .caps = METHOD_DIRECT_ONLY | METHOD_HISTORY | METHOD_SELECTION_STUDY | METHOD_ANIMATED_EMITTERS |
            METHOD_TEMPORAL_GRADIENT,
    .viewer_order = 1,
    .blocks = (const struct param_block *const[]){RESTIR_DI_BLOCKS, NULL},
    .passes = restir_di_passes,
    .variants = "spatial.reuse=spmis spatial.preset=fast mis=balance temporal.permutation=on di.boiling_filter=on",
    .roles = "demo",
    .streams = (const char *const[]){REGIR_STREAM, NULL},
    .check = restir_di_check,
    .create = restir_di_create,
    .destroy = restir_di_destroy,
    .render_frame = restir_di_render_frame,
    .inspect = restir_di_inspect,
};

const struct method method_ris_di = {
    .name = "ris-di",
    .description = "direct lighting by initial RIS only, no reuse (the no-reuse baseline of 001)",
    .caps = METHOD_DIRECT_ONLY | METHOD_HISTORY | METHOD_ANIMATED_EMITTERS,
    .viewer_order = 4,
    .blocks = (const struct param_block *const[]){&di_block, &params_block_depth, NULL},
    .passes = restir_di_passes,
    .defaults = ris_di_defaults, /* its passes are restir-di's: REGIR_STREAM is listed there */
    .check = restir_di_check,
    .create = restir_di_create,
    .destroy = restir_di_destroy,
    .render_frame = restir_di_render_frame,
    .inspect = restir_di_inspect,
};
