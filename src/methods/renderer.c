/* renderer.c: runs one frame of a method as a sequence of passes, keeps the ping-pong state
 * between frames, and times each pass. Must never read or write files. */
#include "methods/renderer.h"

#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/lowdisc.h"
#include "core/simd.h"
#include "gradient/gpt.h"
#include "gradient/grad_after.h"
#include "gradient/grad_common.h"
#include "gradient/grad_frame.h"
#include "gradient/grestir.h"
#include "render/nonfinite.h"
#include "render/pt.h"
#include "render/pt_splat.h"
#include "render/restir_di.h"
#include "render/restir_pt.h"
#include "render/reuse_cells.h"
#include "render/spatial_select.h"

const char *const pass_names[PASS_COUNT] = {"gbuffer", "initial",         "temporal",    "select",
                                            "spatial", "cells",           "cell_search", "spmis_canonical",
                                            "spmis_reuse", "shade", "pt", "gpt", "grad_initial",
                                            "grad_temporal", "grad_select", "grad_spatial", "grad_shade",
                                            "recon_l2", "recon_l1"};

void renderer_init(struct renderer *r, const struct scene *s, enum method_id method, const struct render_params *p)
{
    memset(r, 0, sizeof(*r));
    r->scene = s;
    r->p = *p;
    r->method = method;
    renderer_method_params(method, &r->p);
    p = &r->p;
    size_t n = (size_t)p->width * (size_t)p->height;
    r->image = xcalloc(3 * n, sizeof(float));
    const int di = method == METHOD_RIS_DI || method == METHOD_RESTIR_DI; /* DI reservoirs, pool, shading points */
    if (method_has_gbuffer(method)) {
        gbuffer_init(&r->gb[0], p->width, p->height, di);
        gbuffer_init(&r->gb[1], p->width, p->height, di);
        r->neighbors = xcalloc(n * SPATIAL_MAX_NEIGHBORS, sizeof(int));
        r->disk_offsets = xmalloc(sizeof(float) * 2 * R2_DISK_OFFSETS);
        r2_disk_offsets(R2_DISK_OFFSETS, r->disk_offsets);
        r->age[0] = xcalloc(n, 1);
        r->age[1] = xcalloc(n, 1);
        if (r->p.spatial && r->p.spatial_reuse == REUSE_SPMIS) {
            r->spmis = xmalloc(sizeof(*r->spmis));
            spmis_frame_init(r->spmis, p);
        }
    }
    if (di) {
        r->work = xcalloc(n, sizeof(struct di_reservoir));
        r->hist[0] = xcalloc(n, sizeof(struct di_reservoir));
        r->hist[1] = xcalloc(n, sizeof(struct di_reservoir));
        light_pool_init(&r->lights, r->p.light_candidates);
    }
    if (method_runs_restir_pt(method)) {
        r->pt_work = xcalloc(n, sizeof(struct pt_reservoir));
        r->pt_hist[0] = xcalloc(n, sizeof(struct pt_reservoir));
        r->pt_hist[1] = xcalloc(n, sizeof(struct pt_reservoir));
        r->pt_emission = xcalloc(n, sizeof(vec3));
        r->temporal_flags = xcalloc(n, 1);
        if (p->temporal_reuse != TEMPORAL_BACKPROJECT) {
            r->splat = xmalloc(sizeof(*r->splat));
            pt_splat_buffers_init(r->splat, p->width, p->height, pt_splat_steps(p));
        }
    }
    if (method_table[method].gradient) {
        r->grad = xmalloc(sizeof(*r->grad));
        grad_frame_init(r->grad, p, method == METHOD_GRESTIR_PT);
    }
    if (method_runs_restir_pt(method) || method == METHOD_GPT) {
        r->scene_diagonal = scene_diagonal(s);
        struct shift_params sp;
        pt_shift_params(p, r->scene_diagonal, &sp);
        r->material_rough = xcalloc((size_t)s->num_materials + 1, 1);
        path_shift_rough_table(s, &sp, r->material_rough);
    }
    if (p->threads > 0)
        omp_set_num_threads(p->threads);
}

