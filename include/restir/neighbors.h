/* restir/neighbors.h: spatial-neighbor compatibility from G-buffer data (000 Sec. 4): Bitterli et
 * al.'s binary test and 000's continuous compatibility score. Per-sample code for C, C++ and CUDA
 * device code (restir/hd.h); thread-safe, no state. Points and normals are 3 floats in world space,
 * distances in the same unit from the camera. */
#ifndef RESTIR_NEIGHBORS_H
#define RESTIR_NEIGHBORS_H

#include "restir/hd.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Bitterli et al. 2020's binary test (000 Eq. 7): 1 when n . n_i >= normal_min and
 * |d_i - d| / d < depth_max, with d, d_i the primary-hit distances, else 0. 0 when d <= 0, when any
 * argument is NaN, or when a pointer is NULL. */
RESTIR_HD int restir_neighbors_bitterli(const float n[3], const float n_i[3], float d, float d_i, float normal_min,
                                        float depth_max)
{
    if (!n || !n_i)
        return 0;
    float dot = n[0] * n_i[0] + n[1] * n_i[1] + n[2] * n_i[2];
    return dot >= normal_min && d > 0.0f && fabsf(d_i - d) / d < depth_max;
}

/* 000 Eq. 14-15 with everything that depends only on the scoring pixel's hit x prepared once, for
 * scoring one pixel's K candidates (000 Algorithm 1): 1 / s and beta as an integer exponent when
 * it is one. */
struct restir_neighbors_scorer {
    float x[3], n[3];
    float inv_s;  /* 1 / s; 0 when s is not positive or not finite (every score is then 0) */
    float beta;
    int beta_int; /* beta when it is an integer in [0, 64] (powers by squaring), else -1 */
};

/* Prepares c for hit x with normal n_x at distance d from the camera: s = sqrt(omega d^2 / pi), the
 * world radius of solid angle omega (steradians) at distance d. The paper uses omega = 0.05 and
 * beta = 8. A NULL c is ignored; NULL x or n_x, or an s that is not finite and positive, gives a
 * scorer whose every score is 0. */
RESTIR_HD void restir_neighbors_scorer_init(struct restir_neighbors_scorer *c, const float x[3], const float n_x[3],
                                            float d, float omega, float beta)
{
    if (!c)
        return;
    for (int k = 0; k < 3; k++) {
        c->x[k] = x ? x[k] : 0.0f;
        c->n[k] = n_x ? n_x[k] : 0.0f;
    }
    float s = sqrtf(omega * d * d / 3.14159265358979f); /* 000 Eq. 15 */
    c->inv_s = x && n_x && s > 0.0f && restir_hd_finite(s) ? 1.0f / s : 0.0f;
    c->beta = beta;
    int ib = beta >= 0.0f && beta <= 64.0f ? (int)beta : -1;
    c->beta_int = ((float)ib == beta && ib >= 0 && ib <= 64) ? ib : -1; /* the paper's 8 */
}

/* 000 Eq. 14: h = exp(-|x - y| / s) max(n_x . n_y, 0)^beta for the candidate hit y with normal n_y;
 * in [0, 1] for unit normals. 0 when c or a pointer is NULL, when the normals face apart, or when
 * |x - y| / s > 80 (exp(-80) ~ 2e-35, below any score that matters). */
RESTIR_HD float restir_neighbors_scorer_score(const struct restir_neighbors_scorer *c, const float y[3],
                                              const float n_y[3])
{
    if (!c || !y || !n_y)
        return 0.0f;
    float dx = c->x[0] - y[0], dy = c->x[1] - y[1], dz = c->x[2] - y[2];
    float cos_n = c->n[0] * n_y[0] + c->n[1] * n_y[1] + c->n[2] * n_y[2];
    float t = sqrtf(dx * dx + dy * dy + dz * dz) * c->inv_s;
    if (!(cos_n > 0.0f) || !(c->inv_s > 0.0f) || !(t <= 80.0f))
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
    float h = expf(-t) * hn;
    return restir_hd_finite(h) ? h : 0.0f;
}

/* 000 Eq. 14-15 for one pair: restir_neighbors_scorer_init then restir_neighbors_scorer_score. */
RESTIR_HD float restir_neighbors_compat(const float x[3], const float n_x[3], float d, const float y[3],
                                        const float n_y[3], float omega, float beta)
{
    struct restir_neighbors_scorer c;
    restir_neighbors_scorer_init(&c, x, n_x, d, omega, beta);
    return restir_neighbors_scorer_score(&c, y, n_y);
}

#ifdef __cplusplus
}
#endif

#endif
