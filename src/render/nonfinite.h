/* nonfinite.h: the renderer's guard against NaN and infinity: after each pass that
 * produces radiance or weights, entries that are not finite are discarded (a reservoir is emptied
 * with its confidence kept, an image channel set to 0) and counted, so one bad value cannot spread
 * through reuse and the count shows in metrics.csv. */
#ifndef RESTIR_RENDER_NONFINITE_H
#define RESTIR_RENDER_NONFINITE_H

#include <stddef.h>

#include "render/di_sample.h"
#include "render/restir_pt.h"

/* Each returns how many entries it discarded. */
long long nonfinite_discard_di(struct di_reservoir *res, size_t n);
long long nonfinite_discard_pt(struct pt_reservoir *res, size_t n);
long long nonfinite_discard_rgb(float *rgb, size_t n_pixels);

#endif