void renderer_fini(struct renderer *r)
{
    if (r->grad) {
        grad_frame_fini(r->grad);
        free(r->grad);
    }
    if (method_has_gbuffer(r->method)) {
        gbuffer_fini(&r->gb[0]);
        gbuffer_fini(&r->gb[1]);
    }
    light_pool_fini(&r->lights); /* zeroed by renderer_init for the other methods: frees nothing */
    free(r->work);
    free(r->hist[0]);
    free(r->hist[1]);
    free(r->pt_work);
    free(r->pt_hist[0]);
    free(r->pt_hist[1]);
    free(r->pt_emission);
    free(r->temporal_flags);
    if (r->splat) {
        pt_splat_buffers_fini(r->splat);
        free(r->splat);
    }
    free(r->material_rough);
    free(r->neighbors);
    free(r->disk_offsets);
    if (r->spmis) {
        spmis_frame_fini(r->spmis);
        free(r->spmis);
    }
    free(r->age[0]);
    free(r->age[1]);
    free(r->image);
    memset(r, 0, sizeof(*r));
}

void renderer_reset(struct renderer *r) { r->has_history = 0; }

#define TIMED(st, pass, stmt)                                                                  \
    do {                                                                                       \
        double t0_ = omp_get_wtime();                                                          \
        stmt;                                                                                  \
        (st)->ms[pass] += 1e3 * (omp_get_wtime() - t0_);                                       \
    } while (0)

static long long count_valid(const struct gbuffer *g)
{
    long long valid = 0;
    for (int i = 0; i < g->width * g->height; i++)
        valid += g->valid[i];
    return valid;
}

static void render_restir_di(struct renderer *r, const struct camera_view *view, struct frame_stats *st)
{
    const struct scene *s = r->scene;
    const struct render_params *p = &r->p;
    struct gbuffer *g = &r->gb[r->cur], *prev_g = &r->gb[1 - r->cur];
    struct di_reservoir *out = r->hist[r->cur], *prev_res = r->hist[1 - r->cur];
    const int frame = r->frame;
    const size_t n = (size_t)g->width * (size_t)g->height;
    TIMED(st, PASS_GBUFFER,
          st->rays += gbuffer_pass(g, s, view, r->has_history ? &r->prev_view : NULL, p->jitter, p->seed, frame));
    TIMED(st, PASS_INITIAL, {
        light_pool_fill(&r->lights, s, p->seed, frame);
        st->rays += di_initial_pass(s, &r->lights, p, frame, g, r->work);
        st->nonfinite += nonfinite_discard_di(r->work, n);
    });
    if (p->temporal && r->has_history)
        TIMED(st, PASS_TEMPORAL,
              st->temporal_accepted = di_temporal_pass(s, p, frame, g, prev_g, prev_res, r->work, &st->rays);
              st->nonfinite += nonfinite_discard_di(r->work, n));
    if (p->spatial && r->spmis) {
        struct spmis_frame *f = r->spmis;
        TIMED(st, PASS_CELLS, {
            di_spmis_weights(p, g, r->work, f);
            spmis_cells_pass(f, p, g);
        });
        TIMED(st, PASS_CELL_SEARCH, spmis_search_pass(f, p, g, frame));
        TIMED(st, PASS_SPMIS_CANONICAL, st->rays += di_spmis_canonical_pass(s, p, frame, g, r->work, f));
        TIMED(st, PASS_SPMIS_REUSE, st->rays += di_spmis_reuse_pass(s, p, frame, g, r->work, f, out);
              st->nonfinite += nonfinite_discard_di(out, n));
    } else if (p->spatial) {
        TIMED(st, PASS_SELECT,
              st->neighbors_selected = spatial_select_pass(p, 0, g, frame, r->disk_offsets, r->neighbors));
        TIMED(st, PASS_SPATIAL, st->rays += di_spatial_pass(s, p, frame, g, r->neighbors, r->work, out);
              st->nonfinite += nonfinite_discard_di(out, n));
    } else {
        memcpy(out, r->work, sizeof(*out) * (size_t)g->width * (size_t)g->height);
    }
    TIMED(st, PASS_SHADE, st->rays += di_shade_pass(s, p, g, out, r->image));
    if (p->history_temporal && p->spatial)
        memcpy(out, r->work, sizeof(*out) * (size_t)g->width * (size_t)g->height);
    st->valid_pixels = count_valid(g);
}

