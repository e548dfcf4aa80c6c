/* sampling.c: warps from the unit square to the disk, hemisphere, triangle and sphere, and the
 * Walker/Vose alias table. Must never depend on scene, shading or render code. */
#include "core/sampling.h"

#include <math.h>
#include <stdlib.h>

#include "core/check.h"

#define QUARTER_PI 0.78539816339744830962f

/* Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", in the single-branch
 * form of Pharr, Jakob & Humphreys, PBRT 3rd ed., sec. 13.6.2: the square [-1,1]^2 is split
 * along its diagonals; concentric squares map to concentric circles, which keeps strata
 * compact and makes the map area-preserving (up to the factor pi). */
void warp_concentric_disk(float u1, float u2, float *x, float *y)
{
    float a = 2.0f * u1 - 1.0f;
    float b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f) {
        *x = 0.0f;
        *y = 0.0f;
        return;
    }
    float r, phi;
    if (fabsf(a) > fabsf(b)) {
        r = a;
        phi = QUARTER_PI * (b / a);
    } else {
        r = b;
        phi = 2.0f * QUARTER_PI - QUARTER_PI * (a / b);
    }
    *x = r * cosf(phi);
    *y = r * sinf(phi);
}

/* Inverts the two branches above: |x| >= |y| is exactly the image of |a| > |b| (phi within
 * pi/4 of the x axis, with r = a signed); otherwise r = b and phi lies within pi/4 of the y
 * axis. The signed radius picks the half-plane, so atan of the ratio recovers phi. */
void warp_concentric_disk_inverse(float x, float y, float *u1, float *u2)
{
    float r = sqrtf(x * x + y * y);
    float a, b;
    if (r == 0.0f) {
        a = 0.0f;
        b = 0.0f;
    } else if (fabsf(x) >= fabsf(y)) {
        a = copysignf(r, x);
        float phi = atanf(y / x); /* in [-pi/4, pi/4] */
        b = a * phi / QUARTER_PI;
    } else {
        b = copysignf(r, y);
        /* cos(phi) = x / b, sin(phi) = y / b with phi in [pi/4, 3pi/4]. */
        float phi = atan2f(y / b, x / b);
        a = b * (2.0f * QUARTER_PI - phi) / QUARTER_PI;
    }
    *u1 = 0.5f * (a + 1.0f);
    *u2 = 0.5f * (b + 1.0f);
}

/* Malley's method (PBRT 3rd ed., sec. 13.6.3): lifting a uniform disk point onto the
 * hemisphere gives density cos(theta)/pi. */
vec3 warp_cosine_hemisphere(float u1, float u2)
{
    float x, y;
    warp_concentric_disk(u1, u2, &x, &y);
    float z = sqrtf(fmaxf(0.0f, 1.0f - x * x - y * y));
    return v3(x, y, z);
}

float warp_cosine_hemisphere_pdf(vec3 local_dir) { return fmaxf(0.0f, local_dir.z) * RESTIR_INV_PI; }

/* Archimedes' hat-box theorem: z uniform in [-1,1] and phi uniform give a uniform sphere. */
vec3 warp_uniform_sphere(float u1, float u2)
{
    float z = 1.0f - 2.0f * u1;
    float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    float phi = 2.0f * RESTIR_PI * u2;
    return v3(r * cosf(phi), r * sinf(phi), z);
}

/* Vose 1991, "A Linear Algorithm for Generating Random Numbers with a Given Distribution
 * Function": buckets of height 1 are filled from a "small" list (scaled weight < 1) and topped
 * up by a "large" one, so each bucket holds at most two indices. Scaled weights are kept in
 * double so that the bookkeeping error stays far below float resolution for big tables. */
int alias_table_init(struct alias_table *t, const float *weights, int n)
{
    t->n = 0;
    t->bucket = NULL;
    t->pmf = NULL;
    t->total = 0.0;
    if (n < 1 || !weights)
        return -1;
    double total = 0.0;
    int heaviest = 0;
    for (int i = 0; i < n; i++) {
        float w = weights[i];
        if (!isfinite(w) || w < 0.0f)
            return -1;
        total += (double)w;
        if (w > weights[heaviest])
            heaviest = i;
    }
    if (!(total > 0.0) || !isfinite(total))
        return -1;

    t->n = n;
    t->total = total;
    t->bucket = xmalloc((size_t)n * sizeof *t->bucket);
    t->pmf = xmalloc((size_t)n * sizeof *t->pmf);
    double *scaled = xmalloc((size_t)n * sizeof *scaled);
    int *small = xmalloc((size_t)n * sizeof *small);
    int *large = xmalloc((size_t)n * sizeof *large);
    int ns = 0, nl = 0;
    for (int i = 0; i < n; i++) {
        double p = (double)weights[i] / total;
        t->pmf[i] = (float)p;
        scaled[i] = p * (double)n;
        t->bucket[i].alias = i;
        if (scaled[i] < 1.0)
            small[ns++] = i;
        else
            large[nl++] = i;
    }
    while (ns > 0 && nl > 0) {
        int s = small[--ns];
        int l = large[--nl];
        t->bucket[s].prob = (float)scaled[s];
        t->bucket[s].alias = l;
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0)
            small[ns++] = l;
        else
            large[nl++] = l;
    }
    /* Leftovers have scaled weight 1 up to rounding. A leftover with zero weight can only be
     * a rounding artefact; it must never be returned, so it defers entirely to the heaviest
     * index. */
    while (nl > 0) {
        int l = large[--nl];
        t->bucket[l].prob = 1.0f;
    }
    while (ns > 0) {
        int s = small[--ns];
        if (weights[s] > 0.0f) {
            t->bucket[s].prob = 1.0f;
        } else {
            t->bucket[s].prob = 0.0f;
            t->bucket[s].alias = heaviest;
        }
    }
    free(scaled);
    free(small);
    free(large);
    return 0;
}

void alias_table_fini(struct alias_table *t)
{
    free(t->bucket);
    free(t->pmf);
    t->bucket = NULL;
    t->pmf = NULL;
    t->n = 0;
    t->total = 0.0;
}
