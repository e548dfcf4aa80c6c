/* bench_common.c: what the benchmarks share: loading a built-in scene and rendering a converged
 * reference with pt. Must never be run by the tests. */
#include "bench_common.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "methods/pt/pt.h"
#include "scene/scene_file.h"

struct scene bench_load_scene(const char *name)
{
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_load(name, &s, msg) != 0) {
        fprintf(stderr, "restir_bench: %s\n", msg);
        exit(1);
    }
    return s;
}

float *bench_reference(const struct scene *s, const struct method *method, const struct render_params *p, float frame,
                       int use_path, int spp)
{
    struct render_params rp = *p;
    method_reference_params(method, &rp);
    rp.seed = 0xbe4c4ull;
    struct camera cam = scene_camera_at(s, use_path, frame);
    struct camera_view view;
    camera_view_init(&view, &cam, rp.width, rp.height);
    size_t n = 3 * (size_t)rp.width * (size_t)rp.height;
    float *sum = xcalloc(n, sizeof(float)), *chunk = xcalloc(n, sizeof(float));
    for (int done = 0, c = 0; done < spp; c++) {
        int k = spp - done < 32 ? spp - done : 32;
        pt_pass(s, &view, &rp, 2000000 + c, k, chunk);
        for (size_t i = 0; i < n; i++)
            sum[i] += chunk[i] * (float)k / (float)spp;
        done += k;
    }
    free(chunk);
    return sum;
}

