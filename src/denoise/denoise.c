/* denoise.c: the denoisers' table and what every one shares (denoise.h): the guard that keeps
 * invalid and non-finite pixels out of the filters, demodulation by albedo and remodulation
 * (Schied et al. 2017 Sec. 4), feature planes and depth gradients. Must never name a denoiser
 * but in its table. */
#include "denoise/denoise.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "denoise/denoise_kernel.h"
#include "denoise/denoise_method.h"

const char *const denoise_names[] = {"off", "svgf", "atrous", NULL};
static const struct denoise_method *const methods[] = {NULL, &denoise_svgf, &denoise_atrous};
#define METHOD_COUNT (int)(sizeof(methods) / sizeof(methods[0]))

void denoise_settings_defaults(struct denoise_settings *s)
{
    memset(s, 0, sizeof(*s));
    s->svgf_alpha = 0.2f;
    s->svgf_moments_alpha = 0.2f;
    s->svgf_sigma_depth = 1.0f;
    s->svgf_sigma_normal = 128.0f;
    s->svgf_sigma_lum = 4.0f;
    s->svgf_iterations = 5;
    s->svgf_kernel = 0;
    s->svgf_feedback = 1;
    s->svgf_variance_frames = 4;
    s->svgf_normal_min = 0.9f;
    s->svgf_plane_max = 0.01f;
    s->svgf_taa_alpha = 0.1f;
    s->svgf_taa_motion = 0.5f;
    s->svgf_taa_sky = 1;
    s->atrous_iterations = 5;
    s->atrous_sigma_color = 1.0f;
    s->atrous_sigma_normal = 0.3f;
    s->atrous_sigma_position = 0.05f;
}

/* Albedo channels below this are not divided by (a black channel has no illumination to recover);
 * remodulation multiplies by the same factor, so the pair is the identity on every pixel. Such a
 * channel holds radiance, not illumination, so a pixel's filters read only the taps whose albedo
 * leaves the same channels undivided (the frame's group plane): otherwise the red of a cyan
 * surface (red albedo 0) would average the white floor's red illumination and, multiplied by 1,
 * turn red, and the floor beside it would average the surface's red radiance of 0 and turn cyan. */
#define DEMOD_MIN 1e-3f

struct denoiser {
    const struct denoise_method *method;
    struct denoise_settings s;
    void *state;
    int width, height;
    float *plane[14]; /* illum[3] normal[3] position[3] depth ddx ddy use group */
};

#define PLANES 14

struct denoiser *denoiser_create(const struct denoise_settings *s, int width, int height)
{
    if (!s || s->method <= 0 || s->method >= METHOD_COUNT || width < 1 || height < 1)
        return NULL;
    struct denoiser *d = xcalloc(1, sizeof(*d));
    d->method = methods[s->method];
    d->s = *s;
    d->width = width;
    d->height = height;
    denoise_planes_alloc(d->plane, PLANES, (size_t)width * (size_t)height);
    d->state = d->method->create(s, width, height);
    return d;
}

void denoiser_destroy(struct denoiser *d)
{
    if (!d)
        return;
    d->method->destroy(d->state);
    free(d->plane[0]);
    free(d);
}

const char *denoiser_name(const struct denoiser *d) { return d->method->name; }

const float *denoiser_layer(const struct denoiser *d, const char *name)
{
    return d->method->layer && name ? d->method->layer(d->state, name) : NULL;
}

void denoise_planes_alloc(float **plane, int count, size_t n)
{
    /* Planes one cache line apart modulo 4 KiB: a frame's plane is often a multiple of 4 KiB (640 x
     * 360 floats are), and planes that many bytes apart map pixel i of every plane to the same L1
     * set, which the filters' loops, reading 9 to 28 planes at once, then thrash. */
    const size_t stride = ((n + 15) & ~(size_t)15) + 16;
    float *block = xcalloc((size_t)count * stride, sizeof(float));
    for (int k = 0; k < count; k++)
        plane[k] = block + (size_t)k * stride;
}

void denoise_scratch_reserve(struct denoise_scratch *s, size_t floats)
{
    const int threads = omp_get_max_threads();
    if (threads <= s->threads && floats <= s->per_thread)
        return;
    free(s->data);
    s->data = xmalloc(sizeof(float) * floats * (size_t)threads);
    s->per_thread = floats;
    s->threads = threads;
}

float *denoise_scratch_mine(const struct denoise_scratch *s)
{
    return s->data + (size_t)omp_get_thread_num() * s->per_thread;
}

void denoise_scratch_free(struct denoise_scratch *s)
{
    free(s->data);
    memset(s, 0, sizeof(*s));
}

