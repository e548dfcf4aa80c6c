/* compare_report.c: the page of `restir compare --report` (compare_report.h), from the images it is given.
 * Must never render or read a comparison's files: it shows what the caller measured. */
#include "experiments/compare_report.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/compare_worst.h"
#include "experiments/report_commit.h"
#include "io/atomic_file.h"
#include "io/html_report.h"
#include "io/png.h"
#include "io/svg_plot.h"

/* Heat maps show the per-pixel terms of MAPE (their image mean is the table's MAPE) on one fixed
 * scale for every method, so maps are comparable side by side. */

/* Heat maps saturate at a relative error of 1 (100%). */
#define HEAT_MAX 1.0f
#define MAX_REPORT_METHODS 32
#define SPEC_REL_MAX 512 /* a method's folder and file name, relative to the output folder */

/* The cw x cw window (stride cw / 2) with the largest sum of sign * (a - b). */
static void largest_difference(const float *a, const float *b, int w, int h, int cw, float sign, int *bx, int *by)
{
    double best = -INFINITY;
    *bx = *by = 0;
    for (int y0 = 0; y0 + cw <= h; y0 += cw / 2) {
        for (int x0 = 0; x0 + cw <= w; x0 += cw / 2) {
            double sum = 0.0;
            for (int y = y0; y < y0 + cw; y++)
                for (int x = x0; x < x0 + cw; x++)
                    sum += sign * ((double)a[(size_t)y * w + x] - (double)b[(size_t)y * w + x]);
            if (sum > best) {
                best = sum;
                *bx = x0;
                *by = y0;
            }
        }
    }
}

static int write_crop(const char *path, const float *rgb, int w, int x0, int y0, int cw, char *msg)
{
    float *crop = xmalloc(sizeof(float) * 3 * (size_t)cw * (size_t)cw);
    for (int y = 0; y < cw; y++)
        memcpy(crop + 3 * (size_t)y * cw, rgb + 3 * ((size_t)(y0 + y) * w + x0), sizeof(float) * 3 * (size_t)cw);
    int rc = png_write_srgb(path, crop, cw, cw, 0.0f, msg);
    free(crop);
    return rc;
}

/* Colours of the plots' series and segments, in order (a method's line, a pass's segment). */
static const char *const palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                                      "#7f7f7f", "#bcbd22", "#17becf", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896",
                                      "#c5b0d5", "#c49c94", "#f7b6d2", "#c7c7c7", "#dbdb8d", "#9edae5"};
#define PALETTE (int)(sizeof palette / sizeof palette[0])

/* Pixels for the longest of the n labels at the plots' 12-pixel font, within [lo, hi]. */
static int label_width(int n, const char *const *labels, int lo, int hi)
{
    int w = lo;
    for (int k = 0; k < n; k++)
        w = 7 * (int)strlen(labels[k]) + 12 > w ? 7 * (int)strlen(labels[k]) + 12 : w;
    return w < hi ? w : hi;
}

/* Bars of relMSE per row (linear axis from 0), the denoised rows in a colour of their own. */
static void relmse_plot(struct html_page *pg, int n, const struct compare_report_method *m)
{
    const char *labels[MAX_REPORT_METHODS];
    double values[2 * MAX_REPORT_METHODS];
    int nseg = 1; /* with denoised rows two segments a row, raw and denoised, one of them 0 */
    for (int k = 0; k < n; k++)
        nseg = m[k].denoised ? 2 : nseg;
    for (int k = 0; k < n; k++) {
        labels[k] = m[k].label;
        values[nseg * k] = m[k].denoised ? 0.0 : m[k].err.relmse;
        if (nseg == 2)
            values[2 * k + 1] = m[k].denoised ? m[k].err.relmse : 0.0;
    }
    static const char *const names[2] = {"raw", "denoised (BIASED)"}, *const colors[2] = {"#3b6ea5", "#e08a2e"};
    const struct svg_bars b = {"relMSE (lower is better)", nseg, names, colors, "%.4g",
                               label_width(n, labels, 120, 420), 360};
    svg_hbar_plot(pg->f, &b, n, labels, values);
}

/* relMSE against frame, a line per method, from frames.csv (the frames that have a reference); a
 * log axis where the errors span more than a factor of 10. */
