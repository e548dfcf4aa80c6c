/* bench_main.c: `restir_bench`: per-pass timings with rays per second and the Embree-only replay
 * ratio, equal-time error of pt against restir-di and restir-pt (static camera and camera path),
 * the temporal-reuse experiment of 001 Sec. 6, and the bias of the 1/M weights. Prints Markdown
 * tables for docs/BENCHMARKS.md. Must never be run by the tests. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "core/check.h"
#include "experiments/equal_time.h"
#include "io/atomic_file.h"
#include "io/report.h"
#include "methods/renderer.h"
#include "methods/pt/pt.h"
#include "methods/settings.h"
#include "restir/metrics.h"
#include "scene/scene_ray_log.h"

struct bench_config {
    const char *scene;
    int width, height;
    int frames;   /* frames per timing run; error measured at the last */
    int ref_spp;
    int temporal_frames;
};

static struct render_params base_params(const struct bench_config *c)
{
    struct render_params p;
    render_params_defaults(&p);
    p.width = c->width;
    p.height = c->height;
    return p;
}

/* The CSV twins of the passes and equal-time tables (BENCH_OUT, default out/bench/), so scripts
 * read the numbers docs/BENCHMARKS.md shows. NULL when not open. */
static struct csv_writer *passes_csv, *equal_csv;

/* Opens BENCH_OUT/passes.csv and BENCH_OUT/equal_time.csv (the folder is created). */
static void bench_csv_open(struct csv_writer *pw, struct csv_writer *ew)
{
    const char *dir = getenv("BENCH_OUT");
    char path[4096], msg[RESTIR_MSG_LEN];
    if (!dir || !*dir)
        dir = "out/bench";
    if (io_make_dirs(dir, msg) != 0) {
        fprintf(stderr, "restir_bench: %s (no CSV written)\n", msg);
        return;
    }
    snprintf(path, sizeof(path), "%s/passes.csv", dir);
    if (csv_open(pw, path, "scene,method,width,height,frame_ms,embree_only_ms,ratio", msg) == 0)
        passes_csv = pw;
    else
        fprintf(stderr, "restir_bench: %s\n", msg);
    snprintf(path, sizeof(path), "%s/equal_time.csv", dir);
    if (csv_open(ew, path, "scene,method,camera,ms_per_frame,spp,relmse,mape,smape", msg) == 0)
        equal_csv = ew;
    else
        fprintf(stderr, "restir_bench: %s\n", msg);
}

static void bench_csv_close(void)
{
    char msg[RESTIR_MSG_LEN];
    struct csv_writer *w[2] = {passes_csv, equal_csv};
    for (int k = 0; k < 2; k++)
        if (w[k] && csv_close(w[k], msg) != 0)
            fprintf(stderr, "restir_bench: %s\n", msg);
    passes_csv = equal_csv = NULL;
}

/* Embree-only ms of the rays in each batching (scene_ray_replay_batched), twice in alternating
 * rounds (this machine's speed drifts), the best of each into best[]. */
static void replay_best(const struct scene *s, const struct ray_record *rays, size_t n, double *best)
{
    for (int b = 0; b < RAY_BATCH_COUNT; b++)
        best[b] = INFINITY;
    for (int round = 0; round < 2; round++)
        for (int b = 0; b < RAY_BATCH_COUNT; b++) {
            const double t = scene_ray_replay_batched(s, rays, n, (enum ray_batch)b);
            best[b] = t < best[b] ? t : best[b];
        }
}

/* Per-pass timing over frames 1..N-1 (frame 0 has no history), rays per second, and the last
 * frame's rays replayed through Embree alone. Pass columns: those any of the methods ran. sets:
 * NULL, or per method NULL or a "key=value[:key=value]..." list already checked by
 * render_params_set_list; the row is labelled "method:list". */
