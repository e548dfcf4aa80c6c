/* grestir.c: Gradient with ReSTIR passes (see grestir.h; 002 Sec. 4.2-4.4).
 *
 * Domains. A pixel pair (a, b) with b = a + e is the paired domain X = (Omega_a x {0}) u
 * (Omega_b x {1}) (Eq. 14). Its two pixel domains are pt_domains (path_shift.h), so the outer
 * shift of (x, k) from pair A to pair B is the pixel shift of x from A's pixel k to B's pixel k with
 * k kept (Eq. 21), and its Jacobian is that shift's (Eq. 22). Evaluating the target in B then needs
 * the inner shift of the result into B's other pixel (restir/grad.h gives h and the targets). */
#include "methods/gradient/grestir.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/gradient/grad_common.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "restir/mis.h"
#include "restir/reservoir.h"
#include "methods/gradient/grad_settings.h"

/* The most domains one merge sees: canonical, neighbor r+, neighbor r- (cross-sign reuse); the
 * canonical and four previous pairs (temporal.subpixel=search). */
#define PAIR_MAX_DOMAINS 5

struct pair_domain {
    struct pt_domain px[2];
};

static void pair_offset(int dir, int *ex, int *ey)
{
    *ex = dir == GRAD_PAIR_X;
    *ey = dir == GRAD_PAIR_Y;
}

static struct pair_domain pair_current(const struct camera_view *view, int ax, int ay, int dir)
{
    int ex, ey;
    pair_offset(dir, &ex, &ey);
    struct pair_domain d = {{pt_pixel_domain(view, ax, ay), pt_pixel_domain(view, ax + ex, ay + ey)}};
    return d;
}

static int pair_inside(int w, int h, int ax, int ay, int dir)
{
    int ex, ey;
    pair_offset(dir, &ex, &ey);
    return ax >= 0 && ay >= 0 && ax + ex < w && ay + ey < h;
}

void grestir_state_init(struct grestir_state *st, int width, int height)
{
    memset(st, 0, sizeof(*st));
    st->width = width;
    st->height = height;
    size_t n = (size_t)width * (size_t)height;
    for (int d = 0; d < GRAD_PAIR_DIRS; d++) {
        for (int s = 0; s < GRAD_SIGNS; s++) {
            st->hist[0][d][s] = xcalloc(n, sizeof(struct pair_reservoir));
            st->hist[1][d][s] = xcalloc(n, sizeof(struct pair_reservoir));
            st->work[d][s] = xcalloc(n, sizeof(struct pair_reservoir));
        }
        st->neighbor[d] = xcalloc(n, sizeof(int));
        st->edge[d] = xcalloc(n, 1);
    }
    st->base_other = xcalloc(n * 3 * GRAD_DIRS, sizeof(float));
    st->base_inner_J = xcalloc(n * GRAD_DIRS, sizeof(float));
}

void grestir_state_fini(struct grestir_state *st)
{
    for (int d = 0; d < GRAD_PAIR_DIRS; d++) {
        for (int s = 0; s < GRAD_SIGNS; s++) {
            free(st->hist[0][d][s]);
            free(st->hist[1][d][s]);
            free(st->work[d][s]);
        }
        free(st->neighbor[d]);
        free(st->edge[d]);
    }
    free(st->base_other);
    free(st->base_inner_J);
    memset(st, 0, sizeof(*st));
}

static void pair_clear(struct pair_reservoir *r, float c)
{
    memset(r, 0, sizeof(*r));
    r->c = c;
}

static int pair_has_sample(const struct pair_reservoir *r) { return r->y.length >= 2 && r->W > 0.0f; }

/* The signs in use: r+ and r- with positivization, one |h| reservoir without. */
static int sign_count(const struct render_params *p) { return grad_settings_of(p)->positivize ? 2 : 1; }
static enum restir_grad_sign sign_of(const struct render_params *p, int s)
{
    return grad_settings_of(p)->positivize ? (s == 0 ? RESTIR_GRAD_POS : RESTIR_GRAD_NEG) : RESTIR_GRAD_ABS;
}

