/* restir_di.c: ReSTIR DI reuse and shading passes: temporal reuse with reprojection and
 * validation (001), spatial reuse with Bitterli's neighbor test (000 Eq. 7), GRIS merges with
 * selectable resampling MIS (004 Eq. 5-12), and shading (initial RIS is in di_initial.c).
 * Must never allocate per pixel (one merge batch per thread and pass). */
#include "methods/restir_di/restir_di.h"
#include "denoise/svgf_temporal.h"
#include "scene/scene_animation.h"
#include "scene/scene_motion.h"

#include <stdlib.h>

#include "core/check.h"
#include "core/rng.h"
#include "methods/restir_di/di_visibility.h"
#include "render/tiles.h"
#include "restir/gris.h"
#include "restir/mis.h"
#include "restir/reservoir.h"

/* Canonical domain + at most 5 spatial neighbors. */
#define DI_MAX_DOMAINS 6

/* One GRIS merge (004 Eq. 5-7) into domain 0 (canonical), split around its cross-domain targets
 * and shadow rays so that those of many pixels' merges are evaluated together, across pixels with
 * vector instructions, and traced together as one stream (merge_begin, then merge_batch_flush).
 * For DI the sample space is the same in every pixel (points on lights, area measure), so every
 * shift is the identity with Jacobian 1 and p_hat_{<-k}(y) is simply domain k's target at y
 * (004 Eq. 10), with visibility when the reservoirs' targets have it (di_visibility.h). */
struct di_merge {
    int n;
    const struct di_reservoir *in[DI_MAX_DOMAINS];
    float c[DI_MAX_DOMAINS], P[DI_MAX_DOMAINS * DI_MAX_DOMAINS];
    pcg32 rng;
    struct di_reservoir *out;
};

/* Merges waiting for their cross-domain targets and shadow rays: at most DI_BATCH_MERGES, each
 * with at most DI_MAX_DOMAINS * (DI_MAX_DOMAINS - 1) off-diagonal P entries to evaluate (one
 * target, and with visibility one ray, each). */
#define DI_BATCH_MERGES 64
#define DI_BATCH_ENTRIES (DI_BATCH_MERGES * DI_MAX_DOMAINS * (DI_MAX_DOMAINS - 1))
struct di_merge_batch {
    int merges, entries;
    struct di_merge mg[DI_BATCH_MERGES];
    /* entry e: P entry *entry_P[e] = p_hat of domain entry_sp[e] at sample entry_y[e] */
    const struct shading_point *entry_sp[DI_BATCH_ENTRIES];
    const struct di_sample *entry_y[DI_BATCH_ENTRIES];
    float *entry_P[DI_BATCH_ENTRIES];
    float entry_scale[DI_BATCH_ENTRIES]; /* what the target is multiplied by (1 but for old lights) */
    unsigned char entry_previous[DI_BATCH_ENTRIES]; /* 1: traced in the previous frame's geometry */
    int any_previous;                               /* some entry_previous is 1 */
    struct di_sample previous_y[DI_BATCH_MERGES];   /* canonical samples where moved emitters were */
    float target[DI_BATCH_ENTRIES];
    struct ray_query q[DI_BATCH_ENTRIES]; /* scratch of di_domain_target_many */
    int ray_entry[DI_BATCH_ENTRIES];
    unsigned char occluded[DI_BATCH_ENTRIES];
};

/* Queues the merge: its cached targets set, its cross-domain ones queued. prev_scale multiplies
 * domain 1's target at domain 0's sample (P[1][0]): in a temporal merge with animated emitters,
 * domain 1 (the previous frame) saw that sample's emitter at another strength (1 otherwise).
 * prev_y: NULL, or domain 0's sample where the previous frame had its emitter, which moved: P[1][0]
 * is then that point's target, its shadow ray traced in the previous frame's geometry.
 * c1_scale multiplies domain 1's confidence (di.gradient_confidence; 1 otherwise). */
static void merge_begin(struct di_merge_batch *b, const struct render_params *p, int n,
                        const struct shading_point *const *sp, const struct di_reservoir *const *in, pcg32 rng,
                        float prev_scale, const struct di_sample *prev_y, float c1_scale, struct di_reservoir *out)
{
    if (prev_y) {
        b->previous_y[b->merges] = *prev_y;
        prev_y = &b->previous_y[b->merges];
    }
    struct di_merge *mg = &b->mg[b->merges++];
    mg->n = n;
    mg->rng = rng;
    mg->out = out;
    for (int j = 0; j < n; j++) {
        mg->in[j] = in[j];
        mg->c[j] = fminf(in[j]->c, p->reuse.confidence_cap) * (j == 1 ? c1_scale : 1.0f);
    }
    for (int k = 0; k < n; k++) {
        for (int j = 0; j < n; j++) {
            float *P = &mg->P[k * n + j];
            *P = 0.0f;
            /* Row 0 (canonical target of every sample) is needed for the resampling weights. */
            if ((k != 0 && !restir_mis_needs(p->reuse.mis, k, j)) || in[j]->y.tri < 0)
                continue;
            if (k == j) {
                *P = in[j]->target; /* cached p_hat_j(Y_j) */
                continue;
            }
            const int old_domain = k == 1 && j == 0; /* the previous frame's target of this frame's sample */
            b->entry_sp[b->entries] = sp[k];
            b->entry_y[b->entries] = old_domain && prev_y ? prev_y : &in[j]->y;
            b->entry_scale[b->entries] = old_domain ? prev_scale : 1.0f;
            b->entry_previous[b->entries] = old_domain && prev_y;
            b->any_previous |= old_domain && prev_y;
            b->entry_P[b->entries++] = P;
        }
    }
}

