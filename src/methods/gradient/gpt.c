/* gpt.c: gradient-domain path tracing (see gpt.h; Kettunen et al. 2015, 002 Eq. 3).
 *
 * MIS between the two one-sided estimates of a pair. 002 Eq. 4 writes the balance heuristic on the
 * true path densities. We use the generalized balance heuristic on path contributions (002 Eq. 13)
 * for every method, as the public 002 code does for its inner shift: the true density of a shifted
 * path under the neighbor's sampler needs the densities of the offset's reconnection and of the
 * vertex after it (whose incoming direction changed), of its NEE/BSDF weight and of its Russian
 * roulette, which the compact path sample does not keep. Both weightings satisfy
 * omega_ab(x) + omega_ba(T x) = 1 on the shiftable set and omega = 1 elsewhere, so the estimator is
 * unbiased either way (proved by tests/render/test_gradient_unbiased.c); the variance differs.
 * Per candidate c of pixel a's walk with density p_c and NEE/BSDF weight m_c, the one-sided term
 * toward neighbor n is (m_c / p_c) omega_an(c) (f_a(c) - f_n(T c) |T'|); summed over the NEE/BSDF
 * strategies this is unbiased because omega does not depend on the strategy and the m_c of each
 * pixel sum to one. */
#include "methods/gradient/gpt.h"

#include "methods/gradient/grad_common.h"
#include "render/path_walk.h"
#include "render/tiles.h"
#include "scene/scene_env.h"
#include "shading/lights.h"

struct gpt_ctx {
    const struct scene *s;
    const struct shift_params *sp;
    const struct camera_view *view;
    int px, py, w, h;
    size_t i;
    float inv_spp;
    struct path_sample trial; /* u and seed of the walk */
    float *os;
    vec3 primal;
    long long rays;
};

static void candidate(void *vctx, const struct path_walk *w, const struct path_candidate *c)
{
    struct gpt_ctx *ctx = vctx;
    if (!(c->pdf > 0.0f))
        return;
    float weight = c->mis / c->pdf * ctx->inv_spp;
    ctx->primal = v3_add(ctx->primal, v3_scale(c->f, weight));
    struct path_sample x = ctx->trial;
    path_sample_from_candidate(ctx->s, ctx->sp, w, c, &x);
    ctx->rays += grad_one_sided_all(ctx->s, ctx->sp, ctx->view, &x, ctx->px, ctx->py, ctx->w, ctx->h, weight,
                                    ctx->os, ctx->i);
}

long long gpt_pass(const struct scene *s, const struct shift_params *sp, const struct camera_view *view,
                   const struct render_params *p, int frame, float *primal, float *emission, float *os)
{
    long long rays = 0;
    const int w = view->width, h = view->height, ntiles = tile_count(w, h);
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : rays)
    for (int t = 0; t < ntiles; t++) {
        struct path_walk walk;
        for (struct tile_pixel px = tile_first_pixel(w, h, t); px.i >= 0; tile_advance(&px)) {
            const int x = px.x, y = px.y;
            const size_t i = (size_t)px.i;
            pcg32 rng = rng_for(p->seed, (uint64_t)frame, (uint64_t)i, RNG_PASS_GPT);
            struct gpt_ctx ctx = {s, sp, view, x, y, w, h, i, 1.0f / (float)p->spp, {0}, os, v3s(0.0f), 0};
            vec3 Le = v3s(0.0f);
            for (int k = 0; k < p->spp; k++) {
                ctx.trial.u[0] = p->jitter ? pcg32_float(&rng) : 0.5f;
                ctx.trial.u[1] = p->jitter ? pcg32_float(&rng) : 0.5f;
                ctx.trial.seed = ((uint64_t)pcg32_next(&rng) << 32) | pcg32_next(&rng);
                float fx, fy;
                path_image_position(x, y, ctx.trial.u, &fx, &fy);
                vec3 d = camera_view_ray(view, fx, fy);
                struct surface_hit hit;
                ctx.rays++;
                if (!scene_intersect(s, view->position, d, 0.0f, INFINITY, &hit)) {
                    Le = v3_add(Le, v3_scale(scene_env_radiance(s, d), ctx.inv_spp)); /* the sky seen */
                    continue;
                }
                if (s->tri_emitter[hit.tri] >= 0 && hit.front)
                    Le = v3_add(Le, v3_scale(lights_radiance(s, hit.tri, hit.b1, hit.b2, v3_neg(d)), ctx.inv_spp));
                struct path_vertex x1 = path_vertex_from_hit(&hit, d);
                ctx.rays += path_walk_run(s, &x1, ctx.trial.seed, render_params_light_choice(p), p->max_bounces,
                                          p->rr_bounces, &walk, candidate, &ctx);
            }
            vec3 L = v3_is_finite(ctx.primal) ? ctx.primal : v3s(0.0f);
            primal[3 * i] = L.x + Le.x;
            primal[3 * i + 1] = L.y + Le.y;
            primal[3 * i + 2] = L.z + Le.z;
            emission[3 * i] = Le.x;
            emission[3 * i + 1] = Le.y;
            emission[3 * i + 2] = Le.z;
            rays += ctx.rays;
        }
    }
    return rays;
}
