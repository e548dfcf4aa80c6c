/* svg_plot.c: x-y line plots as SVG (svg_plot.h), through a temporary file and a rename.
 * Must never depend on render code. */
#include "io/svg_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/atomic_file.h"
#include "io/io_msg.h"

enum { PLOT_W = 640, PLOT_H = 440, MARGIN_L = 80, MARGIN_R = 150, MARGIN_T = 40, MARGIN_B = 60 };

static double map(double v, double lo, double hi, double a, double b)
{
    return hi > lo ? a + (v - lo) / (hi - lo) * (b - a) : 0.5 * (a + b);
}

int svg_write_xy_plot(const char *path, const char *title, const char *xlabel, const char *ylabel,
                      const struct plot_series *series, int nseries, char *msg)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int k = 0; k < nseries; k++)
        for (int i = 0; i < series[k].n; i++) {
            x0 = fmin(x0, series[k].x[i]);
            x1 = fmax(x1, series[k].x[i]);
            y0 = fmin(y0, series[k].y[i]);
            y1 = fmax(y1, series[k].y[i]);
        }
    if (!(x1 >= x0)) {
        x0 = y0 = 0.0;
        x1 = y1 = 1.0;
    }
    double px = 0.05 * (x1 - x0) + 1e-12, py = 0.05 * (y1 - y0) + 1e-12;
    x0 -= px, x1 += px, y0 -= py, y1 += py;
    char tmp[4200];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "w", msg);
    if (!f) {
        return -1;
    }
    const double left = MARGIN_L, right = PLOT_W - MARGIN_R, top = MARGIN_T, bottom = PLOT_H - MARGIN_B;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            PLOT_W, PLOT_H);
    fprintf(f, "<text x=\"%d\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">%s</text>\n", PLOT_W / 2, title);
    fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n", left,
            top, right - left, bottom - top);
    for (int t = 0; t <= 4; t++) { /* ticks */
        double vx = x0 + (x1 - x0) * t / 4.0, vy = y0 + (y1 - y0) * t / 4.0;
        double sx = map(vx, x0, x1, left, right), sy = map(vy, y0, y1, bottom, top);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", sx, top, sx, bottom);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, sy, right, sy);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%.3g</text>\n", sx, bottom + 16, vx);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.3g</text>\n", left - 6, sy + 4, vy);
    }
    fprintf(f, "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">%s</text>\n", 0.5 * (left + right), PLOT_H - 18,
            xlabel);
    fprintf(f, "<text transform=\"translate(18 %.1f) rotate(-90)\" text-anchor=\"middle\">%s</text>\n",
            0.5 * (top + bottom), ylabel);
    for (int k = 0; k < nseries; k++) {
        const struct plot_series *s = &series[k];
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\" points=\"", s->color);
        for (int i = 0; i < s->n; i++)
            fprintf(f, "%.1f,%.1f ", map(s->x[i], x0, x1, left, right), map(s->y[i], y0, y1, bottom, top));
        fprintf(f, "\"/>\n");
        for (int i = 0; i < s->n; i++) {
            double sx = map(s->x[i], x0, x1, left, right), sy = map(s->y[i], y0, y1, bottom, top);
            fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3.5\" fill=\"%s\"/>\n", sx, sy, s->color);
            if (s->tag)
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"%s\">%g</text>\n", sx + 5, sy - 5,
                        s->color, s->tag[i]);
        }
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n",
                right + 12, top + 14 + 18 * k, right + 36, top + 14 + 18 * k, s->color);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", right + 42, top + 18 + 18 * k, s->label);
    }
    fprintf(f, "</svg>\n");
    return io_close_commit(f, tmp, path, msg);
}
