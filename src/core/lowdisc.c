/* lowdisc.c: the R2 sequence on the unit disk (see lowdisc.h). */
#include "core/lowdisc.h"

#include <math.h>

#include "core/sampling.h"

void r2_disk_offsets(int n, float *xy)
{
    /* The plastic number g solves g^3 = g + 1; R2 steps by (1/g, 1/g^2). Doubles keep the
     * fractional parts exact enough for 8192 points. */
    const double g = 1.32471795724474602596;
    const double a1 = 1.0 / g, a2 = 1.0 / (g * g);
    for (int i = 0; i < n; i++) {
        double u = 0.5 + a1 * i, v = 0.5 + a2 * i;
        u -= floor(u);
        v -= floor(v);
        warp_concentric_disk((float)u, (float)v, &xy[2 * i], &xy[2 * i + 1]);
    }
}
