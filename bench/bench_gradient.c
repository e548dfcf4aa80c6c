/* bench_gradient.c: the `gradient` section of restir_bench: the evaluation of 002 Sec. 5 on our
 * scenes. Equal time on the camera path (budget: grestir-pt's frame time, L2 included; 002 Fig. 8):
 * grestir-pt (1 instance), grad-after-restir and area-restir (averaged instances), gpt and pt (paths
 * per pixel), error of the last frame for the L2 and the L1 reconstruction and of the gradients; the
 * reconstruction times; the ablations of 002 Fig. 9 (positivization), Fig. 10 (spatial reuse) and
 * Sec. 4.4 (reuse across signs) on ajar; and pictures in the layout of 002 Fig. 7 and 8 for ajar
 * (docs/gradient/). --equal-samples instead: per scene, every method at 1 instance / 1 spp on the
 * same frames, with the rays traced per pixel and grestir-pt's temporal pass per frame. Prints
 * Markdown for docs/BENCHMARKS.md. Must never be run by the tests. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "experiments/equal_time.h"
#include "methods/gradient/grad_method.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/png.h"
#include "methods/settings.h"
#include "restir/metrics.h"
#include "methods/gradient/grad_settings.h"

#define IMAGE_DIR "docs/gradient"
#define REF_CACHE_DIR "out/bench-gradient" /* references are reused from here (git-ignored) */
#define MAX_SCENES 8
#define MAX_INSTANCES 16
#define TIMING_SKIP 2   /* frames 0 and 1 (no history, then the first temporal frame) are not timed */
#define AJAR_EXPOSURE 1.0f /* png_write_srgb exposure (x2) for ajar, the same in every column */
#define SEED_STRIDE 1000003ull /* instance k runs with seed p.seed + k * SEED_STRIDE (as restir compare) */

struct gb_config {
    int width, height, frames, ref_spp;
};

/* The reference of one scene: pt from the last frame's camera, and its forward differences. */
struct gb_ref {
    float *rgb, *dx, *dy;
};

/* One row: a method (with settings) at its budget, measured at the last frame. */
struct gb_result {
    const struct method *method;
    double ms;      /* per frame over the timed frames, all instances, one reconstruction */
    double grad_ms; /* the PASS_GRAD_* passes (gpt: PASS_GPT), per frame, all instances */
    int spp, instances;
    struct restir_metrics_error l2, l1; /* l2: the L2 reconstruction, or the image of a primal method */
    double grad_err;            /* gradient error (gradient_error) */
    double mean_l2, mean_l1;    /* image mean luminance / the reference's (L2 or image; L1) */
    float *image, *l1_image, *dx, *dy; /* last frame (averaged): copies, freed by gb_result_free */
    long long rays;   /* rays traced over the timed frames, all instances */
    int timed_frames; /* frames timed per instance */
    /* --equal-samples only (else NULL): per frame f of the path (instance 0), the ms of
     * PASS_GRAD_TEMPORAL, the frame's ms_total and its rays; freed by gb_result_free */
    double *frame_temporal_ms, *frame_ms;
    long long *frame_rays;
};

/* Per-frame records of render_frames (NULL: none). */
struct gb_frame_log {
    double *temporal_ms, *ms;
    long long *rays;
};

/* Reconstruction timings of every solve, for the medians. */
static double *l2_log, *l1_log;
static int l2_n, l2_cap, l1_n, l1_cap;

static void log_time(double **log, int *n, int *cap, double ms)
{
    if (*n == *cap) {
        *cap = *cap ? 2 * *cap : 256;
        double *grown = realloc(*log, sizeof(double) * (size_t)*cap);
        if (!grown) {
            fprintf(stderr, "restir_bench: out of memory\n");
            exit(1);
        }
        *log = grown;
    }
    (*log)[(*n)++] = ms;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    if (n == 0)
        return NAN;
    qsort(v, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static float lum(const float *c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

static float *copy3(const float *src, size_t npix)
{
    float *d = xmalloc(3 * npix * sizeof(float));
    memcpy(d, src, 3 * npix * sizeof(float));
    return d;
}

/* Forward differences with the renderer's convention (grad_common.h): dx[a] = I(a + x) - I(a),
 * dy[a] = I(a + y) - I(a), 0 in the last column of dx and the last row of dy. */
static void forward_differences(const float *img, int w, int h, float *dx, float *dy)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int c = 0; c < 3; c++) {
                size_t i = 3 * ((size_t)y * w + x) + c;
                dx[i] = x + 1 < w ? img[i + 3] - img[i] : 0.0f;
                dy[i] = y + 1 < h ? img[i + 3 * (size_t)w] - img[i] : 0.0f;
            }
}

/* Relative gradient RMSE: sqrt( sum over pixels a and d in {x, y} of (lum(g_d(a)) - lum(g_ref,d(a)))^2
 * / sum over pixels a of (lum(ref(a))^2 + 1e-4) ), g_ref the reference's forward differences. */
#define GRAD_ERR_EPS 1e-4
static double gradient_error(const float *dx, const float *dy, const struct gb_ref *ref, size_t npix)
{
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < npix; i++) {
        double ex = lum(dx + 3 * i) - lum(ref->dx + 3 * i), ey = lum(dy + 3 * i) - lum(ref->dy + 3 * i);
        double r = lum(ref->rgb + 3 * i);
        num += ex * ex + ey * ey;
        den += r * r + GRAD_ERR_EPS;
    }
    return sqrt(num / den);
}