static void frames_plot(struct html_page *pg, int n, const struct compare_report_method *m)
{
    struct plot_series series[MAX_REPORT_METHODS];
    const char *labels[MAX_REPORT_METHODS];
    int ns = 0, most = 0;
    for (int k = 0; k < n; k++) {
        if (m[k].denoised || m[k].nframes < 1)
            continue;
        series[ns] = (struct plot_series){m[k].label, palette[ns % PALETTE], m[k].nframes, m[k].frame,
                                          m[k].frame_relmse, NULL};
        labels[ns++] = m[k].label;
        most = m[k].nframes > most ? m[k].nframes : most;
    }
    html_raw(pg, "<h2>Error against frame</h2>\n");
    if (most < 2) {
        html_raw(pg, "<p>frames.csv holds %s: <code>--ref-every K</code> also measures frames K-1, 2K-1, ..., each "
                     "against a reference of its own.</p>\n",
                 ns ? "the last frame's error only" : "no errors (a merged plan writes none)");
        return;
    }
    const int log_y = svg_wide_range(series, ns, 10.0);
    html_raw(pg, "<p>relMSE of the frames that have a reference (frames.csv)%s:</p>\n",
             log_y ? ", log scale" : "");
    const int legend_w = label_width(ns, labels, 150, 460) + 40;
    const struct svg_xy_axes ax = {"relMSE against frame", "frame", log_y ? "relMSE (log scale)" : "relMSE",
                                   520 + legend_w, 340, legend_w, log_y, 1};
    svg_xy_plot(pg->f, &ax, series, ns);
}

/* Flicker against block size, a line per row (raw and denoised), as s^2 flicker(s) / flicker(1): a
 * frame-to-frame variance of s x s block means relative to what independent per-pixel noise would leave
 * (1 at every scale), up to s^2 where whole blocks move together (blotches; at 16 px this is the table's
 * boiling index). Leaves the page alone when no row has a flicker. */
static void flicker_plot(struct html_page *pg, int n, const struct compare_report_method *m)
{
    struct plot_series series[MAX_REPORT_METHODS];
    const char *labels[MAX_REPORT_METHODS];
    double xs[MAX_REPORT_METHODS][8], ys[MAX_REPORT_METHODS][8];
    int ns = 0;
    for (int k = 0; k < n; k++) {
        if (m[k].nflicker < 2 || m[k].nflicker > 8 || !(m[k].flicker[0] > 0.0))
            continue;
        int np = 0;
        for (int j = 0; j < m[k].nflicker; j++) {
            const double s = m[k].flicker_block[j];
            if (!isfinite(m[k].flicker[j]))
                continue;
            xs[ns][np] = log2(s);
            ys[ns][np++] = s * s * m[k].flicker[j] / m[k].flicker[0];
        }
        series[ns] = (struct plot_series){m[k].label, palette[ns % PALETTE], np, xs[ns], ys[ns], NULL};
        labels[ns++] = m[k].label;
    }
    if (ns == 0)
        return;
    html_raw(pg, "<h2>Flicker against scale</h2>\n<p>The frame-to-frame variance of s x s block means over the "
                 "second half's frames (compare.csv's flicker1, flicker4, flicker16), as s<sup>2</sup> "
                 "flicker(s) / flicker(1): 1 at every scale for independent per-pixel noise, rising towards "
                 "s<sup>2</sup> where blocks change together (boiling; at s = 16 this is the boiling index, at "
                 "most 256). x is log<sub>2</sub> s: 0 is 1 px, 2 is 4 px, 4 is 16 px; log scale.</p>\n");
    const int legend_w = label_width(ns, labels, 150, 460) + 40;
    const struct svg_xy_axes ax = {"flicker relative to independent noise", "log2 block size (px)",
                                   "s^2 flicker(s) / flicker(1) (log scale)", 520 + legend_w, 340, legend_w, 1, 1};
    svg_xy_plot(pg->f, &ax, series, ns);
}

/* Each method's ms per frame by pass (passes.csv) as stacked bars; the passes no method spent time in
 * are left out. */
static void passes_plot(struct html_page *pg, const struct compare_report_run *run, int n,
                        const struct compare_report_method *m)
{
    if (run->passes < 1)
        return;
    int used[64], nused = 0, rows = 0;
    for (int q = 0; q < run->passes && nused < 64; q++) {
        int any = 0;
        for (int k = 0; k < n; k++)
            any |= m[k].ms_pass && m[k].ms_pass[q] > 0.0;
        if (any)
            used[nused++] = q;
    }
    const char *labels[MAX_REPORT_METHODS], *names[64], *colors[64];
    double *values = xcalloc((size_t)n * (size_t)(nused ? nused : 1), sizeof(double));
    for (int s = 0; s < nused; s++) {
        names[s] = run->pass_names[used[s]];
        colors[s] = palette[s % PALETTE];
    }
    for (int k = 0; k < n; k++) {
        if (!m[k].ms_pass || m[k].denoised)
            continue;
        labels[rows] = m[k].label;
        for (int s = 0; s < nused; s++)
            values[rows * nused + s] = m[k].ms_pass[used[s]];
        rows++;
    }
    if (rows > 0 && nused > 0) {
        html_raw(pg, "<h2>Time per pass</h2>\n<p>Milliseconds per frame of each pass (passes.csv: the fastest run, "
                     "its instances summed); hover a segment for its pass and time.</p>\n");
        const struct svg_bars b = {"ms per frame (lower is faster)", nused, names, colors, "%.2f",
                                   label_width(rows, labels, 120, 420), 420};
        svg_hbar_plot(pg->f, &b, rows, labels, values);
    }
    free(values);
}

