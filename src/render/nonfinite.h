/* nonfinite.h: the renderer's guard against NaN and infinity: after each pass that
 * produces radiance or weights, entries that are not finite are discarded (a reservoir is emptied
 * with its confidence kept, an image channel set to 0) and counted, so one bad value cannot spread
 * through reuse and the count shows in metrics.csv. */
#ifndef RESTIR_RENDER_NONFINITE_H
#define RESTIR_RENDER_NONFINITE_H

#include <math.h>
#include <stddef.h>

/* A reservoir is kept when its W, target and confidence are finite; else its method empties it
 * (nonfinite_discard_di, nonfinite_discard_pt in the method folders), keeping a finite confidence (a
 * non-finite one becomes 0: a domain that produced nothing). */
static inline int nonfinite_reservoir_ok(float W, float target, float c)
{
    return isfinite(W) && isfinite(target) && isfinite(c);
}
static inline float nonfinite_kept_confidence(float c) { return isfinite(c) ? c : 0.0f; }

/* Defines `long long NAME(TYPE *res, size_t n)`: empties, with CLEAR(&res[i], kept confidence), every
 * reservoir of res[0..n) whose W, target or confidence is not finite, and returns how many (OpenMP).
 * TYPE has the members W, target and c. */
#define NONFINITE_DEFINE_DISCARD(NAME, TYPE, CLEAR)                                                                  \
    long long NAME(TYPE *res, size_t n)                                                                              \
    {                                                                                                                \
        long long bad = 0;                                                                                           \
        _Pragma("omp parallel for schedule(static) reduction(+ : bad)") for (long long i = 0; i < (long long)n; i++) \
        {                                                                                                            \
            if (!nonfinite_reservoir_ok(res[i].W, res[i].target, res[i].c)) {                                        \
                CLEAR(&res[i], nonfinite_kept_confidence(res[i].c));                                                 \
                bad++;                                                                                               \
            }                                                                                                        \
        }                                                                                                            \
        return bad;                                                                                                  \
    }

/* Sets every non-finite channel of rgb (3 floats per pixel) to 0; returns how many it set. */
long long nonfinite_discard_rgb(float *rgb, size_t n_pixels);

#endif
