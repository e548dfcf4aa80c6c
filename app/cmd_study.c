/* cmd_study.c: `restir study`, the error-correlation study of 000 Sec. 6-7 and Appendices A-B: per
 * configuration of spatial neighbor selection, N independently seeded static-camera sequences
 * after a warm-up; SMAPE over all and over hard pixels, temporal and spatial relative covariance,
 * pass times. Writes study.csv, study.md, pareto.svg, hard_pixels.png and strip.png.
 * Must never implement a method: it drives the renderer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_file.h"
#include "study_report.h"
#include "cli.h"
#include "core/check.h"
#include "io/image_io.h"
#include "io/report.h"
#include "io/svg_plot.h"
#include "options.h"
#include "render/gbuffer.h"

#define STUDY_MAX_CONFIGS 64
#define HARD_FRACTION 0.1f /* 000 Sec. 7: the hardest 10% of pixels */
#define HARD_RADIUS 30.0f  /* ... judged within Bitterli's 30-pixel radius */
#define COV_RADIUS 8       /* 000 Appendix A: radial covariance over radius-8 disks */
#define COV_LAG 3          /* 000 Appendix A: autocovariance at a lag of 3 frames */
#define COV_EPS 1e-4f
#define STRIP_SCALE 4      /* strip plot: rows per frame */

struct study_config {
    char name[40];
    enum spatial_select_mode select;
    float radius;
    int candidates;
    int sweep; /* 0: named; 1: bitterli radius sweep; 2: compat radius sweep (000 Figure 3) */
};

struct study_result {
    double smape_all, smape_hard, temporal_cov, spatial_cov, ms_select, ms_spatial, ms_frame;
};

static void study_usage(FILE *out)
{
    fprintf(out,
            "usage: restir study --scene NAME --method restir-di|restir-pt --configs LIST [--radii LIST]\n"
            "                    [--runs N] [--warmup N] [--frames F] [--res WxH] [--ref FILE.exr | --ref-spp N]\n"
            "                    [--set key=value]... [--report] --out DIR\n"
            "The error-correlation study of 000 (Sec. 6-7, Appendix A): N independently seeded sequences per\n"
            "configuration (static camera, confidence cap 20, --warmup frames before measuring, default 40),\n"
            "then --frames measured frames (default 16). LIST: bitterli, fast, balanced, conservative,\n"
            "compat, compat-binary. --radii R1,R2,... adds bitterli and compat at each radius (the Pareto\n"
            "curves). Spatial neighbors M: --set spatial.neighbors=M. Default --res 320x180, --runs 8.\n"
            "Writes DIR/study.csv, study.md, pareto.svg, hard_pixels.png, strip.png; with --report also\n"
            "DIR/index.html, one self-contained page showing them with the command, commit and machine.\n");
}

/* A named configuration at radius r (the radius of bitterli, compat and compat-binary). */
static int named_config(const char *name, float r, int candidates, struct study_config *c, char *msg)
{
    memset(c, 0, sizeof(*c));
    snprintf(c->name, sizeof(c->name), "%s", name);
    c->radius = r;
    c->candidates = 32;
    if (!strcmp(name, "bitterli")) {
        c->select = SELECT_BITTERLI;
        c->candidates = 0;
    } else if (!strcmp(name, "fast") || !strcmp(name, "balanced") || !strcmp(name, "conservative")) {
        c->select = SELECT_COMPAT; /* 000 Table 1 presets: K 32 and R 30 / 50 / 100 */
        c->radius = name[0] == 'f' ? 30.0f : name[0] == 'b' ? 50.0f : 100.0f;
    } else if (!strcmp(name, "compat")) {
        c->select = SELECT_COMPAT;
        c->candidates = candidates;
    } else if (!strcmp(name, "compat-binary")) {
        c->select = SELECT_COMPAT_BINARY;
        c->candidates = candidates;
    } else {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--configs: unknown configuration '%s' (bitterli, fast, balanced, conservative, compat, "
                 "compat-binary)",
                 name);
        return -1;
    }
    return 0;
}