static void meta(struct html_page *pg, const struct compare_report_run *run)
{
    html_run_info(pg, run->command, RESTIR_GIT_COMMIT);
    html_raw(pg, "<p>");
    html_text(pg, run->scene);
    html_raw(pg, ", %dx%d, %s camera, error at frame %d%s.</p>\n", run->width, run->height,
             run->moving ? "moving" : "static", run->frame, run->equal_time ? ", equal time" : "");
}

static void table(struct html_page *pg, int n, const struct compare_report_method *m)
{
    static const char *const header[] = {"method", "ms/frame", "spp", "instances", "relMSE", "MAPE", "SMAPE",
                                         "FLIP", "relMSE / first"};
    enum { COLS = 9 };
    char *text = xcalloc((size_t)n * COLS, 64);
    const char **cells = xcalloc((size_t)n * COLS, sizeof(char *));
    for (int k = 0; k < n; k++) {
        char *row = text + (size_t)k * COLS * 64;
        snprintf(row + 64, 64, "%.2f", m[k].ms_per_frame);
        snprintf(row + 128, 64, "%d", m[k].spp);
        snprintf(row + 192, 64, "%d", m[k].instances);
        snprintf(row + 256, 64, "%.5g", m[k].err.relmse);
        snprintf(row + 320, 64, "%.5g", m[k].err.mape);
        snprintf(row + 384, 64, "%.3f", m[k].err.smape);
        if (isfinite(m[k].flip))
            snprintf(row + 448, 64, "%.4f", m[k].flip);
        else
            snprintf(row + 448, 64, "-");
        snprintf(row + 512, 64, "%.3f", m[0].err.relmse > 0 ? m[k].err.relmse / m[0].err.relmse : 0.0);
        cells[k * COLS] = m[k].label;
        for (int c = 1; c < COLS; c++)
            cells[k * COLS + c] = row + 64 * c;
    }
    html_table(pg, COLS, header, n, cells);
    free(cells);
    free(text);
}

/* Heat maps of every method; fills maps (n * w * h) with the per-pixel MAPE terms. */
static int heat_maps(struct html_page *pg, const struct compare_report_run *run, int n,
                     const struct compare_report_method *m, float *maps, char *msg)
{
    const size_t npix = (size_t)run->width * run->height;
    const char *labels[MAX_REPORT_METHODS];
    char srcs[MAX_REPORT_METHODS][64], path[4300];
    const char *src_ptr[MAX_REPORT_METHODS];
    for (int k = 0; k < n; k++) {
        restir_metrics_mape_map(m[k].image, run->reference, npix, maps + (size_t)k * npix);
        snprintf(srcs[k], sizeof srcs[k], "report/heat_%d.png", k);
        snprintf(path, sizeof path, "%s/%s", run->out_dir, srcs[k]);
        if (png_write_heatmap(path, maps + (size_t)k * npix, run->width, run->height, HEAT_MAX, msg) != 0)
            return -1;
        labels[k] = m[k].label;
        src_ptr[k] = srcs[k];
    }
    html_raw(pg, "<h2>Relative error</h2>\n<p>Per pixel |I - R| / (R + 0.01 mean(R)), averaged over the channels: "
                 "the image mean of each map is its MAPE.</p>\n");
    html_colorbar(pg, HEAT_MAX, "relative error");
    html_viewer(pg, n, labels, src_ptr, run->width, run->height);
    return 0;
}

/* HDR-FLIP maps of every method (restir_metrics_flip at FLIP's default viewing condition), on FLIP's own scale
 * [0, 1]. */
