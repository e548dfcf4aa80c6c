/* test_di_domain_targets.c: di_domain_target_many (render/di_visibility.h), the batched targets
 * that restir-di's standard and SPMIS reuse share (004 Eq. 10 with p_hat_{<-k} = p_hat_k V_k), gives
 * di_domain_target's values bit for bit and counts the same rays, on genuine initial samples of
 * many-lights and pillars shifted to other pixels' shading points: with and without visibility,
 * with vector kernels and baseline ones (simd=off), with Embree streams and single rays
 * (rays.streams=off), for batch sizes across the stream width, and with a third of the rays
 * traced in the previous frame's geometry (the same as this frame's: nothing moves). Not vacuous: some pairs are
 * occluded, some visible, some have no sample. */
#include <stdlib.h>
#include <string.h>

#include "core/simd.h"
#include "methods/restir_di/di_visibility.h"
#include "methods/restir_di/light_pool.h"
#include "methods/restir_di/restir_di.h"
#include "scene/scene_file.h"
#include "frame_fixture.h"
#include "test_util.h"
#include "methods/restir_di/di_settings.h"

#define WIDTH 48
#define HEIGHT 28
#define PAIRS (3 * WIDTH * HEIGHT)

static int same_bits(float a, float b) { return memcmp(&a, &b, sizeof(a)) == 0; }

static void check_scene(const char *name)
{
    struct scene s;
    struct render_params p;
    struct gbuffer g;
    struct camera_view view;
    if (frame_fixture(name, WIDTH, HEIGHT, 1, 5, &s, &p, &g, &view) != 0)
        return;
    const int n = WIDTH * HEIGHT;
    struct light_pool lp;
    light_pool_init(&lp, di_settings_of(&p)->light_candidates);
    light_pool_fill(&lp, &s, 5, 0);
    struct di_reservoir *res = calloc((size_t)n, sizeof(*res));
    di_initial_pass(&s, &lp, NULL, &p, 0, &g, res);
    /* pixel a's shading point with the sample of pixel a + k, k = 0, 3, 17: itself and others */
    static const struct shading_point *sp[PAIRS];
    static const struct di_sample *y[PAIRS];
    static float scalar[PAIRS], batch[PAIRS];
    static struct ray_query q[PAIRS];
    static int ray_entry[PAIRS];
    static unsigned char occluded[PAIRS], previous[PAIRS];
    for (int e = 0; e < PAIRS; e++)
        previous[e] = (unsigned char)(e % 3 == 1); /* still emitters: the previous frame's geometry is this one */
    const int shift[3] = {0, 3, 17};
    for (int e = 0; e < PAIRS; e++) {
        sp[e] = gbuffer_shading(&g, e % n);
        y[e] = &res[(e % n + shift[e / n]) % n].y;
    }
    for (int vis = 0; vis <= 1; vis++) {
        long long rays_scalar = 0;
        int occ = 0, positive = 0, none = 0;
        for (int e = 0; e < PAIRS; e++) {
            scalar[e] = di_domain_target(&s, vis, sp[e], y[e], &rays_scalar);
            occ += vis && di_target(sp[e], y[e]) > 0.0f && scalar[e] == 0.0f;
            positive += scalar[e] > 0.0f;
            none += y[e]->tri < 0;
        }
        EXPECT(positive > PAIRS / 10 && none > 0 && (!vis || occ > 0),
               "%s: %d positive, %d occluded, %d without sample: the pairs do not exercise the batch", name,
               positive, occ, none);
        for (int config = 0; config < 4; config++) {
            simd_allow(config & 1);
            scene_set_ray_streams(&s, (config >> 1) & 1);
            const int sizes[] = {1, 2, 63, 64, 65, 130, 257, PAIRS}; /* around RAY_STREAM_MAX (64) */
            for (int z = 0; z < 2 * (int)(sizeof(sizes) / sizeof(sizes[0])); z++) {
                const int m = sizes[z / 2], prev = z & 1;
                long long rays_scalar_m = 0, rays = 0;
                for (int e = 0; e < m; e++)
                    rays_scalar_m += vis && di_target(sp[e], y[e]) > 0.0f;
                rays = di_domain_target_many(&s, vis, m, sp, y, batch, prev ? previous : NULL, q, ray_entry, occluded);
                int diff = 0;
                for (int e = 0; e < m; e++)
                    diff += !same_bits(batch[e], scalar[e]);
                EXPECT(diff == 0, "%s vis %d simd %d streams %d previous %d: %d of %d batched targets differ", name, vis,
                       config & 1, (config >> 1) & 1, prev, diff, m);
                EXPECT(rays == rays_scalar_m, "%s vis %d: %lld rays counted for %d pairs, %lld one at a time", name,
                       vis, rays, m, rays_scalar_m);
            }
        }
        EXPECT(!vis || rays_scalar > 0, "%s: no shadow ray traced", name);
        printf("%s, visibility %d: %d pairs (%d positive, %d occluded, %d without sample) equal bit for bit\n", name,
               vis, PAIRS, positive, occ, none);
    }
    simd_allow(1);
    free(res);
    light_pool_fini(&lp);
    gbuffer_fini(&g);
    scene_destroy(&s);
}

int main(void)
{
    check_scene("many-lights");
    check_scene("pillars");
    return test_finish();
}