static double mean_lum(const float *img, size_t npix)
{
    double sum = 0.0;
    for (size_t i = 0; i < npix; i++)
        sum += lum(img + 3 * i);
    return sum / (double)npix;
}

static struct render_params base_params(const struct gb_config *c)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = c->width;
    p.height = c->height;
    p.camera_path = 1;
    return p;
}

static void apply_sets(struct render_params *p, const char *sets)
{
    char msg[RESTIR_MSG_LEN];
    if (sets && sets[0] && render_params_set_list(p, sets, msg) != 0) {
        fprintf(stderr, "restir_bench: %s\n", msg);
        exit(2);
    }
    if (render_params_validate(p, msg) != 0) {
        fprintf(stderr, "restir_bench: %s\n", msg);
        exit(2);
    }
}

/* Output folders; a failure is reported and the bench goes on without that output. */
static void make_dirs(const char *path)
{
    char msg[RESTIR_MSG_LEN];
    if (io_make_dirs(path, msg) != 0)
        fprintf(stderr, "restir_bench: %s\n", msg);
}

/* The pt reference of the last frame's camera, from the cache when an identical one (scene,
 * resolution, frame, spp; default parameters) was rendered before. */
static void load_reference(const struct scene *s, const char *scene_name, const struct gb_config *c,
                           struct gb_ref *ref)
{
    const int last = c->frames - 1;
    const size_t npix = (size_t)c->width * c->height;
    char path[512], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof(path), "%s/ref_%s_%dx%d_f%d_%dspp.exr", REF_CACHE_DIR, scene_name, c->width, c->height,
             last, c->ref_spp);
    int w = 0, h = 0;
    ref->rgb = NULL;
    if (exr_read_rgb(path, &ref->rgb, &w, &h, msg) == 0 && w == c->width && h == c->height) {
        fprintf(stderr, "restir_bench: reference %s from the cache\n", path);
    } else {
        free(ref->rgb);
        struct render_params p = base_params(c);
        double t0 = omp_get_wtime();
        ref->rgb = bench_reference(s, method_named("pt"), &p, (float)last, 1, c->ref_spp);
        fprintf(stderr, "restir_bench: reference %s rendered in %.0f s\n", path, omp_get_wtime() - t0);
        make_dirs(REF_CACHE_DIR);
        if (exr_write_rgb(path, ref->rgb, c->width, c->height, msg) != 0)
            fprintf(stderr, "restir_bench: %s\n", msg);
    }
    ref->dx = xmalloc(3 * npix * sizeof(float));
    ref->dy = xmalloc(3 * npix * sizeof(float));
    forward_differences(ref->rgb, c->width, c->height, ref->dx, ref->dy);
}

static void free_reference(struct gb_ref *ref)
{
    free(ref->rgb);
    free(ref->dx);
    free(ref->dy);
}

static double grad_pass_ms(const double *ms)
{
    return ms[PASS_GRAD_INITIAL] + ms[PASS_GRAD_TEMPORAL] + ms[PASS_GRAD_SELECT] + ms[PASS_GRAD_SPATIAL] +
           ms[PASS_GRAD_SHADE] + ms[PASS_GPT];
}

/* Renders frames [from, frames) of the camera path with r; frames >= timed_from are timed. Returns
 * their mean frame time and stores the mean per pass in pass_ms and the rays they traced in *rays;
 * logs every L2 solve timed, and, when log is not NULL, every frame rendered into log (by frame). */
