/* restir_di.c: ReSTIR DI (direct lighting, Bitterli et al. 2020) with librestir, from an application
 * that owns its scene, camera, G-buffer, ray caster and random numbers. librestir only decides:
 * which candidate a reservoir keeps (restir/reservoir.h), the resampling weights and contribution weights
 * of each merge (restir/gris.h), the resampling MIS weights (restir/mis.h), whether a neighbor's
 * surface is similar enough to reuse from (restir/neighbors.h), and the error metrics
 * (restir/metrics.h).
 *
 * The scene: a diffuse ground plane with two diffuse spheres standing on it, lit by four one-sided
 * quad lights of different sizes, colours and powers, seen by a pinhole camera at 64 x 48 pixels.
 * Per frame and pixel:
 *   1. initial candidates: M light samples (a light chosen by power, a point uniform on its area)
 *      resampled by streaming WRS with the unshadowed contribution's luminance as target, then one
 *      shadow ray for the survivor;
 *   2. temporal reuse: a GRIS merge of that reservoir with the pixel's reservoir of the previous
 *      frame (static camera: same pixel);
 *   3. spatial reuse: a GRIS merge with the reservoirs of a few random neighbors that pass the
 *      G-buffer similarity test;
 *   4. shading: f(Y) W_Y, one sample per pixel.
 * Every merge uses generalized pairwise MIS (restir_mis_weights), so each frame's image is an
 * unbiased estimate of the direct lighting.
 *
 * The program checks that: it renders a converged reference with many light samples per pixel,
 * then runs the renderer from several independent seeds and tests with a z-test that the mean
 * image brightness of ReSTIR matches the reference; and that ReSTIR's per-pixel error at one
 * sample per pixel is below that of plain one-sample light sampling. For contrast it also prints
 * the mean with the "1/M" weights (RESTIR_MIS_UNIFORM), which are biased here (not checked).
 * Exits 0 on success, 1 with a message on failure. Built against the installed package by
 * scripts/check_core.sh, through CMake's find_package(restir) and through pkg-config. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "restir/gris.h"
#include "restir/metrics.h"
#include "restir/mis.h"
#include "restir/neighbors.h"
#include "restir/version.h"
#include "restir/reservoir.h"

/* ---------------------------------------------------------------------------------------------
 * The application's own parameters. */
enum {
    WIDTH = 64,
    HEIGHT = 48,
    CANDIDATES = 8,       /* M: initial light samples per pixel and frame */
    NEIGHBORS = 4,        /* spatial neighbor taps per pixel (rejected ones are skipped) */
    FRAMES = 8,           /* frames per run */
    RUNS = 32,            /* independent runs (seeds) for the statistical test */
    REFERENCE_SPP = 2048, /* light samples per pixel of the reference */
};
#define SPATIAL_RADIUS 10.0f /* pixels */
#define CONFIDENCE_CAP 20.0f /* a reservoir's confidence never exceeds 20 initial reservoirs' */
#define NORMAL_MIN 0.9f      /* restir_neighbors_bitterli: n . n_i >= 0.9 (about 25 degrees) */
#define DEPTH_MAX 0.1f       /* and depths within 10% */
#define Z_MAX 4.0            /* the unbiasedness test fails beyond 4 standard errors */
#define PI_F 3.14159265358979f

/* ---------------------------------------------------------------------------------------------
 * Random numbers: PCG32 (O'Neill 2014), the 64-bit LCG with the XSH-RR output permutation. */
struct pcg32 {
    uint64_t state, inc;
};

static uint32_t pcg32_next(struct pcg32 *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + r->inc;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((0u - rot) & 31u));
}

static void pcg32_seed(struct pcg32 *r, uint64_t seed, uint64_t stream)
{
    r->state = 0u;
    r->inc = (stream << 1u) | 1u;
    pcg32_next(r);
    r->state += seed;
    pcg32_next(r);
}

/* Uniform in [0, 1): the top 24 bits, so the float is exact and never rounds up to 1. */
static float pcg32_float(struct pcg32 *r)
{
    return (float)(pcg32_next(r) >> 8) * (1.0f / 16777216.0f);
}

/* ---------------------------------------------------------------------------------------------
 * Vectors. */
typedef struct {
    float x, y, z;
} vec3;

