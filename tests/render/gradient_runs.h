/* gradient_runs.h: one unbiasedness case of the gradient-domain methods of 002 (gpt,
 * grad-after-restir, grestir-pt), shared by test_gradient_unbiased.c and
 * test_gradient_unbiased_scenes.c: K independently seeded camera-path runs of a method, whose
 * primal, dx, dy and L2 reconstruction are compared per pixel (Welch, Sidak-corrected) and over the
 * image (pooled z) with K path-traced references from the last camera and their forward
 * differences. L1 is BIASED by design and is measured (printed), never asserted. */
#ifndef RESTIR_TEST_GRADIENT_RUNS_H
#define RESTIR_TEST_GRADIENT_RUNS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "methods/settings.h"
#include "reference_pt.h"
#include "methods/gradient/grad_method.h"
#include "unbiased_runs.h"

#define GRADIENT_FRAMES 3
#define GRADIENT_FRAME_STEP 6
#define GRADIENT_REF_SPP 8
#define GRADIENT_WIDTH 16
#define GRADIENT_HEIGHT 10
#define GRADIENT_ALPHA 0.01
#define GRADIENT_POOLED_Z_MAX 4.5

/* L1 is measured, never asserted: it is biased by design (its weights depend on the samples). */
enum layer { L_PRIMAL, L_DX, L_DY, L_L2, L_L1, LAYERS };
static const char *const layer_names[LAYERS] = {"primal", "dx", "dy", "L2 reconstruction",
                                                "L1 reconstruction (BIASED, measured only)"};

/* Forward differences of an RGB image (the last column of dx and last row of dy are 0). */
static inline void forward_differences(const float *img, int w, int h, float *dx, float *dy)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                int i = y * w + x;
                dx[3 * i + c] = x + 1 < w ? img[3 * (i + 1) + c] - img[3 * i + c] : 0.0f;
                dy[3 * i + c] = y + 1 < h ? img[3 * (i + w) + c] - img[3 * i + c] : 0.0f;
            }
}

/* The path-traced reference from the last camera: runs 0 .. runs-1 of the reference cache, with
 * their forward differences. */
static inline void gradient_run_reference(const struct scene *s, const struct render_params *base, int runs,
                                          struct pixel_stats *st)
{
    const int n = base->width * base->height;
    float *dx = malloc(sizeof(float) * 3 * (size_t)n), *dy = malloc(sizeof(float) * 3 * (size_t)n);
    struct render_params q = *base;
    reference_pt_pin(&q);
    q.spp = GRADIENT_REF_SPP;
    struct camera cam = scene_camera_at(s, 1, (float)((GRADIENT_FRAMES - 1) * GRADIENT_FRAME_STEP));
    const float *images = reference_cache_runs(s, &q, &cam, NULL, runs);
    for (int k = 0; k < runs; k++) {
        const float *img = images + (size_t)k * 3 * (size_t)n;
        forward_differences(img, q.width, q.height, dx, dy);
        pixel_stats_add(&st[L_PRIMAL], img);
        pixel_stats_add(&st[L_DX], dx);
        pixel_stats_add(&st[L_DY], dy);
        pixel_stats_add(&st[L_L2], img);
        pixel_stats_add(&st[L_L1], img);
    }
    free(dx);
    free(dy);
}

static inline void gradient_run_method(const struct scene *s, const struct method *m,
                                       const struct render_params *base, int runs, struct pixel_stats *st)
{
    for (int k = 0; k < runs; k++) {
        struct render_params p = *base;
        p.seed = 1000 + (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, m, &p);
        for (int f = 0; f < GRADIENT_FRAMES; f++) {
            struct frame_stats fs;
            struct camera cam = scene_camera_at(s, 1, (float)(f * GRADIENT_FRAME_STEP));
            renderer_render(&r, f, &cam, &fs);
        }
        pixel_stats_add(&st[L_PRIMAL], grad_method_frame(&r)->primal);
        pixel_stats_add(&st[L_DX], grad_method_frame(&r)->dx);
        pixel_stats_add(&st[L_DY], grad_method_frame(&r)->dy);
        pixel_stats_add(&st[L_L2], grad_method_frame(&r)->l2);
        if (grad_method_frame(&r)->l1)
            pixel_stats_add(&st[L_L1], grad_method_frame(&r)->l1);
        renderer_fini(&r);
    }
}

/* Returns the number of pixels failing over all layers. */
static inline int gradient_check(const char *scene_name, const char *method, int runs, const char *const *sets,
                                 int nsets, int expect_unbiased)
{
    struct scene s;
    char msg[512];
    const struct method *m = method_find(method);
    if (scene_load(scene_name, &s, msg) != 0 || !m) {
        EXPECT(0, "%s", !m ? "unknown method" : msg);
        return 1;
    }
    struct render_params p;
    render_params_defaults(&p);
    p.width = GRADIENT_WIDTH;
    p.height = GRADIENT_HEIGHT;
    EXPECT(render_params_set(&p, "pt.max_bounces=4", msg) == 0, "%s", msg);
    for (int k = 0; k < nsets; k++)
        EXPECT(render_params_set(&p, sets[k], msg) == 0, "%s", msg);
    struct pixel_stats ref[LAYERS], got[LAYERS];
    for (int l = 0; l < LAYERS; l++) {
        pixel_stats_init(&ref[l], GRADIENT_WIDTH * GRADIENT_HEIGHT);
        pixel_stats_init(&got[l], GRADIENT_WIDTH * GRADIENT_HEIGHT);
    }
    const clock_t start = clock();
    gradient_run_reference(&s, &p, runs, ref);
    gradient_run_method(&s, m, &p, runs, got);
    printf("%s %dx%d %s, %d runs of %d frames (%.1f CPU-s):", scene_name, GRADIENT_WIDTH, GRADIENT_HEIGHT, method,
           runs, GRADIENT_FRAMES, (double)(clock() - start) / CLOCKS_PER_SEC);
    for (int k = 0; k < nsets; k++)
        printf(" %s", sets[k]);
    printf("\n");
    int failed = 0;
    for (int l = 0; l < LAYERS; l++) {
        if (got[l].runs == 0) /* L1 only with recon=l1|both */
            continue;
        printf(" %s:\n", layer_names[l]);
        struct unbiased_report rep = unbiased_compare(&got[l], &ref[l], GRADIENT_ALPHA);
        if (l == L_L1) /* measured, never asserted */
            continue;
        failed += rep.pixels_failed;
        if (expect_unbiased) {
            EXPECT(rep.pixels_failed == 0, "%s %s %s: %d pixels fail", scene_name, method, layer_names[l],
                   rep.pixels_failed);
            EXPECT(fabs(rep.pooled_z) < GRADIENT_POOLED_Z_MAX, "%s %s %s: pooled z = %.2f", scene_name, method,
                   layer_names[l], rep.pooled_z);
        }
    }
    for (int l = 0; l < LAYERS; l++) {
        pixel_stats_free(&ref[l]);
        pixel_stats_free(&got[l]);
    }
    scene_destroy(&s);
    return failed;
}

#endif
