/* bench_error.c: `restir_bench error IMAGE.exr REF.exr`: the error metrics of one image against a
 * reference (DESIGN.md's relMSE, MAPE and SMAPE, restir/metrics.h), the ratio of their image
 * means, and HDR-FLIP at the default viewing condition with its wall time and OpenMP threads, one
 * line of name-value pairs, for scripts that compare images rendered elsewhere (references with a
 * relMSE target, Blender Cycles' renders in bench/cycles) and for FLIP's cost (BENCHMARKS.md). */
#include <omp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_common.h"
#include "io/exr.h"
#include "restir/metrics.h"

int bench_error(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: restir_bench error IMAGE.exr REF.exr (RGB of the default layer, the same size)\n");
        return 2;
    }
    char msg[1024];
    float *img = NULL, *ref = NULL;
    int w, h, rw, rh;
    if (exr_read_rgb(argv[1], &img, &w, &h, msg) != 0 || exr_read_rgb(argv[2], &ref, &rw, &rh, msg) != 0) {
        fprintf(stderr, "restir_bench error: %s\n", msg);
        free(img);
        return 1;
    }
    int rc = 0;
    struct restir_metrics_error e;
    if (w != rw || h != rh) {
        fprintf(stderr, "restir_bench error: %s is %dx%d, %s is %dx%d\n", argv[1], w, h, argv[2], rw, rh);
        rc = 1;
    } else if (restir_metrics_compute(img, ref, (size_t)w * (size_t)h, NULL, &e) != 0) {
        fprintf(stderr, "restir_bench error: no pixels\n");
        rc = 1;
    } else {
        double si = 0.0, sr = 0.0;
        for (size_t i = 0; i < 3 * (size_t)w * (size_t)h; i++)
            si += img[i], sr += ref[i];
        double flip = NAN;
        const double t0 = omp_get_wtime();
        if (restir_metrics_flip(img, ref, w, h, RESTIR_METRICS_FLIP_PPD, NULL, &flip) != 0)
            flip = NAN;
        const double flip_s = omp_get_wtime() - t0;
        printf("relMSE %.6g MAPE %.6g SMAPE %.6g mean_ratio %.6f FLIP %.6g flip_s %.3f threads %d\n", e.relmse, e.mape,
               e.smape, sr > 0.0 ? si / sr : 0.0, flip, flip_s, omp_get_max_threads());
    }
    free(img);
    free(ref);
    return rc;
}