static double render_frames(struct renderer *r, const struct scene *s, int from, int timed_from, int frames,
                            double pass_ms[PASS_COUNT], long long *rays, const struct gb_frame_log *log)
{
    double total = 0.0;
    int timed = 0;
    memset(pass_ms, 0, sizeof(double) * PASS_COUNT);
    *rays = 0;
    for (int f = from; f < frames; f++) {
        struct frame_stats st;
        struct camera cam = scene_camera_at(s, 1, (float)f);
        renderer_render(r, f, &cam, &st);
        if (log) {
            log->temporal_ms[f] = st.ms[PASS_GRAD_TEMPORAL];
            log->ms[f] = st.ms_total;
            log->rays[f] = st.rays;
        }
        if (f < timed_from)
            continue;
        timed++;
        total += st.ms_total;
        *rays += st.rays;
        for (int q = 0; q < PASS_COUNT; q++)
            pass_ms[q] += st.ms[q];
        if (grad_method_frame(r))
            log_time(&l2_log, &l2_n, &l2_cap, st.ms[PASS_RECON_L2]);
    }
    for (int q = 0; q < PASS_COUNT; q++)
        pass_ms[q] /= timed;
    return total / timed;
}

/* Runs method m (common parameters, then `sets`) on the camera path and measures its last frame.
 * budget_ms <= 0: 1 instance at 1 spp. equal_samples (with budget_ms <= 0): pt and gpt too render
 * every frame of the path, timed from TIMING_SKIP as the ReSTIR methods, and every frame is logged
 * into res->frame_*. Otherwise pt and gpt get the paths per pixel that fit (they
 * keep no state between frames: only frames N-3 .. N-1 are rendered, the last two timed), and the
 * ReSTIR methods average as many independently seeded instances as fit: instance 0's time t0
 * includes one L2 solve, each further instance costs t0 - L2 (gradient methods average primal, dx
 * and dy, then reconstruct once, 002 Sec. 5). Gradient methods then also get the L1 solve of the
 * final inputs (untimed). */
