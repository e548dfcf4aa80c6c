/* restir/reservoir.h: streaming weighted reservoir sampling (WRS), independent of what a sample is: the
 * caller keeps the sample, the reservoir decides which candidate wins. Per-sample functions, callable
 * from C, C++ and CUDA device code (restir/hd.h); a reservoir is the caller's value, and one
 * reservoir must not be updated from two threads at once. */
#ifndef RESTIR_RESERVOIR_H
#define RESTIR_RESERVOIR_H

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A reservoir after `offered` candidates with weights w_i: candidate i is `selected` with
 * probability w_i / w_sum (Chao 1982). */
struct restir_reservoir {
    float w_sum;  /* sum of the positive finite weights offered */
    int selected; /* index of the selected candidate among those offered, -1 if none */
    int offered;  /* number of candidates offered */
};

/* Empties r (no candidate, w_sum 0). A NULL r is ignored. */
RESTIR_HD void restir_reservoir_init(struct restir_reservoir *r)
{
    if (!r)
        return;
    r->w_sum = 0.0f;
    r->selected = -1;
    r->offered = 0;
}

/* Offers the next candidate with resampling weight w, deciding with u uniform in [0,1). Returns 1
 * when it becomes the selection (the caller then stores its sample), else 0. A weight that is 0,
 * negative, NaN or infinite counts as offered and is never selected; a NaN u selects nothing;
 * a NULL r returns 0.
 * Why it is exact: once w_sum includes w, the candidate replaces the selection with probability
 * w / w_sum, which by induction leaves candidate i selected with probability w_i / sum_j w_j. */
RESTIR_HD int restir_reservoir_offer(struct restir_reservoir *r, float w, float u)
{
    if (!r)
        return 0;
    int index = r->offered++;
    if (!restir_hd_finite(w) || !(w > 0.0f))
        return 0; /* never wins and never pollutes w_sum */
    r->w_sum += w;
    if (u * r->w_sum < w) {
        r->selected = index;
        return 1;
    }
    return 0;
}

/* Merges reservoir b, which summarizes a stream of its own, into a: b's selection is taken with
 * probability b.w_sum / (a.w_sum + b.w_sum), u uniform in [0,1). Returns 1 when it is taken (the
 * caller then copies b's sample into a's). b's stream counts as appended after a's: a.offered
 * grows by b.offered, and a taken selection is re-indexed to a.offered_before + b.selected. A b
 * with no selection or a w_sum that is not finite and positive is never taken (its candidates
 * still count as offered). NULL a or b returns 0 and changes nothing. */
RESTIR_HD int restir_reservoir_merge(struct restir_reservoir *a, const struct restir_reservoir *b, float u)
{
    if (!a || !b)
        return 0;
    int base = a->offered;
    a->offered += b->offered;
    if (b->selected < 0 || !restir_hd_finite(b->w_sum) || !(b->w_sum > 0.0f))
        return 0;
    a->w_sum += b->w_sum;
    if (u * a->w_sum < b->w_sum) {
        a->selected = base + b->selected;
        return 1;
    }
    return 0;
}

#ifdef __cplusplus
}
#endif

#endif
