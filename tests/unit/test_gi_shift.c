/* test_gi_shift.c: restir-gi's reconnection shift (gi_shift, render/restir_gi.h) on genuine initial
 * samples of cornell, ajar and a file scene with shading normals, in both radiance modes:
 *  - the identity shift (a sample into its own shading point) has Jacobian 1 and reproduces the
 *    cached target and f bit for bit;
 *  - a round trip a -> b -> a returns x2 and the seed unchanged, f within 1e-4 relative, and the
 *    two Jacobians multiply to 1 (1e-3): T_{b->a} inverts T_{a->b}, as GRIS needs;
 *  - gi.radiance=reevaluate traces the suffix again, so shifted radiance changes where x2 is
 *    glossy; gi.radiance=stored keeps Lo exactly;
 *  - the checks are not vacuous: many round trips, Jacobians far from 1, refused shifts seen. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/restir_gi/restir_gi.h"
#include "scene/scene_file.h"
#include "frame_fixture.h"
#include "test_util.h"
#include "methods/restir_gi/gi_settings.h"

#define WIDTH 32
#define HEIGHT 20

static float rel_diff(vec3 a, vec3 b)
{
    const float d = fmaxf(fabsf(a.x - b.x), fmaxf(fabsf(a.y - b.y), fabsf(a.z - b.z)));
    const float m = fmaxf(v3_max_component(a), v3_max_component(b));
    return m > 0.0f ? d / m : d;
}

static void check_scene(const char *name, enum gi_radiance_mode mode)
{
    struct scene s;
    struct render_params p;
    struct gbuffer g;
    struct camera_view view;
    if (frame_fixture(name, WIDTH, HEIGHT, 0, 11, &s, &p, &g, &view) != 0)
        return;
    gi_settings_mut(&p)->radiance = mode;
    const int n = WIDTH * HEIGHT;
    struct path_vertex *x1 = calloc((size_t)n, sizeof(*x1));
    vec3 *base = calloc((size_t)n, sizeof(vec3));
    struct gi_reservoir *res = calloc((size_t)n, sizeof(*res));
    const struct gi_frame fr = {&s, &p, &view, 0};
    gi_initial_pass(&fr, &g, x1, base, res);
    int identities = 0, trips = 0, refused = 0, changed = 0;
    double j_min = 1.0, j_max = 1.0;
    long long rays = 0;
    for (int a = 0; a < n; a++) {
        if (!gi_reservoir_has_sample(&res[a]))
            continue;
        struct gi_sample y, z;
        float J, Jb;
        if (gi_shift(&s, &p, &res[a].y, &x1[a], &y, &J, &rays)) {
            identities++;
            EXPECT(fabsf(J - 1.0f) < 1e-5f, "%s: identity shift has J = %g", name, J);
            EXPECT(v3_luminance(y.f) == res[a].target, "%s pixel %d: identity target %g, cached %g", name, a,
                   v3_luminance(y.f), res[a].target);
        }
        for (int k = 1; k <= 7; k += 3) { /* neighbors 1, 4 and 7 pixels to the right, wrapping */
            const int b = (a + k) % n;
            if (!gi_x1_valid(&x1[b]))
                continue;
            if (!gi_shift(&s, &p, &res[a].y, &x1[b], &y, &J, &rays)) {
                refused++;
                continue;
            }
            if (!gi_shift(&s, &p, &y, &x1[a], &z, &Jb, &rays)) {
                EXPECT(0, "%s: pixel %d -> %d -> %d: the way back is refused", name, a, b, a);
                continue;
            }
            trips++;
            j_min = fmin(j_min, J);
            j_max = fmax(j_max, J);
            EXPECT(!memcmp(&z.x2_p, &res[a].y.x2_p, sizeof(vec3)) && z.seed == res[a].y.seed,
                   "%s: round trip %d -> %d moved x2 or the seed", name, a, b);
            EXPECT(fabs((double)J * Jb - 1.0) < 1e-3, "%s: round trip %d -> %d: J J^-1 = %g", name, a, b,
                   (double)J * Jb);
            EXPECT(rel_diff(z.f, res[a].y.f) < 1e-4f, "%s: round trip %d -> %d: f off by %g", name, a, b,
                   rel_diff(z.f, res[a].y.f));
            if (mode == GI_RADIANCE_STORED)
                EXPECT(!memcmp(&y.Lo, &res[a].y.Lo, sizeof(vec3)), "%s: stored radiance changed by a shift", name);
            else
                changed += rel_diff(y.Lo, res[a].y.Lo) > 1e-3f;
        }
    }
    printf("%s (%s): %d identity shifts, %d round trips (J in [%.3g, %.3g]), %d refused, %d with re-traced "
           "radiance changed\n",
           name, mode == GI_RADIANCE_STORED ? "stored" : "reevaluate", identities, trips, j_min, j_max, refused,
           changed);
    EXPECT(identities > 20 && trips > 50, "%s: too few samples to judge (%d, %d)", name, identities, trips);
    EXPECT(j_max / j_min > 1.5, "%s: Jacobians all near 1 (%g .. %g): the check is vacuous", name, j_min, j_max);
    if (mode == GI_RADIANCE_REEVALUATE)
        EXPECT(changed > 0, "%s: reevaluate never changed a sample's radiance", name);
    free(x1);
    free(base);
    free(res);
    gbuffer_fini(&g);
    scene_destroy(&s);
}

int main(void)
{
    char smooth[1024];
    const char *data = getenv("RESTIR_TEST_DATA");
    snprintf(smooth, sizeof smooth, "%s/scenes/smooth.json", data ? data : "tests/data");
    const char *scenes[] = {"cornell", "ajar", smooth};
    for (int k = 0; k < 3; k++) {
        check_scene(scenes[k], GI_RADIANCE_REEVALUATE);
        check_scene(scenes[k], GI_RADIANCE_STORED);
    }
    return test_finish();
}