static int parse_configs(const struct cli_options *o, struct study_config *cfg, int *n, char *msg)
{
    char list[1024];
    *n = 0;
    snprintf(list, sizeof(list), "%s", o->configs ? o->configs : "");
    for (char *t = strtok(list, ","); t; t = strtok(NULL, ",")) {
        if (*n == STUDY_MAX_CONFIGS) {
            snprintf(msg, RESTIR_MSG_LEN, "--configs: more than %d configurations", STUDY_MAX_CONFIGS);
            return -1;
        }
        if (named_config(t, o->params.spatial_radius, o->params.spatial_candidates, &cfg[(*n)++], msg) != 0)
            return -1;
    }
    snprintf(list, sizeof(list), "%s", o->radii ? o->radii : "");
    for (char *t = strtok(list, ","); t; t = strtok(NULL, ",")) {
        char *end;
        double r = strtod(t, &end);
        if (end == t || *end || !(r >= 1.0 && r <= 512.0)) {
            snprintf(msg, RESTIR_MSG_LEN, "--radii: '%s' is not a radius in [1, 512] pixels", t);
            return -1;
        }
        for (int k = 0; k < 2; k++) {
            if (*n == STUDY_MAX_CONFIGS) {
                snprintf(msg, RESTIR_MSG_LEN, "--radii: more than %d configurations in all", STUDY_MAX_CONFIGS);
                return -1;
            }
            struct study_config *c = &cfg[(*n)++];
            named_config(k ? "compat" : "bitterli", (float)r, o->params.spatial_candidates, c, msg);
            snprintf(c->name, sizeof(c->name), "%s@%g", k ? "compat" : "bitterli", r);
            c->sweep = k + 1;
        }
    }
    if (*n == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "study: --configs or --radii must name at least one configuration");
        return -1;
    }
    return 0;
}

static float luminance_at(const float *rgb, size_t i) { return v3_luminance(v3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2])); }

/* The hard-pixel mask of the static view (000 Sec. 7) from a pixel-centre G-buffer. */
static int hard_pixel_mask(const struct scene *s, const struct render_params *p, const struct camera *cam,
                           unsigned char *mask)
{
    struct camera_view view;
    camera_view_init(&view, cam, p->width, p->height);
    struct gbuffer g;
    gbuffer_init(&g, p->width, p->height, 0);
    gbuffer_pass(&g, s, &view, NULL, 0, p->seed, 0);
    size_t n = (size_t)p->width * p->height;
    float *normals = xmalloc(sizeof(float) * 3 * n);
    for (size_t i = 0; i < n; i++) {
        normals[3 * i] = g.normal[i].x;
        normals[3 * i + 1] = g.normal[i].y;
        normals[3 * i + 2] = g.normal[i].z;
    }
    int hard = restir_hard_pixels(normals, g.depth, g.valid, p->width, p->height, HARD_RADIUS, p->spatial_normal,
                                  p->spatial_depth, HARD_FRACTION, mask, NULL);
    free(normals);
    gbuffer_fini(&g);
    return hard;
}

/* Runs one configuration: `runs` sequences of warmup + frames frames; measured luminance goes to
 * seq (run-major, then frame) for the covariances, and run 0's frames of row strip_y to strip. */
/* Runs configuration c (o->runs sequences) into res. Returns 0, or -1 when a stop signal arrived
 * (res is then incomplete). */
static int run_config(const struct scene *s, enum method_id method, const struct render_params *base,
                      const struct study_config *c, const struct cli_options *o, const float *ref,
                      const unsigned char *hard, float *seq, float *strip, int strip_y, struct study_result *res)
{
    const int w = base->width, h = base->height, frames = o->frames;
    const size_t npix = (size_t)w * h;
    struct render_params p = *base;
    p.spatial_select = c->select;
    p.spatial_radius = c->radius;
    if (c->candidates > 0)
        p.spatial_candidates = c->candidates;
    struct camera cam = scene_camera_at(s, 0, 0.0f);
    memset(res, 0, sizeof(*res));
    for (int n = 0; n < o->runs; n++) {
        p.seed = base->seed + 1000003ull * (uint64_t)n;
        struct renderer r;
        renderer_init(&r, s, method, &p);
        for (int f = 0; f < o->warmup + frames; f++) {
            if (cli_stop_signal) {
                renderer_fini(&r);
                return -1;
            }
            struct frame_stats st;
            renderer_render(&r, f, &cam, &st);
            int t = f - o->warmup;
            if (t < 0)
                continue;
            float *lum = &seq[((size_t)n * frames + t) * npix];
            for (size_t i = 0; i < npix; i++)
                lum[i] = luminance_at(r.image, i);
            if (n == 0)
                memcpy(&strip[(size_t)t * w], &lum[(size_t)strip_y * w], sizeof(float) * (size_t)w);
            struct restir_error e_all, e_hard;
            restir_error_compute(r.image, ref, npix, NULL, &e_all);
            if (restir_error_compute(r.image, ref, npix, hard, &e_hard) != 0)
                e_hard.smape = 0.0;
            const double k = 1.0 / ((double)o->runs * frames);
            res->smape_all += e_all.smape * k;
            res->smape_hard += e_hard.smape * k;
            res->ms_select += st.ms[PASS_SELECT] * k;
            res->ms_spatial += st.ms[PASS_SPATIAL] * k;
            res->ms_frame += st.ms_total * k;
        }
        renderer_fini(&r);
    }
    res->temporal_cov = restir_temporal_autocovariance(seq, o->runs, frames, w, h, COV_LAG, COV_EPS, NULL);
    /* Spatial covariance of each measured frame across runs, averaged over frames. */
    float *at_t = xmalloc(sizeof(float) * npix * (size_t)o->runs);
    for (int t = 0; t < frames; t++) {
        for (int n = 0; n < o->runs; n++)
            memcpy(&at_t[(size_t)n * npix], &seq[((size_t)n * frames + t) * npix], sizeof(float) * npix);
        res->spatial_cov += restir_spatial_covariance(at_t, o->runs, w, h, COV_RADIUS, COV_EPS, NULL) / frames;
    }
    free(at_t);
    return 0;
}

