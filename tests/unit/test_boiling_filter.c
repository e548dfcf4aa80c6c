/* test_boiling_filter.c: render/boiling_filter.h's outlier marks (RTXDI's rule): the
 * threshold 10 / s - 9 times the group's mean non-zero weight, empty reservoirs left out of the mean,
 * groups of 8 x 8 from the top-left corner (smaller at the edges), non-finite weights marked. */
#include <math.h>
#include <stdlib.h>

#include "render/boiling_filter.h"
#include "test_util.h"

int main(void)
{
    /* 10 x 9 pixels: groups (0,0) 8x8, (1,0) 2x8, (0,1) 8x1, (1,1) 2x1 */
    enum { W = 10, H = 9 };
    float w[W * H];
    for (int i = 0; i < W * H; i++)
        w[i] = 1.0f;
    /* group (0,0): 63 ones and one value v; mean (63 + v) / 64; marked when v > 41 mean, v > 41 * 63 / 23 */
    const float limit = 41.0f * 63.0f / 23.0f; /* 112.30... */
    w[3 * W + 4] = limit * 1.001f;
    w[5 * W + 9] = 5.0f; /* group (1,0): 15 ones and a 5: mean 1.25, limit 51.25: kept */
    w[8 * W + 2] = 0.0f; /* group (0,1): an empty reservoir, not counted */
    w[8 * W + 3] = 100.0f; /* ... mean of the 7 non-empty (6 + 100) / 7 = 15.1: 100 < 620, kept */
    w[8 * W + 9] = NAN;  /* group (1,1): non-finite, marked */
    long long n = boiling_filter_mark(w, W, H, 0.2f);
    EXPECT(n == 2, "marked %lld, want 2 (the outlier and the NaN)", n);
    EXPECT(w[3 * W + 4] == -1.0f, "the outlier above 41x its group's mean is marked");
    EXPECT(w[5 * W + 9] == 5.0f && w[8 * W + 3] == 100.0f && w[8 * W + 2] == 0.0f, "the others are kept");
    EXPECT(w[8 * W + 9] == -1.0f, "a NaN weight is marked");
    /* just below the limit: kept */
    for (int i = 0; i < W * H; i++)
        w[i] = 1.0f;
    w[3 * W + 4] = limit * 0.999f;
    EXPECT(boiling_filter_mark(w, W, H, 0.2f) == 0, "just below 41x the mean is kept");
    /* strength 1: factor 1, every weight above its group's mean is marked */
    for (int i = 0; i < W * H; i++)
        w[i] = (i % 2) ? 2.0f : 1.0f;
    n = boiling_filter_mark(w, W, H, 1.0f);
    EXPECT(n == W * H / 2, "strength 1 marks the %d values above the mean: %lld", W * H / 2, n);
    /* a lone sample in its group is never an outlier of itself */
    float one[1] = {1e30f};
    EXPECT(boiling_filter_mark(one, 1, 1, 0.2f) == 0 && one[0] == 1e30f, "a lone sample is kept");
    return test_finish();
}
