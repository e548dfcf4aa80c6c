/* test_animated_unbiased.c: scenes with animated emitters (scene/scene_animation.h) render
 * every frame under that frame's lights: K independently seeded runs of a method's first F frames,
 * static camera, against K runs of the direct-lighting (or full) pt rendered at frame F - 1 alone,
 * per pixel (Welch, Sidak) and pooled. tests/data/scenes/switch_lamp.json holds a steady lamp, a lamp
 * switched off at frame 2 and on again at 5 (step keys) and a lamp ramped linearly over frames 0-6.
 * Cases: pt itself (its lights follow the frame); ris-di, gpt and ris-gi (no history); restir-di,
 * whose temporal merge measures each domain under its own frame's lights (di_relight, merge_begin's
 * prev_scale), one frame after the switch-off (frame 3), right after the switch-on (frame 5) and after
 * the ramp (frame 7); restir-pt, restir-gi and grestir-pt, which drop their temporal reuse on a frame
 * whose lights changed (renderer_history_reusable), at frame 5 and restir-pt at 8 too.
 * The cases have power (seen): re-evaluating restir-di's previous domain under this frame's lights
 * fails frame 5 by -30% of the image mean and frame 7 by -17%; keeping the history of restir-pt across
 * the changes fails frame 5 by -30% and frame 8 by -16%, restir-gi's frame 5 by -7%, grestir-pt's by
 * -30%. tests/data/scenes/moving_lamp.json's lamp moves (translation and rotation keys, scene_motion.h):
 * pt renders the pose of the frame; restir-di keeps its history across the move, measuring the previous
 * domain where the lamp was, in that frame's geometry (scene_occluded_previous_batch); restir-pt drops
 * its history while it moves (renderer.h's lights_moved and lights_changed) and reuses it once it
 * stands. Power, seen: restir-di measuring the previous domain at the new pose fails frame 4 by -0.5%
 * (z -7.7) at the default confidence, by -4.5% at full confidence, and frame 8 by -1.8%; at the old pose
 * but in this frame's geometry, frames 4 and 8 at full confidence by +25% and +36%.
 * Bad keys (order, negative strength, an animation on a non-emitter, a scale, a channel missing from a
 * key) are refused by the reader: render.cli_errors. */
#include <stdio.h>
#include <stdlib.h>

#include "methods/settings.h"
#include "reference_pt.h"
#include "methods/renderer.h"
#include "scene/scene_animation.h"
#include "scene/scene_file.h"
#include "test_util.h"
#include "unbiased_util.h"

/* seconds alone on the 2-core machine of docs/BENCHMARKS.md: ctest starts the longest tests first */
#define TEST_COST_SECONDS 85

#define RUNS 1024
#define W 24
#define H 16

/* Whether the last frame must have reused history: REUSE_ANY (not checked), REUSE_NONE (no pixel
 * accepted a temporal neighbour: its lights changed) or REUSE_SOME (some did). */
enum reuse { REUSE_ANY, REUSE_NONE, REUSE_SOME };

/* Returns the number of pixels that fail; expects none (and |pooled z| < 4.5) when expect_unbiased, and
 * the last frame's temporal reuse as `reuse` says in every run. */
static int check_reuse(const struct scene *s, const char *method, int frames, const char *const *sets, int nsets,
                       int expect_unbiased, enum reuse reuse)
{
    const struct method *m = method_named(method);
    char msg[512];
    struct render_params p;
    render_params_defaults(&p);
    p.width = W;
    p.height = H;
    for (int k = 0; k < nsets; k++)
        EXPECT(render_params_set(&p, sets[k], msg) == 0, "%s", msg);
    EXPECT(method_check_settings(m, &p, s, msg) == 0, "%s: %s", method, msg);
    const struct camera cam = scene_camera_at(s, 0, 0.0f);
    struct pixel_stats a, b;
    int reused_wrong = 0; /* runs whose last frame reused history against `reuse` */
    pixel_stats_init(&a, W * H);
    pixel_stats_init(&b, W * H);
    for (int k = 0; k < RUNS; k++) {
        struct render_params q = p;
        q.seed = 5000 + (uint64_t)k;
        struct renderer r;
        renderer_init(&r, s, m, &q);
        struct frame_stats fs;
        for (int f = 0; f < frames; f++)
            renderer_render(&r, f, &cam, &fs);
        if (reuse != REUSE_ANY && (fs.temporal_accepted > 0) != (reuse == REUSE_SOME))
            reused_wrong++;
        pixel_stats_add(&a, r.image);
        renderer_fini(&r);
        /* the reference: pt over the method's integrand, pinned, 4 spp, at the last frame only */
        struct render_params rp = p;
        method_reference_params(m, &rp);
        reference_pt_pin(&rp);
        rp.spp = 4;
        rp.seed = 900000 + (uint64_t)k;
        renderer_init(&r, s, method_named("pt"), &rp);
        renderer_render(&r, frames - 1, &cam, &fs);
        pixel_stats_add(&b, r.image);
        renderer_fini(&r);
    }
    struct unbiased_report rep = unbiased_compare(&a, &b, 0.01);
    printf("%s %dx%d %s, %d runs of %d frames:", s->name, W, H, method, RUNS, frames);
    for (int k = 0; k < nsets; k++)
        printf(" %s", sets[k]);
    printf("\n  %d pixels, %d failed, worst |t| %.2f; pooled z %.2f, relative bias of the image mean %+.4f%%\n",
           rep.pixels_tested, rep.pixels_failed, rep.worst_t, rep.pooled_z, 100.0 * rep.mean_rel_bias);
    EXPECT(reused_wrong == 0, "%s, %d frames: in %d runs the last frame %s temporal reuse", method, frames,
           reused_wrong, reuse == REUSE_NONE ? "kept" : "had no");
    if (expect_unbiased) {
        EXPECT(rep.pixels_failed == 0, "%s, %d frames: %d pixels fail", method, frames, rep.pixels_failed);
        EXPECT(fabs(rep.pooled_z) < 4.5, "%s, %d frames: pooled z %.2f", method, frames, rep.pooled_z);
    }
    pixel_stats_free(&a);
    pixel_stats_free(&b);
    return rep.pixels_failed;
}

