/* restir/neighbors.h: spatial-neighbor compatibility tests and scores from G-buffer data, and the
 * weighted selection of M distinct neighbors (000 Sec. 4-5).
 * Must never depend on a ray tracer, files or the renderer. */
#ifndef RESTIR_NEIGHBORS_H
#define RESTIR_NEIGHBORS_H

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