#define BENCH_MAX_METHODS 4
static void bench_passes(const struct bench_config *c, const struct method **methods, const char *const *sets,
                         int nmethods)
{
    char label[BENCH_MAX_METHODS][160];
    for (int k = 0; k < nmethods; k++)
        snprintf(label[k], sizeof(label[k]), "%s%s%s", methods[k]->name, sets && sets[k] ? ":" : "",
                 sets && sets[k] ? sets[k] : "");
    struct scene s = bench_load_scene(c->scene);
    double ms[BENCH_MAX_METHODS][PASS_COUNT] = {{0}}, total[BENCH_MAX_METHODS] = {0}, rays[BENCH_MAX_METHODS] = {0};
    double replay_ms[BENCH_MAX_METHODS] = {0}, frame_ms[BENCH_MAX_METHODS] = {0}, rays_px[BENCH_MAX_METHODS] = {0};
    double batch_ms[BENCH_MAX_METHODS][RAY_BATCH_COUNT] = {{0}}, kind_ms[BENCH_MAX_METHODS][3][RAY_BATCH_COUNT];
    size_t kind_count[BENCH_MAX_METHODS][3] = {{0}};
    RESTIR_CHECK(nmethods <= BENCH_MAX_METHODS);
    for (int k = 0; k < nmethods; k++) {
        struct render_params p = base_params(c);
        if (methods[k] == method_named("pt"))
            method_reference_params(methods[0], &p); /* pt over the first method's integrand, 1 spp */
        char msg[RESTIR_MSG_LEN];
        if (sets && sets[k])
            RESTIR_CHECK(render_params_set_list(&p, sets[k], msg) == 0);
        struct renderer r;
        renderer_init(&r, &s, methods[k], &p);
        struct frame_stats st;
        struct camera cam = scene_camera_at(&s, 0, 0.0f);
        for (int f = 0; f < c->frames; f++) {
            renderer_render(&r, f, &cam, &st);
            if (f == 0)
                continue;
            for (int q = 0; q < PASS_COUNT; q++)
                ms[k][q] += st.ms[q];
            total[k] += st.ms_total;
            rays[k] += (double)st.rays;
        }
        /* One more frame, logged, only for its rays: logging costs the frame ~36 bytes per ray
         * (page faults included), so timed frames are never logged. The replay is scaled from
         * the logged frame's rays to the timed frames' mean. */
        scene_ray_log_begin(&s);
        renderer_render(&r, c->frames, &cam, &st);
        size_t nrays;
        struct ray_record *log = scene_ray_log_end(&s, &nrays);
        double best[RAY_BATCH_COUNT];
        replay_best(&s, log, nrays, best);
        /* The same by kind of ray (one logged frame's, unscaled): where batching pays. */
        struct ray_record *sub = xmalloc(sizeof(*sub) * (nrays ? nrays : 1));
        for (int kind = 0; kind < 3; kind++) {
            size_t m = 0;
            for (size_t i = 0; i < nrays; i++)
                if (log[i].kind == kind)
                    sub[m++] = log[i];
            kind_count[k][kind] = m;
            replay_best(&s, sub, m, kind_ms[k][kind]);
        }
        free(sub);
        const double mean_rays = rays[k] / (c->frames - 1);
        const double scale = nrays ? mean_rays / (double)nrays : 1.0;
        replay_ms[k] = best[RAY_BATCH_SINGLE] * scale;
        for (int b = 0; b < RAY_BATCH_COUNT; b++)
            batch_ms[k][b] = best[b] * scale;
        frame_ms[k] = total[k] / (c->frames - 1);
        rays_px[k] = mean_rays / ((double)c->width * c->height);
        free(log);
        renderer_fini(&r);
    }
    int used[PASS_COUNT] = {0};
    for (int k = 0; k < nmethods; k++)
        for (int q = 0; q < PASS_COUNT; q++)
            used[q] |= ms[k][q] > 0.0;
    printf("\n### Per-pass time, %s %dx%d, static camera, mean of frames 1-%d (%d threads)\n\n| method |", c->scene,
           c->width, c->height, c->frames - 1, omp_get_max_threads());
    for (int q = 0; q < PASS_COUNT; q++)
        if (used[q])
            printf(" %s |", pass_name(q));
    printf(" frame ms | Mrays/s | rays/px | Embree-only ms | frame / Embree-only |\n|---|");
    for (int q = 0; q < PASS_COUNT; q++)
        if (used[q])
            printf("---|");
    printf("---|---|---|---|---|\n");
    const int n = c->frames - 1;
    for (int k = 0; k < nmethods; k++) {
        printf("| %s |", label[k]);
        for (int q = 0; q < PASS_COUNT; q++)
            if (used[q])
                printf(" %.2f |", ms[k][q] / n);
        printf(" %.2f | %.2f | %.2f | %.2f | %.2f |\n", total[k] / n, rays[k] / (total[k] * 1e3), rays_px[k],
               replay_ms[k], frame_ms[k] / replay_ms[k]);
        if (passes_csv)
            csv_row(passes_csv, "%s,%s,%d,%d,%.3f,%.3f,%.4f", c->scene, label[k], c->width,
                    c->height, frame_ms[k], replay_ms[k], frame_ms[k] / replay_ms[k]);
    }
    printf("\nEmbree-only ms of the same rays batched as the threads traced them (consecutive same-kind "
           "rays):\n\n| method | single | packet 8 | packet 16 | stream 64 | stream 64 coherent |\n"
           "|---|---|---|---|---|---|\n");
    for (int k = 0; k < nmethods; k++) {
        printf("| %s |", label[k]);
        for (int b = 0; b < RAY_BATCH_COUNT; b++)
            printf(" %.2f |", batch_ms[k][b]);
        printf("\n");
    }
    static const char *const kind_names[3] = {"closest hits", "occlusion", "emitters only"};
    printf("\nThe same by kind of ray (one frame's rays, ms; each kind's rays in the order traced):\n\n"
           "| method | rays | count | single | packet 8 | packet 16 | stream 64 | stream 64 coherent |\n"
           "|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < nmethods; k++)
        for (int kind = 0; kind < 3; kind++) {
            if (!kind_count[k][kind])
                continue;
            printf("| %s | %s | %zu |", label[k], kind_names[kind], kind_count[k][kind]);
            for (int b = 0; b < RAY_BATCH_COUNT; b++)
                printf(" %.2f |", kind_ms[k][kind][b]);
            printf("\n");
        }
    scene_destroy(&s);
}

/* Equal time: the method's mean frame time buys pt as many paths per pixel as fit; errors at the
 * last frame against a reference from that frame's camera (static camera or the camera path). */
static void bench_equal_time(const struct bench_config *c, const struct method *method, int use_path)
{
    struct scene s = bench_load_scene(c->scene);
    struct render_params p = base_params(c);
    const int last = c->frames - 1;
    float *ref = bench_reference(&s, method, &p, (float)last, use_path, c->ref_spp);
    size_t npix = (size_t)c->width * c->height;
    struct frame_stats st;

    struct renderer r;
    renderer_init(&r, &s, method, &p);
    double total = 0.0;
    for (int f = 0; f < c->frames; f++) {
        struct camera cam = scene_camera_at(&s, use_path, (float)f);
        renderer_render(&r, f, &cam, &st);
        total += st.ms_total;
    }
    double budget = total / c->frames;
    struct restir_metrics_error e_m;
    restir_metrics_compute(r.image, ref, npix, NULL, &e_m);
    renderer_fini(&r);

    /* pt's paths per pixel in the budget: the cost per path from 1 and 4 spp (their difference removes
     * the per-frame overhead), timed from the last frame's camera. */
    struct camera cam = scene_camera_at(&s, use_path, (float)last);
    struct render_params q = p;
    method_reference_params(method, &q);
    q.spp = equal_time_spp_for(&s, method_named("pt"), &q, &cam, 0, budget); /* as restir compare --equal-time */
    renderer_init(&r, &s, method_named("pt"), &q);
    renderer_render(&r, last, &cam, &st);
    struct restir_metrics_error e_pt;
    restir_metrics_compute(r.image, ref, npix, NULL, &e_pt);
    double pt_ms = st.ms_total;
    renderer_fini(&r);

    const char *name = method->name;
    printf("\n### Equal time, %s, %s %dx%d, %s, error at frame %d (reference: %d spp)\n\n", name, c->scene,
           c->width, c->height, use_path ? "camera path" : "static camera", last, c->ref_spp);
    printf("| method | ms/frame | spp | relMSE | MAPE | SMAPE |\n|---|---|---|---|---|---|\n");
    printf("| %s | %.1f | 1 | %.5g | %.4f | %.2f |\n", name, budget, e_m.relmse, e_m.mape, e_m.smape);
    printf("| pt | %.1f | %d | %.5g | %.4f | %.2f |\n", pt_ms, q.spp, e_pt.relmse, e_pt.mape, e_pt.smape);
    printf("\nrelMSE(pt) / relMSE(%s) = **%.2f**; MAPE ratio %.2f; SMAPE ratio %.2f\n", name,
           e_pt.relmse / e_m.relmse, e_pt.mape / e_m.mape, e_pt.smape / e_m.smape);
    if (equal_csv) {
        const char *camera = use_path ? "path" : "static";
        csv_row(equal_csv, "%s,%s,%s,%.3f,1,%.6g,%.6g,%.6g", c->scene, name, camera, budget, e_m.relmse, e_m.mape,
                e_m.smape);
        csv_row(equal_csv, "%s,pt,%s,%.3f,%d,%.6g,%.6g,%.6g", c->scene, camera, pt_ms, q.spp, e_pt.relmse, e_pt.mape,
                e_pt.smape);
    }
    free(ref);
    scene_destroy(&s);
}

static double luma_rmse(const float *a, const float *b, size_t npix)
{
    double sum = 0.0;
    for (size_t i = 0; i < npix; i++) {
        double d = v3_luminance(v3(a[3 * i], a[3 * i + 1], a[3 * i + 2])) -
                   v3_luminance(v3(b[3 * i], b[3 * i + 1], b[3 * i + 2]));
        sum += d * d;
    }
    return sqrt(sum / (double)npix);
}

/* 001 Sec. 6: per-frame accuracy (static and moving camera), adjacent-frame stability and the
 * accuracy of the progressive average, with and without temporal reuse (spatial reuse off, as in
 * the note), for mis=1/M (the note's biased MVP) and mis=pairwise. */
static void bench_temporal(const struct bench_config *c)
{
    struct scene s = bench_load_scene(c->scene);
    struct render_params p = base_params(c);
    size_t npix = (size_t)c->width * c->height, n3 = 3 * npix;
    const int nf = c->temporal_frames, moving_frames = 16;
    float *ref_static = bench_reference(&s, method_named("restir-di"), &p, 0.0f, 0, c->ref_spp);
    float **ref_moving = xmalloc(sizeof(float *) * moving_frames);
    for (int f = 0; f < moving_frames; f++)
        ref_moving[f] = bench_reference(&s, method_named("restir-di"), &p, (float)f, 1, c->ref_spp / 4);
    printf("\n### Temporal reuse (001 Sec. 6), %s %dx%d, spatial reuse off; static: %d frames, moving: %d "
           "frames of the camera path; references %d / %d spp\n\n",
           c->scene, c->width, c->height, nf, moving_frames, c->ref_spp, c->ref_spp / 4);
    printf("| mis | temporal | static per-frame luma RMSE | adjacent-frame luma RMSE | moving per-frame luma RMSE | "
           "accumulated RGB RMSE | accumulated luma ratio |\n|---|---|---|---|---|---|---|\n");
    const char *mis_names[2] = {"1/M", "pairwise"};
    float *prev = xcalloc(n3, sizeof(float)), *acc = xcalloc(n3, sizeof(float));
    for (int m = 0; m < 2; m++) {
        for (int temporal = 0; temporal < 2; temporal++) {
            struct render_params q = p;
            char msg[RESTIR_MSG_LEN];
            char set[32];
            snprintf(set, sizeof(set), "mis=%s", mis_names[m]);
            render_params_set(&q, set, msg);
            q.reuse.spatial = 0;
            q.reuse.temporal = temporal;
            struct renderer r;
            struct frame_stats st;
            renderer_init(&r, &s, method_named("restir-di"), &q);
            double per_frame = 0.0, adjacent = 0.0;
            memset(acc, 0, n3 * sizeof(float));
            struct camera cam = scene_camera_at(&s, 0, 0.0f);
            for (int f = 0; f < nf; f++) {
                renderer_render(&r, f, &cam, &st);
                if (f > 0) {
                    per_frame += luma_rmse(r.image, ref_static, npix);
                    adjacent += luma_rmse(r.image, prev, npix);
                }
                memcpy(prev, r.image, n3 * sizeof(float));
                for (size_t i = 0; i < n3; i++)
                    acc[i] += r.image[i] / (float)nf;
            }
            renderer_fini(&r);
            double rgb = 0.0, lum_acc = 0.0, lum_ref = 0.0;
            for (size_t i = 0; i < n3; i++)
                rgb += (double)(acc[i] - ref_static[i]) * (acc[i] - ref_static[i]);
            for (size_t i = 0; i < npix; i++) {
                lum_acc += v3_luminance(v3(acc[3 * i], acc[3 * i + 1], acc[3 * i + 2]));
                lum_ref += v3_luminance(v3(ref_static[3 * i], ref_static[3 * i + 1], ref_static[3 * i + 2]));
            }
            q.camera_path = 1;
            renderer_init(&r, &s, method_named("restir-di"), &q);
            double moving = 0.0;
            for (int f = 0; f < moving_frames; f++) {
                struct camera mc = scene_camera_at(&s, 1, (float)f);
                renderer_render(&r, f, &mc, &st);
                if (f > 0)
                    moving += luma_rmse(r.image, ref_moving[f], npix);
            }
            renderer_fini(&r);
            printf("| %s | %s | %.5f | %.5f | %.5f | %.6f | %.6f |\n", mis_names[m], temporal ? "on" : "off",
                   per_frame / (nf - 1), adjacent / (nf - 1), moving / (moving_frames - 1), sqrt(rgb / (double)n3),
                   lum_acc / lum_ref);
        }
    }
    free(prev);
    free(acc);
    for (int f = 0; f < moving_frames; f++)
        free(ref_moving[f]);
    free(ref_moving);
    free(ref_static);
    scene_destroy(&s);
}

/* 000 Table 1 layout: rows are passes, columns are scenes; restir-pt, static camera, mean of
 * frames 1..N-1. */
static void bench_table1(const struct bench_config *c, const char *const *scenes, int nscenes)
{
    enum { ROWS = 7 };
    static const char *const rows[ROWS] = {"G-buffer",      "Initial Sampling", "Temporal Resampling",
                                           "Neighbor Selection", "Spatial Reuse", "Shading", "Full Frame"};
    double ms[8][ROWS] = {{0}};
    for (int sc = 0; sc < nscenes; sc++) {
        struct scene s = bench_load_scene(scenes[sc]);
        struct render_params p = base_params(c);
        struct renderer r;
        renderer_init(&r, &s, method_named("restir-pt"), &p);
        struct camera cam = scene_camera_at(&s, 0, 0.0f);
        for (int f = 0; f < c->frames; f++) {
            struct frame_stats st;
            renderer_render(&r, f, &cam, &st);
            if (f == 0)
                continue;
            const double v[ROWS] = {st.ms[PASS_GBUFFER], st.ms[PASS_INITIAL], st.ms[PASS_TEMPORAL], st.ms[PASS_SELECT],
                                    st.ms[PASS_SPATIAL], st.ms[PASS_SHADE], st.ms_total};
            for (int q = 0; q < ROWS; q++)
                ms[sc][q] += v[q] / (c->frames - 1);
        }
        renderer_fini(&r);
        scene_destroy(&s);
    }
    printf("\n### restir-pt per-pass CPU time (ms), layout of 000 Table 1, %dx%d, %d threads, mean of frames 1-%d\n\n|",
           c->width, c->height, omp_get_max_threads(), c->frames - 1);
    for (int sc = 0; sc < nscenes; sc++)
        printf(" | %s", scenes[sc]);
    printf(" |\n|---");
    for (int sc = 0; sc < nscenes; sc++)
        printf("|---");
    printf("|\n");
    for (int q = 0; q < ROWS; q++) {
        printf("| %s", rows[q]);
        for (int sc = 0; sc < nscenes; sc++)
            printf(" | %.1f", ms[sc][q]);
        printf(" |\n");
    }
}

/* Bias of a MIS choice: the image mean of `runs` independent sequences (last frame) against the
 * reference, with the standard error from the spread of per-run image means. */
static void bench_bias(const char *scene, const struct method *method, int w, int h, int runs, int frames, int ref_spp)
{
    struct scene s = bench_load_scene(scene);
    struct render_params p;
    render_params_defaults(&p);
    p.width = w;
    p.height = h;
    float *ref = bench_reference(&s, method, &p, 0.0f, 0, ref_spp);
    size_t npix = (size_t)w * h;
    double ref_mean = 0.0;
    for (size_t i = 0; i < npix; i++)
        ref_mean += v3_luminance(v3(ref[3 * i], ref[3 * i + 1], ref[3 * i + 2])) / (double)npix;
    printf("\n### Bias of the resampling MIS, %s on %s %dx%d: image mean of frame %d over %d runs vs a %d-spp "
           "reference (mean %.5f)\n\n| mis | image mean | relative bias | z |\n|---|---|---|---|\n",
           method->name, scene, w, h, frames - 1, runs, ref_spp, ref_mean);
    const char *mis[3] = {"pairwise", "balance", "1/M"};
    for (int m = 0; m < 3; m++) {
        char set[32], msg[RESTIR_MSG_LEN];
        snprintf(set, sizeof(set), "mis=%s", mis[m]);
        struct render_params q = p;
        render_params_set(&q, set, msg);
        double sum = 0.0, sum2 = 0.0;
        struct camera cam = scene_camera_at(&s, 0, 0.0f);
        for (int k = 0; k < runs; k++) {
            q.seed = 7000 + (uint64_t)k;
            struct renderer r;
            struct frame_stats st;
            renderer_init(&r, &s, method, &q);
            for (int f = 0; f < frames; f++)
                renderer_render(&r, f, &cam, &st);
            double mean = 0.0;
            for (size_t i = 0; i < npix; i++)
                mean += v3_luminance(v3(r.image[3 * i], r.image[3 * i + 1], r.image[3 * i + 2])) / (double)npix;
            sum += mean;
            sum2 += mean * mean;
            renderer_fini(&r);
        }
        double mu = sum / runs, var = (sum2 / runs - mu * mu) * runs / (runs - 1);
        double se = sqrt(var / runs + 0.0);
        printf("| %s | %.5f | %+.2f%% | %.1f |\n", mis[m], mu, 100.0 * (mu - ref_mean) / ref_mean,
               se > 0.0 ? (mu - ref_mean) / se : 0.0);
    }
    free(ref);
    scene_destroy(&s);
}

/* What the sections of the default run share: the base configuration, the spmis options and the
 * modes. */
struct bench_run {
    struct bench_config c;
    struct bench_spmis_options so;
    int quick;       /* --quick: smaller images and references */
    int bench_quick; /* BENCH_QUICK set (not 0): the rows of passes.csv and equal_time.csv only */
};

static void section_passes(struct bench_run *r)
{
    const struct method *di_methods[] = {method_named("restir-di"), method_named("ris-di"), method_named("pt")};
    bench_passes(&r->c, di_methods, NULL, 3);
}

static void section_equal_time(struct bench_run *r)
{
    bench_equal_time(&r->c, method_named("restir-di"), 0);
    if (r->bench_quick)
        bench_equal_time(&r->c, method_named("restir-di"), 1);
}

static void section_visibility(struct bench_run *r)
{
    bench_di_visibility(r->c.scene, r->c.width, r->c.height, r->c.frames, r->c.ref_spp);
}

/* restir-pt's passes and equal-time rows on scene (both cameras). */
static void pt_rows(const struct bench_config *c, const char *scene)
{
    struct bench_config pc = *c;
    pc.scene = scene;
    const struct method *pt_methods[] = {method_named("restir-pt"), method_named("pt")};
    bench_passes(&pc, pt_methods, NULL, 2);
    bench_equal_time(&pc, method_named("restir-pt"), 0);
    bench_equal_time(&pc, method_named("restir-pt"), 1);
}

static void section_pt(struct bench_run *r)
{
    const char *const pt_scenes[] = {"ajar", "cornell"};
    bench_table1(&r->c, pt_scenes, 2);
    for (int sc = 0; sc < 2; sc++) {
        pt_rows(&r->c, pt_scenes[sc]);
        bench_bias(pt_scenes[sc], method_named("restir-pt"), 64, 36, r->c.width < 640 ? 64 : 256, 8, 4096);
    }
}

static void section_temporal(struct bench_run *r)
{
    struct bench_config t = r->c;
    t.width = r->c.width / 2;
    t.height = r->c.height / 2;
    bench_temporal(&t);
}

static void section_spmis(struct bench_run *r)
{
    if (r->quick) {
        r->so.runs = 1;
        r->so.ref_spp = 256;
    }
    bench_spmis(&r->so);
}

/* `restir_bench frame-ratio SCENE METHOD[:key=value...][,...] [--res WxH] [--frames N]`: only the
 * per-pass table (with Frame / Embree-only) of the methods named, on one scene, without the
 * equal-time references the sections add: the ratio docs/BENCHMARKS.md tracks for ReSTIR DI and
 * PT, cheap enough to take before and after a change, or for two settings of one method in one run. */
static int bench_frame_ratio(int argc, char **argv)
{
    struct bench_config c = {NULL, 640, 360, 17, 0, 0};
    const struct method *methods[BENCH_MAX_METHODS];
    const char *sets[BENCH_MAX_METHODS];
    int n = 0;
    char names[512], msg[RESTIR_MSG_LEN];
    if (argc < 3 || snprintf(names, sizeof(names), "%s", argv[2]) >= (int)sizeof(names))
        goto usage;
    c.scene = argv[1];
    for (char *tok = strtok(names, ","); tok; tok = strtok(NULL, ",")) {
        char *list = strchr(tok, ':');
        if (list)
            *list++ = '\0';
        if (n == BENCH_MAX_METHODS || !(methods[n] = method_named(tok)))
            goto usage;
        struct render_params probe;
        render_params_defaults(&probe);
        if (list && render_params_set_list(&probe, list, msg) != 0) {
            fprintf(stderr, "restir_bench frame-ratio: %s: %s\n", tok, msg);
            return 2;
        }
        sets[n++] = list;
    }
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "--res") && i + 1 < argc && sscanf(argv[i + 1], "%dx%d", &c.width, &c.height) == 2 &&
            c.width > 0 && c.height > 0)
            i++;
        else if (!strcmp(argv[i], "--frames") && i + 1 < argc && sscanf(argv[i + 1], "%d", &c.frames) == 1 &&
                 c.frames >= 2)
            i++;
        else
            goto usage;
    }
    if (n == 0)
        goto usage;
    bench_passes(&c, methods, sets, n);
    return 0;
