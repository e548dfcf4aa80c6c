/* boiling_filter.c: the outliers of each pixel group (boiling_filter.h). */
#include "render/boiling_filter.h"

#include <math.h>
#include <stddef.h>

long long boiling_filter_mark(float *weight, int width, int height, float strength)
{
    const int gw = (width + BOILING_FILTER_GROUP - 1) / BOILING_FILTER_GROUP;
    const int gh = (height + BOILING_FILTER_GROUP - 1) / BOILING_FILTER_GROUP;
    const float s = strength < 1e-6f ? 1e-6f : strength > 1.0f ? 1.0f : strength;
    const double factor = 10.0 / (double)s - 9.0; /* RTXDI: 41 at s = 0.2, 1 at s = 1 */
    long long marked = 0;
#pragma omp parallel for schedule(static) reduction(+ : marked)
    for (int grp = 0; grp < gw * gh; grp++) {
        const int x0 = (grp % gw) * BOILING_FILTER_GROUP, y0 = (grp / gw) * BOILING_FILTER_GROUP;
        const int x1 = x0 + BOILING_FILTER_GROUP < width ? x0 + BOILING_FILTER_GROUP : width;
        const int y1 = y0 + BOILING_FILTER_GROUP < height ? y0 + BOILING_FILTER_GROUP : height;
        double sum = 0.0;
        int count = 0;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                const float v = weight[(size_t)y * (size_t)width + (size_t)x];
                if (v > 0.0f && isfinite(v)) {
                    sum += (double)v;
                    count++;
                }
            }
        const double limit = count ? factor * sum / (double)count : 0.0;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                float *v = &weight[(size_t)y * (size_t)width + (size_t)x];
                if (!isfinite(*v) || (*v > 0.0f && (double)*v > limit)) {
                    *v = -1.0f;
                    marked++;
                }
            }
    }
    return marked;
}
