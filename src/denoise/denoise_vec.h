/* denoise_vec.h: float vectors of DV_LANES lanes (GCC and Clang vector extensions) for the filters'
 * tap loops, which keep a block of pixels' centre features and sums in registers across all of a
 * kernel's taps (loading each centre once instead of once per tap). A translation unit sets
 * DV_LANES before including this (8 by default): 8 lanes fill one AVX2 register in a function
 * compiled for AVX2 and FMA (DV_TARGET_AVX2) and two SSE2 ones in the baseline; 16 lanes one
 * AVX-512 register (SIMD_TARGET_AVX512, svgf_taps512.c). Every helper is always inlined into such a
 * function, never called across the ABI, whose vector passing differs between instruction sets
 * (the files that use this are compiled with -Wno-psabi, which silences the compilers' note on it).
 * They are also compiled with -ffp-contract=fast (CMakeLists.txt): where the target has FMA,
 * a * b + c contracts to it, so the twins' results differ from the baseline's by rounding (the
 * denoisers are not estimators; their tests compare with a tolerance). Internal to src/denoise. */
#ifndef RESTIR_DENOISE_DENOISE_VEC_H
#define RESTIR_DENOISE_DENOISE_VEC_H

#include <stdint.h>
#include <string.h>

#include "core/simd.h"
#include "denoise/denoise_kernel.h"

/* The 8-lane AVX2 twin, with FMA; take it only where dv_avx2_fma() says so. */
#define DV_TARGET_AVX2 __attribute__((target("avx2,fma")))
#if RESTIR_SIMD_DISPATCH
static inline int dv_avx2_fma(void)
{
    return simd_isa_active() >= SIMD_ISA_AVX2 && __builtin_cpu_supports("fma");
}
#endif

#ifndef DV_LANES
#define DV_LANES 8
#endif
typedef float dv_f __attribute__((vector_size(4 * DV_LANES)));
typedef int32_t dv_i __attribute__((vector_size(4 * DV_LANES)));

SIMD_INLINE dv_f dv_load(const float *p)
{
    dv_f v;
    memcpy(&v, p, sizeof(v));
    return v;
}

SIMD_INLINE void dv_store(float *p, dv_f v) { memcpy(p, &v, sizeof(v)); }

SIMD_INLINE dv_f dv_splat(float a) { return (dv_f){0} + a; }

/* m ? a : b per lane; m from a vector comparison (all bits set or none). */
SIMD_INLINE dv_f dv_select(dv_i m, dv_f a, dv_f b) { return (dv_f)((m & (dv_i)a) | (~m & (dv_i)b)); }

SIMD_INLINE dv_f dv_abs(dv_f a) { return (dv_f)((dv_i)a & 0x7fffffff); }

/* denoise_exp2_neg(-x) per lane for x >= 0 (the same polynomial, evaluated by Estrin's scheme for a
 * shorter dependency chain): 2^-x, exactly 0 for x above -DENOISE_EXP2_CUT, and for NaN. */
SIMD_INLINE dv_f dv_exp2_neg(dv_f x)
{
    const dv_i keep = x <= -DENOISE_EXP2_CUT;
    const dv_f y = dv_select(keep, -x, dv_splat(DENOISE_EXP2_CUT));
    const dv_f t = y + 12582912.0f;
    const dv_f f = y - (t - 12582912.0f), f2 = f * f;
    const dv_f p = (1.0f + f * 0.693147182f) +
                   f2 * ((0.240226507f + f * 0.0555041087f) +
                         f2 * ((0.00961812911f + f * 0.00133335581f) + f2 * 0.000154035304f));
    const dv_f scale = (dv_f)(((dv_i)t - 0x4B400000 + 127) << 23);
    return (dv_f)((dv_i)(p * scale) & keep);
}

#endif
