/* params_denoise.c: the denoiser's settings block (denoise, denoise.svgf.*, denoise.atrous.*; DENOISE.md).
 * Every method reads it: the denoiser runs on the finished frame, never inside an estimator. */
#include <stddef.h>
#include <stdio.h>

#include "core/check.h"
#include "render/params.h"

static const char *const svgf_kernel_names[] = {"5x5", "3x3", NULL}; /* denoise_types.h */
static const char *const svgf_lum_weight_names[] = {"symmetric", "paper", NULL};
static const char *const svgf_taa_clamp_names[] = {"moving", "always", "off", NULL};
/* denoise: denoise_names (denoise.h) */

#define F(field) offsetof(struct render_params, field)
static const struct param_def denoise_rows[] = {
    {"denoise", P_NAMES, F(denoise.method), 0, 0, "off", NULL,
     "denoise the finished frame into a layer of its own (frame_NNNN_denoised.exr / .png, and errors after "
     "denoising in compare and study): off, svgf (Schied et al. 2017: temporal accumulation, variance "
     "estimate, 5 edge-stopping a-trous iterations on albedo-demodulated illumination, temporal antialiasing) or "
     "atrous (Dammertz et "
     "al. 2010, spatial only); the denoised layer is BIASED by nature, the frame itself is unchanged; methods "
     "without a G-buffer trace one for it through pixel centres",
     denoise_names},
    {"denoise.svgf.alpha", P_FLOAT, F(denoise.svgf_alpha), 1e-4, 1, "0.2", NULL,
     "svgf: colour's moving-average weight (Sec. 4.1)", NULL},
    {"denoise.svgf.moments_alpha", P_FLOAT, F(denoise.svgf_moments_alpha), 1e-4, 1, "0.2", NULL,
     "svgf: luminance moments' moving-average weight", NULL},
    {"denoise.svgf.sigma_depth", P_FLOAT, F(denoise.svgf_sigma_depth), 1e-6, 1e6, "1", NULL,
     "svgf: sigma_z, the depth weight's scale on the depth gradient (Eq. 3)", NULL},
    {"denoise.svgf.sigma_normal", P_FLOAT, F(denoise.svgf_sigma_normal), 0, 4096, "128", NULL,
     "svgf: sigma_n, the power of max(0, n_p . n_q) (Eq. 4)", NULL},
    {"denoise.svgf.sigma_luminance", P_FLOAT, F(denoise.svgf_sigma_lum), 1e-6, 1e6, "4", NULL,
     "svgf: sigma_l, the luminance weight's scale on the filtered standard deviation (Eq. 5)", NULL},
    {"denoise.svgf.luminance_weight", P_NAMES, F(denoise.svgf_lum_weight), 0, 0, "symmetric", NULL,
     "svgf: whose standard deviation scales Eq. 5's luminance difference: symmetric, the mean of the centre's and "
     "the tap's, so that a bright outlier gives its energy to the neighbours that take it in; paper, the "
     "centre's alone, which drops outliers' energy (many-lights, restir-di: denoised image 2% darker; "
     "docs/DENOISE.md)",
     svgf_lum_weight_names},
    {"denoise.svgf.iterations", P_INT, F(denoise.svgf_iterations), 0, 12, "5", NULL, "svgf: a-trous iterations", NULL},
    {"denoise.svgf.kernel", P_NAMES, F(denoise.svgf_kernel), 0, 0, "5x5", NULL,
     "svgf: the a-trous kernel: 5x5, the paper's B3 spline (Sec. 4.3), or 3x3, (1 2 1) / 4 per axis, which "
     "takes 9 taps instead of 25 and reaches half as far: a deviation for speed, its error after denoising "
     "measured in docs/DENOISE.md",
     svgf_kernel_names},
    {"denoise.svgf.feedback", P_INT, F(denoise.svgf_feedback), 0, 12, "1", NULL,
     "svgf: the a-trous iteration whose output is the next frame's colour history (0: the unfiltered "
     "accumulation)", NULL},
    {"denoise.svgf.variance_frames", P_INT, F(denoise.svgf_variance_frames), 0, 255, "4", NULL,
     "svgf: histories shorter than this estimate variance spatially (7x7, Sec. 4.2)", NULL},
    {"denoise.svgf.normal", P_FLOAT, F(denoise.svgf_normal_min), -1, 1, "0.9", NULL,
     "svgf: history rejected where n . n_prev is below", NULL},
    {"denoise.svgf.plane", P_FLOAT, F(denoise.svgf_plane_max), 0, 1e30, "0.01", NULL,
     "svgf: history rejected where the plane distance exceeds this times the depth", NULL},
    {"denoise.svgf.taa", P_FLOAT, F(denoise.svgf_taa_alpha), 1e-3, 1, "0.1", NULL,
     "svgf: temporal antialiasing after remodulation (Schied et al. Sec. 4's last step; Karis 2014: the "
     "reprojected output blended with this weight of the new frame, or 1 / frames while the pixel's history "
     "is shorter; 1: off); it integrates the pixel area the jittered primary rays cover, which the "
     "feature-tested history cannot where a pixel straddles an edge",
     NULL},
    {"denoise.svgf.taa_motion", P_FLOAT, F(denoise.svgf_taa_motion), 0, 1e6, "0.5", NULL,
     "svgf: the antialiasing's history only where the pixel moved at most this many pixels since the last "
     "frame; under camera motion the history lets light bleed across silhouettes (docs/DENOISE.md); 1e6: "
     "everywhere, as Karis 2014",
     NULL},
    {"denoise.svgf.taa_sky", P_BOOL, F(denoise.svgf_taa_sky), 0, 1, "on", NULL,
     "svgf: the antialiasing also on the pixels that see nothing, from the sky pixels of its history (through "
     "their direction's motion, never clamped): where a jittered pixel straddles a silhouette against the sky "
     "(an emitter's edge, a leaf) its output otherwise alternates between the two (docs/DENOISE.md); off: the "
     "sky is left raw (what SVGF did before this setting existed)",
     NULL},
    {"denoise.svgf.temporal_gradient", P_BOOL, F(denoise.svgf_temporal_gradient), 0, 1, "off", NULL,
     "svgf: A-SVGF (Schied et al. 2018): where the method's temporal gradient lambda (the relative change of "
     "the lighting its reused samples see between frames, 7x7 box-filtered) is high, the colour's, moments' "
     "and antialiasing's weights of this frame rise toward 1 (weight + g (1 - weight), g = 1 - (1 - lambda)^10, "
     "Q2RTX's response) and the colour history's length shrinks by (1 - lambda)^10, so the history of a changed "
     "light fades in a frame or two; restir-di provides the gradient",
     NULL},
    {"denoise.svgf.taa_clamp", P_NAMES, F(denoise.svgf_taa_clamp), 0, 0, "moving", NULL,
     "svgf: where the antialiasing's history is clamped to this frame's 3x3 neighbourhood (Karis 2014), "
     "against change: moving, on the pixels that moved since the last frame (nothing changes under a "
     "still pixel of a static scene); always, as Karis, which also drops sub-pixel emitters' energy "
     "whenever no sample of the 3x3 block hits them (many-lights: 4% darker, docs/DENOISE.md); off",
     svgf_taa_clamp_names},
    {"denoise.atrous.iterations", P_INT, F(denoise.atrous_iterations), 0, 12, "5", NULL, "atrous: iterations", NULL},
    {"denoise.atrous.sigma_color", P_FLOAT, F(denoise.atrous_sigma_color), 1e-6, 1e6, "1", NULL,
     "atrous: sigma_rt in units of the frame's mean illumination, halved per iteration", NULL},
    {"denoise.atrous.sigma_normal", P_FLOAT, F(denoise.atrous_sigma_normal), 1e-6, 1e6, "0.3", NULL,
     "atrous: sigma_n on |n_p - n_q|", NULL},
    {"denoise.atrous.sigma_position", P_FLOAT, F(denoise.atrous_sigma_position), 1e-6, 1e6, "0.05", NULL,
     "atrous: sigma_x on |x_p - x_q| as a fraction of the pixel's depth", NULL},
};
#undef F

static int denoise_validate(const struct render_params *p, const void *block, char *msg)
{
    (void)block;
    if (p->denoise.svgf_feedback > p->denoise.svgf_iterations) {
        snprintf(msg, RESTIR_MSG_LEN, "denoise.svgf.feedback = %d exceeds denoise.svgf.iterations = %d",
                 p->denoise.svgf_feedback, p->denoise.svgf_iterations);
        return -1;
    }
    return 0;
}

const struct param_block params_block_denoise = {
    "denoise", denoise_rows, sizeof(denoise_rows) / sizeof(denoise_rows[0]), 0, 0, 0, 1, denoise_validate, NULL};