/* The gradient passes of grad-after-restir and grestir-pt after their area-ReSTIR primal
 * (r->image), from the final primal reservoirs res. */
static void gradient_passes(struct renderer *r, const struct pt_frame *fr, const struct gbuffer *g,
                            const struct gbuffer *prev_g, const struct pt_reservoir *res, struct frame_stats *st)
{
    const struct render_params *p = &r->p;
    struct grad_frame *gf = r->grad;
    const size_t n = (size_t)g->width * (size_t)g->height;
    memcpy(gf->primal, r->image, sizeof(float) * 3 * n);
    grad_frame_begin(gf);
    if (r->method == METHOD_GRAD_AFTER_RESTIR) {
        TIMED(st, PASS_GRAD_INITIAL, st->rays += grad_after_pass(fr, res, gf->os));
    } else {
        struct grestir_state *gs = gf->grestir;
        long long accepted = 0;
        TIMED(st, PASS_GRAD_INITIAL, {
            if (!p->grad_base) {
                /* independent initial paths: the same sampler on streams of another seed */
                struct render_params q = *p;
                q.seed = p->seed ^ 0x6772616442617365ull;
                struct pt_frame fb = *fr;
                fb.p = &q;
                st->rays += pt_initial_pass(&fb, g, gf->base, (vec3 *)(void *)gf->emission);
            }
            st->rays += grestir_initial_pass(fr, g, gf->base, gs);
        });
        if (p->temporal && p->grad_temporal && r->has_history)
            TIMED(st, PASS_GRAD_TEMPORAL,
                  st->rays += grestir_temporal_pass(fr, g, prev_g, gs, 1 - r->cur, &accepted));
        TIMED(st, PASS_GRAD_SELECT, grestir_select_pass(fr, g, gs));
        TIMED(st, PASS_GRAD_SPATIAL, st->rays += grestir_spatial_pass(fr, g, gs, r->cur));
        st->edge_pairs = gs->edge_pairs;
        st->pair_neighbors = gs->neighbors_found;
        TIMED(st, PASS_GRAD_SHADE, grestir_shade_pass(p, gs, r->cur, gf->dx, gf->dy));
        if (p->history_temporal && p->grad_spatial != GRAD_SPATIAL_OFF)
            for (int d = 0; d < GRAD_PAIR_DIRS; d++)
                for (int s = 0; s < GRAD_SIGNS; s++)
                    memcpy(gs->hist[r->cur][d][s], gs->work[d][s], sizeof(struct pair_reservoir) * n);
    }
    /* Emission seen directly (restir-pt's paths start after the primary hit): the differences of
     * the primal's own estimate of it (grad_add_image_differences). */
    TIMED(st, PASS_GRAD_SHADE, {
        grad_combine(g->width, g->height, gf->os, gf->dx, gf->dy);
        grad_add_image_differences(g->width, g->height, &r->pt_emission[0].x, gf->dx, gf->dy);
    });
}

_Static_assert(sizeof(vec3) == 3 * sizeof(float), "pt_emission is read as RGB floats");

void renderer_reconstruct(struct renderer *r, struct frame_stats *st)
{
    struct grad_frame *gf = r->grad;
    const size_t n = (size_t)gf->width * (size_t)gf->height;
    TIMED(st, PASS_RECON_L2, grad_reconstruct_l2(&r->p, gf));
    st->l2_residual = gf->l2_stats.residual;
    if (r->p.recon != RECON_L2) {
        TIMED(st, PASS_RECON_L1, grad_reconstruct_l1(&r->p, gf));
        st->l1_residual = gf->l1_stats.residual;
    }
    memcpy(r->image, r->p.recon == RECON_L1 ? gf->l1 : gf->l2, sizeof(float) * 3 * n);
}