static int flip_maps(struct html_page *pg, const struct compare_report_run *run, int n,
                     const struct compare_report_method *m, char *msg)
{
    const size_t npix = (size_t)run->width * run->height;
    const char *labels[MAX_REPORT_METHODS];
    char srcs[MAX_REPORT_METHODS][64], path[4300];
    const char *src_ptr[MAX_REPORT_METHODS];
    float *map = xmalloc(sizeof(float) * npix);
    for (int k = 0; k < n; k++) {
        double mean;
        if (restir_metrics_flip(m[k].image, run->reference, run->width, run->height, RESTIR_METRICS_FLIP_PPD, map,
                                &mean) != 0) {
            snprintf(msg, RESTIR_MSG_LEN, "FLIP of %.200s: out of memory", m[k].label);
            free(map);
            return -1;
        }
        snprintf(srcs[k], sizeof srcs[k], "report/flip_%d.png", k);
        snprintf(path, sizeof path, "%s/%s", run->out_dir, srcs[k]);
        if (png_write_heatmap(path, map, run->width, run->height, 1.0f, msg) != 0) {
            free(map);
            return -1;
        }
        labels[k] = m[k].label;
        src_ptr[k] = srcs[k];
    }
    free(map);
    html_raw(pg, "<h2>FLIP</h2>\n<p>Per pixel HDR-FLIP (Andersson et al. 2021) at 67 pixels per degree: the perceived "
                 "difference from the reference, 0 none, 1 the largest (green against blue); the image mean of each map "
                 "is its FLIP.</p>\n");
    html_colorbar(pg, 1.0f, "FLIP");
    html_viewer(pg, n, labels, src_ptr, run->width, run->height);
    return 0;
}

/* Crops of the regions where the first method's error most exceeds the second's, and the reverse (the
 * first two rows that are no denoised frame, or the first two rows where there are fewer). */
static int crops(struct html_page *pg, const struct compare_report_run *run, int n,
                 const struct compare_report_method *m, const float *maps, char *msg)
{
    const int w = run->width, h = run->height, side = w < h ? w : h, cw = side / 6 >= 8 ? side / 6 : side;
    const size_t npix = (size_t)w * h;
    const int scale = cw < 32 ? 8 : cw < 64 ? 4 : 2;
    int pair[2] = {0, 1}, raw = 0;
    for (int k = 0; k < n && raw < 2; k++)
        if (!m[k].denoised)
            pair[raw++] = k;
    if (raw < 2) { /* one method and its denoised frame */
        pair[0] = 0;
        pair[1] = 1;
    }
    html_raw(pg, "<h2>Where the first two methods differ most</h2>\n");
    for (int r = 0; r < 2; r++) {
        int x0, y0;
        largest_difference(maps + pair[0] * npix, maps + pair[1] * npix, w, h, cw, r == 0 ? 1.0f : -1.0f, &x0, &y0);
        html_raw(pg, "<p>%dx%d pixels at (%d, %d), where <b>", cw, cw, x0, y0);
        html_text(pg, m[pair[r == 0 ? 1 : 0]].label);
        html_raw(pg, "</b> has the lower error:</p><div class=\"grid crops\">\n");
        for (int k = -1; k < n; k++) {
            char rel[64], path[4300];
            snprintf(rel, sizeof rel, "report/crop_%d_%s%d.png", r, k < 0 ? "ref" : "", k < 0 ? 0 : k);
            snprintf(path, sizeof path, "%s/%s", run->out_dir, rel);
            if (write_crop(path, k < 0 ? run->reference : m[k].image, w, x0, y0, cw, msg) != 0)
                return -1;
            html_raw(pg, "<figure class=\"pane\"><img width=\"%d\" height=\"%d\" alt=\"crop\" src=\"", cw * scale,
                     cw * scale);
            html_src(pg, rel);
            html_raw(pg, "\"><figcaption>");
            html_text(pg, k < 0 ? "reference" : m[k].label);
            html_raw(pg, "</figcaption></figure>\n");
        }
        html_raw(pg, "</div>\n");
    }
    return 0;
}

/* 1 when out_dir/rel exists. */
static int report_file_exists(const char *out_dir, const char *rel)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s", out_dir, rel);
    FILE *f = fopen(path, "rb");
    if (f)
        fclose(f);
    return f != NULL;
}

/* Every method's declared outputs (method.h) that cli_write_frame wrote as pictures beside its image
 * (the gradient methods of 002: the primal image and the x and y gradients, red positive, blue negative),
 * and, for forward differences, where the worst 1% of the gradient relMSE's pairs are (compare_worst.h)
 * when that image was written. */
