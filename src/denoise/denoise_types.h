/* denoise_types.h: the records the denoisers and their callers share (denoise.h, denoise_method.h):
 * a frame's features, the settings, the per-frame counts. Must never depend on anything but
 * core/vec3.h. */
#ifndef RESTIR_DENOISE_DENOISE_TYPES_H
#define RESTIR_DENOISE_DENOISE_TYPES_H

#include "core/vec3.h"

/* A motion vector component at or above this means "no motion known" (the point was behind the
 * previous camera): the same convention as the renderer's G-buffer. */
#define DENOISE_NO_MOTION 1e29f

/* Per-pixel features of the frame's primary hits, row-major, width * height entries each (motion:
 * 2 per pixel). Borrowed: the denoiser reads them during denoiser_run only. */
struct denoise_guide {
    int width, height;
    const vec3 *position;       /* world position */
    const vec3 *normal;         /* unit shading normal, facing the camera */
    const float *depth;         /* distance from the camera, > 0 */
    const int *object;          /* mesh id: history is rejected where it changes */
    const vec3 *albedo;         /* base colour the illumination is demodulated by */
    const vec3 *emission;       /* radiance the hit emits toward the camera (NULL: none) */
    const float *motion;        /* backward motion, previous - current image position, in pixels */
    const unsigned char *valid; /* 1 where the primary ray hit geometry; other pixels pass through */
    const float *temporal_gradient; /* per pixel in [0, 1]: how much of the history is stale (A-SVGF's lambda,
                                       from the method), or NULL: none */
};

/* denoise_settings.svgf_lum_weight and svgf_taa_clamp, in the order of their names in params.c. */
enum { DENOISE_LUM_SYMMETRIC, DENOISE_LUM_PAPER };
/* denoise_settings.method, in the order of denoise_names (denoise.c). */
enum { DENOISE_OFF, DENOISE_SVGF, DENOISE_ATROUS };
enum { DENOISE_TAA_CLAMP_MOVING, DENOISE_TAA_CLAMP_ALWAYS, DENOISE_TAA_CLAMP_OFF };

/* What the denoisers read (render_params' denoise.* keys; the defaults are the papers' but where
 * docs/DENOISE.md says why not). */
struct denoise_settings {
    int method; /* index into denoise_names: DENOISE_OFF, DENOISE_SVGF, DENOISE_ATROUS */
    /* SVGF (Schied et al. 2017, Sec. 4) */
    float svgf_alpha;         /* colour's exponential moving average weight (0.2) */
    float svgf_moments_alpha; /* moments' weight (0.2) */
    float svgf_sigma_depth;   /* sigma_z of Eq. 3 (1) */
    float svgf_sigma_normal;  /* sigma_n of Eq. 4 (128) */
    float svgf_sigma_lum;     /* sigma_l of Eq. 5 (4) */
    int svgf_lum_weight;      /* Eq. 5's deviation: DENOISE_LUM_SYMMETRIC, the mean of the centre's and the
                                 tap's (keeps the image's energy); DENOISE_LUM_PAPER, the centre's alone */
    int svgf_iterations;      /* à-trous iterations (5) */
    int svgf_kernel;          /* à-trous kernel: 0, the paper's 5x5 B3 spline; 1, 3x3 (1 2 1) / 4, faster */
    int svgf_feedback;        /* the iteration whose output becomes the colour history (1; 0: unfiltered) */
    int svgf_variance_frames; /* histories shorter than this estimate variance spatially (4) */
    float svgf_normal_min;    /* reprojection: history rejected where n . n_prev is below (0.9) */
    float svgf_plane_max;     /* reprojection: ... where the plane distance exceeds this * depth (0.01) */
    float svgf_taa_alpha;     /* temporal antialiasing's weight of the current frame (0.1; 1: off) */
    float svgf_taa_motion;    /* ... only where the pixel moved at most this many pixels (0.5; 1e6: all) */
    int svgf_temporal_gradient; /* 1: the method's temporal gradient raises the moving averages' weights
                                   (A-SVGF, Schied et al. 2018) */
    int svgf_taa_sky;         /* ... also on the pixels that see nothing, from the history's own (1) */
    int svgf_taa_clamp;       /* ... its history clamped to the 3x3 neighbourhood's range: where the pixel
                                 moved (DENOISE_TAA_CLAMP_MOVING), everywhere (_ALWAYS, Karis), nowhere (_OFF) */
    /* edge-avoiding à-trous (Dammertz et al. 2010, Sec. 3) */
    int atrous_iterations;       /* (5) */
    float atrous_sigma_color;    /* sigma_rt, in units of the frame's mean illumination; halved per iteration */
    float atrous_sigma_normal;   /* sigma_n on |n_p - n_q| */
    float atrous_sigma_position; /* sigma_x on |x_p - x_q|, as a fraction of the pixel's depth */
};

/* A denoiser's per-frame counts. */
struct denoise_stats {
    long long passed_through; /* valid pixels left raw: a non-finite input value or feature */
    long long history_reset;  /* SVGF: valid pixels whose history was rejected this frame */
};

#endif
