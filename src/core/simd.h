/* simd.h: which vector instruction set the structure-of-arrays kernels run with, chosen at run
 * time. The project builds for plain x86-64 (SSE2) unless RESTIR_NATIVE is asked for; the hot
 * kernels (initial RIS's candidate batches, the reuse merges' targets across pixels) are compiled
 * a second time for AVX2 (SIMD_TARGET_AVX2) and take that path when the CPU has it. Both paths do
 * the same float operations in the same order (ISO C mode: no FMA contraction), so they give the
 * same bits; tests run both (simd_allow). */
#ifndef RESTIR_CORE_SIMD_H
#define RESTIR_CORE_SIMD_H

enum simd_isa {
    SIMD_ISA_BASELINE = 0, /* what the build targets (SSE2 on x86-64) */
    SIMD_ISA_AVX2,
};

#if defined(__x86_64__) && defined(__GNUC__)
#define RESTIR_SIMD_DISPATCH 1
/* A kernel's AVX2 twin: the same source compiled for AVX2 (no FMA: the same roundings). */
#define SIMD_TARGET_AVX2 __attribute__((target("avx2")))
#else
#define RESTIR_SIMD_DISPATCH 0
#define SIMD_TARGET_AVX2
#endif
/* A kernel body that each twin inlines, so each is compiled for its own instruction set. */
#define SIMD_INLINE static inline __attribute__((always_inline))

/* The instruction set the kernels use now: AVX2 where the CPU has it and simd_allow has not
 * turned it off, else the baseline. */
enum simd_isa simd_isa_active(void);
/* on = 0: baseline kernels only (`--set simd=off`, and the tests of both paths); 1: the best the
 * CPU has. Process-wide. */
void simd_allow(int on);
/* "avx2" or "baseline". */
const char *simd_isa_name(enum simd_isa isa);

#endif
