/* restir/neighbors.h: spatial-neighbor compatibility tests and scores from G-buffer data, and the
 * weighted selection of M distinct neighbors (000 Sec. 4-5).
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_NEIGHBORS_H
#define RESTIR_NEIGHBORS_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bitterli et al. 2020's binary test (000 Eq. 7): n . n_i >= normal_min and
 * |d_i - d| / d < depth_max, with d, d_i the primary-hit distances. */
int restir_bitterli_compatible(const float n[3], const float n_i[3], float d, float d_i, float normal_min,
                               float depth_max);

/* 000 Eq. 14-15: compatibility of primary hits x (normal n_x, distance d from the camera) and y:
 * h = exp(-|x - y| / s) max(n_x . n_y, 0)^beta with s = sqrt(omega d^2 / pi), the world radius of
 * solid angle omega at distance d. The paper uses omega = 0.05, beta = 8. */
float restir_compat_score(const float x[3], const float n_x[3], float d, const float y[3], const float n_y[3],
                          float omega, float beta);

/* restir_compat_score with everything that depends only on x prepared once, for scoring one pixel's
 * K candidates (000 Algorithm 1): 1 / s, and beta as an integer exponent when it is one. */
struct restir_compat_scorer {
    float x[3], n[3];
    float inv_s;  /* 1 / s; 0 when s is not positive (every score is then 0) */
    float beta;
    int beta_int; /* beta when it is an integer in [0, 64] (powers by squaring), else -1 */
};

void restir_compat_scorer_init(struct restir_compat_scorer *c, const float x[3], const float n_x[3], float d,
                               float omega, float beta);

static inline float restir_compat_scorer_score(const struct restir_compat_scorer *c, const float y[3],
                                               const float n_y[3])
{
    /* 000 Eq. 14-15 */
    float dx = c->x[0] - y[0], dy = c->x[1] - y[1], dz = c->x[2] - y[2];
    float cos_n = c->n[0] * n_y[0] + c->n[1] * n_y[1] + c->n[2] * n_y[2];
    float t = sqrtf(dx * dx + dy * dy + dz * dz) * c->inv_s;
    if (!(cos_n > 0.0f) || !(c->inv_s > 0.0f) || t > 80.0f) /* exp(-80) ~ 2e-35: below any score that matters */
        return 0.0f;
    float hn = 1.0f;
    if (c->beta_int >= 0) {
        float b = cos_n; /* powers by squaring over the bits of beta */
        for (int ib = c->beta_int; ib; ib >>= 1, b *= b)
            if (ib & 1)
                hn *= b;
    } else {
        hn = powf(cos_n, c->beta);
    }
    return expf(-t) * hn;
}

/* Most neighbors a selection returns. */
#define RESTIR_SELECT_MAX 8

/* Weighted sampling of up to m distinct items from a stream without replacement (000 Sec. 5):
 * A-Chao (Chao 1982) when m = 1, A-ES (Efraimidis and Spirakis 2006: keep the m largest keys
 * u^(1/w), compared as log(u) / w) when m > 1. Items with w <= 0 are never selected. */
struct restir_select {
    int m;
    int count;                   /* items selected so far (<= m) */
    int item[RESTIR_SELECT_MAX];
    float key[RESTIR_SELECT_MAX]; /* A-ES keys; for m = 1, key[0] holds A-Chao's weight sum */
};

void restir_select_init(struct restir_select *s, int m);
/* Offers item with weight w, using uniform u in [0,1). */
void restir_select_offer(struct restir_select *s, int item, float w, float u);

#ifdef __cplusplus
}
#endif

#endif