static void run_method(const struct scene *s, const struct gb_config *c, const struct method *m, const char *sets,
                       double budget_ms, int equal_samples, const struct gb_ref *ref, struct gb_result *res)
{
    memset(res, 0, sizeof(*res));
    res->method = m;
    struct render_params p = base_params(c);
    apply_sets(&p, sets);
    const size_t npix = (size_t)c->width * c->height, n3 = 3 * npix;
    const int last = c->frames - 1;
    double pass_ms[PASS_COUNT];
    long long rays_k;
    struct renderer r0;
    struct gb_frame_log log_store, *log = NULL;
    if (equal_samples) {
        budget_ms = 0.0;
        res->frame_temporal_ms = xcalloc((size_t)c->frames, sizeof(double));
        res->frame_ms = xcalloc((size_t)c->frames, sizeof(double));
        res->frame_rays = xcalloc((size_t)c->frames, sizeof(long long));
        log_store = (struct gb_frame_log){res->frame_temporal_ms, res->frame_ms, res->frame_rays};
        log = &log_store;
    }
    res->instances = 1;
    res->spp = 1;
    if (m == method_named("pt") || m == method_named("gpt")) {
        if (budget_ms > 0.0) { /* as restir compare --equal-time, from the last frame's camera */
            struct camera cam = scene_camera_at(s, 1, (float)last);
            p.spp = equal_time_spp_for(s, m, &p, &cam, last, budget_ms);
        }
        res->spp = p.spp;
        renderer_init(&r0, s, m, &p);
        int from = equal_samples ? 0 : c->frames - 3, timed_from = equal_samples ? TIMING_SKIP : from + 1;
        res->ms = render_frames(&r0, s, from, timed_from, c->frames, pass_ms, &res->rays, log);
        res->timed_frames = c->frames - timed_from;
        res->grad_ms = grad_pass_ms(pass_ms);
    } else {
        renderer_init(&r0, s, m, &p);
        res->ms = render_frames(&r0, s, 0, TIMING_SKIP, c->frames, pass_ms, &res->rays, log);
        res->timed_frames = c->frames - TIMING_SKIP;
        res->grad_ms = grad_pass_ms(pass_ms);
        if (budget_ms > 0.0) {
            double extra = res->ms - pass_ms[PASS_RECON_L2] - pass_ms[PASS_RECON_L1];
            int k = 1 + (int)lrint((budget_ms - res->ms) / extra);
            res->instances = k < 1 ? 1 : k > MAX_INSTANCES ? MAX_INSTANCES : k;
        }
        if (res->instances > 1) {
            float *sum[4] = {copy3(r0.image, npix), NULL, NULL, NULL};
            if (grad_method_frame(&r0)) {
                sum[1] = copy3(grad_method_frame(&r0)->primal, npix);
                sum[2] = copy3(grad_method_frame(&r0)->dx, npix);
                sum[3] = copy3(grad_method_frame(&r0)->dy, npix);
            }
            for (int k = 1; k < res->instances; k++) {
                struct render_params q = p;
                q.seed = p.seed + SEED_STRIDE * (uint64_t)k;
                struct renderer rk;
                renderer_init(&rk, s, m, &q);
                double ms_k = render_frames(&rk, s, 0, TIMING_SKIP, c->frames, pass_ms, &rays_k, NULL);
                res->rays += rays_k;
                res->ms += ms_k - pass_ms[PASS_RECON_L2] - pass_ms[PASS_RECON_L1];
                res->grad_ms += grad_pass_ms(pass_ms);
                const float *src[4] = {rk.image, grad_method_frame(&rk) ? grad_method_frame(&rk)->primal : NULL,
                                       grad_method_frame(&rk) ? grad_method_frame(&rk)->dx : NULL,
                                       grad_method_frame(&rk) ? grad_method_frame(&rk)->dy : NULL};
                for (int b = 0; b < 4; b++)
                    if (sum[b])
                        for (size_t i = 0; i < n3; i++)
                            sum[b][i] += src[b][i];
                renderer_fini(&rk);
            }
            float *dst[4] = {r0.image, grad_method_frame(&r0) ? grad_method_frame(&r0)->primal : NULL,
                             grad_method_frame(&r0) ? grad_method_frame(&r0)->dx : NULL,
                             grad_method_frame(&r0) ? grad_method_frame(&r0)->dy : NULL};
            const float inv = 1.0f / (float)res->instances;
            for (int b = 0; b < 4; b++) {
                if (!sum[b])
                    continue;
                for (size_t i = 0; i < n3; i++)
                    dst[b][i] = sum[b][i] * inv;
                free(sum[b]);
            }
        }
    }
    if (grad_method_frame(&r0)) {
        /* L2 again (the averaged inputs) and L1 (recon defaults), outside the budget */
        struct frame_stats st;
        memset(&st, 0, sizeof(st));
        recon_settings_mut(&r0.p)->mode = RECON_BOTH;
        renderer_reconstruct(&r0, &st);
        log_time(&l1_log, &l1_n, &l1_cap, st.ms[PASS_RECON_L1]);
        res->l1_image = copy3(grad_method_frame(&r0)->l1, npix);
        res->dx = copy3(grad_method_frame(&r0)->dx, npix);
        res->dy = copy3(grad_method_frame(&r0)->dy, npix);
        restir_metrics_compute(res->l1_image, ref->rgb, npix, NULL, &res->l1);
        res->mean_l1 = mean_lum(res->l1_image, npix) / mean_lum(ref->rgb, npix);
    } else {
        res->dx = xmalloc(n3 * sizeof(float));
        res->dy = xmalloc(n3 * sizeof(float));
        forward_differences(r0.image, c->width, c->height, res->dx, res->dy);
    }
    res->image = copy3(r0.image, npix);
    restir_metrics_compute(res->image, ref->rgb, npix, NULL, &res->l2);
    res->mean_l2 = mean_lum(res->image, npix) / mean_lum(ref->rgb, npix);
    res->grad_err = gradient_error(res->dx, res->dy, ref, npix);
    renderer_fini(&r0);
}

static void gb_result_free(struct gb_result *r)
{
    free(r->image);
    free(r->l1_image);
    free(r->dx);
    free(r->dy);
    free(r->frame_temporal_ms);
    free(r->frame_ms);
    free(r->frame_rays);
}

/* The equal-time rows of one scene (002 Fig. 8), in table order. */
enum { ROW_OURS, ROW_GRAD_AFTER, ROW_GPT, ROW_AREA, ROW_PT, ROWS };
static const char *const row_method[ROWS] = {"grestir-pt", "grad-after-restir", "gpt", "area-restir", "pt"};

