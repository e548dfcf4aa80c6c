/* svg_plot.c: x-y line plots and horizontal bar plots as SVG (svg_plot.h), into a stream or a file
 * of their own (a temporary file and a rename). Must never depend on render code. */
#include "io/svg_plot.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/atomic_file.h"

enum { MARGIN_L = 80, MARGIN_T = 40, MARGIN_B = 60, FILE_W = 640, FILE_H = 440, FILE_LEGEND_W = 150 };

static double map(double v, double lo, double hi, double a, double b)
{
    return hi > lo ? a + (v - lo) / (hi - lo) * (b - a) : 0.5 * (a + b);
}

/* s with &, <, > and " escaped. */
static void svg_text(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
    }
}

/* The y a point is drawn at: log10(y) on a log axis (NaN for y <= 0, which is left out). */
static double plot_y(const struct svg_xy_axes *ax, double y)
{
    return ax->log_y ? (y > 0.0 ? log10(y) : NAN) : y;
}

int svg_wide_range(const struct plot_series *series, int nseries, double ratio)
{
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < nseries; k++)
        for (int i = 0; i < series[k].n; i++) {
            const double y = series[k].y[i];
            if (!(y > 0.0))
                return 0;
            lo = fmin(lo, y);
            hi = fmax(hi, y);
        }
    return hi > ratio * lo;
}

/* The smallest of 1, 2, 5, 10, 20, 50, ... that is at least span / 8 (whole-number ticks). */
static double integer_step(double span)
{
    double step = 1.0;
    for (int k = 0; step < span / 8.0; k++)
        step *= k % 3 == 1 ? 2.5 : 2.0;
    return step;
}

static void tick(FILE *f, int vertical, double s, double lo, double hi, double label, double at)
{
    if (vertical) {
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", s, lo, s, hi);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%.3g</text>\n", s, at, label);
    } else {
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", lo, s, hi, s);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.3g</text>\n", at, s + 4, label);
    }
}

void svg_xy_plot(FILE *f, const struct svg_xy_axes *ax, const struct plot_series *series, int nseries)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < nseries; k++)
        for (int i = 0; i < series[k].n; i++) {
            const double y = plot_y(ax, series[k].y[i]);
            if (!isfinite(y) || !isfinite(series[k].x[i]))
                continue;
            x0 = fmin(x0, series[k].x[i]);
            x1 = fmax(x1, series[k].x[i]);
            y0 = fmin(y0, y);
            y1 = fmax(y1, y);
        }
    if (!(x1 >= x0)) {
        x0 = y0 = 0.0;
        x1 = y1 = 1.0;
    }
    double px = 0.05 * (x1 - x0) + 1e-12, py = 0.05 * (y1 - y0) + 1e-12;
    if (ax->x_integer && x1 - x0 < 1.0)
        px = 0.5;
    if (ax->log_y && y1 - y0 < 0.3)
        py = 0.15;
    x0 -= px, x1 += px, y0 -= py, y1 += py;
    const double left = MARGIN_L, right = ax->width - ax->legend_w, top = MARGIN_T, bottom = ax->height - MARGIN_B;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            ax->width, ax->height);
    fprintf(f, "<text x=\"%d\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">", ax->width / 2);
    svg_text(f, ax->title);
    fprintf(f, "</text>\n<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n",
            left, top, right - left, bottom - top);
    if (ax->x_integer) {
        const double step = integer_step(x1 - x0);
        for (double v = ceil(x0 / step) * step + 0.0; v <= x1; v += step) /* + 0.0: no "-0" */
            tick(f, 1, map(v, x0, x1, left, right), top, bottom, v, bottom + 16);
    } else {
        for (int t = 0; t <= 4; t++) {
            const double v = x0 + (x1 - x0) * t / 4.0;
            tick(f, 1, map(v, x0, x1, left, right), top, bottom, v, bottom + 16);
        }
    }
    if (ax->log_y) { /* powers of 10, and 2x and 5x where the axis spans less than two decades */
        const int fine = y1 - y0 < 2.0;
        for (int d = (int)floor(y0); d <= (int)ceil(y1); d++)
            for (int m = 1; m <= 5; m += fine ? (m == 1 ? 1 : 3) : 5) {
                const double v = d + log10((double)m);
                if (v >= y0 && v <= y1)
                    tick(f, 0, map(v, y0, y1, bottom, top), left, right, pow(10.0, v), left - 6);
            }
    } else {
        for (int t = 0; t <= 4; t++) {
            const double v = y0 + (y1 - y0) * t / 4.0;
            tick(f, 0, map(v, y0, y1, bottom, top), left, right, v, left - 6);
        }
    }
    fprintf(f, "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">", 0.5 * (left + right), ax->height - 18);
    svg_text(f, ax->xlabel);
    fprintf(f, "</text>\n<text transform=\"translate(18 %.1f) rotate(-90)\" text-anchor=\"middle\">",
            0.5 * (top + bottom));
    svg_text(f, ax->ylabel);
    fprintf(f, "</text>\n");
    for (int k = 0; k < nseries; k++) {
        const struct plot_series *s = &series[k];
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\" points=\"", s->color);
        for (int i = 0; i < s->n; i++) {
            const double y = plot_y(ax, s->y[i]);
            if (isfinite(y))
                fprintf(f, "%.1f,%.1f ", map(s->x[i], x0, x1, left, right), map(y, y0, y1, bottom, top));
        }
        fprintf(f, "\"/>\n");
        for (int i = 0; i < s->n; i++) {
            if (!isfinite(plot_y(ax, s->y[i])))
                continue;
            double sx = map(s->x[i], x0, x1, left, right), sy = map(plot_y(ax, s->y[i]), y0, y1, bottom, top);
            fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"%s\"><title>", sx, sy, s->color);
            svg_text(f, s->label);
            fprintf(f, ": %.4g at %g</title></circle>\n", s->y[i], s->x[i]);
            if (s->tag)
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"%s\">%g</text>\n", sx + 5, sy - 5,
                        s->color, s->tag[i]);
        }
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n",
                right + 12, top + 14 + 18 * k, right + 36, top + 14 + 18 * k, s->color);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">", right + 42, top + 18 + 18 * k);
        svg_text(f, s->label);
        fprintf(f, "</text>\n");
    }
    fprintf(f, "</svg>\n");
}

