/* lowdisc.c: the R2 sequence on the unit disk (see lowdisc.h). */
#include "core/lowdisc.h"

#include <math.h>
#include <pthread.h>

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

static float r2_table[2 * R2_DISK_OFFSETS];
static pthread_once_t r2_table_once = PTHREAD_ONCE_INIT;

static void r2_table_fill(void) { r2_disk_offsets(R2_DISK_OFFSETS, r2_table); }

const float *r2_disk_table(void)
{
    /* 8192 sincos per renderer cost 0.4 ms each time one started (4% of a test rendering
     * thousands of small runs); the points never change. */
    pthread_once(&r2_table_once, r2_table_fill);
    return r2_table;
}
