/* neighbors.c: G-buffer compatibility tests for spatial neighbor selection (000 Sec. 3).
 * Must never depend on a ray tracer, files or the renderer. */
#include "restir/neighbors.h"

#include <math.h>

int restir_bitterli_compatible(const float n[3], const float n_i[3], float d, float d_i, float normal_min,
                               float depth_max)
{
    /* 000 Eq. 7 */
    float dot = n[0] * n_i[0] + n[1] * n_i[1] + n[2] * n_i[2];
    return dot >= normal_min && d > 0.0f && fabsf(d_i - d) / d < depth_max;
}