usage:
    fprintf(stderr, "usage: restir_bench frame-ratio SCENE METHOD[:key=value...][,...] [--res WxH] [--frames N>=2]\n");
    return 2;
}

/* The sections of the default run, in the order they run: `restir_bench NAME...` runs those named,
 * none named runs them all (BENCH_QUICK: those marked quick, then restir-pt's rows on ajar). */
static const struct bench_section {
    const char *name;
    void (*run)(struct bench_run *r);
    const char *help;
    int quick; /* run by BENCH_QUICK when no section is named: what fills passes.csv and equal_time.csv */
} sections[] = {
    {"passes", section_passes,
     "per-pass ms of restir-di, ris-di and pt with rays per second and the Embree-only replay ratio", 1},
    {"equal-time", section_equal_time, "equal-time error of restir-di against pt (BENCH_QUICK: both cameras)", 1},
    {"visibility", section_visibility, "restir-di's visibility reuse variants and its defaults at equal time", 0},
    {"pt", section_pt, "restir-pt against pt on ajar and cornell: 000's Table 1, passes, equal time, 1/M bias", 0},
    {"temporal", section_temporal, "the temporal-reuse experiment of 001 Sec. 6", 0},
    {"spmis", section_spmis, "004 Sec. 6: standard spatial reuse against SPMIS, its tables and ablations", 0},
};