static void render_gpt(struct renderer *r, const struct camera_view *view, struct frame_stats *st)
{
    struct grad_frame *gf = r->grad;
    struct shift_params sp;
    pt_shift_params(&r->p, r->scene_diagonal, &sp);
    sp.rough = r->material_rough;
    grad_frame_begin(gf);
    TIMED(st, PASS_GPT, {
        st->rays += gpt_pass(r->scene, &sp, view, &r->p, r->frame, gf->primal, gf->emission, gf->os);
        grad_combine(gf->width, gf->height, gf->os, gf->dx, gf->dy);
        grad_add_image_differences(gf->width, gf->height, gf->emission, gf->dx, gf->dy);
    });
}

static void render_restir_pt(struct renderer *r, const struct camera_view *view, struct frame_stats *st)
{
    const struct render_params *p = &r->p;
    struct gbuffer *g = &r->gb[r->cur], *prev_g = &r->gb[1 - r->cur];
    struct pt_reservoir *out = r->pt_hist[r->cur], *prev_res = r->pt_hist[1 - r->cur];
    struct pt_frame fr = {r->scene, p, {0}, view, &r->prev_view, r->frame};
    pt_shift_params(p, r->scene_diagonal, &fr.shift);
    fr.shift.rough = r->material_rough;
    TIMED(st, PASS_GBUFFER,
          st->rays += gbuffer_pass(g, r->scene, view, r->has_history ? &r->prev_view : NULL, 0, p->seed,
                                   r->frame)); /* pixel centres: see pt_initial_pass */
    const size_t n = (size_t)g->width * (size_t)g->height;
    TIMED(st, PASS_INITIAL, st->rays += pt_initial_pass(&fr, g, r->pt_work, r->pt_emission);
          st->nonfinite += nonfinite_discard_pt(r->pt_work, n));
    if (r->grad && r->grad->base && p->grad_base) /* grestir-pt, grad.base=shared: the pairs' candidates */
        memcpy(r->grad->base, r->pt_work, sizeof(*out) * (size_t)g->width * (size_t)g->height);
    memset(r->temporal_flags, 0, n);
    if (p->temporal && r->has_history)
        TIMED(st, PASS_TEMPORAL, {
            if (r->splat)
                st->rays += pt_temporal_splat_pass(&fr, g, prev_g, prev_res, r->pt_work, r->splat, r->temporal_flags);
            else
                st->rays += pt_temporal_pass(&fr, g, prev_g, prev_res, r->pt_work, &st->temporal_accepted,
                                             r->temporal_flags);
            st->nonfinite += nonfinite_discard_pt(r->pt_work, n);
        });
    pt_temporal_counts(r->temporal_flags, (int)n, &st->temporal);
    if (r->splat) /* pixels that reused history: a candidate of either technique shifted in */
        st->temporal_accepted = temporal_counts_any_accepted(r->temporal_flags, (int)n);
    if (p->spatial && r->spmis) {
        struct spmis_frame *f = r->spmis;
        TIMED(st, PASS_CELLS, {
            pt_spmis_weights(&fr, g, r->pt_work, f);
            spmis_cells_pass(f, p, g);
        });
        TIMED(st, PASS_CELL_SEARCH, spmis_search_pass(f, p, g, r->frame));
        TIMED(st, PASS_SPMIS_CANONICAL, st->rays += pt_spmis_canonical_pass(&fr, g, r->pt_work, f));
        TIMED(st, PASS_SPMIS_REUSE, st->rays += pt_spmis_reuse_pass(&fr, g, r->pt_work, f, out);
              st->nonfinite += nonfinite_discard_pt(out, n));
    } else if (p->spatial) {
        TIMED(st, PASS_SELECT,
              st->neighbors_selected = spatial_select_pass(p, 1, g, r->frame, r->disk_offsets, r->neighbors));
        TIMED(st, PASS_SPATIAL, st->rays += pt_spatial_pass(&fr, g, r->neighbors, r->pt_work, out);
              st->nonfinite += nonfinite_discard_pt(out, n));
    } else {
        memcpy(out, r->pt_work, sizeof(*out) * (size_t)g->width * (size_t)g->height);
    }
    TIMED(st, PASS_SHADE, pt_shade_pass(g, out, r->pt_emission, r->image));
    if (r->grad)
        gradient_passes(r, &fr, g, prev_g, out, st);
    if (p->history_temporal && p->spatial)
        memcpy(out, r->pt_work, sizeof(*out) * (size_t)g->width * (size_t)g->height);
    st->valid_pixels = count_valid(g);
}

