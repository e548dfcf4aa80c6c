/* svgf_kernels.h: SVGF's two cross-bilateral pixel kernels, vectorised across pixels (svgf_taps.h,
 * compiled per instruction set by svgf_taps.c and svgf_taps512.c): the à-trous iteration of Sec.
 * 4.3 (Eq. 1-5) and the 7x7 moments filter of Sec. 4.2 for short histories. Internal to
 * src/denoise; svgf.c drives them. */
#ifndef RESTIR_DENOISE_SVGF_KERNELS_H
#define RESTIR_DENOISE_SVGF_KERNELS_H

#include "denoise/denoise_method.h"

/* What one pass of a kernel reads and writes. */
struct svgf_pass {
    const struct denoise_frame *f;
    const float *val[4]; /* à-trous: colour planes and variance; moments: the temporal moments m1, m2 */
    const float *lum;    /* à-trous: luminance of val[0..2] */
    const float *invl;   /* à-trous: log2(e) / (sigma_l sqrt(g_3x3(Var)) + eps), Eq. 5 */
    int lum_symmetric;   /* à-trous: Eq. 5's term by the mean of the centre's and the tap's deviations */
    const float *len;    /* moments: history length; pixels with len < short_history are filtered */
    float short_history;
    float *out[4];       /* à-trous: filtered colour and variance (Eq. 1-2); moments: out[0] = variance */
    int step;            /* à-trous: 2^iteration */
    int radius;          /* à-trous: 2, the paper's 5x5 kernel, or 1, the 3x3 of denoise.svgf.kernel=3 */
    float sz_ln2, eps_ln2; /* sigma_z and Eq. 3's eps (relative to depth) times ln 2 */
    float nd_min, sn;      /* sigma_n and the normal product below which n.n'^sigma_n counts as 0 */
};

/* One image row y of a pass; rows are independent (one per OpenMP iteration). */
typedef void (*svgf_row_fn)(const struct svgf_pass *p, int y);

/* The rows of the instruction set simd_isa_active() names. */
svgf_row_fn svgf_atrous_row(void);
svgf_row_fn svgf_moments_row(void);

#if RESTIR_SIMD_DISPATCH
/* svgf_taps512.c */
void svgf_atrous_row_avx512(const struct svgf_pass *p, int y);
void svgf_moments_row_avx512(const struct svgf_pass *p, int y);
#endif

#endif
