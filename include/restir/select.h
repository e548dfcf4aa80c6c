/* restir/select.h: weighted sampling of up to m distinct items from a stream without replacement
 * (000 Sec. 5), the selection of M spatial neighbors among K candidates: A-Chao (Chao 1982) when
 * m = 1, A-ES (Efraimidis and Spirakis 2006: keep the m largest keys u^(1/w), compared as
 * log(u) / w) when m > 1. Per-sample code for C, C++ and CUDA device code (restir/hd.h); a
 * selection is the caller's value, updated by one thread at a time. */
#ifndef RESTIR_SELECT_H
#define RESTIR_SELECT_H

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most items a selection keeps. */
#define RESTIR_SELECT_MAX 8

struct restir_select {
    int m;                        /* capacity, 1..RESTIR_SELECT_MAX */
    int count;                    /* items selected so far (<= m) */
    int item[RESTIR_SELECT_MAX];  /* item[0..count): the selected items, in no particular order */
    float key[RESTIR_SELECT_MAX]; /* A-ES keys; for m = 1, key[0] holds A-Chao's weight sum */
};

/* Empties s with capacity m, clamped to [1, RESTIR_SELECT_MAX]. A NULL s is ignored. */
RESTIR_HD void restir_select_init(struct restir_select *s, int m)
{
    if (!s)
        return;
    s->m = m < 1 ? 1 : (m > RESTIR_SELECT_MAX ? RESTIR_SELECT_MAX : m);
    s->count = 0;
    s->key[0] = 0.0f;
}

/* Offers item with weight w, deciding with u uniform in [0,1). A weight that is 0, negative, NaN or
 * infinite is never selected; a NULL s is ignored. */
RESTIR_HD void restir_select_offer(struct restir_select *s, int item, float w, float u)
{
    if (!s || !(w > 0.0f) || !restir_hd_finite(w))
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

#ifdef __cplusplus
}
#endif

#endif