/* h(y, k) in pair dom, y in pixel dom->px[k]: the inner shift of y into the other pixel, whose
 * |T'| goes to *inner_J. The pair's pixels share their offsets (origins a whole pixel apart), so the
 * inner shift keeps u even where the pair's outer shifts clip (temporal.subpixel=search). */
static long long pair_integrand(const struct pt_frame *fr, const struct path_sample *y, int k,
                                const struct pair_domain *dom, float h[3], float *inner_J)
{
    float other[3];
    struct pt_domain from = dom->px[k], to = dom->px[1 - k];
    from.clip = to.clip = 0;
    long long rays = grad_shift_other(fr->s, &fr->shift, y, &from, &to, other, inner_J);
    const float own[3] = {y->f.x, y->f.y, y->f.z};
    restir_grad_pair_integrand(k, own, other, h);
    return rays;
}

/* grad.inner_jacobian_ratio (002's public code: 10): are the inner shifts' Jacobians of a path
 * before and after an outer shift too far apart (ratio above `ratio`, or one undefined and the
 * other not)? Symmetric in the two, so a rejected outer shift is rejected back too: the rule only
 * narrows the shift's domain, as a failed shift does. 0 turns it off. */
static int inner_jacobians_disagree(float a, float b, float ratio)
{
    if (!(ratio > 0.0f))
        return 0;
    if (!(a > 0.0f) || !(b > 0.0f))
        return (a > 0.0f) != (b > 0.0f);
    return a > ratio * b || b > ratio * a;
}

/* Outer shift T* of (x, k) from pair `from` to pair `to` (Eq. 21-22) and h there; x_inner_J is
 * x's inner-shift Jacobian in `from`. Returns 1 with y, h, |T*'| and y's inner-shift Jacobian, or 0
 * where tau is undefined (or grad.inner_jacobian_ratio rejects it). */
static int pair_shift(const struct pt_frame *fr, const struct path_sample *x, float x_inner_J, int k,
                      const struct pair_domain *from, const struct pair_domain *to, struct path_sample *y, float h[3],
                      float *J, float *y_inner_J, long long *rays)
{
    if (!path_shift(fr->s, &fr->shift, x, &from->px[k], &to->px[k], y, J, rays))
        return 0;
    *rays += pair_integrand(fr, y, k, to, h, y_inner_J);
    return !inner_jacobians_disagree(x_inner_J, *y_inner_J, grad_settings_of(fr->p)->inner_jacobian_ratio);
}

/* ---- initial candidates ------------------------------------------------------------------------ */

