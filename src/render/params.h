/* params.h: every method parameter with its default, reachable from the command line through
 * `--set key=value`, and described for `--help`. Must never depend on the ray tracer. */
#ifndef RESTIR_RENDER_PARAMS_H
#define RESTIR_RENDER_PARAMS_H

#include <stdint.h>
#include <stdio.h>

#include "restir/mis.h"

struct render_params {
    int width, height;
    int spp;          /* pt: paths per pixel per frame */
    uint64_t seed;
    int threads;      /* 0: all cores */
    int camera_path;  /* 0 static camera, 1 default camera path */
    int jitter;       /* jitter primary rays over the pixel footprint */

    /* path tracer */
    int max_bounces;  /* scattering events; 1 = direct lighting only */
    int rr_bounces;   /* Russian roulette starts after this many bounces */

    /* ReSTIR DI */
    int light_candidates;
    int bsdf_candidates;
    int temporal;
    int spatial;
    int spatial_neighbors;
    float spatial_radius;
    float spatial_normal;   /* Bitterli test, 000 Eq. 7: n . n_i >= spatial_normal */
    float spatial_depth;    /* Bitterli test, 000 Eq. 7: |d_i - d| / d < spatial_depth */
    float confidence_cap;
    enum restir_mis mis;
    float temporal_normal;  /* history rejected when n . n_prev < temporal_normal */
    float temporal_plane;   /* ... or when the plane distance exceeds temporal_plane * depth */
    int temporal_ratio_guard; /* 001 Sec. 5 target-ratio guard (biased) */
    float ratio_lo, ratio_hi;
};

void render_params_defaults(struct render_params *p);
/* Applies one "key=value". Returns 0, or -1 with msg naming the key or the bad value. */
int render_params_set(struct render_params *p, const char *assignment, char *msg);
/* Checks ranges (resolution, counts, ...). Returns 0, or -1 with msg naming the problem. */
int render_params_validate(const struct render_params *p, char *msg);
/* Prints every key with its default and meaning. */
void render_params_help(FILE *out);

#endif
