/* pt_splat.c: reservoir splatting for temporal path reuse (see pt_splat.h; Liu et al. 2025).
 * Every previous reservoir is forward-projected by its primary hit, once per shutter-time
 * stratum; the landings are bucketed per current pixel in a fixed order (so the image does not
 * depend on the thread count); each pixel then resamples its canonical reservoir, the paths that
 * landed in it and, for temporal.reuse=both, its backprojected history, with generalized balance
 * weights over the techniques that can produce each path (docs/RESTIR_PT.md).
 * Must never allocate per pixel. */
#include "methods/restir_pt/pt_splat.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "render/tiles.h"
#include "restir/gris.h"

void pt_splat_buffers_init(struct pt_splat_buffers *b, int width, int height, int steps)
{
    const size_t n = (size_t)width * (size_t)height;
    b->pixels = (int)n;
    b->steps = steps;
    b->land = xmalloc(sizeof(int) * n * (size_t)steps);
    b->start = xmalloc(sizeof(int) * (n + 1));
    b->entries = xmalloc(sizeof(int) * n * (size_t)steps);
}

void pt_splat_buffers_fini(struct pt_splat_buffers *b)
{
    free(b->land);
    free(b->start);
    free(b->entries);
    memset(b, 0, sizeof(*b));
}

int pt_splat_steps(const struct render_params *p)
{
    return p->camera_shutter > 0.0f ? p->reuse.temporal_splat_steps : 1;
}

/* The shutter-time map of stratum k of K: t -> (k + t) / K, onto [k/K, (k+1)/K) (|dt'/dt| = 1/K).
 * With K = 1 the time is kept. */
static float stratum_time(float t, int k, int K) { return K == 1 ? t : ((float)k + t) / (float)K; }

/* Its inverse at a current time t': the stratum and the previous time. */
static float stratum_inverse(float t, int K, int *k)
{
    if (K == 1) {
        *k = 0;
        return t;
    }
    float s = t * (float)K;
    int j = (int)s;
    j = j < 0 ? 0 : (j >= K ? K - 1 : j);
    *k = j;
    float prev = s - (float)j;
    return prev < 1.0f ? (prev > 0.0f ? prev : 0.0f) : 0x1.fffffep-1f;
}

/* ---- landing and bucketing ---------------------------------------------------------------- */

static void land_pass(const struct pt_frame *fr, const struct pt_reservoir *prev_res, struct pt_splat_buffers *b)
{
    const int n = b->pixels, K = b->steps;
#pragma omp parallel for schedule(static)
    for (int q = 0; q < n; q++) {
        for (int k = 0; k < K; k++) {
            int *land = &b->land[(size_t)q * K + k];
            *land = -1;
            const struct pt_reservoir *r = &prev_res[q];
            float px, py;
            if (pt_reservoir_has_sample(r) &&
                path_splat_position(&r->y, fr->view, stratum_time(r->y.time, k, K), &px, &py))
                *land = (int)py * fr->view->width + (int)px;
        }
    }
}

/* Counting sort of the landings by pixel, in (previous pixel, step) order within each bucket. */
static void bucket_pass(struct pt_splat_buffers *b)
{
    const int n = b->pixels;
    const size_t entries = (size_t)n * (size_t)b->steps;
    memset(b->start, 0, sizeof(int) * ((size_t)n + 1));
    for (size_t e = 0; e < entries; e++)
        if (b->land[e] >= 0)
            b->start[b->land[e] + 1]++;
    for (int i = 0; i < n; i++)
        b->start[i + 1] += b->start[i];
    /* fill with a moving cursor per bucket: start[i] walks to start[i+1], then is shifted back */
    for (size_t e = 0; e < entries; e++)
        if (b->land[e] >= 0)
            b->entries[b->start[b->land[e]]++] = (int)e;
    for (int i = n; i > 0; i--)
        b->start[i] = b->start[i - 1];
    b->start[0] = 0;
}

/* ---- the merge ---------------------------------------------------------------------------- */

/* The techniques that can propose a path of pixel p: the canonical sample, the splat of the
 * previous pixel its primary hit back-projects to, and (both) the backprojected pixel. */
enum { TECH_CANONICAL = 0, TECH_SPLAT, TECH_BACKPROJECT, TECH_COUNT };

