/* test_simd_kernels.c: the vector kernels chosen at run time (core/simd.h) give the scalar
 * functions' bits on both paths: bsdf_frame_eval_lanes = bsdf_frame_eval and di_target_many =
 * di_target for random shading points (Lambert, dielectric, metal, near-mirror alphas, backfacing
 * views), random light points, environment directions, "no sample" entries, coincident points
 * and NaN inputs, with AVX2 allowed (where the CPU has it) and with the baseline kernels only. */
#include <math.h>
#include <string.h>

#include "core/rng.h"
#include "core/simd.h"
#include "methods/restir_di/di_sample.h"
#include "shading/bsdf.h"
#include "test_util.h"

#define N 3000

static vec3 random_unit(pcg32 *r)
{
    for (;;) {
        vec3 v = v3(2.0f * pcg32_float(r) - 1.0f, 2.0f * pcg32_float(r) - 1.0f, 2.0f * pcg32_float(r) - 1.0f);
        float l2 = v3_length2(v);
        if (l2 > 1e-4f && l2 <= 1.0f)
            return v3_scale(v, 1.0f / sqrtf(l2));
    }
}

static void random_point(pcg32 *r, int k, struct shading_point *sp)
{
    memset(sp, 0, sizeof(*sp));
    const float roughness[] = {1.0f, 0.5f, 0.2f, 0.05f, 0.0f};
    struct material m = {.base_color = v3(pcg32_float(r), pcg32_float(r), pcg32_float(r)),
                         .metallic = (k % 3) == 0   ? 1.0f
                                     : (k % 3) == 1 ? 0.0f
                                                    : pcg32_float(r),
                         .roughness = roughness[k % 5],
                         .lambert_only = (k % 7) == 0};
    struct bsdf b;
    bsdf_from_material(&m, &b);
    sp->valid = (k % 11) != 0;
    sp->p = v3(4.0f * pcg32_float(r), 4.0f * pcg32_float(r), 4.0f * pcg32_float(r));
    sp->ng = random_unit(r);
    sp->n = v3_normalize(v3_madd(sp->ng, random_unit(r), 0.3f));
    sp->wo = random_unit(r); /* a quarter or so below the surface: bsdf frame invalid */
    bsdf_frame_init(&sp->bf, &b, sp->n, sp->wo);
}

static void random_sample(pcg32 *r, int k, const struct shading_point *sp, struct di_sample *y)
{
    memset(y, 0, sizeof(*y));
    y->tri = 5;
    y->Le = v3(10.0f * pcg32_float(r), 10.0f * pcg32_float(r), pcg32_float(r));
    if (k % 13 == 1) {
        y->tri = -1; /* no sample */
    } else if (k % 13 == 2) {
        y->tri = DI_ENV_TRI;
        y->p = random_unit(r);
        y->n = v3_neg(y->p);
    } else if (k % 13 == 3) {
        y->p = sp->p; /* coincident: d2 = 0 */
        y->n = random_unit(r);
    } else {
        y->p = v3(4.0f * pcg32_float(r), 4.0f * pcg32_float(r), 4.0f * pcg32_float(r));
        y->n = random_unit(r);
    }
    if (k % 97 == 5)
        y->p.x = NAN;
    if (k % 89 == 7)
        y->Le.y = INFINITY;
}

/* The same bits, or both NaN: which NaN (sign, payload) an operation returns depends on operand
 * order and optimization (seen: -O0 gives +NaN where -O3 gives -NaN), and nothing reads it. */
static int same_bits(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0 || (isnan(a) && isnan(b));
}

static void check_path(int allow)
{
    simd_allow(allow);
    const char *isa = simd_isa_name(simd_isa_active());
    printf("kernels on the %s path\n", isa);
    static struct shading_point sp[N];
    static struct di_sample y[N];
    static const struct shading_point *spp[N];
    static const struct di_sample *yp[N];
    static const struct bsdf_frame *bf[N];
    static float wx[N], wy[N], wz[N], fr[N], fg[N], fb[N], target[N];
    pcg32 r = rng_for(11, 0, 0, 0);
    for (int k = 0; k < N; k++) {
        random_point(&r, k, &sp[k]);
        random_sample(&r, k, &sp[k], &y[k]);
        /* pairs across pixels: sample k seen from another point */
        spp[k] = &sp[(k * 7) % N];
        yp[k] = &y[k];
        bf[k] = &sp[k].bf;
        vec3 w = random_unit(&r);
        wx[k] = w.x, wy[k] = w.y, wz[k] = w.z;
    }
    bsdf_frame_eval_lanes(N, bf, wx, wy, wz, fr, fg, fb);
    int bsdf_diff = 0, nonzero = 0;
    for (int k = 0; k < N; k++) {
        vec3 f = bsdf_frame_eval(bf[k], v3(wx[k], wy[k], wz[k]), NULL);
        bsdf_diff += !same_bits(f.x, fr[k]) || !same_bits(f.y, fg[k]) || !same_bits(f.z, fb[k]);
        nonzero += f.x > 0.0f;
    }
    EXPECT(bsdf_diff == 0, "%s: bsdf_frame_eval_lanes differs from bsdf_frame_eval in %d of %d lanes", isa,
           bsdf_diff, N);
    EXPECT(nonzero > N / 5, "%s: only %d of %d BSDF values positive: the cases do not exercise the lobes", isa,
           nonzero, N);
    di_target_many(N, spp, yp, target);
    int di_diff = 0, positive = 0, nan = 0;
    for (int k = 0; k < N; k++) {
        float t = di_target(spp[k], yp[k]);
        di_diff += !same_bits(t, target[k]);
        positive += t > 0.0f;
        nan += isnan(t);
    }
    EXPECT(di_diff == 0, "%s: di_target_many differs from di_target in %d of %d pairs", isa, di_diff, N);
    EXPECT(positive > N / 20 && nan > 0, "%s: %d positive and %d NaN targets: the cases do not exercise the kernel",
           isa, positive, nan);
    /* any count, any offset into the arrays */
    for (int n = 0; n <= 70; n += 7) {
        float t[71];
        di_target_many(n, spp + 13, yp + 13, t);
        for (int k = 0; k < n; k++)
            EXPECT(same_bits(t[k], target[13 + k]), "%s: di_target_many of %d pairs differs at %d", isa, n, k);
    }
    printf("%s: %d BSDF lanes, %d targets (%d positive, %d NaN) equal the scalar functions bit for bit\n", isa, N,
           N, positive, nan);
}

int main(void)
{
    check_path(1);
    check_path(0);
    EXPECT(simd_isa_active() == SIMD_ISA_BASELINE, "simd_allow(0) left %s active",
           simd_isa_name(simd_isa_active()));
    simd_allow(1);
    return test_finish();
}
