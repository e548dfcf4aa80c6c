/* restir/neighbors.h: spatial-neighbor compatibility tests from G-buffer data.
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

#ifdef __cplusplus
}
#endif

#endif
