/* study_run.c: a study's configurations, units, unit files and rows (study_run.h).
 * Must never implement a method or call into cmd_study.c: it drives the renderer. */
#include "experiments/study_run.h"

#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/plan.h"
#include "experiments/stats.h"
#include "render/gbuffer.h"
#include "restir/metrics.h"

#define HARD_FRACTION 0.1f /* 000 Sec. 7: the hardest 10% of pixels */
#define HARD_RADIUS 30.0f  /* ... judged within Bitterli's 30-pixel radius */
#define COV_RADIUS 8       /* 000 Appendix A: radial covariance over radius-8 disks */
#define COV_EPS 1e-4f

/* 1 when name is exactly "bitterli-rR" (k == 0) or "compat-rR-kK" (k >= 1), R in [1, 512] pixels and
 * K in [1, 1024]: the name the parsed numbers print back to, so "compat-r30.0-k8" or "bitterli-r30x" is
 * no configuration. */
static int radius_name(const char *name, float r, int k)
{
    char again[40];
    if (k == 0)
        snprintf(again, sizeof again, "bitterli-r%g", r);
    else
        snprintf(again, sizeof again, "compat-r%g-k%d", r, k);
    return r >= 1.0f && r <= 512.0f && k >= 0 && k <= 1024 && !strcmp(again, name);
}

/* A named configuration at radius r (the radius of bitterli, compat and compat-binary). */
static int named_config(const char *name, float r, int candidates, struct study_config *c, char *msg)
{
    memset(c, 0, sizeof(*c));
    snprintf(c->name, sizeof(c->name), "%s", name);
    float grid_r = 0.0f;
    int grid_k = 0;
    c->radius = r;
    c->candidates = 32;
    if (!strcmp(name, "bitterli")) {
        c->select = SELECT_BITTERLI;
        c->candidates = 0;
    } else if (!strcmp(name, "fast") || !strcmp(name, "balanced") || !strcmp(name, "conservative")) {
        c->select = SELECT_COMPAT; /* 000 Table 1 presets: K 32 and R 30 / 50 / 100 */
        c->radius = name[0] == 'f' ? 30.0f : name[0] == 'b' ? 50.0f : 100.0f;
    } else if (sscanf(name, "bitterli-r%f", &grid_r) == 1 && radius_name(name, grid_r, 0)) {
        c->select = SELECT_BITTERLI; /* 000 Figure 3: Bitterli's selection at radius R */
        c->radius = grid_r;
        c->candidates = 0;
    } else if (sscanf(name, "compat-r%f-k%d", &grid_r, &grid_k) == 2 && grid_k >= 1 &&
               radius_name(name, grid_r, grid_k)) {
        c->select = SELECT_COMPAT; /* 000 Table 2: radius R and candidates K */
        c->radius = grid_r;
        c->candidates = grid_k;
    } else if (!strcmp(name, "spatial-off")) {
        c->select = SELECT_BITTERLI; /* no spatial pass: temporal reuse alone */
        c->candidates = 0;
        c->spatial_off = 1;
    } else if (!strcmp(name, "bitterli-history-temporal") || !strcmp(name, "fast-history-temporal")) {
        /* the spatial output shown, not fed back: spatial reuse cannot compound over frames */
        c->select = name[0] == 'b' ? SELECT_BITTERLI : SELECT_COMPAT;
        c->candidates = name[0] == 'b' ? 0 : 32;
        c->radius = name[0] == 'b' ? r : 30.0f; /* as bitterli and fast */
        c->history_temporal = 1;
    } else if (!strcmp(name, "compat")) {
        c->select = SELECT_COMPAT;
        c->candidates = candidates;
    } else if (!strcmp(name, "compat-binary")) {
        c->select = SELECT_COMPAT_BINARY;
        c->candidates = candidates;
    } else {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--configs: unknown configuration '%s' (bitterli, bitterli-rR, fast, balanced, conservative, "
                 "compat, compat-binary, compat-rR-kK, spatial-off, bitterli-history-temporal, "
                 "fast-history-temporal)",
                 name);
        return -1;
    }
    return 0;
}

int study_pareto_series(const struct study_config *c)
{
    if (c->spatial_off || c->history_temporal)
        return -1; /* not a point of either radius curve */
    return c->select == SELECT_BITTERLI ? 0 : c->select == SELECT_COMPAT && c->candidates == 32 ? 1 : -1;
}

