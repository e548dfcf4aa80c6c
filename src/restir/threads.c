/* threads.c: the thread count of librestir's parallel loops (restir/threads.h). */
#include "restir/threads.h"

#include <stdatomic.h>

#ifdef _OPENMP
#include <omp.h>
#endif

static atomic_int threads_requested; /* 0: OpenMP's own choice */

int restir_threads_set(int n)
{
    if (n < 0)
        return -1;
    atomic_store(&threads_requested, n);
    return 0;
}

int restir_threads_get(void)
{
#ifdef _OPENMP
    int n = atomic_load(&threads_requested);
    return n > 0 ? n : omp_get_max_threads();
#else
    return 1;
#endif
}
