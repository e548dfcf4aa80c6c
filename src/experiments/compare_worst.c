/* compare_worst.c: the image of a gradient method's worst pairs (compare_worst.h). Issue 42: the gradient relMSE
 * (002 Fig. 7 as a number) divides each pair's error by the pair's own mean squared, so ~1% of the pairs carry
 * most of it; this shows where they are. Must never render. */
#include "experiments/compare_worst.h"

#include <stdio.h>
#include <stdlib.h>

#include "core/check.h"
#include "io/png.h"
#include "restir/metrics.h"

int compare_write_worst_pairs(const char *out_dir, const char *dir, const float *dx, const float *dy, const float *ref,
                              int width, int height, double fraction, char *msg)
{
    const size_t npix = (size_t)width * (size_t)height;
    unsigned char *mask = xmalloc(npix), *rgb = xmalloc(3 * npix);
    int rc = -1;
    if (restir_metrics_gradient_worst_pairs(dx, dy, ref, width, height, fraction, mask) < 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: cannot rank the gradient pairs (%dx%d)", dir, width, height);
        goto done;
    }
    encode_srgb8(ref, npix, 0.0f, rgb);
    static const unsigned char paint[4][3] = {{0, 0, 0}, {255, 0, 0}, {0, 255, 255}, {255, 255, 255}};
    for (size_t i = 0; i < npix; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + (size_t)c] = mask[i] ? paint[mask[i] & 3][c] : (unsigned char)(rgb[3 * i + (size_t)c] / 3);
    char path[4400];
    snprintf(path, sizeof path, "%s/%s%s", out_dir, dir, COMPARE_WORST_SUFFIX);
    rc = png_write_rgb8(path, rgb, width, height, msg);
done:
    free(mask);
    free(rgb);
    return rc;
}