int study_parse_configs(const struct cli_options *o, struct study_config *cfg, int *n, char *msg)
{
    char list[1024];
    *n = 0;
    snprintf(list, sizeof(list), "%s", o->configs ? o->configs : "");
    for (char *t = strtok(list, ","); t; t = strtok(NULL, ",")) {
        if (*n == STUDY_MAX_CONFIGS) {
            snprintf(msg, RESTIR_MSG_LEN, "--configs: more than %d configurations", STUDY_MAX_CONFIGS);
            return -1;
        }
        if (named_config(t, o->params.reuse.spatial_radius, o->params.reuse.spatial_candidates, &cfg[(*n)++], msg) != 0)
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
            named_config(k ? "compat" : "bitterli", (float)r, o->params.reuse.spatial_candidates, c, msg);
            snprintf(c->name, sizeof(c->name), "%s@%g", k ? "compat" : "bitterli", r);
        }
    }
    if (*n == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "study: --configs or --radii must name at least one configuration");
        return -1;
    }
    return 0;
}

/* From a pixel-centre G-buffer. */
int study_hard_pixel_mask(const struct scene *s, const struct render_params *p, const struct camera *cam,
                           int counting, unsigned char *mask)
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
    int hard = restir_metrics_hard_pixels_counting(normals, g.depth, g.valid, p->width, p->height, HARD_RADIUS,
                                                   p->reuse.spatial_normal, p->reuse.spatial_depth, HARD_FRACTION,
                                                   (enum restir_hard_neighbors)counting, mask, NULL);
    free(normals);
    gbuffer_fini(&g);
    return hard;
}

int study_strip_row(const unsigned char *hard, int w, int h)
{
    int row = 0, best = -1;
    for (int y = 0; y < h; y++) {
        int c = 0;
        for (int x = 0; x < w; x++)
            c += hard[(size_t)y * w + x];
        if (c > best)
            best = c, row = y;
    }
    return row;
}

struct camera study_camera(const struct scene *s)
{
    return scene_camera_at(s, 0, 0.0f);
}

void study_config_apply(const struct study_config *c, struct render_params *p)
{
    p->reuse.spatial_select = c->select;
    p->reuse.spatial_radius = c->radius;
    if (c->candidates > 0)
        p->reuse.spatial_candidates = c->candidates;
    if (c->spatial_off)
        p->reuse.spatial = 0;
    if (c->history_temporal)
        p->reuse.history_temporal = 1;
}

int study_run_unit(const struct scene *s, const struct method *method, const struct render_params *base,
                   const struct study_config *c, const struct cli_options *o, int run, struct study_unit *u)
{
    struct render_params p = *base;
    study_config_apply(c, &p);
    p.seed = base->seed + STUDY_RUN_SEED_STRIDE * (uint64_t)run;
    const struct camera cam = study_camera(s);
    u->frames = o->frames;
    u->npix = (size_t)p.width * (size_t)p.height;
    u->luminance = xmalloc(sizeof(double) * u->npix * (size_t)u->frames);
    u->ms = xmalloc(sizeof(double) * 3 * (size_t)u->frames);
    u->luminance_dn = p.denoise.method > 0 ? xmalloc(sizeof(double) * u->npix * (size_t)u->frames) : NULL;
    struct renderer r;
    renderer_init(&r, s, method, &p);
    for (int f = 0; f < o->warmup + o->frames; f++) {
        if (cli_stop_signal) {
            renderer_fini(&r);
            study_unit_free(u);
            return -1;
        }
        struct frame_stats st;
        renderer_render(&r, f, &cam, &st);
        const int t = f - o->warmup;
        if (t < 0)
            continue;
        restir_metrics_luminance(r.image, u->npix, &u->luminance[(size_t)t * u->npix]);
        if (u->luminance_dn)
            restir_metrics_luminance(r.denoised, u->npix, &u->luminance_dn[(size_t)t * u->npix]);
        u->ms[3 * t] = st.ms[PASS_SELECT];
        u->ms[3 * t + 1] = st.ms[PASS_SPATIAL];
        u->ms[3 * t + 2] = st.ms_total;
    }
    renderer_fini(&r);
    return 0;
}

void study_unit_free(struct study_unit *u)
{
    free(u->luminance);
    free(u->ms);
    free(u->luminance_dn);
    u->luminance = u->ms = u->luminance_dn = NULL;
}

struct study_unit study_unit_denoised(const struct study_unit *u)
{
    struct study_unit d = *u;
    d.luminance = u->luminance_dn;
    d.luminance_dn = NULL;
    return d;
}

/* 2: the shape says whether the denoised luminance follows the timings */
static const char unit_magic[8] = {'R', 'S', 'T', 'U', 'D', 'Y', 'U', '2'};

int study_unit_write(const char *path, uint64_t id, const struct study_unit *u, char *msg)
{
    const int32_t shape[4] = {u->frames, (int32_t)u->npix, u->luminance_dn != NULL, 0};
    const size_t lum = sizeof(double) * u->npix * (size_t)u->frames;
    const void *parts[4] = {shape, u->luminance, u->ms, u->luminance_dn};
    const size_t sizes[4] = {sizeof shape, lum, sizeof(double) * 3 * (size_t)u->frames, lum};
    return plan_blob_write(path, unit_magic, id, parts, sizes, u->luminance_dn ? 4 : 3, msg);
}