/* The rows of an equal-time or equal-samples table; npix > 0 adds the rays/px column. */
static void print_rows(const struct gb_result *res, double npix)
{
    for (int k = 0; k < ROWS; k++) {
        const struct gb_result *r = &res[k];
        const int grad = method_has(r->method, METHOD_GRADIENT);
        char l1a[32], l1b[32], l1m[32], rays[32] = "";
        snprintf(l1a, sizeof(l1a), grad ? "%.5g" : "-", r->l1.relmse);
        snprintf(l1b, sizeof(l1b), grad ? "%.4f" : "-", r->l1.mape);
        snprintf(l1m, sizeof(l1m), grad ? ", %.3f" : "", r->mean_l1);
        if (npix > 0.0)
            snprintf(rays, sizeof(rays), " %.2f |", (double)r->rays / r->timed_frames / npix);
        printf("| %s%s | %.1f | %d | %d |%s %.5g | %.4f | %s | %s | %.2f | %.4f%s | %.3f%s |\n",
               r->method->name, k == ROW_OURS ? " (ours)" : "", r->ms, r->spp, r->instances, rays,
               r->l2.relmse, r->l2.mape, l1a, l1b, r->l2.relmse / res[ROW_OURS].l2.relmse, r->grad_err,
               grad ? "" : " *", r->mean_l2, l1m);
    }
}

