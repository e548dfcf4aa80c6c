/* restir/threads.h: how many threads librestir's own parallel loops use. Only the whole-image
 * functions run in parallel (restir_cells_build, restir_cells_pack_taps and the Poisson solves of
 * restir/poisson.h); every per-sample function runs on its caller's thread. In a librestir built
 * without OpenMP (RESTIR_WITH_OPENMP=OFF) every function runs on the calling thread only. */
#ifndef RESTIR_THREADS_H
#define RESTIR_THREADS_H

#ifdef __cplusplus
extern "C" {
#endif

/* Sets the thread count of the library's parallel loops for every call that starts after this
 * returns, process-wide (an atomic store; safe to call from any thread):
 *   0      OpenMP's own choice at the time of each call (omp_get_max_threads(): OMP_NUM_THREADS or
 *          the cores), the default;
 *   1      the calling thread only: what an engine with its own job system wants, calling
 *          librestir from its workers;
 *   n > 1  n threads per parallel loop.
 * A parallel function called from inside an OpenMP parallel region runs on the calling thread
 * unless the application enabled nested parallelism. Returns 0, or -1 (nothing changed) for
 * n < 0. Without OpenMP any n >= 0 is accepted and ignored. */
int restir_threads_set(int n);

/* The number of threads a parallel loop started now would ask for (>= 1; 1 without OpenMP). */
int restir_threads_get(void);

#ifdef __cplusplus
}
#endif

#endif
