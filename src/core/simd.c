/* simd.c: run-time choice of the SoA kernels' instruction set (simd.h). */
#include "core/simd.h"

static enum simd_isa limit = SIMD_ISA_AVX512;

void simd_allow(int on)
{
    limit = on ? SIMD_ISA_AVX512 : SIMD_ISA_BASELINE;
}

void simd_limit(enum simd_isa max)
{
    limit = max;
}

enum simd_isa simd_isa_active(void)
{
#if RESTIR_SIMD_DISPATCH
    if (limit >= SIMD_ISA_AVX512 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2") &&
        __builtin_cpu_supports("fma"))
        return SIMD_ISA_AVX512;
    if (limit >= SIMD_ISA_AVX2 && __builtin_cpu_supports("avx2"))
        return SIMD_ISA_AVX2;
#endif
    return SIMD_ISA_BASELINE;
}

const char *simd_isa_name(enum simd_isa isa)
{
    return isa == SIMD_ISA_AVX512 ? "avx512" : isa == SIMD_ISA_AVX2 ? "avx2" : "baseline";
}