int study_unit_read(const char *path, uint64_t id, int frames, size_t npix, struct study_unit *u, char *msg)
{
    void *data = NULL;
    size_t size = 0;
    int rc = plan_blob_read(path, unit_magic, id, &data, &size, msg);
    if (rc != 0)
        return rc;
    int32_t shape[4] = {0, 0, 0, 0};
    if (size >= sizeof shape)
        memcpy(shape, data, sizeof shape);
    const size_t lum = sizeof(double) * npix * (size_t)frames;
    const size_t want = sizeof shape + lum + sizeof(double) * 3 * (size_t)frames + (shape[2] ? lum : 0);
    if (size != want || shape[0] != frames || (size_t)shape[1] != npix) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: holds %d frames of %d pixels, not the plan's %d of %zu", path,
                 shape[0], shape[1], frames, npix);
        free(data);
        return -1;
    }
    u->frames = frames;
    u->npix = npix;
    u->luminance = xmalloc(sizeof(double) * npix * (size_t)frames);
    u->ms = xmalloc(sizeof(double) * 3 * (size_t)frames);
    memcpy(u->luminance, (char *)data + sizeof shape, sizeof(double) * npix * (size_t)frames);
    memcpy(u->ms, (char *)data + sizeof shape + sizeof(double) * npix * (size_t)frames,
           sizeof(double) * 3 * (size_t)frames);
    u->luminance_dn = NULL;
    if (shape[2]) {
        u->luminance_dn = xmalloc(lum);
        memcpy(u->luminance_dn, (char *)data + sizeof shape + lum + sizeof(double) * 3 * (size_t)frames, lum);
    }
    free(data);
    return 0;
}

void study_row_begin(struct study_row *row, int runs, int frames, int w, int h)
{
    memset(row, 0, sizeof *row);
    row->runs = runs;
    row->frames = frames;
    row->w = w;
    row->h = h;
    row->seq = xmalloc(sizeof(float) * (size_t)w * h * (size_t)runs * (size_t)frames);
    row->run_smape = xcalloc(2 * (size_t)runs, sizeof(double));
    row->run_ms = xcalloc(3 * (size_t)runs, sizeof(double));
}

const char *const study_run_columns[STUDY_RUN_COLS] = {
    "smape_all", "smape_hard",      "ms_select",      "ms_spatial", "ms_frame", "temporal_cov_loo",
    "spatial_cov_loo", "temporal_cov_hard_loo"};

void study_result_free(struct study_result *res)
{
    free(res->per_run);
    res->per_run = NULL;
    res->runs = 0;
}

void study_row_add(struct study_row *row, const struct study_unit *u, const float *ref, const unsigned char *hard,
                   int strip_y, float *strip)
{
    const size_t npix = (size_t)row->w * row->h;
    const int n = row->added++, frames = row->frames;
    RESTIR_CHECK(n < row->runs && u->frames == frames && u->npix == npix);
    row->ref = ref;
    struct study_result *res = &row->res;
    const double k = 1.0 / ((double)row->runs * frames);
    for (int t = 0; t < frames; t++) {
        const double *lum = &u->luminance[(size_t)t * npix];
        double all = 0.0, hard_smape = 0.0;
        restir_metrics_smape_luminance(lum, ref, npix, NULL, &all);
        if (restir_metrics_smape_luminance(lum, ref, npix, hard, &hard_smape) != 0)
            hard_smape = 0.0;
        res->smape_all += all * k;
        res->smape_hard += hard_smape * k;
        row->run_smape[2 * n] += all / frames;
        row->run_smape[2 * n + 1] += hard_smape / frames;
        res->ms_select += u->ms[3 * t] * k;
        res->ms_spatial += u->ms[3 * t + 1] * k;
        res->ms_frame += u->ms[3 * t + 2] * k;
        for (int q = 0; q < 3; q++)
            row->run_ms[3 * n + q] += u->ms[3 * t + q] / frames;
        /* covariances work on float luminance, run-major then frame */
        float *out = &row->seq[((size_t)n * frames + t) * npix];
        for (size_t i = 0; i < npix; i++)
            out[i] = (float)lum[i];
        if (n == 0 && strip)
            memcpy(&strip[(size_t)t * row->w], &out[(size_t)strip_y * row->w], sizeof(float) * (size_t)row->w);
    }
}

/* Swaps blocks i and j (each `block` floats) of a, element by element (no copy of a block). */
static void swap_blocks(float *a, size_t block, int i, int j)
{
    if (i == j)
        return;
    float *x = a + (size_t)i * block, *y = a + (size_t)j * block;
    for (size_t k = 0; k < block; k++) {
        const float t = x[k];
        x[k] = y[k];
        y[k] = t;
    }
}

