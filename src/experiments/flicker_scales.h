/* flicker_scales.h: the block sizes compare and study measure flicker at, and the measurement
 * (flicker_scales.c) both run on their run-major luminance sequences, so that their numbers mean the
 * same. Must never render: it measures the frames it is given. */
#ifndef RESTIR_EXPERIMENTS_FLICKER_SCALES_H
#define RESTIR_EXPERIMENTS_FLICKER_SCALES_H

/* Flicker (restir_metrics_flicker) at these block sizes in pixels, then the boiling index. */
#define FLICKER_SCALES 3
#define FLICKER_COLS (FLICKER_SCALES + 1)
extern const int flicker_block[FLICKER_SCALES];

/* out: flicker at each of flicker_block's sizes, normalised over the largest block, then the boiling
 * index (restir_metrics_boiling_index), of seq (runs sequences of `frames` luminance images of w x h,
 * run-major) against the reference reference_rgb (RGB, w x h; its Rec. 709 luminance, as the frames').
 * NaN where the metric is undefined (fewer than 2 frames, an image smaller than the largest block). */
void flicker_measure(const float *seq, int runs, int frames, int w, int h, const float *reference_rgb,
                     double out[FLICKER_COLS]);

#endif
