/* fuzz_poisson.c: libFuzzer harness for librestir's public screened Poisson solves
 * (restir/poisson.h) with fuzzed sizes, parameters and pixel values (NaN and infinities included):
 * every call returns 0 with finite output or -1 on bad arguments, never a crash, a sanitizer report
 * or a leak. The first 16 bytes are the arguments (alpha as raw float bits), the rest the images
 * (reused cyclically). Sizes stay under 48 x 48 so that each input takes milliseconds. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "restir/poisson.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 20)
        return 0;
    const int w = (int)(int8_t)data[0] % 48, h = (int)(int8_t)data[1] % 48; /* negatives and 0 too */
    float alpha;
    memcpy(&alpha, data + 2, 4);
    /* iteration counts stay small (each input a few milliseconds), negatives and 0 included */
    const int solver = data[6] % 3, iters = (int)(data[7] % 24) - 2, precond = data[8] % 3;
    const int steps = (int)(data[9] % 64) - 2;
    double tol = data[10] ? 1e-6 : 0.0;
    const int which = data[11] % 3;
    const uint8_t *img = data + 16;
    const size_t nimg = size - 16;
    const size_t n = w > 0 && h > 0 ? (size_t)w * (size_t)h * 3 : 1;
    float *buf = malloc(sizeof(float) * 4 * n);
    if (!buf)
        return 0;
    for (size_t k = 0; k < 3 * n; k++) { /* primal, dx, dy: two bytes each, in [-128, 128), or NaN / +-inf */
        const uint8_t lo = img[(2 * k) % nimg], hi = img[(2 * k + 1) % nimg];
        const float v = (float)(int16_t)(hi << 8 | lo) / 256.0f;
        buf[k] = lo == 0xff ? NAN : lo == 0xfe ? INFINITY : lo == 0xfd ? -INFINITY : v;
    }
    float *primal = buf, *dx = buf + n, *dy = buf + 2 * n, *out = buf + 3 * n;
    struct restir_poisson_stats st;
    int rc;
    if (which == 0)
        rc = restir_poisson_l2(w, h, primal, dx, dy, alpha, (enum restir_poisson_solver)solver, tol, iters, out, &st);
    else if (which == 1)
        rc = restir_poisson_l1(w, h, primal, dx, dy, alpha, iters, (enum restir_poisson_precond)precond, steps, out,
                               &st);
    else {
        const double e = restir_poisson_l1_energy(w, h, primal, dx, dy, alpha, primal);
        rc = isnan(e) ? -1 : 0;
    }
    if (rc != 0 && rc != -1)
        abort();
    if (rc == 0 && which < 2 && alpha >= 1e-3f && alpha <= 1e3f) /* (tiny alphas may overflow, as they should) */
        for (size_t k = 0; k < n; k++)
            if (!isfinite(out[k]))
                abort(); /* non-finite inputs read as 0: the output is finite */
    free(buf);
    return 0;
}
