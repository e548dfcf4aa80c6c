/* reference.h: a converged reference image as a running mean of pt chunks, resumable from its
 * state (the mean and the sample count) with bit-identical results.
 * Must never depend on files or the command line: saving the state is the caller's job. */
#ifndef RESTIR_METHODS_PT_REFERENCE_H
#define RESTIR_METHODS_PT_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

#include "methods/method.h"
#include "render/params.h"
#include "scene/camera.h"
#include "scene/scene.h"

/* Samples per chunk. Chunk c renders pt frame REFERENCE_FRAME_BASE + c, so chunk c's samples are
 * the same whatever ran before it: a run resumed at a chunk boundary continues exactly. */
#define REFERENCE_CHUNK_SPP 16
/* The seed of a reference made next to runs of `seed`: its noise is independent of theirs. */
static inline uint64_t reference_seed(uint64_t seed) { return seed ^ 0x7265666572656e63ull; }
/* A frame number no render uses keeps reference noise independent of the compared runs. */
#define REFERENCE_FRAME_BASE 1000000

struct reference_accum {
    const struct scene *scene;
    struct render_params params; /* with method_reference_params applied: the integrand */
    struct camera_view view;
    int first_chunk; /* the chunk this accumulation starts at (0; a shard's first chunk) */
    int spp;     /* samples the finished image holds */
    int done;    /* samples in mean so far */
    float *mean; /* w*h*3: the running mean of the done samples */
    float *chunk;
    /* With reference_accum_track_variance: w*h*3 sums of weighted squared deviations of the chunk
     * means (West 1979's weighted update: a chunk of k samples is an observation of weight k; the
     * samples before tracking began, if any, one observation), and the observations so far. */
    float *m2;
    int var_obs;
};

/* The least observations (chunks) reference_accum_relmse_estimate reports from. */
#define REFERENCE_VARIANCE_MIN_OBS 8

/* Prepares a reference of what method estimates (pt over the same integrand) from cam with spp
 * samples, starting empty. open is the camera at the shutter opening (the previous frame's; NULL:
 * cam), which camera.shutter > 0 blurs toward (renderer_camera_view). */
void reference_accum_init(struct reference_accum *a, const struct scene *s, const struct method *method,
                          const struct render_params *p, const struct camera *cam, const struct camera *open, int spp);
/* The same for a shard: the samples of chunks first_chunk, first_chunk + 1, ... (spp of them). */
void reference_accum_init_shard(struct reference_accum *a, const struct scene *s, const struct method *method,
                                const struct render_params *p, const struct camera *cam, const struct camera *open,
                                int first_chunk, int spp);
/* Continues from a saved state: mean (w*h*3, copied) holding done samples. done must be a chunk
 * boundary (a multiple of REFERENCE_CHUNK_SPP) or spp itself (reference_accum_can_resume). */
void reference_accum_resume(struct reference_accum *a, const float *mean, int done);
/* Whether a state of done samples continues exactly into a run of spp samples. */
int reference_accum_can_resume(int done, int spp);
/* Renders the next chunk (REFERENCE_CHUNK_SPP samples or what is left) and folds it into the
 * mean: mean' = (mean * done + chunk * k) / (done + k) in double, rounded once to float. Returns
 * the rays traced. Call only while done < spp. */
long long reference_accum_step(struct reference_accum *a);
void reference_accum_fini(struct reference_accum *a);

/* Tracks the per-pixel variance of the samples from now on (after init or a resume): a->m2 zeroed
 * and a->var_obs = 1 when samples are already in (their mean is one observation), else 0. Or
 * continues a saved state: m2 (w*h*3, copied) with var_obs observations, when m2 is not NULL. */
void reference_accum_track_variance(struct reference_accum *a, const float *m2, int var_obs);
/* The expected relMSE of a->mean against the converged image (DESIGN.md's relMSE: mean over pixels
 * and channels of E[(mean - R)^2] / (R^2 + 1e-3)), estimated as Var(mean) / (mean^2 + 1e-3) with
 * Var(mean) = (m2 / (var_obs - 1)) / done, the spread of the chunk means scaled to one sample. The
 * chunk means are independent with sampler=independent; sampler=sobol's chunks continue one
 * scrambled sequence, whose mean usually converges faster than independent chunks' would (the
 * estimate then runs high). The ratio of noisy terms runs low where rare bright samples dominate
 * a pixel's variance and few are in: a chunk that holds one raises the mean it divides by.
 * INFINITY while fewer than REFERENCE_VARIANCE_MIN_OBS observations are in or without tracking. */
double reference_accum_relmse_estimate(const struct reference_accum *a);

/* The params and camera a reference's samples depend on, as "key=value; ..." text: scene content
 * (scene_content_hash), camera, resolution, seed and pt's parameters. Two runs with the same text
 * produce the same chunks. out holds len bytes. */
void reference_describe(const struct reference_accum *a, char *out, size_t len);

#endif
