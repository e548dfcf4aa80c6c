/* restir_di.c: ReSTIR DI reuse and shading passes: temporal reuse with reprojection and
 * validation (001), spatial reuse with Bitterli's neighbor test (000 Eq. 7), GRIS merges with
 * selectable resampling MIS (004 Eq. 5-12), and shading (initial RIS is in di_initial.c).
 * Must never allocate per pixel. */
#include "render/restir_di.h"

#include "core/rng.h"
#include "render/di_visibility.h"
#include "render/tiles.h"
#include "restir/mis.h"
#include "restir/reservoir.h"

/* Canonical domain + at most 5 spatial neighbors. */
#define DI_MAX_DOMAINS 6

/* One GRIS merge (004 Eq. 5-7) into domain 0 (canonical). For DI the sample space is the same
 * in every pixel (points on lights, area measure), so every shift is the identity with Jacobian 1
 * and p_hat_{<-k}(y) is simply domain k's target at y (004 Eq. 10), with visibility when the
 * reservoirs' targets have it (di_visibility.h). Returns the shadow rays traced. */
static long long gris_merge(const struct scene *s, const struct render_params *p, int n,
                            const struct shading_point *const *sp, const struct di_reservoir *const *in, pcg32 *rng,
                            struct di_reservoir *out)
{
    const int with_visibility = di_targets_visible(p);
    long long rays = 0;
    float c[DI_MAX_DOMAINS] = {0}, P[DI_MAX_DOMAINS * DI_MAX_DOMAINS] = {0}, m[DI_MAX_DOMAINS] = {0};
    float c_sum = 0.0f;
    for (int j = 0; j < n; j++) {
        c[j] = fminf(in[j]->c, p->confidence_cap);
        c_sum += c[j];
    }
    for (int k = 0; k < n; k++) {
        for (int j = 0; j < n; j++) {
            /* Row 0 (canonical target of every sample) is needed for the resampling weights. */
            if (k != 0 && !restir_mis_needs(p->mis, k, j))
                continue;
            if (in[j]->y.tri < 0)
                P[k * n + j] = 0.0f;
            else if (k == j)
                P[k * n + j] = in[j]->target; /* cached p_hat_j(Y_j) */
            else
                P[k * n + j] = di_domain_target(s, with_visibility, sp[k], &in[j]->y, &rays);
        }
    }
    restir_mis_weights(p->mis, n, c, P, m);
    struct restir_wrs wrs;
    restir_wrs_init(&wrs);
    int chosen = -1;
    for (int j = 0; j < n; j++) {
        /* 004 Eq. 6 with |dT/dX| = 1 */
        float w = in[j]->y.tri >= 0 ? m[j] * P[j] * in[j]->W : 0.0f;
        if (restir_wrs_offer(&wrs, w, pcg32_float(rng)))
            chosen = j;
    }
    struct di_reservoir result;
    di_reservoir_clear(&result, restir_confidence_merge(c_sum, p->confidence_cap));
    if (chosen >= 0) {
        result.y = in[chosen]->y;
        result.target = P[chosen];
        result.W = restir_gris_contribution_weight(&wrs, result.target); /* 004 Eq. 7 */
        if (result.W <= 0.0f)
            di_reservoir_clear(&result, result.c);
    }
    *out = result;
    return rays;
}

long long di_temporal_pass(const struct scene *s, const struct render_params *p, int frame,
                           const struct gbuffer *g, const struct gbuffer *prev_g,
                           const struct di_reservoir *prev_res, struct di_reservoir *io, long long *rays)
{
    long long accepted = 0, traced = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : accepted, traced)
    for (int t = 0; t < ntiles; t++) {
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int i = px.i;
            int q = gbuffer_history_pixel(g, i, prev_g, p->temporal_normal, p->temporal_plane);
            if (q < 0)
                continue;
            const struct shading_point *sp[2] = {gbuffer_shading(g, i), gbuffer_shading(prev_g, q)};
            const struct di_reservoir *hist = &prev_res[q];
            if (p->temporal_ratio_guard && hist->y.tri >= 0) {
                /* 001 Sec. 5 guard: depends on the sample, hence BIASED (documented in --help). */
                float ratio = di_target(sp[0], &hist->y) / hist->target;
                if (!(ratio >= p->ratio_lo && ratio <= p->ratio_hi))
                    continue;
            }
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_DI_TEMPORAL);
            const struct di_reservoir *in[2] = {&io[i], hist};
            traced += gris_merge(s, p, 2, sp, in, &rng, &io[i]);
            accepted++;
        }
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
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
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
            rays += gris_merge(s, p, n, sp, src, &rng, &out[i]);
        }
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
