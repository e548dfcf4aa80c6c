/* restir_pt_spmis.c: stochastic pairwise MIS spatial reuse for ReSTIR PT (004 Algorithm 2): the
 * canonical weight m~_c by shifting the canonical path into N_c cell pixels (Eq. 18-19), then a
 * GRIS merge of the canonical path and N paths drawn by Eq. 17 and shifted in (Eq. 14-16).
 * Must never allocate per pixel. */
#include "restir_pt.h"

#include "restir/reservoir.h"
#include "reuse_cells.h"
#include "tiles.h"

static struct pt_domain domain_of(const struct pt_frame *fr, const struct gbuffer *g, int i)
{
    return pt_pixel_domain(fr->view, i % g->width, i / g->width);
}

void pt_spmis_weights(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                      struct spmis_frame *f)
{
    const int n = g->width * g->height;
    const float cap = fr->p->confidence_cap;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        f->conf[i] = fminf(in[i].c, cap);
        /* 004 Eq. 17: c_i p_hat(X_i) W_i, with p_hat(X_i) the target cached in pixel i */
        f->weight[i] = pt_reservoir_has_sample(&in[i]) ? f->conf[i] * in[i].target * in[i].W : 0.0f; /* non-finite: 0 in cells */
    }
}

long long pt_spmis_canonical_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                                  struct spmis_frame *f)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        struct restir_spmis_draws draws;
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                int c = y * w + x;
                f->m_c[c] = 1.0f;
                if (!g->valid[c] || !pt_reservoir_has_sample(&in[c]))
                    continue; /* Algorithm 2 line 6: only a contributing canonical needs m~_c */
                struct restir_spmis_conf k;
                spmis_canonical_plan(f, p, fr->frame, c, &k, &draws);
                const struct pt_domain dc = pt_pixel_domain(fr->view, x, y);
                const float p_c = in[c].target; /* p_hat(Y_c) */
                double m_c = restir_spmis_canonical_share(&k);
                for (int d = 0; d < draws.count; d++) {
                    int i = draws.pixel[d];
                    const struct pt_domain di = domain_of(fr, g, i);
                    struct path_sample z;
                    float jb;
                    float p_from = 0.0f; /* p_hat_{<-i}(Y_c) = p_hat_i(T_i^{-1}(Y_c)) |dT_i^{-1}/dY| (Eq. 10) */
                    if (path_shift(fr->s, &fr->shift, &in[c].y, &dc, &di, &z, &jb, &rays))
                        p_from = v3_luminance(z.f) * jb;
                    m_c += restir_spmis_canonical_term(&k, f->conf[i], p_from, p_c, draws.factor[d]);
                }
                f->m_c[c] = (float)m_c;
            }
        }
    }
    return rays;
}

long long pt_spmis_reuse_pass(const struct pt_frame *fr, const struct gbuffer *g, const struct pt_reservoir *in,
                              const struct spmis_frame *f, struct pt_reservoir *out)
{
    const struct render_params *p = fr->p;
    long long rays = 0;
    const int w = g->width, h = g->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct tile_range r = tile_get(w, h, t);
        struct restir_spmis_draws draws;
        for (int y = r.y0; y < r.y1; y++) {
            for (int x = r.x0; x < r.x1; x++) {
                int c = y * w + x;
                if (!g->valid[c]) {
                    out[c] = in[c];
                    continue;
                }
                struct restir_spmis_conf k;
                float merged_c;
                pcg32 rng = spmis_neighbor_plan(f, p, fr->frame, c, &k, &merged_c, &draws);
                struct restir_wrs wrs;
                restir_wrs_init(&wrs);
                struct pt_reservoir result;
                pt_reservoir_clear(&result, merged_c);
                /* Algorithm 2 lines 11-12: the canonical sample with w~_c = m~_c p_hat(X_c) W_c (Eq. 14) */
                if (pt_reservoir_has_sample(&in[c]) &&
                    restir_wrs_offer(&wrs, f->m_c[c] * in[c].target * in[c].W, pcg32_float(&rng))) {
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
                    if (restir_wrs_offer(&wrs, wz, pcg32_float(&rng))) {
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
    }
    return rays;
}