long long grestir_initial_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *base,
                               struct grestir_state *st)
{
    const struct render_params *p = fr->p;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const size_t n = (size_t)w * (size_t)h;
    long long rays = 0;
    /* f(T x_i) |T'| of every pixel's initial path in each neighbor */
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y;
            const size_t i = (size_t)px.i;
            struct pt_domain from = pt_pixel_domain(fr->view, x, y);
            for (int d = 0; d < GRAD_DIRS; d++) {
                float *other = grad_os(st->base_other, n, d, i);
                float *inner_J = &st->base_inner_J[(size_t)d * n + i];
                other[0] = other[1] = other[2] = 0.0f;
                *inner_J = 0.0f;
                int ox, oy;
                grad_dir_offset(d, &ox, &oy);
                if (!pt_reservoir_has_sample(&base[i]) || x + ox < 0 || x + ox >= w || y + oy < 0 || y + oy >= h)
                    continue;
                struct pt_domain to = pt_pixel_domain(fr->view, x + ox, y + oy);
                rays += grad_shift_other(fr->s, &fr->shift, &base[i].y, &from, &to, other, inner_J);
            }
        }
    }
    const int ns = sign_count(p);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            size_t a = (size_t)y * (size_t)w + (size_t)x;
            for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
                for (int s = 0; s < ns; s++)
                    pair_clear(&st->work[dir][s][a], 0.0f);
                if (!pair_inside(w, h, x, y, dir))
                    continue;
                size_t b = dir == GRAD_PAIR_X ? a + 1 : a + (size_t)w;
                const struct pt_reservoir *src[2] = {&base[a], &base[b]};
                float hk[2][3], inner_J[2];
                for (int k = 0; k < 2; k++) {
                    const float own[3] = {src[k]->y.f.x, src[k]->y.f.y, src[k]->y.f.z};
                    /* a's path toward b: RIGHT / DOWN; b's path toward a: LEFT / UP */
                    int d = k == 0 ? (dir == GRAD_PAIR_X ? GRAD_RIGHT : GRAD_DOWN)
                                   : (dir == GRAD_PAIR_X ? GRAD_LEFT : GRAD_UP);
                    restir_grad_pair_integrand(k, own, grad_os(st->base_other, n, d, k ? b : a), hk[k]);
                    inner_J[k] = st->base_inner_J[(size_t)d * n + (k ? b : a)];
                }
                pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, a * 2 + (size_t)dir, RNG_PASS_GRAD_INITIAL);
                for (int s = 0; s < ns; s++) {
                    enum restir_grad_sign sg = sign_of(p, s);
                    struct restir_reservoir wrs;
                    restir_reservoir_init(&wrs);
                    int chosen = -1;
                    float target[2];
                    for (int k = 0; k < 2; k++) {
                        target[k] = pt_reservoir_has_sample(src[k]) ? restir_grad_target(sg, hk[k]) : 0.0f;
                        /* Eq. 20 with m = 1 (disjoint parts) and the pixel path's UCW */
                        if (restir_reservoir_offer(&wrs,
                                                   restir_gris_resampling_weight(1.0f, target[k], src[k]->W, 1.0f),
                                                   pcg32_float(&rng)))
                            chosen = k;
                    }
                    struct pair_reservoir *out = &st->work[dir][s][a];
                    pair_clear(out, 1.0f);
                    if (chosen < 0)
                        continue;
                    out->y = src[chosen]->y;
                    out->k = chosen;
                    out->inner_J = inner_J[chosen];
                    memcpy(out->h, hk[chosen], sizeof(out->h));
                    out->target = target[chosen];
                    out->W = restir_gris_contribution_weight(&wrs, out->target); /* Eq. 18 */
                    if (!(out->W > 0.0f))
                        pair_clear(out, 1.0f);
                }
            }
        }
    }
    return rays;
}

/* ---- GRIS merge over paired domains ------------------------------------------------------------- */

/* One GRIS merge into dom[0] (the canonical pair, identity shift) of n reservoirs; reservoir j lives
 * in pair dom_id[j] (dom[] indexed by it) with target sign sg[j]. P[k * n + j] = p_hat_{<-k}(Y_j)
 * (004 Eq. 10) as in restir_pt.c's gris_merge, with the outer shift and each technique's own
 * target, under resampling MIS `mis`. c_sum counts each pair once, times share[dom_id] (NULL: 1). */