static int write_tables(const char *dir, const struct study_config *cfg, const struct study_result *res, int n,
                        int m, char *msg)
{
    char path[4200];
    snprintf(path, sizeof(path), "%s/study.csv", dir);
    struct csv_writer csv;
    if (csv_open(&csv, path,
                 "config,radius,K,M,smape_all,smape_hard,temporal_cov,spatial_cov,ms_select,ms_spatial,ms_frame",
                 msg) != 0)
        return -1;
    for (int k = 0; k < n; k++)
        csv_row(&csv, "%s,%g,%d,%d,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f,%.4f", cfg[k].name, cfg[k].radius,
                cfg[k].candidates, m, res[k].smape_all, res[k].smape_hard, res[k].temporal_cov, res[k].spatial_cov,
                res[k].ms_select, res[k].ms_spatial, res[k].ms_frame);
    if (csv_close(&csv, msg) != 0)
        return -1;
    snprintf(path, sizeof(path), "%s/study.md", dir);
    char tmp[4300];
    io_temp_path(path, tmp, sizeof(tmp));
    FILE *f = fopen(tmp, "w");
    if (!f) {
        snprintf(msg, RESTIR_MSG_LEN, "%.400s: cannot write", path);
        return -1;
    }
    /* 000 Table 2 layout (quality) and Table 1 (time), relative to the first bitterli row. */
    int base = -1;
    for (int k = 0; k < n && base < 0; k++)
        if (cfg[k].select == SELECT_BITTERLI)
            base = k;
    fprintf(f, "| config | R | K | M | SMAPE all | SMAPE hard | temporal cov | spatial cov | select ms | spatial ms "
               "| frame ms |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; k++) {
        fprintf(f, "| %s | %g | %d | %d | %.3f | %.3f | %.4g | %.4g | %.2f | %.2f | %.2f |\n", cfg[k].name,
                cfg[k].radius, cfg[k].candidates, m, res[k].smape_all, res[k].smape_hard, res[k].temporal_cov,
                res[k].spatial_cov, res[k].ms_select, res[k].ms_spatial, res[k].ms_frame);
    }
    if (base >= 0) {
        const struct study_result *b = &res[base];
        fprintf(f, "\nChange against %s: SMAPE all, SMAPE hard, temporal covariance, frame time; "
                   "selection pass as a share of the frame.\n\n| config | SMAPE all | SMAPE hard | temporal cov | "
                   "frame | select / frame |\n|---|---|---|---|---|---|\n",
                cfg[base].name);
        for (int k = 0; k < n; k++)
            fprintf(f, "| %s | %+.1f%% | %+.1f%% | %+.1f%% | %+.1f%% | %.1f%% |\n", cfg[k].name,
                    100.0 * (res[k].smape_all / b->smape_all - 1.0), 100.0 * (res[k].smape_hard / b->smape_hard - 1.0),
                    100.0 * (res[k].temporal_cov / b->temporal_cov - 1.0), 100.0 * (res[k].ms_frame / b->ms_frame - 1.0),
                    100.0 * res[k].ms_select / res[k].ms_frame);
    }
    if (ferror(f) | fclose(f)) {
        remove(tmp);
        snprintf(msg, RESTIR_MSG_LEN, "%.400s: write failed", path);
        return -1;
    }
    return io_commit(tmp, path, msg);
}

