/* svg_plot.h: small SVG plots: x-y line plots (the Pareto curves of 000 Figure 3, error against frame)
 * and horizontal bars, stacked or not (relMSE per method, time per pass), either into a stream (a
 * report page's inline plots) or as a file of their own through a temporary file and a rename.
 * Must never depend on render code. */
#ifndef RESTIR_IO_SVG_PLOT_H
#define RESTIR_IO_SVG_PLOT_H

#include <stdio.h>

struct plot_series {
    const char *label;
    const char *color; /* SVG colour, e.g. "#1f77b4" */
    int n;
    const double *x, *y;
    const double *tag; /* optional value printed next to each point (e.g. the radius), NULL: none */
};

/* How svg_xy_plot lays out its axes. */
struct svg_xy_axes {
    const char *title, *xlabel, *ylabel;
    int width, height; /* of the whole plot, in pixels */
    int legend_w;      /* room right of the axes for the legend's lines and labels */
    int log_y;         /* a log10 y axis with ticks at powers of 10 (and 2x, 5x within a decade); y <= 0 is left out */
    int x_integer;     /* x ticks at whole numbers only (frames) */
};

/* Writes series as polylines with markers on axes fitted to the data, as one <svg> element (text
 * escaped), into f. */
void svg_xy_plot(FILE *f, const struct svg_xy_axes *ax, const struct plot_series *series, int nseries);
/* 1 when every y of series is > 0 and the largest is more than `ratio` times the smallest (a log axis
 * reads better). */
int svg_wide_range(const struct plot_series *series, int nseries, double ratio);
/* svg_xy_plot at 640 x 440 on linear axes, to the file path. Returns 0, or -1 with msg
 * (RESTIR_MSG_LEN) naming the file. */
int svg_write_xy_plot(const char *path, const char *title, const char *xlabel, const char *ylabel,
                      const struct plot_series *series, int nseries, char *msg);

/* Horizontal bars, one per row, each a stack of segments (one segment: plain bars) on a linear axis
 * from 0; the row's total is printed after its bar. */
struct svg_bars {
    const char *caption;             /* under the bars */
    int nseg;                        /* segments per bar */
    const char *const *seg_names;    /* nseg names for the legend (shown when nseg > 1) and the tooltips */
    const char *const *seg_colors;   /* nseg SVG colours */
    const char *value_fmt;           /* printf format of a total, e.g. "%.4g" */
    int label_w, plot_w;             /* room for the row labels; the longest bar's length */
};
/* Writes nrows bars, row r labelled labels[r] with segment values values[r * nseg + s] (negative and
 * non-finite values count as 0; a zero segment draws nothing), into f as one <svg> element. */
void svg_hbar_plot(FILE *f, const struct svg_bars *b, int nrows, const char *const *labels, const double *values);

#endif