static long long pair_merge(const struct pt_frame *fr, int n, const struct pair_domain *dom, const int *dom_id,
                            const enum restir_grad_sign *sg, const struct pair_reservoir *const *in,
                            enum restir_mis mis, const float *share, pcg32 *rng, struct pair_reservoir *out)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    float c[PAIR_MAX_DOMAINS], J[PAIR_MAX_DOMAINS];
    float P[PAIR_MAX_DOMAINS * PAIR_MAX_DOMAINS] = {0};
    struct path_sample Y[PAIR_MAX_DOMAINS];
    float H[PAIR_MAX_DOMAINS][3], YJ[PAIR_MAX_DOMAINS]; /* YJ: Y_j's inner-shift Jacobian */
    int ok[PAIR_MAX_DOMAINS];
    float c_sum = 0.0f;
    for (int j = 0; j < n; j++) {
        c[j] = fminf(in[j]->c, p->reuse.confidence_cap);
        if (j == 0 || dom_id[j] != dom_id[j - 1])
            c_sum += share ? share[dom_id[j]] * c[j] : c[j];
        J[j] = 0.0f;
        ok[j] = 0;
        if (!pair_has_sample(in[j]))
            continue;
        if (dom_id[j] == dom_id[0]) {
            Y[j] = in[j]->y;
            memcpy(H[j], in[j]->h, sizeof(H[j]));
            YJ[j] = in[j]->inner_J;
            J[j] = 1.0f;
            ok[j] = 1;
        } else {
            ok[j] = pair_shift(fr, &in[j]->y, in[j]->inner_J, in[j]->k, &dom[dom_id[j]], &dom[dom_id[0]], &Y[j], H[j],
                               &J[j], &YJ[j], &rays);
        }
        if (ok[j])
            P[j] = restir_grad_target(sg[0], H[j]);
    }
    for (int j = 0; j < n; j++) {
        if (!ok[j])
            continue;
        const int kj = in[j]->k;
        int shifted_to = -1; /* dom_id whose back-shift of Y_j is cached in hz, Jb */
        float hz[3] = {0, 0, 0}, Jb = 0.0f, zJ;
        for (int k = 1; k < n; k++) {
            if (!restir_mis_needs(mis, k, j))
                continue;
            if (dom_id[k] == dom_id[j]) {
                P[k * n + j] = restir_grad_target(sg[k], in[j]->h) / J[j]; /* p_hat_k(X_j) |dT^-1/dy| */
                continue;
            }
            if (dom_id[k] == dom_id[0]) {
                P[k * n + j] = restir_grad_target(sg[k], H[j]);
                continue;
            }
            if (shifted_to != dom_id[k]) {
                struct path_sample z;
                shifted_to = dom_id[k];
                if (!pair_shift(fr, &Y[j], YJ[j], kj, &dom[dom_id[0]], &dom[dom_id[k]], &z, hz, &Jb, &zJ, &rays))
                    Jb = 0.0f;
            }
            P[k * n + j] = Jb > 0.0f ? restir_grad_target(sg[k], hz) * Jb : 0.0f;
        }
    }
    float W[PAIR_MAX_DOMAINS], u[PAIR_MAX_DOMAINS], W_Y;
    for (int j = 0; j < n; j++) {
        W[j] = in[j]->W;
        u[j] = pcg32_float(rng);
        J[j] = ok[j] ? J[j] : 0.0f;
    }
    const int chosen = restir_gris_resample(mis, n, c, P, W, J, u, &W_Y); /* Eq. 20, 004 Eq. 5-7 */
    struct pair_reservoir result;
    pair_clear(&result, restir_gris_confidence_merge(c_sum, p->reuse.confidence_cap));
    if (chosen >= 0) {
        result.y = Y[chosen];
        result.k = in[chosen]->k;
        result.inner_J = YJ[chosen];
        memcpy(result.h, H[chosen], sizeof(result.h));
        result.target = P[chosen];
        result.W = W_Y; /* Eq. 18 */
        if (!(result.W > 0.0f))
            pair_clear(&result, result.c);
    }
    *out = result;
    return rays;
}

/* ---- temporal reuse ----------------------------------------------------------------------------- */

/* The previous pairs that pair (x, y) along dir reuses: dom[1 .. n], their first pixels qa[0 .. n),
 * and the share of each in the merged confidence (share[0] = 1 for the canonical dom[0]). The pair
 * moves with the nearer pixel's fractional motion (Sec. 4.3.1). wrap: the pair under it, with its
 * offsets translated on the torus; search: the up to four pairs the pair's squares overlap, with
 * clipped shifts and their overlap areas as shares (restir_pt.c's temporal_search_merge says why the
 * balance heuristic over them is unbiased). Returns n (0: no history). */