/* 000 Figure 3: SMAPE against spatial covariance over the radius sweeps. */
static int write_pareto(const char *dir, const struct study_config *cfg, const struct study_result *res, int n,
                        char *msg)
{
    double x[2][STUDY_MAX_CONFIGS], y[2][STUDY_MAX_CONFIGS], r[2][STUDY_MAX_CONFIGS];
    int cnt[2] = {0, 0};
    for (int k = 0; k < n; k++) {
        if (!cfg[k].sweep)
            continue;
        int q = cfg[k].sweep - 1;
        x[q][cnt[q]] = res[k].spatial_cov;
        y[q][cnt[q]] = res[k].smape_all;
        r[q][cnt[q]++] = cfg[k].radius;
    }
    struct plot_series series[2] = {{"bitterli", "#d62728", cnt[0], x[0], y[0], r[0]},
                                    {"compat (K 32)", "#1f77b4", cnt[1], x[1], y[1], r[1]}};
    char path[4200];
    snprintf(path, sizeof(path), "%s/pareto.svg", dir);
    return svg_write_xy_plot(path, "SMAPE against spatial covariance over reuse radii (labels: R)",
                             "average relative covariance (radius 8)", "SMAPE", series, 2, msg);
}

/* Hard pixels in white over the dimmed reference. */
static int write_mask(const char *dir, const float *ref, const unsigned char *hard, int w, int h, char *msg)
{
    size_t n = (size_t)w * h;
    float *rgb = xmalloc(sizeof(float) * 3 * n);
    for (size_t i = 0; i < n; i++) {
        float l = fminf(luminance_at(ref, i), 1.0f) * 0.3f;
        rgb[3 * i] = hard[i] ? 1.0f : l;
        rgb[3 * i + 1] = hard[i] ? 0.2f : l;
        rgb[3 * i + 2] = hard[i] ? 0.2f : l;
    }
    char path[4200];
    snprintf(path, sizeof(path), "%s/hard_pixels.png", dir);
    int rc = png_write_srgb(path, rgb, w, h, 0.0f, msg);
    free(rgb);
    return rc;
}

/* 000 Figure 5: (x, t) plot of one row over the measured frames of run 0, one panel per listed
 * configuration (up to 4), each pixel as luminance over the reference (0.5 gray = exact). */
static int write_strip(const char *dir, const float *strips, const float *ref_row, int w, int frames, int n,
                       char *msg)
{
    int panels = n < 4 ? n : 4, gap = 4, width = panels * w + (panels - 1) * gap, height = frames * STRIP_SCALE;
    float *rgb = xcalloc((size_t)3 * width * height, sizeof(float));
    for (int k = 0; k < panels; k++)
        for (int t = 0; t < frames; t++)
            for (int x = 0; x < w; x++) {
                float v = strips[((size_t)k * frames + t) * w + x] / (ref_row[x] + 1e-4f);
                v = fminf(fmaxf(0.25f * v, 0.0f), 1.0f);
                for (int q = 0; q < STRIP_SCALE; q++) {
                    size_t o = 3 * ((size_t)(t * STRIP_SCALE + q) * width + (size_t)k * (w + gap) + x);
                    rgb[o] = rgb[o + 1] = rgb[o + 2] = v;
                }
            }
    char path[4200];
    snprintf(path, sizeof(path), "%s/strip.png", dir);
    int rc = png_write_srgb(path, rgb, width, height, 0.0f, msg);
    free(rgb);
    return rc;
}