void study_row_end(struct study_row *row, const unsigned char *hard, struct study_result *res)
{
    const int runs = row->runs, frames = row->frames, w = row->w, h = row->h;
    const size_t npix = (size_t)w * h;
    RESTIR_CHECK(row->added == runs);
    *res = row->res;
    double sem[2];
    for (int c = 0; c < 2; c++) { /* sd of the runs' SMAPEs / sqrt(runs), about their own mean */
        double mean = 0.0, ss = 0.0;
        for (int n = 0; n < runs; n++)
            mean += row->run_smape[2 * n + c] / runs;
        for (int n = 0; n < runs; n++)
            ss += (row->run_smape[2 * n + c] - mean) * (row->run_smape[2 * n + c] - mean);
        sem[c] = runs > 1 ? sqrt(ss / (runs - 1) / runs) : NAN;
    }
    res->smape_all_sem = sem[0];
    res->smape_hard_sem = sem[1];
    /* The covariances, and their jackknife standard errors over the runs (with at least 3 runs): each
     * recomputed without run i, which is swapped to the end of the run-major arrays so that the others
     * are the first runs - 1; se = sqrt((n - 1) / n sum_i (theta_i - mean theta_i)^2). */
    const int jack = runs >= 3;
    double *theta_t = xcalloc((size_t)runs, sizeof(double)), *theta_s = xcalloc((size_t)runs, sizeof(double)),
           *theta_h = xcalloc((size_t)runs, sizeof(double));
    const size_t seq_block = (size_t)frames * npix;
    res->temporal_cov =
        restir_metrics_temporal_autocovariance(row->seq, runs, frames, w, h, STUDY_COV_LAG, COV_EPS, NULL);
    res->temporal_cov_hard =
        restir_metrics_temporal_autocovariance(row->seq, runs, frames, w, h, STUDY_COV_LAG, COV_EPS, hard);
    for (int i = 0; i < runs && jack; i++) {
        swap_blocks(row->seq, seq_block, i, runs - 1);
        theta_t[i] =
            restir_metrics_temporal_autocovariance(row->seq, runs - 1, frames, w, h, STUDY_COV_LAG, COV_EPS, NULL);
        theta_h[i] =
            restir_metrics_temporal_autocovariance(row->seq, runs - 1, frames, w, h, STUDY_COV_LAG, COV_EPS, hard);
        swap_blocks(row->seq, seq_block, i, runs - 1);
    }
    /* Spatial covariance of each measured frame across runs, averaged over frames. */
    float *at_t = xmalloc(sizeof(float) * npix * (size_t)runs);
    for (int t = 0; t < frames; t++) {
        for (int n = 0; n < runs; n++)
            memcpy(&at_t[(size_t)n * npix], &row->seq[((size_t)n * frames + t) * npix], sizeof(float) * npix);
        res->spatial_cov += restir_metrics_spatial_covariance(at_t, runs, w, h, COV_RADIUS, COV_EPS, NULL) / frames;
        for (int i = 0; i < runs && jack; i++) {
            swap_blocks(at_t, npix, i, runs - 1);
            theta_s[i] += restir_metrics_spatial_covariance(at_t, runs - 1, w, h, COV_RADIUS, COV_EPS, NULL) / frames;
            swap_blocks(at_t, npix, i, runs - 1);
        }
    }
    free(at_t);
    flicker_measure(row->seq, runs, frames, w, h, row->ref, res->flicker);
    res->runs = runs;
    res->per_run = xmalloc(sizeof(double) * STUDY_RUN_COLS * (size_t)runs);
    for (int n = 0; n < runs; n++) {
        double *v = &res->per_run[(size_t)n * STUDY_RUN_COLS];
        const double per_run[STUDY_RUN_COLS] = {row->run_smape[2 * n], row->run_smape[2 * n + 1], row->run_ms[3 * n],
                                                row->run_ms[3 * n + 1], row->run_ms[3 * n + 2],
                                                jack ? theta_t[n] : NAN, jack ? theta_s[n] : NAN,
                                                jack ? theta_h[n] : NAN};
        memcpy(v, per_run, sizeof per_run);
    }
    res->temporal_cov_sem = jack ? jackknife_se(theta_t, runs) : NAN;
    res->spatial_cov_sem = jack ? jackknife_se(theta_s, runs) : NAN;
    res->temporal_cov_hard_sem = jack ? jackknife_se(theta_h, runs) : NAN;
    free(theta_t);
    free(theta_s);
    free(theta_h);
    study_row_free(row);
}

void study_row_free(struct study_row *row)
{
    free(row->seq);
    free(row->run_smape);
    free(row->run_ms);
    row->seq = NULL;
    row->run_smape = NULL;
    row->run_ms = NULL;
}