static int temporal_pairs(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g, int x,
                          int y, int dir, struct pair_domain *dom, int *qa, float *share)
{
    const struct render_params *p = fr->p;
    const int w = g->width, a = y * w + x;
    int ex, ey;
    pair_offset(dir, &ex, &ey);
    const int b = a + ex + ey * w;
    int pivot = -1;
    if (g->valid[a] && (!g->valid[b] || g->depth[a] <= g->depth[b]))
        pivot = a;
    else if (g->valid[b])
        pivot = b;
    if (pivot < 0)
        return 0;
    struct gbuffer_history_cell cells[4];
    int m;
    const int search = p->reuse.temporal_subpixel == TEMPORAL_SUBPIXEL_SEARCH;
    if (search) {
        m = gbuffer_history_square(g, pivot, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane, cells);
    } else {
        cells[0].q = gbuffer_history_pixel(g, pivot, prev_g, p->reuse.temporal_normal, p->reuse.temporal_plane);
        cells[0].area = 1.0f;
        m = cells[0].q >= 0;
    }
    dom[0] = pair_current(fr->view, x, y, dir);
    share[0] = 1.0f;
    int n = 0;
    for (int c = 0; c < m; c++) {
        const int q = cells[c].q, off = pivot == a ? 0 : ex + ey * w;
        const int qax = q % w - (pivot == a ? 0 : ex), qay = q / w - (pivot == a ? 0 : ey);
        if (!pair_inside(w, g->height, qax, qay, dir))
            continue;
        struct pair_domain *d = &dom[n + 1];
        *d = pair_current(fr->prev_view, qax, qay, dir);
        for (int k = 0; k < 2; k++) {
            if (p->jitter) {
                /* Area ReSTIR: the previous pair's offsets move with the pair motion */
                d->px[k].origin[0] -= g->motion[2 * pivot];
                d->px[k].origin[1] -= g->motion[2 * pivot + 1];
            }
            d->px[k].clip = dom[0].px[k].clip = search;
        }
        qa[n] = q - off;
        share[n + 1] = cells[c].area;
        n++;
    }
    return n;
}

long long grestir_temporal_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct gbuffer *prev_g,
                                struct grestir_state *st, int prev_slot, long long *accepted)
{
    const struct render_params *p = fr->p;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h), ns = sign_count(p);
    const enum restir_mis mis =
        p->reuse.temporal_subpixel == TEMPORAL_SUBPIXEL_SEARCH ? render_params_tiled_mis(p) : p->reuse.mis;
    long long rays = 0, acc = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays, acc)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, a = px.i;
            for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
                if (!pair_inside(w, h, x, y, dir))
                    continue;
                struct pair_domain dom[PAIR_MAX_DOMAINS];
                int qa[PAIR_MAX_DOMAINS - 1];
                float share[PAIR_MAX_DOMAINS];
                const int m = temporal_pairs(fr, g, prev_g, x, y, dir, dom, qa, share);
                if (m == 0)
                    continue;
                const int dom_id[PAIR_MAX_DOMAINS] = {0, 1, 2, 3, 4};
                pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)a * 2 + (uint64_t)dir,
                                    RNG_PASS_GRAD_TEMPORAL);
                for (int s = 0; s < ns; s++) {
                    enum restir_grad_sign sg[PAIR_MAX_DOMAINS];
                    const struct pair_reservoir *in[PAIR_MAX_DOMAINS] = {&st->work[dir][s][a]};
                    for (int k = 0; k <= m; k++)
                        sg[k] = sign_of(p, s);
                    for (int k = 0; k < m; k++)
                        in[k + 1] = &st->hist[prev_slot][dir][s][qa[k]];
                    struct pair_reservoir res;
                    rays += pair_merge(fr, m + 1, dom, dom_id, sg, in, mis, share, &rng, &res);
                    st->work[dir][s][a] = res;
                }
                acc++;
            }
        }
    }
    *accepted = acc;
    return rays;
}

/* ---- spatial neighbor pairs ---------------------------------------------------------------------- */

