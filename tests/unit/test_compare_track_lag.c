/* test_compare_track_lag.c: compare's lag after a change of the lights (compare_track_lag) on synthetic
 * frames of 4 blocks of 16 x 16 pixels, the lights changing at frame 4 of 12, every frame against a
 * reference of 1. Block 0's relMSE is 1.3 for frames 4-8 and 1 after, the other blocks' 1 throughout: the
 * whole image's relMSE (1.075 at most) is within 10% of its steady state 1 at once (lag 0), block 0
 * settles 5 frames after the change, and so does the 90% quantile over the 4 blocks (the largest). A
 * second run identical to the first leaves both unchanged (the sums are means over runs). The denoised
 * lags, without denoised frames, are NaN; so are the block lags of an image smaller than a block. The
 * ghost (compare_track_ghost): frames whose block 0 is 1.3 times the reference's for frames 4-6 and every
 * pixel +-0.5 in a checkerboard (noise: no block mean moves) settle 3 frames after the change, where the
 * relMSE lag of the blocks reads the noise; an offset that stays to the segment's end is the block's steady
 * deviation (a bias), not a ghost: 0. */
#include <math.h>
#include <stdlib.h>

#include "experiments/compare_track.h"
#include "test_util.h"

enum { FRAMES = 12, CHANGE = 4, W = 4 * COMPARE_LAG_BLOCK, H = COMPARE_LAG_BLOCK };

/* The ghost's frames: how many frames after the change block 0 stays 1.3 times too bright (FRAMES: always). */
static int ghost_frames = 0;

/* Frame f: every pixel 1 + d with d^2 / (1 + 1e-3) its block's relMSE term (the reference is 1); with
 * ghost_frames > 0, the ghost's frames instead. */
static void synthetic_frame(int f, float *img)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const double rel = x < COMPARE_LAG_BLOCK && f >= CHANGE && f < CHANGE + 5 ? 1.3 : 1.0;
            float v = (float)(1.0 + sqrt(rel * 1.001));
            if (ghost_frames > 0)
                v = (x < COMPARE_LAG_BLOCK && f >= CHANGE && f < CHANGE + ghost_frames ? 1.3f : 1.0f) +
                    ((x + y) % 2 ? 0.5f : -0.5f);
            float *p = &img[3 * (y * W + x)];
            p[0] = p[1] = p[2] = v;
        }
}

static void run_track(int w, int h, int runs, double *lag, double *block, double *lag_dn, double *block_dn,
                      double *ghost)
{
    const size_t n = (size_t)w * (size_t)h;
    float *ref = malloc(sizeof(float) * 3 * n), *img = malloc(sizeof(float) * 3 * (size_t)W * H);
    float *crop = malloc(sizeof(float) * 3 * n);
    for (size_t i = 0; i < 3 * n; i++)
        ref[i] = 1.0f;
    struct compare_track t;
    compare_track_init(&t, FRAMES, runs, 1, w, h, ref);
    for (int k = 0; k + 1 < t.nref; k++) { /* the earlier frames' references: the same image */
        t.ref[k] = malloc(sizeof(float) * 3 * n);
        for (size_t i = 0; i < 3 * n; i++)
            t.ref[k][i] = 1.0f;
    }
    t.nchanges = 1;
    t.change[0] = CHANGE;
    compare_track_begin(&t);
    for (int r = 0; r < runs; r++)
        for (int f = 0; f < FRAMES; f++) {
            synthetic_frame(f, img);
            for (int y = 0; y < h; y++) /* the top-left w x h of the synthetic frame */
                for (int x = 0; x < w; x++)
                    for (int c = 0; c < 3; c++)
                        crop[3 * (y * w + x) + c] = img[3 * (y * W + x) + c];
            compare_track_image(&t, r, f, crop);
        }
    compare_track_end(&t, "synthetic");
    compare_track_lag(&t, 0, lag, block);
    compare_track_lag(&t, 1, lag_dn, block_dn);
    compare_track_ghost(&t, 0, ghost);
    compare_track_fini(&t);
    free(ref);
    free(img);
    free(crop);
}

int main(void)
{
    double lag, block, lag_dn, block_dn, ghost;
    for (int runs = 1; runs <= 2; runs++) {
        run_track(W, H, runs, &lag, &block, &lag_dn, &block_dn, &ghost);
        EXPECT(lag == 0.0, "%d run(s): the image's lag %g, want 0 (within 10%% at once)", runs, lag);
        EXPECT(block == 5.0, "%d run(s): the blocks' 90%% lag %g, want block 0's 5", runs, block);
        EXPECT(isnan(lag_dn) && isnan(block_dn), "%d run(s): denoised lags %g %g without denoised frames", runs,
               lag_dn, block_dn);
    }
    run_track(COMPARE_LAG_BLOCK - 1, COMPARE_LAG_BLOCK - 1, 1, &lag, &block, &lag_dn, &block_dn, &ghost);
    EXPECT(isfinite(lag) && isnan(block), "an image smaller than a block: lag %g, block lag %g (want NaN)", lag,
           block);
    ghost_frames = 3;
    run_track(W, H, 2, &lag, &block, &lag_dn, &block_dn, &ghost);
    EXPECT(ghost == 3.0, "the ghost of block 0 fades after 3 frames: %g", ghost);
    ghost_frames = FRAMES;
    run_track(W, H, 1, &lag, &block, &lag_dn, &block_dn, &ghost);
    EXPECT(ghost == 0.0, "an offset that stays is a bias, not a ghost: %g, want 0", ghost);
    return test_finish();
}
