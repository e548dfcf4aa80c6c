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

/* Bars of relMSE per method, as inline SVG (linear axis from 0). */
static void relmse_plot(struct html_page *pg, int n, const struct compare_report_method *m)
{
    double top = 0.0;
    for (int k = 0; k < n; k++)
        top = m[k].err.relmse > top ? m[k].err.relmse : top;
    const int bar_h = 22, label_w = 260, plot_w = 360, height = n * (bar_h + 6) + 30;
    html_raw(pg, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-size=\"12\">",
             label_w + plot_w + 90, height);
    for (int k = 0; k < n; k++) {
        int y = 10 + k * (bar_h + 6);
        double len = top > 0.0 ? plot_w * m[k].err.relmse / top : 0.0;
        html_raw(pg, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\">", label_w - 6, y + 15);
        html_text(pg, m[k].label);
        html_raw(pg, "</text><rect x=\"%d\" y=\"%d\" width=\"%.1f\" height=\"%d\" fill=\"#3b6ea5\"/>"
                     "<text x=\"%.1f\" y=\"%d\">%.4g</text>",
                 label_w, y, len, bar_h, label_w + len + 4, y + 15, m[k].err.relmse);
    }
    html_raw(pg, "<text x=\"%d\" y=\"%d\">relMSE (lower is better)</text></svg>\n", label_w, height - 4);
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

/* Crops of the regions where the first method's error most exceeds the second's, and the reverse. */
static int crops(struct html_page *pg, const struct compare_report_run *run, int n,
                 const struct compare_report_method *m, const float *maps, char *msg)
{
    const int w = run->width, h = run->height, side = w < h ? w : h, cw = side / 6 >= 8 ? side / 6 : side;
    const size_t npix = (size_t)w * h;
    const int scale = cw < 32 ? 8 : cw < 64 ? 4 : 2;
    html_raw(pg, "<h2>Where the first two methods differ most</h2>\n");
    for (int r = 0; r < 2; r++) {
        int x0, y0;
        largest_difference(maps, maps + npix, w, h, cw, r == 0 ? 1.0f : -1.0f, &x0, &y0);
        html_raw(pg, "<p>%dx%d pixels at (%d, %d), where <b>", cw, cw, x0, y0);
        html_text(pg, m[r == 0 ? 1 : 0].label);
        html_raw(pg, "</b> has the lower error:</p><div class=\"grid crops\">\n");
        for (int k = -1; k < n; k++) {
            char rel[64], path[4300];
            snprintf(rel, sizeof rel, "report/crop_%d_%s%d.png", r, k < 0 ? "ref" : "", k < 0 ? 0 : k);
            snprintf(path, sizeof path, "%s/%s", run->out_dir, rel);
            if (write_crop(path, k < 0 ? run->reference : m[k].image, w, x0, y0, cw, msg) != 0)
                return -1;
            html_raw(pg, "<figure class=\"pane\"><img width=\"%d\" height=\"%d\" alt=\"crop\" src=\"%s\"><figcaption>",
                     cw * scale, cw * scale, rel);
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

/* 002's layers of every gradient method: the primal image and the x and y gradients (the PNGs
 * cli_write_frame wrote beside the reconstruction; red positive, blue negative), and where the worst 1% of the
 * gradient relMSE's pairs are (compare_worst.h) when that image was written. */
static void gradient_layers(struct html_page *pg, const struct compare_report_run *run, int n,
                            const struct compare_report_method *m)
{
    static const char *const layers[3] = {"primal", "dx", "dy"};
    int any = 0;
    for (int k = 0; k < n; k++) {
        if (!m[k].dir)
            continue;
        char rel[4][SPEC_REL_MAX];
        const char *labels[5], *srcs[5];
        labels[0] = "reconstruction";
        srcs[0] = m[k].png;
        int found = 1;
        for (int q = 0; q < 3 && found; q++) {
            snprintf(rel[q], sizeof rel[q], "%s/frame_%04d_%s.png", m[k].dir, run->frame, layers[q]);
            found = report_file_exists(run->out_dir, rel[q]);
            labels[q + 1] = layers[q];
            srcs[q + 1] = rel[q];
        }
        if (!found)
            continue;
        snprintf(rel[3], sizeof rel[3], "%s%s", m[k].dir, COMPARE_WORST_SUFFIX);
        const int worst = report_file_exists(run->out_dir, rel[3]);
        labels[4] = "worst 1% pairs";
        srcs[4] = rel[3];
        if (!any)
            html_raw(pg, "<h2>Gradient layers (002)</h2>\n<p>Per gradient method: the reconstruction, its primal "
                         "image, the x and y gradients (red positive, blue negative) and where the worst 1%% of the "
                         "pixel pairs of the gradient relMSE are, which carry most of it (over the dimmed "
                         "reference: red the pair with the right neighbour, cyan with the one below, white "
                         "both).</p>\n");
        any = 1;
        html_raw(pg, "<h3>");
        html_text(pg, m[k].label);
        html_raw(pg, "</h3>\n");
        html_viewer(pg, worst ? 5 : 4, labels, srcs, run->width, run->height);
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
    html_raw(&pg, "<h1>restir compare: ");
    html_text(&pg, run->scene);
    html_raw(&pg, "</h1>\n");
    meta(&pg, run);
    table(&pg, n, m);
    relmse_plot(&pg, n, m);
    const char *labels[MAX_REPORT_METHODS + 1], *srcs[MAX_REPORT_METHODS + 1];
    labels[0] = "reference";
    srcs[0] = "reference.png";
    for (int k = 0; k < n; k++) {
        labels[k + 1] = m[k].label;
        srcs[k + 1] = m[k].png;
    }
    html_raw(&pg, "<h2>Images</h2>\n");
    html_viewer(&pg, n + 1, labels, srcs, run->width, run->height);
    gradient_layers(&pg, run, n, m);
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