int svg_write_xy_plot(const char *path, const char *title, const char *xlabel, const char *ylabel,
                      const struct plot_series *series, int nseries, char *msg)
{
    char tmp[4200];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "w", msg);
    if (!f)
        return -1;
    const struct svg_xy_axes ax = {title, xlabel, ylabel, FILE_W, FILE_H, FILE_LEGEND_W, 0, 0};
    svg_xy_plot(f, &ax, series, nseries);
    return io_close_commit(f, tmp, path, msg);
}

void svg_hbar_plot(FILE *f, const struct svg_bars *b, int nrows, const char *const *labels, const double *values)
{
    enum { BAR_H = 22, GAP = 6, TOP = 10, LEGEND_ROW = 18 };
    double top = 0.0;
    for (int r = 0; r < nrows; r++) {
        double sum = 0.0;
        for (int s = 0; s < b->nseg; s++)
            sum += isfinite(values[r * b->nseg + s]) && values[r * b->nseg + s] > 0.0 ? values[r * b->nseg + s] : 0.0;
        top = fmax(top, sum);
    }
    const int width = b->label_w + b->plot_w + 90, per_row = width / 150 > 0 ? width / 150 : 1;
    const int legend_rows = b->nseg > 1 ? (b->nseg + per_row - 1) / per_row : 0;
    const int bars_end = TOP + nrows * (BAR_H + GAP), height = bars_end + 24 + legend_rows * LEGEND_ROW;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-size=\"12\">", width,
            height);
    for (int r = 0; r < nrows; r++) {
        const int y = TOP + r * (BAR_H + GAP);
        fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"end\">", b->label_w - 6, y + 15);
        svg_text(f, labels[r]);
        fprintf(f, "</text>");
        double x = b->label_w, sum = 0.0;
        for (int s = 0; s < b->nseg; s++) {
            const double v = values[r * b->nseg + s];
            if (!(isfinite(v) && v > 0.0))
                continue;
            const double len = top > 0.0 ? b->plot_w * v / top : 0.0;
            fprintf(f, "<rect x=\"%.1f\" y=\"%d\" width=\"%.1f\" height=\"%d\" fill=\"%s\"><title>", x, y, len, BAR_H,
                    b->seg_colors[s]);
            svg_text(f, labels[r]);
            if (b->nseg > 1) {
                fputs(", ", f);
                svg_text(f, b->seg_names[s]);
            }
            fputs(": ", f);
            fprintf(f, b->value_fmt, v);
            fputs("</title></rect>", f);
            x += len;
            sum += v;
        }
        fprintf(f, "<text x=\"%.1f\" y=\"%d\">", x + 4, y + 15);
        fprintf(f, b->value_fmt, sum);
        fputs("</text>\n", f);
    }
    fprintf(f, "<text x=\"%d\" y=\"%d\">", b->label_w, bars_end + 12);
    svg_text(f, b->caption);
    fputs("</text>", f);
    for (int s = 0; legend_rows && s < b->nseg; s++) { /* the legend: a swatch and a name per segment */
        const int lx = 10 + (s % per_row) * 150, ly = bars_end + 24 + (s / per_row) * LEGEND_ROW;
        fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"12\" height=\"12\" fill=\"%s\"/><text x=\"%d\" y=\"%d\">", lx, ly,
                b->seg_colors[s], lx + 16, ly + 10);
        svg_text(f, b->seg_names[s]);
        fputs("</text>", f);
    }
    fputs("</svg>\n", f);
}