static int check(const struct scene *s, const char *method, int frames, const char *const *sets, int nsets,
                 int expect_unbiased)
{
    return check_reuse(s, method, frames, sets, nsets, expect_unbiased, REUSE_ANY);
}

int main(void)
{
    const char *data = getenv("RESTIR_TEST_DATA");
    if (!data)
        return test_skip("RESTIR_TEST_DATA is not set (run through ctest)");
    char path[1024], msg[512];
    snprintf(path, sizeof path, "%s/scenes/switch_lamp.json", data);
    struct scene s;
    EXPECT(scene_load(path, &s, msg) == 0, "%s", msg);
    EXPECT(scene_is_animated(&s), "switch_lamp.json has animated emitters");
    /* the keys as the file gives them: the switched lamp's material is 3, the ramp's 4 */
    EXPECT(emission_animation_at(&s.emission_anim[3], 1.0f) == 1.0f &&
               emission_animation_at(&s.emission_anim[3], 2.0f) == 0.0f &&
               emission_animation_at(&s.emission_anim[3], 4.9f) == 0.0f &&
               emission_animation_at(&s.emission_anim[3], 5.0f) == 1.0f,
           "step keys: on, off from frame 2, on from 5");
    EXPECT_NEAR(emission_animation_at(&s.emission_anim[4], 3.0f), 0.85f, 1e-6, "linear keys halfway");
    const char *none[] = {"spp=1"};
    check(&s, "pt", 4, none, 1, 1);
    const char *di[] = {"jitter=off"};
    check(&s, "ris-di", 4, di, 1, 1);
    const char *reuse[] = {"mis=pairwise", "jitter=off"};
    check(&s, "restir-di", 4, reuse, 2, 1);
    check(&s, "restir-di", 8, reuse, 2, 1);
    check(&s, "restir-di", 6, reuse, 2, 1);
    /* di.gradient_confidence (BIASED): history confidence from the samples' own temporal gradient;
     * measured right after the switch-on, not judged */
    const char *confidence[] = {"mis=pairwise", "jitter=off", "di.gradient_confidence=on"};
    check(&s, "restir-di", 6, confidence, 3, 0);
    /* The methods that drop their temporal reuse on a frame whose lights changed: right after the
     * switch-on (frame 5: no history taken), and restir-pt two frames after the ramp's end (frame 8:
     * history taken, from frames 6 and 7, shaded under the lights of frame 8). gpt and ris-gi reuse
     * nothing. */
    const char *walk[] = {"jitter=off"};
    check_reuse(&s, "restir-pt", 6, walk, 1, 1, REUSE_NONE);
    check_reuse(&s, "restir-pt", 9, walk, 1, 1, REUSE_SOME);
    check_reuse(&s, "restir-gi", 6, walk, 1, 1, REUSE_NONE);
    const char *l2[] = {"jitter=off", "recon=l2"};
    check_reuse(&s, "grestir-pt", 6, l2, 2, 1, REUSE_NONE);
    check(&s, "gpt", 4, l2, 2, 1);
    check(&s, "ris-gi", 4, walk, 1, 1);
    scene_destroy(&s);
    /* Moving emitters (moving_lamp.json: a lamp that translates and turns over frames 0-6, its
     * shadow of the box moving with it): pt mid-move; restir-di keeps its history while it moves
     * (frame 4, its confidence lowered to 1 by default; frame 8 after a whole move at full
     * confidence); restir-pt drops its history while it moves and takes it once it stands */
    snprintf(path, sizeof path, "%s/scenes/moving_lamp.json", data);
    EXPECT(scene_load(path, &s, msg) == 0, "%s", msg);
    check(&s, "pt", 3, none, 1, 1);
    check_reuse(&s, "restir-di", 5, reuse, 2, 1, REUSE_SOME);
    const char *whole[] = {"mis=pairwise", "jitter=off", "di.moved_confidence=1e6"};
    check_reuse(&s, "restir-di", 9, whole, 3, 1, REUSE_SOME);
    check_reuse(&s, "restir-pt", 5, walk, 1, 1, REUSE_NONE);
    check_reuse(&s, "restir-pt", 9, walk, 1, 1, REUSE_SOME);
    scene_destroy(&s);
    return test_finish();
}
