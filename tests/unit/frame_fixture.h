/* frame_fixture.h: what the unit tests of reuse kernels set up first: a built-in or file scene,
 * default render parameters at width x height, and the jittered G-buffer of the scene camera's
 * frame 0 (jitter streams from `seed`). The caller frees the G-buffer and the scene. */
#ifndef RESTIR_TESTS_FRAME_FIXTURE_H
#define RESTIR_TESTS_FRAME_FIXTURE_H

#include <stdint.h>

#include "methods/settings.h"
#include "render/gbuffer.h"
#include "render/params.h"
#include "scene/scene_file.h"
#include "test_util.h"

/* Returns 0, or -1 (after a failed EXPECT naming why) when the scene does not load. */
static inline int frame_fixture(const char *name, int width, int height, int with_shading, uint64_t seed,
                                struct scene *s, struct render_params *p, struct gbuffer *g, struct camera_view *view)
{
    char msg[512];
    if (scene_load(name, s, msg) != 0) {
        EXPECT(0, "%s", msg);
        return -1;
    }
    render_params_defaults(p);
    p->width = width;
    p->height = height;
    gbuffer_init(g, width, height, with_shading);
    struct camera cam = scene_camera_at(s, 0, 0.0f);
    camera_view_init(view, &cam, width, height);
    gbuffer_pass(g, s, view, NULL, 1, seed, 0);
    return 0;
}

#endif