static int gb_edge(const struct render_params *p, const struct gbuffer *g, int i, int j)
{
    const struct grad_settings *gs = grad_settings_of(p);
    const struct restir_grad_edge_test t = {gs->edge_albedo, gs->edge_normal, gs->edge_depth};
    const vec3 ai = g->albedo[i], aj = g->albedo[j], ni = g->normal[i], nj = g->normal[j];
    const float A[3] = {ai.x, ai.y, ai.z}, B[3] = {aj.x, aj.y, aj.z}, N[3] = {ni.x, ni.y, ni.z},
                M[3] = {nj.x, nj.y, nj.z};
    return restir_grad_edge(&t, g->valid[i], A, N, g->depth[i], g->valid[j], B, M, g->depth[j]);
}

/* Whether pair (c, d) may serve pair (a, b) (both along dir): similar to it pixel by pixel, and
 * for adaptive reuse an edge pair itself (the table first: the cheapest test). */
static int candidate_ok(const struct render_params *p, const struct gbuffer *g, const struct grestir_state *st,
                        int a, int b, int c, int d, int dir)
{
    if (grad_settings_of(p)->spatial == GRAD_SPATIAL_ADAPTIVE && !st->edge[dir][c])
        return 0;
    return !gb_edge(p, g, a, c) && !gb_edge(p, g, b, d);
}

/* Whether any pair the search's taps can reach from pair (x, y) passes candidate_ok. A tap lands
 * at (lrint(r cos phi), lrint(r sin phi)) with r <= grad.radius, so within grad.radius + sqrt(1/2)
 * of the pair; when no pair there passes, every tap fails and the search's answer is -1 without
 * drawing a tap (the search's random stream serves nothing else, so skipping it changes no
 * result). Many edge pairs have no such neighbor (thin features, silhouettes), and their 256
 * taps were most of the pass. */
static int any_candidate(const struct render_params *p, const struct gbuffer *g, const struct grestir_state *st,
                         int x, int y, int dir)
{
    const int w = g->width, h = g->height;
    int ex, ey;
    pair_offset(dir, &ex, &ey);
    const int a = y * w + x, b = a + ex + ey * w;
    const float reach = grad_settings_of(p)->radius + 0.71f; /* a little over sqrt(1/2): a superset is safe */
    const int R = (int)ceilf(reach);
    for (int dy = -R; dy <= R; dy++) {
        for (int dx = -R; dx <= R; dx++) {
            const int cx = x + dx, cy = y + dy;
            if ((dx == 0 && dy == 0) || (float)(dx * dx + dy * dy) > reach * reach ||
                !pair_inside(w, h, cx, cy, dir))
                continue;
            const int c = cy * w + cx;
            if (candidate_ok(p, g, st, a, b, c, c + ex + ey * w, dir))
                return 1;
        }
    }
    return 0;
}

void grestir_select_pass(const struct pt_frame *fr, const struct gbuffer *g, struct grestir_state *st)
{
    const struct render_params *p = fr->p;
    const struct grad_settings *gs = grad_settings_of(p);
    const int w = g->width, h = g->height;
    const int adaptive = gs->spatial == GRAD_SPATIAL_ADAPTIVE;
    /* Every pair's edge test once: the search below asks it of up to grad.search candidate pairs
     * per pair, most of them many times over (the disk of radius 4 holds ~50 pixels). */
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const int a = y * w + x;
            for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
                int ex, ey;
                pair_offset(dir, &ex, &ey);
                st->edge[dir][a] = pair_inside(w, h, x, y, dir) && gb_edge(p, g, a, a + ex + ey * w);
            }
        }
    }
    long long edges = 0, found = 0;