struct pixel_merge {
    const struct pt_frame *fr;
    const struct pt_reservoir *prev_res;
    int K;
    float share;                      /* each history technique's share of its confidence */
    float c0;                         /* canonical confidence */
    int q_bp;                         /* backprojected pixel (both), or -1 */
    float c_bp;
    struct pt_domain dom, dom_bp;     /* this pixel; the backprojected previous pixel */
    long long rays;
    struct restir_reservoir wrs;
    float c_offered;                  /* 1/M: the confidences of the candidates offered */
    struct path_sample chosen;
    float chosen_target;
};

static float capped(const struct pixel_merge *m, float c) { return min_f(c, m->fr->p->reuse.confidence_cap); }

/* c_s p_hat_{<-s}(y): the splat technique at path y of this pixel, by the inverse splat into the
 * previous frame (its primary hit projected through the previous camera at the inverse time). */
static float splat_term(struct pixel_merge *m, const struct path_sample *y)
{
    int k, q;
    const float t_prev = stratum_inverse(y->time, m->K, &k);
    struct path_sample z;
    float J;
    if (!path_shift_splat(m->fr->s, &m->fr->shift, y, m->fr->view, m->fr->prev_view, t_prev, (float)m->K, &q, &z, &J,
                          &m->rays))
        return 0.0f;
    return m->share * capped(m, m->prev_res[q].c) * v3_luminance(z.f) * J;
}

/* c_b p_hat_{<-b}(y): the backprojection technique at path y, by the inverse backprojection shift. */
static float backproject_term(struct pixel_merge *m, const struct path_sample *y)
{
    if (m->q_bp < 0)
        return 0.0f;
    struct path_sample z;
    float J;
    if (!path_shift(m->fr->s, &m->fr->shift, y, &m->dom, &m->dom_bp, &z, &J, &m->rays))
        return 0.0f;
    return m->c_bp * v3_luminance(z.f) * J;
}

/* Offers path y (target P0 = p_hat(y) here) from technique `own`, whose term c_own p_hat_{<-own}(y)
 * is known, with resampling weight m(y) P0 W |J| (004 Eq. 6), m the generalized balance heuristic
 * (004 Eq. 9) over the techniques that can produce y (or 1/M, BIASED). */
static void offer(struct pixel_merge *m, int own, float own_term, float c_own, const struct path_sample *y, float P0,
                  float W, float J, pcg32 *rng)
{
    float term[TECH_COUNT] = {0};
    term[own] = own_term;
    if (own != TECH_CANONICAL)
        term[TECH_CANONICAL] = m->c0 * P0;
    if (own != TECH_SPLAT)
        term[TECH_SPLAT] = splat_term(m, y);
    if (own != TECH_BACKPROJECT)
        term[TECH_BACKPROJECT] = backproject_term(m, y);
    float mis;
    if (m->fr->p->reuse.mis == RESTIR_MIS_UNIFORM) {
        mis = c_own; /* divided by the sum of offered confidences when the merge ends */
        m->c_offered += c_own;
    } else {
        const double denom = (double)term[0] + term[1] + term[2];
        mis = denom > 0.0 ? (float)(term[own] / denom) : 0.0f;
    }
    const float w = restir_gris_resampling_weight(mis, P0, W, J); /* 004 Eq. 6 */
    if (restir_reservoir_offer(&m->wrs, w, pcg32_float(rng))) {
        m->chosen = *y;
        m->chosen_target = P0;
    }
}

/* The history confidence a merged pixel adds: that of the previous pixel under its G-buffer
 * motion vector (gbuffer_motion_pixel). A function of G-buffers only, like every confidence
 * here, so the MIS weights that read confidences stay unbiased. */
static float history_confidence(const struct gbuffer *g, const struct gbuffer *prev_g,
                                const struct pt_reservoir *prev_res, int i)
{
    int q = gbuffer_motion_pixel(g, i, prev_g);
    return q >= 0 ? prev_res[q].c : 0.0f;
}

