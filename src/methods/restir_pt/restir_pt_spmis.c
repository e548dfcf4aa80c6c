/* restir_pt_spmis.c: stochastic pairwise MIS spatial reuse for ReSTIR PT (004 Algorithm 2): the
 * canonical weight m~_c by shifting the canonical path into N_c cell pixels (Eq. 18-19), then a
 * GRIS merge of the canonical path and N paths drawn by Eq. 17 and shifted in (Eq. 14-16).
 * Must never allocate per pixel. */
#include "methods/restir_pt/restir_pt.h"
#include "render/reuse_cells.h"
#include "render/tiles.h"
#include "restir/gris.h"

static struct pt_domain domain_of(const struct pt_frame *fr, const struct gbuffer *g, int i)
{
    return pt_pixel_domain(fr->view, i % g->width, i / g->width);
}

void pt_spmis_weights(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                      struct spmis_frame *f)
{
    const int n = g->width * g->height;
    const float cap = fr->p->reuse.confidence_cap;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        f->conf[i] = fminf(in[i].c, cap);
        /* 004 Eq. 17: c_i p_hat(X_i) W_i, with p_hat(X_i) the target cached in pixel i */
        f->weight[i] =
            pt_reservoir_has_sample(&in[i]) ? f->conf[i] * in[i].target * in[i].W : 0.0f; /* non-finite: 0 in cells */
    }
}

struct pt_canonical_ctx {
    const struct pt_frame *fr;
    const struct gbuffer *g;
    const struct pt_reservoir *in;
};

static int pt_canonical_has_sample(const void *ctx, int c)
{
    return pt_reservoir_has_sample(&((const struct pt_canonical_ctx *)ctx)->in[c]);
}

static float pt_canonical_target(const void *ctx, int c)
{
    return ((const struct pt_canonical_ctx *)ctx)->in[c].target;
}

/* p_hat_{<-i}(Y_c) = p_hat_i(T_i^{-1}(Y_c)) |dT_i^{-1}/dY| (Eq. 10): the canonical path shifted
 * into pixel i, 0 where the shift fails */
static float pt_canonical_target_from(const void *ctx, int c, int i, long long *rays)
{
    const struct pt_canonical_ctx *k = ctx;
    const struct pt_domain dc = domain_of(k->fr, k->g, c), di = domain_of(k->fr, k->g, i);
    struct path_sample z;
    float jb;
    if (!path_shift(k->fr->s, &k->fr->shift, &k->in[c].y, &dc, &di, &z, &jb, rays))
        return 0.0f;
    return v3_luminance(z.f) * jb;
}

long long pt_spmis_canonical_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                                  struct spmis_frame *f)
{
    const struct pt_canonical_ctx ctx = {fr, g, in};
    const struct spmis_canonical_ops ops = {&ctx, pt_canonical_has_sample, pt_canonical_target,
                                            pt_canonical_target_from, NULL}; /* one shift at a time */
    return spmis_canonical_pass(f, fr->p, fr->frame, g, &ops);
}

long long pt_spmis_reuse_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                              const struct spmis_frame *f, struct pt_reservoir *out)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct restir_spmis_draws draws;
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y, c = px.i;
            if (!g->valid[c]) {
                out[c] = in[c];
                continue;
            }
            struct restir_spmis_conf k;
            float merged_c;
            pcg32 rng = spmis_neighbor_plan(f, p, fr->frame, c, &k, &merged_c, &draws);
            spmis_prefetch_draws(&draws, in, sizeof in[0]);
            struct restir_reservoir wrs;
            restir_reservoir_init(&wrs);
            struct pt_reservoir result;
            pt_reservoir_clear(&result, merged_c);
            /* Algorithm 2 lines 11-12: the canonical sample with w~_c = m~_c p_hat(X_c) W_c (Eq. 14) */
            if (pt_reservoir_has_sample(&in[c]) &&
                restir_reservoir_offer(&wrs, restir_gris_resampling_weight(f->m_c[c], in[c].target, in[c].W, 1.0f),
                                       pcg32_float(&rng))) {
                result.y = in[c].y;
                result.target = in[c].target;
            }
            const struct pt_domain dc = pt_pixel_domain(fr->view, x, y);
            for (int d = 0; d < draws.count; d++) {
                /* Lines 13-18. Line 15 of the paper writes T_z(X_c); what is shifted is the drawn
                 * neighbor's own sample X_z into pixel c, as Eq. 14 says. */
                int z = draws.pixel[d];
                const struct pt_domain dz = domain_of(fr, g, z);
                struct path_sample yz;
                float jac;
                float wz = 0.0f;
                if (path_shift(fr->s, &fr->shift, &in[z].y, &dz, &dc, &yz, &jac, &rays)) {
                    float p_c = v3_luminance(yz.f);   /* p_hat(y) */
                    float p_from = in[z].target / jac; /* p_hat_{<-z}(y) = p_hat_z(X_z) / |dT_z/dX_z| */
                    /* Eq. 14 with Eq. 16 */
                    wz = (float)(restir_spmis_noncanonical(&k, f->conf[z], p_from, p_c, draws.factor[d]) * p_c *
                                 in[z].W * jac);
                }
                if (restir_reservoir_offer(&wrs, wz, pcg32_float(&rng))) {
                    result.y = yz;
                    result.target = v3_luminance(yz.f);
                }
            }
            result.W = restir_gris_contribution_weight(&wrs, result.target); /* line 19, Eq. 7 */
            if (!(result.W > 0.0f))
                pt_reservoir_clear(&result, result.c);
            out[c] = result;
        }
    }
    return rays;
}
