/* simd.c: run-time choice of the SoA kernels' instruction set (simd.h). */
#include "core/simd.h"

static int allowed = 1;

void simd_allow(int on)
{
    allowed = on != 0;
}

enum simd_isa simd_isa_active(void)
{
#if RESTIR_SIMD_DISPATCH
    if (allowed && __builtin_cpu_supports("avx2"))
        return SIMD_ISA_AVX2;
#endif
    return SIMD_ISA_BASELINE;
}

const char *simd_isa_name(enum simd_isa isa)
{
    return isa == SIMD_ISA_AVX2 ? "avx2" : "baseline";
}