static vec3 v3(float x, float y, float z)
{
    vec3 v = {x, y, z};
    return v;
}
static vec3 add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static vec3 sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static vec3 scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
static vec3 mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static float dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vec3 cross(vec3 a, vec3 b) { return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
static vec3 normalize(vec3 a) { return scale(a, 1.0f / sqrtf(dot(a, a))); }
/* Rec. 709 luminance, the scalar the targets and the checks use (as restir/metrics.h does). */
static float luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

/* ---------------------------------------------------------------------------------------------
 * The scene and the application's ray caster: analytic ray-plane and ray-sphere tests. */
struct sphere {
    vec3 center;
    float radius;
    vec3 albedo;
};

/* A one-sided parallelogram light corner + s u + t v (s, t in [0,1)), emitting radiance Le on the
 * side of normalize(u x v). */
struct quad_light {
    vec3 corner, u, v, Le;
    vec3 normal;      /* derived in scene_init */
    float area;       /* |u x v| */
    float pmf;        /* probability of choosing this light: proportional to its power */
};

#define N_SPHERES 2
#define N_LIGHTS 4
static const vec3 ground_albedo = {0.7f, 0.7f, 0.7f};
static struct sphere spheres[N_SPHERES] = {
    {{0.0f, 0.6f, 0.6f}, 0.6f, {0.8f, 0.3f, 0.3f}},
    {{-1.3f, 0.35f, -0.5f}, 0.35f, {0.3f, 0.4f, 0.8f}},
};
/* All in the plane y = 3 facing down (u x v points to -y), so no light occludes another. */
static struct quad_light lights[N_LIGHTS] = {
    {{-2.0f, 3.0f, 0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {6.0f, 5.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, 0.0f, 0.0f},
    {{1.5f, 3.0f, -0.3f}, {0.4f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.4f}, {8.0f, 16.0f, 40.0f}, {0.0f, 0.0f, 0.0f}, 0.0f, 0.0f},
    {{-0.5f, 3.0f, 2.4f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.25f}, {3.0f, 3.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.0f, 0.0f},
    {{-0.1f, 3.0f, -1.6f}, {0.2f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.2f}, {250.0f, 160.0f, 90.0f}, {0.0f, 0.0f, 0.0f}, 0.0f, 0.0f},
};

static void scene_init(void)
{
    double total = 0.0;
    for (int l = 0; l < N_LIGHTS; l++) {
        vec3 n = cross(lights[l].u, lights[l].v);
        lights[l].area = sqrtf(dot(n, n));
        lights[l].normal = normalize(n);
        total += (double)luminance(lights[l].Le) * lights[l].area; /* power up to a factor pi */
    }
    for (int l = 0; l < N_LIGHTS; l++)
        lights[l].pmf = (float)((double)luminance(lights[l].Le) * lights[l].area / total);
}

/* Smallest t in (t_min, t_max) where o + t d hits sphere s (d need not be unit), or -1. */
static float hit_sphere(const struct sphere *s, vec3 o, vec3 d, float t_min, float t_max)
{
    vec3 oc = sub(o, s->center);
    float a = dot(d, d), b = dot(oc, d), c = dot(oc, oc) - s->radius * s->radius;
    float disc = b * b - a * c;
    if (disc < 0.0f)
        return -1.0f;
    float root = sqrtf(disc);
    float t = (-b - root) / a;
    if (!(t > t_min))
        t = (-b + root) / a;
    return t > t_min && t < t_max ? t : -1.0f;
}

struct hit {
    vec3 position, normal, albedo;
    float t;
};

/* Closest hit of the ray o + t d, t in (t_min, t_max), against the ground y = 0 and the spheres.
 * Returns 1 and fills h (when not NULL), or 0 for a miss. */
static int trace(vec3 o, vec3 d, float t_min, float t_max, struct hit *h)
{
    int found = 0;
    float best = t_max;
    vec3 normal = v3(0.0f, 1.0f, 0.0f), albedo = ground_albedo;
    if (d.y != 0.0f) {
        float t = -o.y / d.y;
        if (t > t_min && t < best) {
            best = t;
            found = 1;
        }
    }
    for (int k = 0; k < N_SPHERES; k++) {
        float t = hit_sphere(&spheres[k], o, d, t_min, best);
        if (t > 0.0f) {
            best = t;
            found = 1;
            normal = normalize(sub(add(o, scale(d, t)), spheres[k].center));
            albedo = spheres[k].albedo;
        }
    }
    if (found && h) {
        h->t = best;
        h->position = add(o, scale(d, best));
        h->normal = normal;
        h->albedo = albedo;
    }
    return found;
}

/* The shadow ray: 1 when something blocks the segment from surface point x (normal n) to the
 * light point y. The origin is pushed off the surface along n to avoid hitting x itself. */
static int occluded(vec3 x, vec3 n, vec3 y)
{
    vec3 o = add(x, scale(n, 1e-3f));
    return trace(o, sub(y, o), 1e-4f, 1.0f - 1e-4f, NULL);
}

/* ---------------------------------------------------------------------------------------------
 * The G-buffer: what the primary rays hit, one entry per pixel. librestir never sees it, except
 * the normals and depths given to restir_neighbors_bitterli. */
struct gpixel {
    int valid;     /* 0 where the primary ray hit nothing */
    vec3 position, normal_v, albedo;
    float normal[3]; /* the normal again, as the float[3] restir/neighbors.h takes */
    float depth;     /* distance from the camera */
};

static struct gpixel gbuffer[WIDTH * HEIGHT];

static void gbuffer_build(void)
{
    const vec3 eye = v3(0.0f, 2.2f, -4.2f), at = v3(0.0f, 0.2f, 0.4f), up = v3(0.0f, 1.0f, 0.0f);
    const float tan_half = tanf(0.5f * 55.0f * PI_F / 180.0f); /* 55 degrees horizontal field of view */
    vec3 f = normalize(sub(at, eye)), r = normalize(cross(f, up)), u = cross(r, f);
    for (int j = 0; j < HEIGHT; j++)
        for (int i = 0; i < WIDTH; i++) {
            float sx = (2.0f * ((float)i + 0.5f) / WIDTH - 1.0f) * tan_half;
            float sy = (1.0f - 2.0f * ((float)j + 0.5f) / HEIGHT) * tan_half * HEIGHT / WIDTH;
            vec3 d = normalize(add(f, add(scale(r, sx), scale(u, sy))));
            struct gpixel *g = &gbuffer[j * WIDTH + i];
            struct hit h;
            memset(g, 0, sizeof *g);
            if (!trace(eye, d, 1e-4f, 1e30f, &h))
                continue;
            g->valid = 1;
            g->position = h.position;
            g->normal_v = h.normal;
            g->albedo = h.albedo;
            g->normal[0] = h.normal.x;
            g->normal[1] = h.normal.y;
            g->normal[2] = h.normal.z;
            g->depth = h.t;
        }
}

/* ---------------------------------------------------------------------------------------------
 * Light samples, integrand and target. A sample is a point on a light, in the area measure of the
 * lights. Every pixel's integrand is a function of that same point, so reusing a neighbor's sample
 * is the identity shift with Jacobian 1: no conversion between solid angles is needed. */
struct light_sample {
    int light;
    vec3 point;
};

/* Chooses a light by power and a point uniformly on it; returns the area-measure density. */
static float sample_light(struct pcg32 *rng, struct light_sample *s)
{
    float u = pcg32_float(rng), acc = 0.0f;
    int l = N_LIGHTS - 1;
    for (int k = 0; k < N_LIGHTS; k++) {
        acc += lights[k].pmf;
        if (u < acc) {
            l = k;
            break;
        }
    }
    float a = pcg32_float(rng), b = pcg32_float(rng);
    s->light = l;
    s->point = add(lights[l].corner, add(scale(lights[l].u, a), scale(lights[l].v, b)));
    return lights[l].pmf / lights[l].area;
}

/* The integrand without visibility, in area measure: BRDF * Le * cos at x * cos at the light / d^2. */
static vec3 unshadowed(const struct gpixel *g, const struct light_sample *s)
{
    const struct quad_light *L = &lights[s->light];
    vec3 d = sub(s->point, g->position);
    float dist2 = dot(d, d);
    vec3 w = scale(d, 1.0f / sqrtf(dist2));
    float cos_x = dot(g->normal_v, w), cos_l = -dot(L->normal, w);
    if (!(cos_x > 0.0f) || !(cos_l > 0.0f))
        return v3(0.0f, 0.0f, 0.0f);
    return scale(mul(g->albedo, L->Le), cos_x * cos_l / (PI_F * dist2));
}

/* The target p_hat of a pixel at a sample, as every merge uses it: the luminance of the shadowed
 * integrand. Visibility is part of it so that the MIS weights know which pixels can actually
 * produce a sample: a neighbor that cannot see the light point gets no share of it. With targets
 * that ignore visibility, pairwise MIS would hand shares to neighbors in shadow, which never
 * produce the sample; that share is lost and the image comes out too dark (the bias of Bitterli et
 * al.'s "biased" ReSTIR). Costs one shadow ray per evaluation. */
static float target(const struct gpixel *g, const struct light_sample *s)
{
    float p = luminance(unshadowed(g, s));
    return p > 0.0f && !occluded(g->position, g->normal_v, s->point) ? p : 0.0f;
}

/* ---------------------------------------------------------------------------------------------
 * The application's reservoir: librestir's struct restir_reservoir lives only during one pass; what
 * persists between passes and frames is the selected sample with its contribution weight W, its
 * confidence c and its cached target p_hat (of its own pixel, at its sample). */
struct reservoir {
    struct light_sample s;
    float W;     /* unbiased contribution weight of s; 0 when the reservoir holds no sample */
    float p_hat; /* target(own pixel, s), > 0 whenever W > 0 */
    float c;     /* confidence */
};

static const struct reservoir empty_reservoir = {{0, {0.0f, 0.0f, 0.0f}}, 0.0f, 0.0f, 0.0f};

/* Step 1: RIS over CANDIDATES light samples. In GRIS terms each candidate x_i has contribution
 * weight 1 / p(x_i) and MIS weight 1/M, so its resampling weight is (1/M) p_hat(x_i) / p(x_i).
 * The candidates are resampled with the unshadowed target (no shadow ray per candidate); the one
 * survivor gets a shadow ray and, when blocked, W = 0. W V(Y) is still an unbiased contribution
 * weight of Y, now for the shadowed integrand: the target every merge uses. */
static struct reservoir initial_reservoir(const struct gpixel *g, struct pcg32 *rng)
{
    struct reservoir r = empty_reservoir;
    if (!g->valid)
        return r;
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    float p_selected = 0.0f;
    for (int k = 0; k < CANDIDATES; k++) {
        struct light_sample x;
        float pdf = sample_light(rng, &x);
        float p = luminance(unshadowed(g, &x));
        float w = restir_gris_resampling_weight(1.0f / CANDIDATES, p, 1.0f / pdf, 1.0f);
        if (restir_reservoir_offer(&wrs, w, pcg32_float(rng))) {
            r.s = x;
            p_selected = p;
        }
    }
    r.W = restir_gris_contribution_weight(&wrs, p_selected); /* 0 when nothing was selected */
    if (r.W > 0.0f && occluded(g->position, g->normal_v, r.s.point))
        r.W = 0.0f;
    r.p_hat = r.W > 0.0f ? p_selected : 0.0f;
    r.c = 1.0f; /* one initial reservoir's worth, sample or not */
    return r;
}

/* Most reservoirs one merge takes: the canonical and its spatial neighbors. */
#define MAX_MERGE (1 + NEIGHBORS)

/* Steps 2 and 3: one GRIS merge of 1 <= n <= MAX_MERGE reservoirs into the canonical domain 0. in[j] is reservoir j
 * and pix[j] the pixel whose target it was built for (pix[0] the canonical pixel). The target
 * matrix P of restir/mis.h: P[k * n + j] = p_hat of domain k at sample Y_j (the identity shift
 * has Jacobian 1 both ways). Row 0 (the canonical targets) is needed by every mode, for the
 * resampling weights; the other entries only where restir_mis_needs asks (for pairwise: the
 * diagonal, already cached in the reservoirs, and column 0, the canonical sample seen from each
 * neighbor). */
static struct reservoir merge(enum restir_mis mode, int n, const struct reservoir *const in[], const int pix[],
                              struct pcg32 *rng)
{
    float c[MAX_MERGE], W[MAX_MERGE], J[MAX_MERGE], m[MAX_MERGE], P[MAX_MERGE * MAX_MERGE];
    float c_sum = 0.0f;
    for (int j = 0; j < n; j++) {
        c[j] = in[j]->c;
        W[j] = in[j]->W;
        J[j] = in[j]->W > 0.0f ? 1.0f : 0.0f; /* identity shift; 0 marks "no sample to shift" */
        c_sum += c[j];
    }
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++) {
            float p = 0.0f;
            if (k == j)
                p = in[j]->p_hat; /* cached: p_hat_j(X_j) */
            else if ((k == 0 || restir_mis_needs(mode, k, j)) && J[j] > 0.0f)
                p = target(&gbuffer[pix[k]], &in[j]->s);
            P[k * n + j] = p;
        }
    if (restir_mis_weights(mode, n, c, P, m) != 0) {
        fprintf(stderr, "restir_di: restir_mis_weights failed\n");
        exit(1);
    }
    /* w_j = m_j p_hat(Y_j) W_j J_j, streamed through one reservoir; restir_gris_resample does the
     * same in one call. */
    struct restir_reservoir wrs;
    restir_reservoir_init(&wrs);
    int chosen = -1;
    for (int j = 0; j < n; j++)
        if (restir_reservoir_offer(&wrs, restir_gris_resampling_weight(m[j], P[j], W[j], J[j]), pcg32_float(rng)))
            chosen = j;
    struct reservoir out = empty_reservoir;
    if (chosen >= 0) {
        out.s = in[chosen]->s;
        out.p_hat = P[chosen]; /* p_hat of the canonical pixel at the chosen sample */
        out.W = restir_gris_contribution_weight(&wrs, out.p_hat);
    }
    out.c = restir_gris_confidence_merge(c_sum, CONFIDENCE_CAP);
    return out;
}

/* ---------------------------------------------------------------------------------------------
 * The renderer: buffers of one run. */
static struct reservoir initial[WIDTH * HEIGHT], temporal[WIDTH * HEIGHT], previous[WIDTH * HEIGHT];
static struct reservoir spatial[WIDTH * HEIGHT];
static float reference[WIDTH * HEIGHT * 3];
static unsigned char valid_mask[WIDTH * HEIGHT];

/* Step 3's neighbors of pixel p: up to NEIGHBORS random pixels within SPATIAL_RADIUS that pass
 * Bitterli's test (similar normal and depth). The choice reads only the G-buffer and random
 * numbers, never the reservoirs' samples, so it cannot bias the merge. */
static int pick_neighbors(int p, struct pcg32 *rng, int out[])
{
    const struct gpixel *g = &gbuffer[p];
    int count = 0, px = p % WIDTH, py = p / WIDTH;
    for (int t = 0; t < NEIGHBORS; t++) {
        float r = SPATIAL_RADIUS * sqrtf(pcg32_float(rng)), phi = 2.0f * PI_F * pcg32_float(rng);
        int qx = px + (int)lroundf(r * cosf(phi)), qy = py + (int)lroundf(r * sinf(phi));
        if (qx < 0 || qx >= WIDTH || qy < 0 || qy >= HEIGHT)
            continue;
        int q = qy * WIDTH + qx;
        const struct gpixel *h = &gbuffer[q];
        if (q == p || !h->valid ||
            !restir_neighbors_bitterli(g->normal, h->normal, g->depth, h->depth, NORMAL_MIN, DEPTH_MAX))
            continue;
        out[count++] = q;
    }
    return count;
}

/* Renders one frame into image (RGB, WIDTH * HEIGHT * 3). */
static void render_frame(enum restir_mis mode, int frame, struct pcg32 *rng, float *image)
{
    const int n_pixels = WIDTH * HEIGHT;
    for (int p = 0; p < n_pixels; p++) /* 1. initial candidates */
        initial[p] = initial_reservoir(&gbuffer[p], rng);
    for (int p = 0; p < n_pixels; p++) { /* 2. temporal reuse */
        if (frame == 0 || !gbuffer[p].valid) {
            temporal[p] = initial[p];
            continue;
        }
        /* static camera: the previous frame's reservoir of the same pixel, built for the same
         * target (a moving camera would reproject, and pix[1] would name the previous frame's
         * surface) */
        const struct reservoir *in[2] = {&initial[p], &previous[p]};
        const int pix[2] = {p, p};
        temporal[p] = merge(mode, 2, in, pix, rng);
    }
    for (int p = 0; p < n_pixels; p++) { /* 3. spatial reuse */
        if (!gbuffer[p].valid) {
            spatial[p] = temporal[p];
            continue;
        }
        int pix[MAX_MERGE];
        const struct reservoir *in[MAX_MERGE];
        pix[0] = p;
        in[0] = &temporal[p];
        int n = 1 + pick_neighbors(p, rng, pix + 1);
        for (int j = 1; j < n; j++)
            in[j] = &temporal[pix[j]];
        spatial[p] = merge(mode, n, in, pix, rng);
    }
    for (int p = 0; p < n_pixels; p++) { /* 4. shading: f(Y) W_Y (visible: p_hat(Y) > 0) */
        vec3 f = v3(0.0f, 0.0f, 0.0f);
        if (spatial[p].W > 0.0f && spatial[p].p_hat > 0.0f)
            f = scale(unshadowed(&gbuffer[p], &spatial[p].s), spatial[p].W);
        image[3 * p] = f.x;
        image[3 * p + 1] = f.y;
        image[3 * p + 2] = f.z;
        previous[p] = spatial[p];
    }
}

/* Plain light sampling with one candidate: f(x) V(x) / p(x), for comparison (and, with many
 * samples, the reference). */
static vec3 light_sampling(const struct gpixel *g, struct pcg32 *rng)
{
    struct light_sample x;
    float pdf = sample_light(rng, &x);
    vec3 f = unshadowed(g, &x);
    if (luminance(f) <= 0.0f || occluded(g->position, g->normal_v, x.point))
        return v3(0.0f, 0.0f, 0.0f);
    return scale(f, 1.0f / pdf);
}

static double image_mean_luminance(const float *image)
{
    double sum = 0.0;
    int count = 0;
    for (int p = 0; p < WIDTH * HEIGHT; p++)
        if (valid_mask[p]) {
            sum += luminance(v3(image[3 * p], image[3 * p + 1], image[3 * p + 2]));
            count++;
        }
    return sum / count;
}

/* The luminance RMSE of an image against the reference over the valid pixels (restir/metrics.h). */
static double luma_rmse(const float *image)
{
    struct restir_metrics_error e;
    if (restir_metrics_compute(image, reference, WIDTH * HEIGHT, valid_mask, &e) != 0) {
        fprintf(stderr, "restir_di: restir_metrics_compute failed\n");
        exit(1);
    }
    return e.luma_rmse;
}

struct run_stats {
    double mean[RUNS]; /* per run: mean luminance over the frames and valid pixels */
    double rmse;       /* luminance RMSE per frame, averaged over the frames and runs */
};

/* RUNS independent runs of FRAMES frames of ReSTIR DI with the given MIS. */
static void run_restir(enum restir_mis mode, struct run_stats *st)
{
    static float image[WIDTH * HEIGHT * 3];
    st->rmse = 0.0;
    for (int run = 0; run < RUNS; run++) {
        struct pcg32 rng;
        pcg32_seed(&rng, 0x853c49e6748fea9bull + (uint64_t)run, 1000u + (uint64_t)run);
        st->mean[run] = 0.0;
        for (int frame = 0; frame < FRAMES; frame++) {
            render_frame(mode, frame, &rng, image);
            st->mean[run] += image_mean_luminance(image) / FRAMES;
            st->rmse += luma_rmse(image) / (FRAMES * RUNS);
        }
    }
}

/* Mean and standard error of the mean of n values. */
static void mean_se(const double *x, int n, double *mean, double *se)
{
    double s = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++)
        s += x[i];
    *mean = s / n;
    for (int i = 0; i < n; i++)
        s2 += (x[i] - *mean) * (x[i] - *mean);
    *se = sqrt(s2 / (n - 1) / n);
}

int main(void)
{
    clock_t start = clock();
    scene_init();
    gbuffer_build();
    int n_valid = 0;
    for (int p = 0; p < WIDTH * HEIGHT; p++) {
        valid_mask[p] = (unsigned char)gbuffer[p].valid;
        n_valid += gbuffer[p].valid;
    }
    if (n_valid == 0) {
        fprintf(stderr, "restir_di: FAIL: the camera sees nothing\n");
        return 1;
    }

    /* The reference: REFERENCE_SPP independent light samples per pixel, and the standard error of
     * its mean luminance from the per-pixel sample variances. */
    struct pcg32 rng;
    pcg32_seed(&rng, 42u, 7u);
    double ref_var = 0.0;
    for (int p = 0; p < WIDTH * HEIGHT; p++) {
        vec3 sum = v3(0.0f, 0.0f, 0.0f);
        double s = 0.0, s2 = 0.0;
        if (gbuffer[p].valid)
            for (int k = 0; k < REFERENCE_SPP; k++) {
                vec3 f = light_sampling(&gbuffer[p], &rng);
                double l = luminance(f);
                sum = add(sum, f);
                s += l;
                s2 += l * l;
            }
        vec3 mean = scale(sum, 1.0f / REFERENCE_SPP);
        reference[3 * p] = mean.x;
        reference[3 * p + 1] = mean.y;
        reference[3 * p + 2] = mean.z;
        double m = s / REFERENCE_SPP;
        ref_var += (s2 / REFERENCE_SPP - m * m) / (REFERENCE_SPP - 1); /* variance of this pixel's mean */
    }
    double ref_mean = image_mean_luminance(reference), ref_se = sqrt(ref_var) / n_valid;

    /* Plain light sampling at one sample per pixel: its per-frame error. */
    static float image[WIDTH * HEIGHT * 3];
    double plain_rmse = 0.0;
    for (int frame = 0; frame < FRAMES * RUNS; frame++) {
        for (int p = 0; p < WIDTH * HEIGHT; p++) {
            vec3 f = gbuffer[p].valid ? light_sampling(&gbuffer[p], &rng) : v3(0.0f, 0.0f, 0.0f);
            image[3 * p] = f.x;
            image[3 * p + 1] = f.y;
            image[3 * p + 2] = f.z;
        }
        plain_rmse += luma_rmse(image) / (FRAMES * RUNS);
    }

    /* ReSTIR DI with pairwise MIS (checked), then with 1/M (shown only). */
    static struct run_stats pairwise, uniform;
    run_restir(RESTIR_MIS_PAIRWISE, &pairwise);
    run_restir(RESTIR_MIS_UNIFORM, &uniform);
    double mean, se, umean, use;
    mean_se(pairwise.mean, RUNS, &mean, &se);
    mean_se(uniform.mean, RUNS, &umean, &use);
    double z = (mean - ref_mean) / sqrt(se * se + ref_se * ref_se);
    double uz = (umean - ref_mean) / sqrt(use * use + ref_se * ref_se);
    double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;

    printf("librestir %s: ReSTIR DI, %d x %d pixels (%d lit surface pixels), %d lights, M = %d candidates,\n"
           "temporal + spatial reuse (%d neighbor taps), %d frames x %d independent runs\n",
           RESTIR_VERSION_STRING, WIDTH, HEIGHT, n_valid, N_LIGHTS, CANDIDATES, NEIGHBORS, FRAMES, RUNS);
    printf("  mean luminance: reference (%d spp)   %.5f +- %.5f\n", REFERENCE_SPP, ref_mean, ref_se);
    printf("                  ReSTIR, pairwise MIS %.5f +- %.5f   z = %+.2f (pass: |z| < %.0f)\n", mean, se, z,
           Z_MAX);
    printf("                  ReSTIR, 1/M weights  %.5f +- %.5f   z = %+.2f (biased; not checked)\n", umean, use,
           uz);
    printf("  luminance RMSE per frame at 1 spp: plain light sampling %.5f, ReSTIR (pairwise) %.5f (%.1fx lower),\n"
           "                                     ReSTIR (1/M) %.5f\n",
           plain_rmse, pairwise.rmse, plain_rmse / pairwise.rmse, uniform.rmse);
    printf("  %.2f s\n", seconds);

    int ok = 1;
    if (!(fabs(z) < Z_MAX)) {
        printf("restir_di: FAIL: ReSTIR's mean differs from the reference by %.1f standard errors\n", z);
        ok = 0;
    }
    if (!(pairwise.rmse < plain_rmse)) {
        printf("restir_di: FAIL: ReSTIR's RMSE %.5f is not below plain light sampling's %.5f\n", pairwise.rmse,
               plain_rmse);
        ok = 0;
    }
    if (ok)
        printf("restir_di: PASS\n");
    return ok ? 0 : 1;
}