static void equal_time(const struct scene *s, const char *name, const struct gb_config *c, const struct gb_ref *ref,
                       struct gb_result res[ROWS])
{
    double t0 = omp_get_wtime();
    run_method(s, c, method_named("grestir-pt"), "", 0.0, 0, ref, &res[ROW_OURS]);
    const double budget = res[ROW_OURS].ms;
    for (int k = 1; k < ROWS; k++)
        run_method(s, c, method_named(row_method[k]), "", budget, 0, ref, &res[k]);
    printf("\n### Equal time (002 Fig. 8) on %s, %dx%d, camera path, error of frame %d against a %d-spp pt "
           "reference; budget = grestir-pt's %.1f ms/frame (L2 included, frames %d-%d)\n\n",
           name, c->width, c->height, c->frames - 1, c->ref_spp, budget, TIMING_SKIP, c->frames - 1);
    printf("| method | ms/frame | spp | instances | relMSE L2 | MAPE L2 | relMSE L1 | MAPE L1 | relMSE L2 / ours L2 "
           "| gradient error | mean / ref L2, L1 |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    print_rows(res, 0.0);
    printf("\nL2 columns: the L2 reconstruction of the gradient methods, the image itself for area-restir and pt; "
           "L1: IRLS (20 x 50) of the same averaged inputs, untimed (BIASED). Gradient error: relative gradient "
           "RMSE sqrt(sum_a sum_{d=x,y} (lum(g_d(a)) - lum(g_ref,d(a)))^2 / sum_a (lum(ref(a))^2 + 1e-4)), "
           "g_ref the forward differences of the reference (which keep its own noise); * = the forward "
           "differences of the method's image (it estimates no gradients). Mean / ref: the image's mean luminance over "
           "the reference's. %.0f s.\n",
           omp_get_wtime() - t0);
    fflush(stdout);
}

/* --equal-samples: the rows of equal_time, each at 1 instance and 1 spp on the same frames (0 .. N-1
 * rendered, TIMING_SKIP .. N-1 timed), with the rays traced per pixel per timed frame; then
 * grestir-pt's PASS_GRAD_TEMPORAL, frame time and rays for frames 1 .. N-1 (frame 0 has no history). */
static void equal_samples(const struct scene *s, const char *name, const struct gb_config *c,
                          const struct gb_ref *ref)
{
    double t0 = omp_get_wtime();
    const double npix = (double)c->width * c->height;
    struct gb_result res[ROWS];
    for (int k = 0; k < ROWS; k++)
        run_method(s, c, method_named(row_method[k]), "", 0.0, 1, ref, &res[k]);
    printf("\n### Equal samples on %s, %dx%d, camera path, error of frame %d against a %d-spp pt reference; "
           "1 instance each, gpt and pt at 1 spp, all frames 0-%d rendered, frames %d-%d timed\n\n",
           name, c->width, c->height, c->frames - 1, c->ref_spp, c->frames - 1, TIMING_SKIP, c->frames - 1);
    printf("| method | ms/frame | spp | instances | rays/px per frame | relMSE L2 | MAPE L2 | relMSE L1 | MAPE L1 "
           "| relMSE L2 / ours L2 | gradient error | mean / ref L2, L1 |\n"
           "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    print_rows(res, npix);
    printf("\nColumns as in the equal-time tables; rays/px per frame: frame_stats.rays summed over the timed "
           "frames / frames / pixels (the reconstructions trace none).\n");
    const struct gb_result *o = &res[ROW_OURS];
    printf("\ngrestir-pt per frame on %s (frames 0-%d untimed in the table):\n\n", name, TIMING_SKIP - 1);
    for (int f = 1; f < c->frames; f++)
        printf("    frame %2d: grad_temporal %7.2f ms, frame %8.2f ms, rays %lld (%.2f/px)\n", f,
               o->frame_temporal_ms[f], o->frame_ms[f], o->frame_rays[f], (double)o->frame_rays[f] / npix);
    printf("\n%.0f s.\n", omp_get_wtime() - t0);
    fflush(stdout);
    for (int k = 0; k < ROWS; k++)
        gb_result_free(&res[k]);
}

/* Copies the w x h window at (x0, y0) of img (width W), upscaled by zoom (nearest), into out (width OW)
 * at (ox, oy). */
static void blit(float *out, int OW, int ox, int oy, const float *img, int W, int x0, int y0, int w, int h, int zoom)
{
    for (int y = 0; y < h * zoom; y++)
        for (int x = 0; x < w * zoom; x++) {
            const float *src = img + 3 * ((size_t)(y0 + y / zoom) * W + x0 + x / zoom);
            float *dst = out + 3 * ((size_t)(oy + y) * OW + ox + x);
            dst[0] = src[0], dst[1] = src[1], dst[2] = src[2];
        }
}

/* 002 Fig. 8 for ajar: rows = 2 crops (W/2 x H/2, 2x nearest), columns = gpt L2 | grad-after L2 |
 * ours L2 | area-restir | ours L1 | reference; and 002 Fig. 7: dx of gpt | grad-after | ours |
 * reference in false colour, one common scale (1 / the 99th percentile of the reference's |lum(dx)|). */
static void write_figures(const struct gb_config *c, const struct gb_result res[ROWS], const struct gb_ref *ref)
{
    const int W = c->width, H = c->height, cw = W / 2, ch = H / 2, zoom = 2, gap = 4;
    /* the door gap with the blue box and the gold sphere (upper middle), and the glossy floor with the
     * light's streak and the red box (bottom left) */
    const int crops[2][2] = {{W * 2 / 5, H / 10}, {W / 8, H / 2}};
    const float *cols[6] = {res[ROW_GPT].image,  res[ROW_GRAD_AFTER].image, res[ROW_OURS].image,
                            res[ROW_AREA].image, res[ROW_OURS].l1_image,   ref->rgb};
    const int PW = cw * zoom, PH = ch * zoom, OW = 6 * PW + 5 * gap, OH = 2 * PH + gap;
    float *out = xmalloc(3 * (size_t)OW * OH * sizeof(float));
    for (size_t i = 0; i < 3 * (size_t)OW * OH; i++)
        out[i] = 1e3f; /* white separators */
    for (int row = 0; row < 2; row++)
        for (int col = 0; col < 6; col++)
            blit(out, OW, col * (PW + gap), row * (PH + gap), cols[col], W, crops[row][0], crops[row][1], cw, ch,
                 zoom);
    char path[256], msg[RESTIR_MSG_LEN];
    make_dirs(IMAGE_DIR);
    snprintf(path, sizeof(path), "%s/ajar_fig8_%dx%d.png", IMAGE_DIR, W, H);
    if (png_write_srgb(path, out, OW, OH, AJAR_EXPOSURE, msg) != 0)
        fprintf(stderr, "restir_bench: %s\n", msg);
    else
        printf("\n%s: rows = crops (%d, %d) and (%d, %d), %dx%d each, 2x nearest; columns = gpt L2 | "
               "grad-after-restir L2 | grestir-pt L2 | area-restir | grestir-pt L1 | reference; exposure %+g "
               "(x%g)\n",
               path, crops[0][0], crops[0][1], crops[1][0], crops[1][1], cw, ch, AJAR_EXPOSURE,
               pow(2.0, AJAR_EXPOSURE));
    free(out);

    const float *gcols[4] = {res[ROW_GPT].dx, res[ROW_GRAD_AFTER].dx, res[ROW_OURS].dx, ref->dx};
    const int GW = 4 * W + 3 * gap;
    float *g = xcalloc(3 * (size_t)GW * H, sizeof(float)); /* separators: 0 = black */
    for (int col = 0; col < 4; col++)
        blit(g, GW, col * (W + gap), 0, gcols[col], W, 0, 0, W, H, 1);
    const size_t npix = (size_t)W * H;
    double *a = xmalloc(npix * sizeof(double));
    for (size_t i = 0; i < npix; i++)
        a[i] = fabs(lum(ref->dx + 3 * i));
    qsort(a, npix, sizeof(double), cmp_double);
    double p99 = a[(size_t)(0.99 * (double)(npix - 1))];
    free(a);
    float scale = p99 > 0.0 ? (float)(1.0 / p99) : 0.0f;
    snprintf(path, sizeof(path), "%s/ajar_gradients_%dx%d.png", IMAGE_DIR, W, H);
    if (png_write_signed(path, g, GW, H, scale, msg) != 0)
        fprintf(stderr, "restir_bench: %s\n", msg);
    else
        printf("\n%s: dx of gpt | grad-after-restir | grestir-pt | reference (forward differences), false colour "
               "(red +, blue -), common scale 1 / %.4g (99th percentile of the reference's |lum(dx)|)\n",
               path, p99);
    free(g);
}

/* 002 Fig. 9 (positivization), Fig. 10 (spatial reuse of paired-pixel samples) and Sec. 4.4 (reuse
 * across signs) on ajar: grestir-pt at its own cost, 1 instance. */
static void ablations(const struct scene *s, const struct gb_config *c, const struct gb_ref *ref)
{
    static const char *const sets[][2] = {
        {"", "default (positivize on, spatial adaptive, cross_sign off, base independent)"},
        {"grad.positivize=off", "grad.positivize=off (Fig. 9)"},
        {"grad.spatial=off", "grad.spatial=off (Fig. 10)"},
        {"grad.spatial=dense", "grad.spatial=dense (Fig. 10)"},
        {"grad.spatial=adaptive", "grad.spatial=adaptive (Fig. 10; = default, rerun: timing repeatability)"},
        {"grad.cross_sign=on", "grad.cross_sign=on (Sec. 4.4)"},
        {"grad.temporal=off", "grad.temporal=off (no temporal reuse of pairs)"},
        {"grad.base=shared", "grad.base=shared (pairs start from the primal's initial paths)"},
    };
    const int n = (int)(sizeof(sets) / sizeof(sets[0]));
    printf("\n### Ablations of grestir-pt on ajar (002 Fig. 9, Fig. 10, Sec. 4.4), %dx%d, camera path, error of "
           "frame %d, 1 instance each at its own cost (frames %d-%d timed)\n\n",
           c->width, c->height, c->frames - 1, TIMING_SKIP, c->frames - 1);
    printf("| configuration | ms/frame | ms grad passes | relMSE L2 | MAPE L2 | relMSE L1 | MAPE L1 | gradient error "
           "| mean / ref L2, L1 |\n|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; k++) {
        struct gb_result r;
        run_method(s, c, method_named("grestir-pt"), sets[k][0], 0.0, 0, ref, &r);
        printf("| %s | %.1f | %.1f | %.5g | %.4f | %.5g | %.4f | %.4f | %.3f, %.3f |\n", sets[k][1], r.ms,
               r.grad_ms, r.l2.relmse, r.l2.mape, r.l1.relmse, r.l1.mape, r.grad_err, r.mean_l2, r.mean_l1);
        fflush(stdout);
        gb_result_free(&r);
    }
    printf("\nms grad passes: grad_initial + grad_temporal + grad_select + grad_spatial + grad_shade per frame. "
           "Gradient error as in the equal-time tables.\n");
}

static int usage(void)
{
    fprintf(stderr, "usage: restir_bench gradient [--res WxH] [--frames N] [--ref-spp N] [--scenes a,b,c] [--quick]\n"
                    "                             [--equal-samples]\n"
                    "  defaults: 640x360, 16 frames, 2048 ref spp, scenes ajar,cornell,foliage;\n"
                    "  --quick: 320x180, 8 frames, 512 ref spp (explicit options override it);\n"
                    "  --equal-samples: per scene, every method at 1 instance / 1 spp on the same frames\n"
                    "  (with rays per pixel and grestir-pt's temporal pass per frame) instead of the\n"
                    "  equal-time tables, pictures and ablations\n");
    return 2;
}

int bench_gradient(int argc, char **argv)
{
    struct gb_config c = {640, 360, 16, 2048};
    char scene_list[256] = "ajar,cornell,foliage";
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--quick"))
            c = (struct gb_config){320, 180, 8, 512};
    int equal_samples_mode = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            continue;
        else if (!strcmp(argv[i], "--equal-samples"))
            equal_samples_mode = 1;
        else if (!strcmp(argv[i], "--res") && i + 1 < argc &&
                 sscanf(argv[i + 1], "%dx%d", &c.width, &c.height) == 2 && c.width >= 8 && c.height >= 8)
            i++;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && sscanf(argv[i + 1], "%d", &c.frames) == 1 &&
                 c.frames > TIMING_SKIP)
            i++;
        else if (!strcmp(argv[i], "--ref-spp") && i + 1 < argc && sscanf(argv[i + 1], "%d", &c.ref_spp) == 1 &&
                 c.ref_spp > 0)
            i++;
        else if (!strcmp(argv[i], "--scenes") && i + 1 < argc && strlen(argv[i + 1]) < sizeof(scene_list))
            snprintf(scene_list, sizeof(scene_list), "%s", argv[++i]);
        else
            return usage();
    }
    const char *scenes[MAX_SCENES];
    int nscenes = 0;
    for (char *tok = strtok(scene_list, ","); tok && nscenes < MAX_SCENES; tok = strtok(NULL, ","))
        scenes[nscenes++] = tok;
    if (nscenes == 0)
        return usage();