static void merge_pixel(struct pixel_merge *m, const struct gbuffer *g, const struct gbuffer *prev_g,
                        const struct pt_splat_buffers *b, int i, struct pt_reservoir *io, unsigned char *flags)
{
    const struct pt_frame *fr = m->fr;
    const struct render_params *p = fr->p;
    pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)i, RNG_PASS_PT_TEMPORAL);
    const struct pt_reservoir canonical = io[i];
    unsigned char fl = 0;
    restir_reservoir_init(&m->wrs);
    m->c_offered = 0.0f;
    m->c0 = capped(m, canonical.c);
    if (pt_reservoir_has_sample(&canonical))
        offer(m, TECH_CANONICAL, m->c0 * canonical.target, m->c0, &canonical.y, canonical.target, canonical.W, 1.0f,
              &rng);
    else
        m->c_offered += m->c0;
    /* the paths that landed here */
    for (int e = b->start[i]; e < b->start[i + 1]; e++) {
        const int entry = b->entries[e], q = entry / m->K, k = entry % m->K;
        const struct pt_reservoir *h = &m->prev_res[q];
        struct path_sample y;
        float J;
        int pixel;
        fl |= TEMPORAL_SPLAT_RECEIVED;
        const float c_s = m->share * capped(m, h->c);
        if (!path_shift_splat(fr->s, &fr->shift, &h->y, fr->prev_view, fr->view, stratum_time(h->y.time, k, m->K),
                              1.0f / (float)m->K, &pixel, &y, &J, &m->rays)) {
            m->c_offered += p->reuse.mis == RESTIR_MIS_UNIFORM ? c_s : 0.0f;
            continue;
        }
        RESTIR_CHECK(pixel == i); /* the same projection as land_pass */
        fl |= TEMPORAL_SPLAT_ACCEPTED;
        offer(m, TECH_SPLAT, c_s * h->target / J, c_s, &y, v3_luminance(y.f), h->W, J, &rng);
    }
    /* temporal.reuse=both: the backprojected history */
    if (m->q_bp >= 0) {
        const struct pt_reservoir *h = &m->prev_res[m->q_bp];
        fl |= TEMPORAL_BP_RECEIVED;
        struct path_sample y;
        float J;
        if (pt_reservoir_has_sample(h) && path_shift(fr->s, &fr->shift, &h->y, &m->dom_bp, &m->dom, &y, &J, &m->rays)) {
            fl |= TEMPORAL_BP_ACCEPTED;
            offer(m, TECH_BACKPROJECT, m->c_bp * h->target / J, m->c_bp, &y, v3_luminance(y.f), h->W, J, &rng);
        } else if (p->reuse.mis == RESTIR_MIS_UNIFORM) {
            m->c_offered += m->c_bp;
        }
    }
    flags[i] = fl;
    struct pt_reservoir out;
    pt_reservoir_clear(&out, restir_gris_confidence_merge(canonical.c + history_confidence(g, prev_g, m->prev_res, i),
                                                     p->reuse.confidence_cap));
    if (m->wrs.selected >= 0) {
        if (p->reuse.mis == RESTIR_MIS_UNIFORM && m->c_offered > 0.0f)
            m->wrs.w_sum /= m->c_offered; /* 1/M: m_j = c_j / sum of the offered confidences */
        out.y = m->chosen;
        out.target = m->chosen_target;
        out.W = restir_gris_contribution_weight(&m->wrs, out.target); /* 004 Eq. 7 */
        if (!(out.W > 0.0f))
            pt_reservoir_clear(&out, out.c);
    }
    io[i] = out;
}

long long pt_temporal_splat_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                                 const struct pt_reservoir *prev_res, struct pt_reservoir *io,
                                 struct pt_splat_buffers *b, unsigned char *flags)
{
    const struct render_params *p = fr->p;
    const int both = p->reuse.temporal_reuse == TEMPORAL_BOTH;
    land_pass(fr, prev_res, b);
    bucket_pass(b);
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct pixel_merge m;
        memset(&m, 0, sizeof(m));
        m.fr = fr;
        m.prev_res = prev_res;
        m.K = b->steps;
        /* both: the previous frame is proposed twice, so each technique takes half its confidence */
        m.share = both ? 0.5f : 1.0f;
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, i = px.i;
            m.dom = pt_pixel_domain(fr->view, x, y);
            m.q_bp = both ? gbuffer_history_pixel(g, i, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane) : -1;
            if (m.q_bp >= 0) {
                m.dom_bp = pt_pixel_domain(fr->prev_view, m.q_bp % w, m.q_bp / w);
                m.dom_bp.origin[0] -= g->motion[2 * i]; /* as pt_temporal_pass */
                m.dom_bp.origin[1] -= g->motion[2 * i + 1];
                m.c_bp = m.share * capped(&m, prev_res[m.q_bp].c);
            }
            m.rays = 0;
            merge_pixel(&m, g, prev_g, b, i, io, flags);
            rays += m.rays;
        }
    }
    return rays;
}
