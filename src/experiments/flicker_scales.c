/* flicker_scales.c: flicker at compare's and study's block sizes (flicker_scales.h). */
#include "experiments/flicker_scales.h"

#include <stdlib.h>

#include "core/check.h"
#include "core/vec3.h"
#include "restir/metrics.h"

const int flicker_block[FLICKER_SCALES] = {1, 4, 16};

void flicker_measure(const float *seq, int runs, int frames, int w, int h, const float *reference_rgb,
                     double out[FLICKER_COLS])
{
    const size_t npix = (size_t)w * (size_t)h;
    float *ref = xmalloc(sizeof(float) * (npix ? npix : 1));
    for (size_t i = 0; i < npix; i++)
        ref[i] = v3_luminance(v3(reference_rgb[3 * i], reference_rgb[3 * i + 1], reference_rgb[3 * i + 2]));
    for (int k = 0; k < FLICKER_SCALES; k++)
        out[k] = restir_metrics_flicker(seq, runs, frames, w, h, ref, flicker_block[k],
                                        flicker_block[FLICKER_SCALES - 1]);
    out[FLICKER_SCALES] = restir_metrics_boiling_index(out[0], out[FLICKER_SCALES - 1]);
    free(ref);
}