/* Follows each pixel's history chain by the same G-buffer validation as temporal reuse. */
static void update_age(struct renderer *r)
{
    const struct gbuffer *g = &r->gb[r->cur], *prev_g = &r->gb[1 - r->cur];
    const unsigned char *prev = r->age[1 - r->cur];
    unsigned char *age = r->age[r->cur];
    const int n = g->width * g->height;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        int q = r->has_history ? gbuffer_history_pixel(g, i, prev_g, r->p.temporal_normal, r->p.temporal_plane) : -1;
        age[i] = q < 0 ? 0 : (unsigned char)(prev[q] < 255 ? prev[q] + 1 : 255);
    }
}

long long renderer_disoccluded(const struct renderer *r, int frames, unsigned char *mask)
{
    const struct gbuffer *g = &r->gb[1 - r->cur]; /* the last frame's (cur was flipped after it) */
    const unsigned char *age = r->age[1 - r->cur];
    long long marked = 0;
    for (int i = 0; i < g->width * g->height; i++) {
        mask[i] = g->valid[i] && age[i] < frames;
        marked += mask[i];
    }
    return marked;
}

void renderer_camera_view(const struct render_params *p, const struct camera *cam, const struct camera *open,
                          struct camera_view *v)
{
    struct camera c = *cam, o = open ? *open : *cam;
    if (p->camera_aperture > 0.0f)
        c.aperture = o.aperture = p->camera_aperture;
    if (p->camera_focus > 0.0f)
        c.focus_distance = o.focus_distance = p->camera_focus;
    camera_view_init(v, &c, p->width, p->height);
    if (p->camera_shutter > 0.0f)
        camera_view_set_shutter(v, &o, p->camera_shutter);
}

void renderer_set_shutter_open(struct renderer *r, const struct camera *open)
{
    r->prev_cam = *open;
    r->has_prev_cam = 1;
}

void renderer_render(struct renderer *r, int frame, const struct camera *cam, struct frame_stats *st)
{
    memset(st, 0, sizeof(*st));
    struct camera_view view;
    renderer_camera_view(&r->p, cam, r->has_prev_cam ? &r->prev_cam : NULL, &view);
    r->prev_cam = *cam;
    r->has_prev_cam = 1;
    scene_ray_streams(r->scene, r->p.ray_streams); /* the scene may be shared with other renderers */
    simd_allow(r->p.simd);                         /* process-wide */
    double t0 = omp_get_wtime();
    r->frame = frame;
    if (r->method == METHOD_PT) {
        TIMED(st, PASS_PT, st->rays += pt_pass(r->scene, &view, &r->p, frame, r->p.spp, r->image));
    } else if (r->method == METHOD_GPT) {
        render_gpt(r, &view, st);
    } else {
        if (method_runs_restir_pt(r->method))
            render_restir_pt(r, &view, st);
        else
            render_restir_di(r, &view, st);
        update_age(r);
        r->cur = 1 - r->cur;
        r->has_history = 1;
    }
    if (r->grad)
        renderer_reconstruct(r, st);
    /* the frame's radiance (every method, reconstructions included) */
    st->nonfinite += nonfinite_discard_rgb(r->image, (size_t)r->p.width * (size_t)r->p.height);
    r->prev_view = view;
    st->ms_total = 1e3 * (omp_get_wtime() - t0);
}
