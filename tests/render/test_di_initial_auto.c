/* test_di_initial_auto.c: restir-di's di.initial=auto takes ReGIR's grid in a frame whose grid fill is
 * at most DI_AUTO_REGIR_MAX_FILL_SHARE of the pixels' own candidates, else the pool: on many-lights at
 * 24x16 (share 4.6, docs/BENCHMARKS.md) its frames are bit for bit di.initial=pool's, and at 640x360
 * (share 0.076) di.initial=regir's; each differs from the other choice's. Three frames, so that the
 * temporal and spatial passes see the choice's reservoirs. */
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "methods/renderer.h"
#include "methods/settings.h"
#include "scene/scenes_builtin.h"
#include "test_util.h"

/* The third frame of restir-di with `initial` at w x h, into a new buffer (the caller frees it). */
static float *third_frame(const struct scene *s, int w, int h, const char *initial)
{
    struct render_params p;
    char msg[RESTIR_MSG_LEN], set[64];
    render_params_defaults(&p);
    p.width = w;
    p.height = h;
    p.seed = 11;
    snprintf(set, sizeof set, "di.initial=%s", initial);
    EXPECT(render_params_set(&p, set, msg) == 0, "%s", msg);
    const struct method *m = method_named("restir-di");
    EXPECT(method_check_settings(m, &p, s, msg) == 0, "%s", msg);
    const struct camera cam = scene_camera_at(s, 0, 0.0f);
    struct renderer r;
    renderer_init(&r, s, m, &p);
    struct frame_stats st;
    for (int f = 0; f < 3; f++)
        renderer_render(&r, f, &cam, &st);
    float *img = malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    memcpy(img, r.image, sizeof(float) * 3 * (size_t)w * (size_t)h);
    renderer_fini(&r);
    return img;
}

static void check_size(const struct scene *s, int w, int h, const char *same, const char *other)
{
    float *a = third_frame(s, w, h, "auto"), *b = third_frame(s, w, h, same), *c = third_frame(s, w, h, other);
    const size_t bytes = sizeof(float) * 3 * (size_t)w * (size_t)h;
    EXPECT(memcmp(a, b, bytes) == 0, "%dx%d: di.initial=auto's frame is not di.initial=%s's", w, h, same);
    EXPECT(memcmp(a, c, bytes) != 0, "%dx%d: di.initial=auto's frame is di.initial=%s's too", w, h, other);
    printf("many-lights %dx%d: di.initial=auto renders what di.initial=%s does\n", w, h, same);
    free(a);
    free(b);
    free(c);
}

int main(void)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_create_builtin("many-lights", &s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return test_finish();
    }
    check_size(&s, 24, 16, "pool", "regir");
    check_size(&s, 640, 360, "regir", "pool");
    scene_destroy(&s);
    return test_finish();
}
