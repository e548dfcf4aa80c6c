/* neighbors.c: G-buffer compatibility tests and scores for spatial neighbor selection, and
 * weighted selection of distinct neighbors (000 Sec. 3-5).
 * Must never depend on a ray tracer, files or the renderer. */
#include <math.h>

#include "restir/neighbors.h"

int restir_bitterli_compatible(const float n[3], const float n_i[3], float d, float d_i, float normal_min,
                               float depth_max)
{
    /* 000 Eq. 7 */
    float dot = n[0] * n_i[0] + n[1] * n_i[1] + n[2] * n_i[2];
    return dot >= normal_min && d > 0.0f && fabsf(d_i - d) / d < depth_max;
}

void restir_compat_scorer_init(struct restir_compat_scorer *c, const float x[3], const float n_x[3], float d,
                               float omega, float beta)
{
    for (int k = 0; k < 3; k++) {
        c->x[k] = x[k];
        c->n[k] = n_x[k];
    }
    float s = sqrtf(omega * d * d / 3.14159265358979f); /* 000 Eq. 15 */
    c->inv_s = s > 0.0f ? 1.0f / s : 0.0f;
    c->beta = beta;
    int ib = (int)beta;
    c->beta_int = ((float)ib == beta && ib >= 0 && ib <= 64) ? ib : -1; /* the paper's 8 */
}

float restir_compat_score(const float x[3], const float n_x[3], float d, const float y[3], const float n_y[3],
                          float omega, float beta)
{
    struct restir_compat_scorer c;
    restir_compat_scorer_init(&c, x, n_x, d, omega, beta);
    return restir_compat_scorer_score(&c, y, n_y);
}

void restir_select_init(struct restir_select *s, int m)
{
    s->m = m < 1 ? 1 : (m > RESTIR_SELECT_MAX ? RESTIR_SELECT_MAX : m);
    s->count = 0;
    s->key[0] = 0.0f;
}

void restir_select_offer(struct restir_select *s, int item, float w, float u)
{
    if (!(w > 0.0f) || !isfinite(w))
        return;
    if (s->m == 1) {
        /* A-Chao with capacity 1: replace with probability w / (running sum). */
        s->key[0] += w;
        if (u * s->key[0] < w) {
            s->item[0] = item;
            s->count = 1;
        }
        return;
    }
    /* A-ES: key = u^(1/w), as log(u) / w; u = 0 gives -inf, never kept over a finite key. */
    float key = logf(u) / w;
    if (s->count < s->m) {
        s->item[s->count] = item;
        s->key[s->count++] = key;
        return;
    }
    int lo = 0;
    for (int k = 1; k < s->m; k++)
        if (s->key[k] < s->key[lo])
            lo = k;
    if (key > s->key[lo]) {
        s->item[lo] = item;
        s->key[lo] = key;
    }
}
