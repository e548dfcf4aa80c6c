/* svgf_taps512.c: SVGF's kernels (svgf_taps.h) on 16 lanes, one AVX-512 register each: twice the
 * pixels per instruction of the AVX2 twin, and 32 registers, so a block's centre and sums never
 * spill. svgf_taps.c chooses them where the CPU has AVX-512F. */
#define DV_LANES 16
#include "denoise/svgf_taps.h"

#if RESTIR_SIMD_DISPATCH
SIMD_TARGET_AVX512 void svgf_atrous_row_avx512(const struct svgf_pass *p, int y)
{
    p->radius == 1 ? svgf_row(p, y, SVGF_ATROUS3) : svgf_row(p, y, SVGF_ATROUS);
}

SIMD_TARGET_AVX512 void svgf_moments_row_avx512(const struct svgf_pass *p, int y) { svgf_row(p, y, SVGF_MOMENTS); }
#endif