#define REPORT_MAX_OUTPUTS 8 /* pictures per method beside its image; more are left out of the page */
static void output_layers(struct html_page *pg, const struct compare_report_run *run, int n,
                          const struct compare_report_method *m)
{
    int any = 0;
    for (int k = 0; k < n; k++) {
        if (!m[k].dir || !m[k].method)
            continue;
        char rel[REPORT_MAX_OUTPUTS + 1][SPEC_REL_MAX];
        const char *labels[REPORT_MAX_OUTPUTS + 2], *srcs[REPORT_MAX_OUTPUTS + 2];
        labels[0] = m[k].method->reconstruct ? "reconstruction" : "image";
        srcs[0] = m[k].png;
        int shown = 1;
        for (int q = 0; q < method_output_count(m[k].method) && shown <= REPORT_MAX_OUTPUTS; q++) {
            const struct method_output *o = &m[k].method->outputs[q];
            if (o->kind == METHOD_OUTPUT_DEBUG)
                continue; /* an EXR layer only */
            snprintf(rel[shown - 1], sizeof rel[0], "%s/frame_%04d_%s.png", m[k].dir, run->frame, o->name);
            if (!report_file_exists(run->out_dir, rel[shown - 1]))
                continue;
            labels[shown] = o->name;
            srcs[shown] = rel[shown - 1];
            shown++;
        }
        if (shown == 1)
            continue;
        snprintf(rel[shown - 1], sizeof rel[0], "%s%s", m[k].dir, COMPARE_WORST_SUFFIX);
        if (report_file_exists(run->out_dir, rel[shown - 1])) {
            labels[shown] = "worst 1% pairs";
            srcs[shown] = rel[shown - 1];
            shown++;
        }
        if (!any)
            html_raw(pg, "<h2>Gradient layers and other outputs</h2>\n<p>Per method that declares outputs: its "
                         "image and each output written as a picture; for 002's gradient methods the "
                         "reconstruction, its primal image, the x and y gradients (red positive, blue negative) "
                         "and where the worst 1%% of the pixel pairs of the gradient relMSE are, which carry most "
                         "of it (over the dimmed reference: red the pair with the right neighbour, cyan with the "
                         "one below, white both).</p>\n");
        any = 1;
        html_raw(pg, "<h3>");
        html_text(pg, m[k].label);
        html_raw(pg, "</h3>\n");
        html_viewer(pg, shown, labels, srcs, run->width, run->height);
    }
}

int compare_write_report(const struct compare_report_run *run, int n, const struct compare_report_method *m,
                         char *msg)
{
    if (n < 1 || n > MAX_REPORT_METHODS) {
        snprintf(msg, RESTIR_MSG_LEN, "--report takes 1 to %d methods", MAX_REPORT_METHODS);
        return -1;
    }
    char path[4300];
    snprintf(path, sizeof path, "%s/report", run->out_dir);
    if (io_make_dirs(path, msg) != 0)
        return -1;
    snprintf(path, sizeof path, "%s/reference.png", run->out_dir);
    if (png_write_srgb(path, run->reference, run->width, run->height, 0.0f, msg) != 0)
        return -1;
    struct html_page pg;
    snprintf(path, sizeof path, "%s/index.html", run->out_dir);
    if (html_begin(&pg, path, "restir compare", msg) != 0)
        return -1;
    pg.embed = run->self_contained;
    html_raw(&pg, "<h1>restir compare: ");
    html_text(&pg, run->scene);
    html_raw(&pg, "</h1>\n");
    meta(&pg, run);
    table(&pg, n, m);
    relmse_plot(&pg, n, m);
    frames_plot(&pg, n, m);
    flicker_plot(&pg, n, m);
    passes_plot(&pg, run, n, m);
    const char *labels[MAX_REPORT_METHODS + 1], *srcs[MAX_REPORT_METHODS + 1];
    labels[0] = "reference";
    srcs[0] = "reference.png";
    for (int k = 0; k < n; k++) {
        labels[k + 1] = m[k].label;
        srcs[k + 1] = m[k].png;
    }
    html_raw(&pg, "<h2>Images</h2>\n");
    html_viewer(&pg, n + 1, labels, srcs, run->width, run->height);
    output_layers(&pg, run, n, m);
    float *maps = xmalloc(sizeof(float) * (size_t)n * (size_t)run->width * (size_t)run->height);
    int rc = heat_maps(&pg, run, n, m, maps, msg);
    if (rc == 0)
        rc = flip_maps(&pg, run, n, m, msg);
    if (rc == 0 && n >= 2)
        rc = crops(&pg, run, n, m, maps, msg);
    free(maps);
    if (rc != 0) {
        html_abort(&pg);
        return -1;
    }
    return html_end(&pg, msg);
}