    struct render_params d = base_params(&c);
    double t_start = omp_get_wtime();
    printf("\n## Gradient-domain ReSTIR (002 Sec. 5), %dx%d, %d frames of the camera path, %d-spp references, "
           "%d threads\n\nPixel-scale parameters kept at their defaults, not scaled with the resolution: "
           "spatial.radius %g px, grad.radius %g px, grad.search %d. Primal: area ReSTIR (1 initial candidate, "
           "2 spatial neighbors) for area-restir, grad-after-restir and grestir-pt.\n",
           c.width, c.height, c.frames, c.ref_spp, omp_get_max_threads(), d.reuse.spatial_radius,
           grad_settings_of(&d)->radius, grad_settings_of(&d)->search);
    fflush(stdout);

    if (equal_samples_mode) {
        for (int k = 0; k < nscenes; k++) {
            struct scene s = bench_load_scene(scenes[k]);
            struct gb_ref ref;
            load_reference(&s, scenes[k], &c, &ref);
            equal_samples(&s, scenes[k], &c, &ref);
            free_reference(&ref);
            scene_destroy(&s);
        }
        printf("\nWall time of the section: %.0f s\n", omp_get_wtime() - t_start);
        free(l2_log);
        free(l1_log);
        return 0;
    }

    struct scene ajar;
    struct gb_ref ajar_ref = {NULL, NULL, NULL};
    int have_ajar = 0;
    for (int k = 0; k < nscenes; k++) {
        struct scene s = bench_load_scene(scenes[k]);
        struct gb_ref ref;
        load_reference(&s, scenes[k], &c, &ref);
        struct gb_result res[ROWS];
        equal_time(&s, scenes[k], &c, &ref, res);
        int is_ajar = !strcmp(scenes[k], "ajar") && !have_ajar;
        if (is_ajar)
            write_figures(&c, res, &ref);
        for (int r = 0; r < ROWS; r++)
            gb_result_free(&res[r]);
        if (is_ajar) { /* kept for the ablations */
            ajar = s;
            ajar_ref = ref;
            have_ajar = 1;
        } else {
            free_reference(&ref);
            scene_destroy(&s);
        }
    }
    printf("\n### Screened Poisson reconstruction times at %dx%d (%d threads)\n\n| solve | median ms | solves |\n"
           "|---|---|---|\n| L2 (%s, alpha %g) | %.1f | %d |\n| L1 (IRLS %d x %d CG) | %.1f | %d |\n",
           c.width, c.height, omp_get_max_threads(), recon_settings_of(&d)->solver == RESTIR_POISSON_DCT ? "DCT" : "CG",
           recon_settings_of(&d)->alpha, median(l2_log, l2_n), l2_n, recon_settings_of(&d)->l1_iterations,
           recon_settings_of(&d)->l1_cg, median(l1_log, l1_n), l1_n);
    fflush(stdout);
    if (!have_ajar) {
        ajar = bench_load_scene("ajar");
        load_reference(&ajar, "ajar", &c, &ajar_ref);
    }
    ablations(&ajar, &c, &ajar_ref);
    free_reference(&ajar_ref);
    scene_destroy(&ajar);
    printf("\nWall time of the section: %.0f s\n", omp_get_wtime() - t_start);
    free(l2_log);
    free(l1_log);
    return 0;
}