/* The commands with their own arguments, `restir_bench NAME ARGS...` (run receives argv from NAME
 * on); never part of the default run. */
static const struct bench_command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *args, *help;
} commands[] = {
    {"poisson", bench_poisson, "[--runs N] [--res WxH[,WxH...]] [--lib-threads N]",
     "wall time of the Poisson reconstructions on a synthetic image"},
    {"l1-bias", bench_l1_bias, "FRAME.exr REF.exr", "where L1 reconstruction's dark bias comes from"},
    {"error", bench_error, "IMAGE.exr REF.exr", "the error metrics and HDR-FLIP of one image against a reference"},
    {"gi-bias", bench_gi_bias, "[--scenes a,b] [--res WxH] [--runs N] [--frames N]",
     "the bias of restir-gi's gi.radiance=stored"},
    {"streams", bench_streams, "[--res WxH] [--rounds N]", "the batched passes with rays.streams on against off"},
    {"gradient", bench_gradient, "[--res WxH] [--frames N] [--ref-spp N] [--scenes a,b,c] [--quick]",
     "002 Sec. 5 on our scenes (restir_bench gradient --help: all its options)"},
    {"frame-ratio", bench_frame_ratio, "SCENE METHOD[:key=value...][,...] [--res WxH] [--frames N]",
     "per-pass ms and Frame / Embree-only of the methods named, nothing else"},
    {"denoise", bench_denoise,
     "[--scene S] [--method M] [--res WxH] [--frames N>=3] [--threads T] [--camera static|path] "
     "[--isa baseline|avx2|avx512] [--set key=value]...",
     "what each denoiser costs beside the frame it denoises"},
};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* The usage: the default run's sections, each command's arguments, spmis's options, then what each
 * section and command measures. */