#pragma omp parallel for schedule(static) reduction(+ : edges, found)
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const int a = y * w + x;
            for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
                st->neighbor[dir][a] = -1;
                if (gs->spatial == GRAD_SPATIAL_OFF || !pair_inside(w, h, x, y, dir))
                    continue;
                int ex, ey;
                pair_offset(dir, &ex, &ey);
                const int b = a + ex + ey * w;
                if (adaptive && !st->edge[dir][a])
                    continue; /* interior pair: keeps its temporal result (Sec. 4.3.2) */
                edges++;
                if (!any_candidate(p, g, st, x, y, dir))
                    continue; /* no tap could be accepted: the search below would return -1 */
                pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)a * 2 + (uint64_t)dir,
                                    RNG_PASS_GRAD_SELECT);
                for (int tap = 0; tap < gs->search; tap++) {
                    float rad = gs->radius * sqrtf(pcg32_float(&rng)),
                          phi = 6.2831853f * pcg32_float(&rng);
                    int cx = x + (int)lrintf(rad * cosf(phi)), cy = y + (int)lrintf(rad * sinf(phi));
                    if ((cx == x && cy == y) || !pair_inside(w, h, cx, cy, dir))
                        continue;
                    const int c = cy * w + cx, d = c + ex + ey * w;
                    if (!candidate_ok(p, g, st, a, b, c, d, dir))
                        continue;
                    st->neighbor[dir][a] = c;
                    found++;
                    break;
                }
            }
        }
    }
    st->edge_pairs = edges;
    st->neighbors_found = found;
}

/* ---- spatial reuse -------------------------------------------------------------------------------- */

long long grestir_spatial_pass(const struct pt_frame *fr, const struct gbuffer *g, struct grestir_state *st,
                               int slot)
{
    const struct render_params *p = fr->p;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h), ns = sign_count(p);
    const int cross = grad_settings_of(p)->cross_sign && ns == 2;
    long long rays = 0;
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, a = px.i;
            for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
                const int c = st->neighbor[dir][a];
                if (c < 0) {
                    for (int s = 0; s < ns; s++)
                        st->hist[slot][dir][s][a] = st->work[dir][s][a];
                    continue;
                }
                struct pair_domain dom[2];
                dom[0] = pair_current(fr->view, x, y, dir);
                dom[1] = pair_current(fr->view, c % w, c / w, dir);
                const int dom_id[3] = {0, 1, 1};
                pcg32 rng = rng_for(p->seed, (uint64_t)fr->frame, (uint64_t)a * 2 + (uint64_t)dir,
                                    RNG_PASS_GRAD_SPATIAL);
                for (int s = 0; s < ns; s++) {
                    const enum restir_grad_sign sg[3] = {sign_of(p, s), sign_of(p, s), sign_of(p, 1 - s)};
                    const struct pair_reservoir *in[3] = {&st->work[dir][s][a], &st->work[dir][s][c],
                                                          &st->work[dir][1 - s][c]};
                    rays += pair_merge(fr, cross ? 3 : 2, dom, dom_id, sg, in, p->reuse.mis, NULL, &rng,
                                       &st->hist[slot][dir][s][a]);
                }
            }
        }
    }
    return rays;
}

/* ---- evaluation ------------------------------------------------------------------------------------ */

void grestir_shade_pass(const struct render_params *p, const struct grestir_state *st, int slot, float *dx,
                        float *dy)
{
    const int w = st->width, h = st->height, ns = sign_count(p);
    float *out[GRAD_PAIR_DIRS] = {dx, dy};
#pragma omp parallel for schedule(static)
    for (int a = 0; a < w * h; a++) {
        for (int dir = 0; dir < GRAD_PAIR_DIRS; dir++) {
            for (int s = 0; s < ns; s++) {
                const struct pair_reservoir *r = &st->hist[slot][dir][s][a];
                if (!pair_has_sample(r))
                    continue;
                enum restir_grad_sign sg = sign_of(p, s);
                float part[3];
                restir_grad_part(sg, r->h, part);
                float sign = sg == RESTIR_GRAD_NEG ? -1.0f : 1.0f; /* Eq. 24: r+ estimate - r- estimate */
                for (int k = 0; k < 3; k++) {
                    float v = sign * part[k] * r->W;
                    if (isfinite(v))
                        out[dir][3 * a + k] += v;
                }
            }
        }
    }
}
