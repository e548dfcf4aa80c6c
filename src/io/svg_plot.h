/* svg_plot.h: a small x-y line plot written as SVG (the Pareto curves of 000 Figure 3), through a
 * temporary file and a rename. Must never depend on render code. */
#ifndef RESTIR_IO_SVG_PLOT_H
#define RESTIR_IO_SVG_PLOT_H

struct plot_series {
    const char *label;
    const char *color; /* SVG colour, e.g. "#1f77b4" */
    int n;
    const double *x, *y;
    const double *tag; /* optional value printed next to each point (e.g. the radius), NULL: none */
};

/* Writes series as polylines with markers on linear axes fitted to the data. Returns 0, or -1
 * with msg (RESTIR_MSG_LEN) naming the file. */
int svg_write_xy_plot(const char *path, const char *title, const char *xlabel, const char *ylabel,
                      const struct plot_series *series, int nseries, char *msg);

#endif