static int usage(void)
{
    fprintf(stderr, "usage: restir_bench");
    for (int k = 0; k < COUNT(sections); k++)
        fprintf(stderr, " [%s]", sections[k].name);
    fprintf(stderr, " [--quick]\n");
    for (int k = 0; k < COUNT(commands); k++)
        fprintf(stderr, "       restir_bench %s %s\n", commands[k].name, commands[k].args);
    fprintf(stderr, "       spmis options: [--spmis-res WxH] [--spmis-scaled] [--spmis-main | --spmis-ablations | "
                    "--spmis-interplay]\n"
                    "sections (none named: all of them; BENCH_QUICK=1: passes and equal-time, then restir-pt's "
                    "rows on ajar):\n");
    for (int k = 0; k < COUNT(sections); k++)
        fprintf(stderr, "  %-12s %s\n", sections[k].name, sections[k].help);
    fprintf(stderr, "commands (their own arguments; not part of the default run):\n");
    for (int k = 0; k < COUNT(commands); k++)
        fprintf(stderr, "  %-12s %s\n", commands[k].name, commands[k].help);
    return 2;
}

int main(int argc, char **argv)
{
    struct bench_run r = {.c = {"many-lights", 640, 360, 17, 1024, 64}, .so = {320, 180, 2, 1024, 0, 1, 1, 1}};
    int selected[COUNT(sections)] = {0}, any = 0;
    for (int k = 0; argc > 1 && k < COUNT(commands); k++)
        if (!strcmp(argv[1], commands[k].name))
            return commands[k].run(argc - 1, argv + 1);
    for (int i = 1; i < argc; i++) {
        int section = -1;
        for (int k = 0; k < COUNT(sections) && section < 0; k++)
            if (!strcmp(argv[i], sections[k].name))
                section = k;
        if (section >= 0)
            selected[section] = any = 1;
        else if (!strcmp(argv[i], "--spmis-res") && i + 1 < argc &&
                 sscanf(argv[i + 1], "%dx%d", &r.so.width, &r.so.height) == 2 && r.so.width > 0 && r.so.height > 0)
            i++;
        else if (!strcmp(argv[i], "--spmis-scaled"))
            r.so.scale_radii = 1;
        else if (!strcmp(argv[i], "--spmis-main"))
            r.so.ablations = r.so.interplay = 0;
        else if (!strcmp(argv[i], "--spmis-ablations"))
            r.so.main = r.so.interplay = 0;
        else if (!strcmp(argv[i], "--spmis-interplay"))
            r.so.main = r.so.ablations = 0;
        else if (!strcmp(argv[i], "--quick")) {
            r.quick = 1;
            r.c.width = 320;
            r.c.height = 180;
            r.c.ref_spp = 256;
            r.c.temporal_frames = 16;
        } else
            return usage();
    }
    const char *bq = getenv("BENCH_QUICK");
    r.bench_quick = bq && *bq && strcmp(bq, "0") != 0;
    /* none named: all, or under BENCH_QUICK what fills passes.csv and equal_time.csv (the DI tables and
     * restir-pt's on ajar, below) with 256-spp references (BENCHMARKS.md says which rows came from
     * this mode) */
    for (int k = 0; k < COUNT(sections) && !any; k++)
        selected[k] = !r.bench_quick || sections[k].quick;
    if (r.bench_quick && !any)
        r.c.ref_spp = 256;
    struct csv_writer pw, ew;
    bench_csv_open(&pw, &ew);
    int ran_pt = 0;
    for (int k = 0; k < COUNT(sections); k++)
        if (selected[k]) {
            sections[k].run(&r);
            ran_pt |= sections[k].run == section_pt;
        }
    if (r.bench_quick && !ran_pt)
        pt_rows(&r.c, "ajar");
    bench_csv_close();
    return 0;
}