int cmd_study(int argc, char **argv)
{
    struct cli_options o;
    char msg[RESTIR_MSG_LEN];
    if (cli_parse_options("study", argc, argv, &o, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (o.help) {
        study_usage(stdout);
        return 0;
    }
    if (!o.res_given) {
        o.params.width = 320;
        o.params.height = 180;
    }
    if (!o.out) {
        cli_error("study: --out DIR is required");
        return EXIT_USAGE;
    }
    int m = o.method ? method_find(o.method) : -1;
    if (m != METHOD_RESTIR_DI && m != METHOD_RESTIR_PT) {
        cli_error("study: --method must be restir-di or restir-pt (methods with spatial reuse), got '%s'",
                  o.method ? o.method : "(none)");
        return EXIT_USAGE;
    }
    if (o.frames <= COV_LAG || o.runs < 2) {
        cli_error("study: needs --frames > %d (autocovariance lag) and --runs >= 2", COV_LAG);
        return EXIT_USAGE;
    }
    static struct study_config cfg[STUDY_MAX_CONFIGS];
    int ncfg;
    if (parse_configs(&o, cfg, &ncfg, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    struct scene s;
    if (scene_load(o.scene, &s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (cli_check_memory(&s, (enum method_id)m, &o.params, o.max_memory_mb, msg) != 0) {
        cli_error("%s", msg);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    cli_catch_stop_signals();
    const int w = o.params.width, h = o.params.height;
    const size_t npix = (size_t)w * h;
    struct camera cam = scene_camera_at(&s, 0, 0.0f);
    float *ref = NULL;
    int rc = 0;
    if (o.ref) {
        if (cli_load_reference(o.ref, w, h, &ref, msg) != 0) {
            cli_error("%s", msg);
            scene_destroy(&s);
            return EXIT_RUNTIME;
        }
    } else {
        struct render_params rp = o.params;
        rp.seed ^= 0x7265666572656e63ull;
        ref = cli_render_reference(&s, (enum method_id)m, &rp, &cam, o.ref_spp);
        if (!ref) {
            cli_error("interrupted by %s while rendering the reference; nothing written", cli_stop_signal_name());
            scene_destroy(&s);
            return 128 + (int)cli_stop_signal;
        }
    }
    if (io_make_dirs(o.out, msg) != 0) {
        cli_error("%s", msg);
        free(ref);
        scene_destroy(&s);
        return EXIT_RUNTIME;
    }
    unsigned char *hard = xcalloc(npix, 1);
    int nhard = hard_pixel_mask(&s, &o.params, &cam, hard);
    /* The strip row: the one with the most hard pixels. */
    int strip_y = 0, best = -1;
    for (int y = 0; y < h; y++) {
        int c = 0;
        for (int x = 0; x < w; x++)
            c += hard[(size_t)y * w + x];
        if (c > best)
            best = c, strip_y = y;
    }
    float *seq = xmalloc(sizeof(float) * npix * (size_t)o.runs * (size_t)o.frames);
    float *strips = xmalloc(sizeof(float) * (size_t)w * o.frames * ncfg);
    static struct study_result res[STUDY_MAX_CONFIGS];
    struct progress pg;
    progress_begin(&pg, "study", ncfg);
    int stopped_at = -1;
    for (int k = 0; k < ncfg && stopped_at < 0; k++) {
        if (run_config(&s, (enum method_id)m, &o.params, &cfg[k], &o, ref, hard, seq,
                       &strips[(size_t)k * w * o.frames], strip_y, &res[k]) != 0)
            stopped_at = k;
        progress_update(&pg, k + 1);
    }
    progress_end(&pg);
    if (stopped_at >= 0) { /* the tables compare every configuration: none is written from a part */
        cli_error("interrupted by %s in configuration %s (%d of %d); nothing written", cli_stop_signal_name(),
                  cfg[stopped_at].name, stopped_at + 1, ncfg);
        free(strips);
        free(seq);
        free(hard);
        free(ref);
        scene_destroy(&s);
        return 128 + (int)cli_stop_signal;
    }
    float *ref_row = xmalloc(sizeof(float) * (size_t)w);
    for (int x = 0; x < w; x++)
        ref_row[x] = luminance_at(ref, (size_t)strip_y * w + x);
    const int neighbors = render_params_spatial_neighbors(&o.params, m == METHOD_RESTIR_PT);
    if (write_tables(o.out, cfg, res, ncfg, neighbors, msg) != 0 || write_pareto(o.out, cfg, res, ncfg, msg) != 0 ||
        write_mask(o.out, ref, hard, w, h, msg) != 0 ||
        write_strip(o.out, strips, ref_row, w, o.frames, ncfg, msg) != 0) {
        cli_error("%s", msg);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0) {
        printf("study of %s on %s, %dx%d, %d runs, %d warm-up + %d frames, %d hard pixels (row %d in strip.png)\n",
               o.method, o.scene, w, h, o.runs, o.warmup, o.frames, nhard, strip_y);
        for (int k = 0; k < ncfg; k++)
            printf("  %-16s R %-5g SMAPE %.3f hard %.3f  temporal cov %.4g  spatial cov %.4g  select %.2f ms  "
                   "frame %.2f ms\n",
                   cfg[k].name, cfg[k].radius, res[k].smape_all, res[k].smape_hard, res[k].temporal_cov,
                   res[k].spatial_cov, res[k].ms_select, res[k].ms_frame);
        printf("output: %s\n", o.out);
    }
    if (rc == 0 && o.report) {
        char command[8192];
        cli_command_line("study", argc, argv, command, sizeof command);
        const struct study_report_run run = {o.out, command, s.name, o.method, w, h, o.runs, o.warmup, o.frames,
                                             nhard, strip_y, ref};
        if (study_write_report(&run, msg) != 0) {
            cli_error("--report: %s", msg);
            rc = EXIT_RUNTIME;
        } else {
            printf("report: %s/index.html\n", o.out);
        }
    }
    free(ref_row);
    free(strips);
    free(seq);
    free(hard);
    free(ref);
    scene_destroy(&s);
    return rc;
}
