/* simd.h: which vector instruction set the structure-of-arrays kernels run with, chosen at run
 * time. The project builds for plain x86-64 (SSE2) unless RESTIR_NATIVE is asked for; the hot
 * kernels (initial RIS's candidate batches, the reuse merges' targets across pixels) are compiled
 * a second time for AVX2 (SIMD_TARGET_AVX2) and take that path when the CPU has it. Both paths do
 * the same float operations in the same order (ISO C mode: no FMA contraction), so they give the
 * same bits; tests run both (simd_allow). The denoisers' tap kernels, outside every estimator, also
 * have an AVX-512 twin (SIMD_TARGET_AVX512) and contract to FMA (src/denoise/denoise_vec.h); on an
 * AVX-512 CPU every other kernel takes its AVX2 path. */
#ifndef RESTIR_CORE_SIMD_H
#define RESTIR_CORE_SIMD_H

enum simd_isa {
    SIMD_ISA_BASELINE = 0, /* what the build targets (SSE2 on x86-64) */
    SIMD_ISA_AVX2,
    SIMD_ISA_AVX512, /* AVX-512F with AVX2 and FMA */
};

#if defined(__x86_64__) && defined(__GNUC__)
#define RESTIR_SIMD_DISPATCH 1
/* A kernel's AVX2 twin: the same source compiled for AVX2 (no FMA: the same roundings). */
#define SIMD_TARGET_AVX2 __attribute__((target("avx2")))
/* An AVX-512 twin (the denoisers' only): 16-lane vectors, FMA. */
#define SIMD_TARGET_AVX512 __attribute__((target("avx512f,avx2,fma")))
#else
#define RESTIR_SIMD_DISPATCH 0
#define SIMD_TARGET_AVX2
#define SIMD_TARGET_AVX512
#endif
/* A kernel body that each twin inlines, so each is compiled for its own instruction set. */
#define SIMD_INLINE static inline __attribute__((always_inline))

/* The best instruction set the CPU has, up to the limit simd_allow / simd_limit set. Kernels with
 * an AVX2 twin take it where this is SIMD_ISA_AVX2 or above. */
enum simd_isa simd_isa_active(void);
/* on = 0: baseline kernels only (`--set simd=off`, and the tests of both paths); 1: the best the
 * CPU has. Process-wide. */
void simd_allow(int on);
/* The best the CPU has up to max (the tests of each path). Process-wide. */
void simd_limit(enum simd_isa max);
/* "avx512", "avx2" or "baseline". */
const char *simd_isa_name(enum simd_isa isa);

#endif