/* The GRIS resampling of a merge whose targets are final. */
static void merge_end(const struct render_params *p, struct di_merge *mg)
{
    const int n = mg->n;
    float c_sum = 0.0f, W[DI_MAX_DOMAINS], J[DI_MAX_DOMAINS], u[DI_MAX_DOMAINS], W_Y;
    for (int j = 0; j < n; j++) {
        c_sum += mg->c[j];
        W[j] = mg->in[j]->W;
        J[j] = mg->in[j]->y.tri >= 0 ? 1.0f : 0.0f; /* a light sample keeps its point: |dT/dX| = 1 */
        u[j] = pcg32_float(&mg->rng);
    }
    const int chosen = restir_gris_resample(p->reuse.mis, n, mg->c, mg->P, W, J, u, &W_Y); /* 004 Eq. 5-7 */
    struct di_reservoir result;
    di_reservoir_clear(&result, restir_gris_confidence_merge(c_sum, p->reuse.confidence_cap));
    if (chosen >= 0) {
        result.y = mg->in[chosen]->y;
        result.target = mg->P[chosen];
        result.W = W_Y;
        if (result.W <= 0.0f)
            di_reservoir_clear(&result, result.c);
    }
    *mg->out = result;
}

/* Evaluates the queued targets across the merges at once (SIMD across pixels) with the shadow rays
 * of the positive ones as one stream (di_domain_target_many), then finishes every queued merge in
 * order. Returns the rays counted. */
static long long merge_batch_flush(struct di_merge_batch *b, const struct scene *s, const struct render_params *p)
{
    long long rays = di_domain_target_many(s, di_targets_visible(p), b->entries, b->entry_sp, b->entry_y, b->target,
                                           b->any_previous ? b->entry_previous : NULL, b->q, b->ray_entry,
                                           b->occluded);
    for (int e = 0; e < b->entries; e++)
        *b->entry_P[e] = b->target[e] * b->entry_scale[e];
    for (int k = 0; k < b->merges; k++)
        merge_end(p, &b->mg[k]);
    b->merges = b->entries = b->any_previous = 0;
    return rays;
}

static struct di_merge_batch *merge_batch_new(void)
{
    struct di_merge_batch *b = xmalloc(sizeof(*b));
    b->merges = b->entries = b->any_previous = 0;
    return b;
}

/* Room for one more merge of any size; returns the rays of a flush it needed. */
static long long merge_batch_reserve(struct di_merge_batch *b, const struct scene *s, const struct render_params *p)
{
    if (b->merges == DI_BATCH_MERGES || b->entries > DI_BATCH_ENTRIES - DI_MAX_DOMAINS * (DI_MAX_DOMAINS - 1))
        return merge_batch_flush(b, s, p);
    return 0;
}

