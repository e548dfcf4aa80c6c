/* restir/metrics.h: image error metrics against a reference, defined once for the whole project
 * (DESIGN.md "Metrics"). Images are interleaved RGB floats, row-major.
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_METRICS_H
#define RESTIR_METRICS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

struct restir_error {
    double relmse; /* mean over pixels and channels of (I - R)^2 / (R^2 + 1e-3) */
    double mape;   /* 004: mean over pixels and channels of |I - R| / (R + 0.01 mean(R)) */
    double smape;  /* 000 footnote 3: 100 mean over pixels of |I - R| / (|I| + |R| + 1e-4), luminance */
    double luma_rmse; /* sqrt(mean over pixels of (lum(I) - lum(R))^2) */
};

/* Computes all metrics over n_pixels RGB pixels; mask (may be NULL) selects pixels with nonzero
 * entries. Returns 0, or -1 if no pixel is selected. */
int restir_error_compute(const float *image, const float *reference, size_t n_pixels,
                         const unsigned char *mask, struct restir_error *out);

/* Text with the definitions above, for --help. */
const char *restir_metrics_help(void);

#ifdef __cplusplus
}
#endif

#endif