static inline int finite3(vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static inline float demod_factor(float albedo) { return albedo >= DEMOD_MIN ? albedo : 1.0f; }

/* The frame's group of a used pixel of albedo a (struct denoise_frame): 1 + which channels are divided. */
static inline float demod_group(vec3 a)
{
    return (float)(1 + (a.x >= DEMOD_MIN) + 2 * (a.y >= DEMOD_MIN) + 4 * (a.z >= DEMOD_MIN));
}

/* Depth's derivative along one axis at pixel i: the one-sided difference of smaller magnitude
 * among the used neighbours (a step across an edge would claim a slope the surface does not have;
 * Schied et al. use the rasteriser's per-quad derivative). 0 without a used neighbour. */
static float depth_derivative(const float *z, const float *use, int i, int stride, int has_lo, int has_hi)
{
    float best = 0.0f;
    int found = 0;
    if (has_hi && use[i + stride] > 0.0f) {
        best = z[i + stride] - z[i];
        found = 1;
    }
    if (has_lo && use[i - stride] > 0.0f) {
        const float lo = z[i] - z[i - stride];
        if (!found || fabsf(lo) < fabsf(best))
            best = lo;
    }
    return best;
}

int denoiser_run(struct denoiser *d, const float *rgb, const struct denoise_guide *g, float *out,
                 struct denoise_stats *st)
{
    if (g->width != d->width || g->height != d->height)
        return -1;
    const int w = d->width, h = d->height;
    const size_t n = (size_t)w * (size_t)h;
    float *illum[3], *nrm[3], *pos[3];
    for (int c = 0; c < 3; c++) {
        illum[c] = d->plane[c];
        nrm[c] = d->plane[3 + c];
        pos[c] = d->plane[6 + c];
    }
    float *depth = d->plane[9], *ddx = d->plane[10], *ddy = d->plane[11], *use = d->plane[12], *group = d->plane[13];
    long long passed = 0;
    double lum_sum = 0.0;
    long long lum_count = 0;
#pragma omp parallel for schedule(static) reduction(+ : passed, lum_sum, lum_count)
    for (long long i = 0; i < (long long)n; i++) {
        const vec3 e = g->emission ? g->emission[i] : v3s(0.0f);
        const vec3 c = v3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
        const int ok = g->valid[i] && finite3(c) && finite3(e) && finite3(g->albedo[i]) && finite3(g->normal[i]) &&
                       finite3(g->position[i]) && isfinite(g->depth[i]) && g->depth[i] > 0.0f;
        passed += g->valid[i] && !ok;
        use[i] = ok ? 1.0f : 0.0f;
        const vec3 a = g->albedo[i];
        group[i] = ok ? demod_group(a) : 0.0f;
        illum[0][i] = ok ? (c.x - e.x) / demod_factor(a.x) : 0.0f;
        illum[1][i] = ok ? (c.y - e.y) / demod_factor(a.y) : 0.0f;
        illum[2][i] = ok ? (c.z - e.z) / demod_factor(a.z) : 0.0f;
        nrm[0][i] = ok ? g->normal[i].x : 0.0f;
        nrm[1][i] = ok ? g->normal[i].y : 0.0f;
        nrm[2][i] = ok ? g->normal[i].z : 0.0f;
        pos[0][i] = ok ? g->position[i].x : 0.0f;
        pos[1][i] = ok ? g->position[i].y : 0.0f;
        pos[2][i] = ok ? g->position[i].z : 0.0f;
        depth[i] = ok ? g->depth[i] : INFINITY; /* a filter's depth weight of an unused tap is 0 */
        if (ok) {
            lum_sum += denoise_luminance(illum[0][i], illum[1][i], illum[2][i]);
            lum_count++;
        }
    }
#pragma omp parallel for schedule(static)
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const int i = y * w + x;
            ddx[i] = use[i] > 0.0f ? depth_derivative(depth, use, i, 1, x > 0, x < w - 1) : 0.0f;
            ddy[i] = use[i] > 0.0f ? depth_derivative(depth, use, i, w, y > 0, y < h - 1) : 0.0f;
        }
    struct denoise_frame f = {w,
                              h,
                              {illum[0], illum[1], illum[2]},
                              {nrm[0], nrm[1], nrm[2]},
                              {pos[0], pos[1], pos[2]},
                              depth,
                              ddx,
                              ddy,
                              use,
                              group,
                              g->object,
                              g->motion,
                              d->s.svgf_temporal_gradient ? g->temporal_gradient : NULL,
                              lum_count ? lum_sum / (double)lum_count : 0.0};
    struct denoise_stats local = {passed, 0};
    d->method->run(d->state, &d->s, &f, &local);
#pragma omp parallel for schedule(static)
    for (long long i = 0; i < (long long)n; i++) {
        if (use[i] == 0.0f) {
            out[3 * i] = rgb[3 * i];
            out[3 * i + 1] = rgb[3 * i + 1];
            out[3 * i + 2] = rgb[3 * i + 2];
            continue;
        }
        const vec3 e = g->emission ? g->emission[i] : v3s(0.0f);
        const vec3 a = g->albedo[i];
        out[3 * i] = illum[0][i] * demod_factor(a.x) + e.x;
        out[3 * i + 1] = illum[1][i] * demod_factor(a.y) + e.y;
        out[3 * i + 2] = illum[2][i] * demod_factor(a.z) + e.z;
    }
    if (d->method->post)
        d->method->post(d->state, &d->s, &f, out);
    if (st)
        *st = local;
    return 0;
}
