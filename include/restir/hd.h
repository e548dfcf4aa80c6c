/* restir/hd.h: what lets the per-sample functions of librestir's headers compile as C, C++ and CUDA
 * device code from one source. RESTIR_HD marks a function defined in a public header: static inline
 * in C and C++, and also __host__ __device__ under nvcc, so a CUDA kernel calls the same code as
 * the CPU. Those functions use only <math.h> functions that CUDA provides on the device (sqrtf,
 * expf, powf, fabsf) and no library state. */
#ifndef RESTIR_HD_H
#define RESTIR_HD_H

#include <float.h>
#include <math.h>

#if defined(__CUDACC__)
#define RESTIR_HD static inline __host__ __device__
#else
#define RESTIR_HD static inline
#endif

/* 1 when x is neither NaN nor infinite (isfinite without the C / C++ / CUDA differences). */
RESTIR_HD int restir_hd_finite(float x)
{
    return fabsf(x) <= FLT_MAX;
}

/* x when it is a finite positive number, else 0: how weights, confidences and targets that are
 * negative, NaN or infinite are read wherever a header says so. */
RESTIR_HD float restir_hd_weight(float x)
{
    return restir_hd_finite(x) && x > 0.0f ? x : 0.0f;
}

#endif
