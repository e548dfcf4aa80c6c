/* restir/reservoir.c: streaming weighted reservoir sampling, reservoir merging, GRIS contribution
 * weights. Must never depend on a ray tracer, files, the renderer or anything else in src/. */
#include <math.h>

#include "restir/reservoir.h"

void restir_wrs_init(struct restir_wrs *r)
{
    r->w_sum = 0.0f;
    r->selected = -1;
    r->offered = 0;
}

/* Chao 1982 streaming WRS (004 Sec. 2.2): after the running sum includes w, the new candidate
 * replaces the current selection with probability w / w_sum, which by induction leaves every
 * candidate i selected with probability w_i / sum_j w_j. */
int restir_wrs_offer(struct restir_wrs *r, float w, float u)
{
    int index = r->offered++;
    if (!isfinite(w) || !(w > 0.0f))
        return 0; /* a zero, negative or non-finite weight never wins and never pollutes w_sum */
    r->w_sum += w;
    if (u * r->w_sum < w) {
        r->selected = index;
        return 1;
    }
    return 0;
}

/* Merging two independent reservoirs is one WRS step whose candidate is b's selection with
 * weight b.w_sum: b's candidate i ends selected with probability
 * (b.w_i / b.w_sum) * (b.w_sum / (a.w_sum + b.w_sum)). b's stream is treated as appended after
 * a's, so a taken selection is re-indexed by a's offered count. */
int restir_wrs_merge(struct restir_wrs *a, const struct restir_wrs *b, float u)
{
    int base = a->offered;
    a->offered += b->offered;
    if (b->selected < 0 || !isfinite(b->w_sum) || !(b->w_sum > 0.0f))
        return 0;
    a->w_sum += b->w_sum;
    if (u * a->w_sum < b->w_sum) {
        a->selected = base + b->selected;
        return 1;
    }
    return 0;
}

/* 004 Eq. 7: W_Y = (1 / p_hat(Y)) * sum_j w_j. */
float restir_gris_contribution_weight(const struct restir_wrs *r, float target_of_selected)
{
    if (r->selected < 0 || !(target_of_selected > 0.0f) || !isfinite(target_of_selected))
        return 0.0f;
    return r->w_sum / target_of_selected;
}

/* 004 Sec. 2.5: confidence is the summed input confidence, capped to a user parameter so that
 * repeatedly reused samples do not dominate; cap <= 0 disables the cap. */
float restir_confidence_merge(float c_sum, float cap)
{
    if (cap > 0.0f && c_sum > cap)
        return cap;
    return c_sum;
}