long long di_temporal_pass(const struct scene *s, const struct render_params *p, int frame, float prev_t,
                           int moved, const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct di_reservoir *prev_res, const float *confidence_grad, struct di_reservoir *io,
                           long long *rays)
{
    long long accepted = 0, traced = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    int ox = 0, oy = 0; /* temporal.permutation: this frame's tile offset */
    const int permute = p->reuse.temporal_permutation;
    const int animated = scene_is_animated(s);
    const float moved_c = di_reuse_settings_of(p)->moved_confidence;
    if (permute)
        gbuffer_permutation_offset(p->seed, frame, &ox, &oy);
#pragma omp parallel reduction(+ : accepted, traced)
    {
        struct di_merge_batch *b = merge_batch_new(); /* one per thread and pass */
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < ntiles; t++) {
            for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
                const int i = px.i;
                const float nmin = p->reuse.temporal_normal, plane = p->reuse.temporal_plane;
                int q = permute ? gbuffer_history_pixel_permuted(g, i, prev_g, nmin, plane, ox, oy)
                                : gbuffer_history_pixel(g, i, prev_g, nmin, plane);
                if (q < 0)
                    continue;
                const struct shading_point *sp[2] = {gbuffer_shading(g, i), gbuffer_shading(prev_g, q)};
                const struct di_reservoir *hist = &prev_res[q];
                if (p->reuse.temporal_ratio_guard && hist->y.tri >= 0) {
                    /* 001 Sec. 5 guard: depends on the sample, hence BIASED (documented in --help). */
                    float ratio = di_target(sp[0], &hist->y) / hist->target;
                    if (!(ratio >= p->reuse.ratio_lo && ratio <= p->reuse.ratio_hi))
                        continue;
                }
                pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_DI_TEMPORAL);
                const struct di_reservoir *in[2] = {&io[i], hist};
                traced += merge_batch_reserve(b, s, p);
                /* animated emitters: the previous frame saw the canonical sample's emitter at its
                 * strength then, and where it was then if it moved (di_relight gave the history this
                 * frame's radiance and place, and kept its target, the previous frame's) */
                float prev_scale = 1.0f;
                struct di_sample then;
                const int light = io[i].y.tri >= 0 && io[i].y.tri != DI_ENV_TRI;
                if (animated && light) {
                    const float now = scene_emission_strength(s, io[i].y.tri, (float)frame);
                    prev_scale = now > 0.0f ? scene_emission_strength(s, io[i].y.tri, prev_t) / now : 0.0f;
                }
                if (moved && light) {
                    then = io[i].y;
                    scene_motion_point_previous(s, then.tri, then.b1, then.b2, &then.p, &then.n); /* at prev_t */
                }
                float c1 = confidence_grad ? 1.0f - svgf_gradient_response(confidence_grad[i]) : 1.0f;
                if (moved && hist->c > moved_c) /* di.moved_confidence: a function of c alone, so unbiased */
                    c1 *= moved_c / hist->c;
                merge_begin(b, p, 2, sp, in, rng, prev_scale, moved && light ? &then : NULL, c1, &io[i]);
                accepted++;
            }
            traced += merge_batch_flush(b, s, p);
        }
        free(b);
    }
    *rays += traced;
    return accepted;
}

long long di_spatial_pass(const struct scene *s, const struct render_params *p, int frame, const struct gbuffer *g,
                          const int *neighbors, const struct di_reservoir *in, struct di_reservoir *out)
{
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
    const int m = render_params_spatial_neighbors(p, 0); /* at most 5 = DI_MAX_DOMAINS - 1 */
#pragma omp parallel reduction(+ : rays)
    {
        struct di_merge_batch *b = merge_batch_new(); /* one per thread and pass */
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < ntiles; t++) {
            for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
                const int i = px.i;
                /* Neighbors sit at random within the radius: their reservoirs and shading points
                 * miss the cache, so the next pixel's are fetched while this one merges. */
                int next = tile_peek(&px);
                for (int k = 0; next >= 0 && k < m; k++) {
                    int j = neighbors[(size_t)next * m + k];
                    if (j >= 0) {
                        prefetch_bytes(&in[j], sizeof(in[j]));
                        prefetch_bytes(gbuffer_shading(g, j), sizeof(struct shading_point));
                    }
                }
                if (!g->valid[i]) {
                    out[i] = in[i];
                    continue;
                }
                pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_DI_SPATIAL);
                const struct shading_point *sp[DI_MAX_DOMAINS];
                const struct di_reservoir *src[DI_MAX_DOMAINS];
                sp[0] = gbuffer_shading(g, i);
                src[0] = &in[i];
                int n = 1;
                for (int k = 0; k < m; k++) {
                    int j = neighbors[(size_t)i * m + k];
                    if (j < 0)
                        continue;
                    sp[n] = gbuffer_shading(g, j);
                    src[n++] = &in[j];
                }
                rays += merge_batch_reserve(b, s, p);
                merge_begin(b, p, n, sp, src, rng, 1.0f, NULL, 1.0f, &out[i]);
            }
            rays += merge_batch_flush(b, s, p);
        }
        free(b);
    }
    return rays;
}

long long di_shade_pass(const struct scene *s, const struct render_params *p, const struct gbuffer *g,
                        const struct di_reservoir *res, float *rgb)
{
    /* A target with visibility that is positive was traced visible from this very pixel. */
    const int with_visibility = di_targets_visible(p);
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            vec3 L = g->emission[i]; /* emitters seen directly, or the environment where the ray left */
            const struct di_reservoir *rv = &res[i];
            if (g->valid[i] && rv->y.tri >= 0 && rv->W > 0.0f) {
                const struct shading_point *sp = gbuffer_shading(g, i);
                vec3 f = di_unshadowed(sp, &rv->y);
                if (v3_max_component(f) > 0.0f) {
                    int seen = with_visibility && rv->target > 0.0f;
                    if (!seen) {
                        rays++;
                        seen = di_sample_visible(s, sp, &rv->y);
                    }
                    if (seen)
                        L = v3_add(L, v3_scale(f, rv->W)); /* f(Y) W_Y */
                }
            }
            rgb[3 * i] = L.x;
            rgb[3 * i + 1] = L.y;
            rgb[3 * i + 2] = L.z;
        }
    }
    return rays;
}
