/* svgf_taps.c: SVGF's kernels (svgf_taps.h) on 8 lanes, for the SSE2 baseline and AVX2 with FMA,
 * and the choice among them and svgf_taps512.c's AVX-512 twins (svgf_kernels.h). */
#include "denoise/svgf_taps.h"

static void atrous_base(const struct svgf_pass *p, int y)
{
    p->radius == 1 ? svgf_row(p, y, SVGF_ATROUS3) : svgf_row(p, y, SVGF_ATROUS);
}
static void moments_base(const struct svgf_pass *p, int y) { svgf_row(p, y, SVGF_MOMENTS); }

#if RESTIR_SIMD_DISPATCH
DV_TARGET_AVX2 static void atrous_avx2(const struct svgf_pass *p, int y)
{
    p->radius == 1 ? svgf_row(p, y, SVGF_ATROUS3) : svgf_row(p, y, SVGF_ATROUS);
}

DV_TARGET_AVX2 static void moments_avx2(const struct svgf_pass *p, int y)
{
    svgf_row(p, y, SVGF_MOMENTS);
}
#endif

/* The twin of the instruction set simd_isa_active() names (AVX2 only with FMA). */
#if RESTIR_SIMD_DISPATCH
#define SVGF_PICK(avx512, avx2, base)                                                                             \
    (simd_isa_active() == SIMD_ISA_AVX512 ? (avx512) : dv_avx2_fma() ? (avx2) : (base))
#else
#define SVGF_PICK(avx512, avx2, base) (base)
#endif

svgf_row_fn svgf_atrous_row(void) { return SVGF_PICK(svgf_atrous_row_avx512, atrous_avx2, atrous_base); }

svgf_row_fn svgf_moments_row(void) { return SVGF_PICK(svgf_moments_row_avx512, moments_avx2, moments_base); }
