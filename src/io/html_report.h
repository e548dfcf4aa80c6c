/* html_report.h: one HTML page with its style and script inline (nothing from a network): its images are the
 * files beside it, or with `embed` inside the page itself as data: URIs, so that the one file holds everything.
 * Must never depend on render code. */
#ifndef RESTIR_IO_HTML_REPORT_H
#define RESTIR_IO_HTML_REPORT_H

#include <stdio.h>

/* A page: escaped text, tables, an image viewer with synchronized zoom and pan and an A/B flip,
 * heat-map colour bars. Written to a temporary name and renamed when complete. */
struct html_page {
    FILE *f;
    char path[4096];
    char tmp[4200];
    int viewers; /* viewers written, so each gets its own ids */
    int embed;   /* set after html_begin: every image inline (base64), read from the file it names */
    int failed;  /* an image could not be embedded: html_end fails with why */
    char why[512];
};

/* Opens the page and writes its head (title escaped) and the opening of its body. */
int html_begin(struct html_page *pg, const char *path, const char *title, char *msg);
/* Escaped text (&, <, >, "). */
void html_text(struct html_page *pg, const char *s);
/* Markup, as is. */
void html_raw(struct html_page *pg, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* This machine as "CPU model, N cores" (from /proc/cpuinfo; "unknown CPU" without it). */
void html_machine_name(char *out, size_t len);
/* The run: the command line, the commit, the machine (CPU model and cores) and the time. */
void html_run_info(struct html_page *pg, const char *command, const char *commit);
/* A table: header cells, then rows of cells (escaped), rows * cols entries row-major. */
void html_table(struct html_page *pg, int cols, const char *const *header, int rows, const char *const *cells);
/* Images (all width x height pixels; srcs as html_src takes them) in a grid, shown at least ~320 pixels wide
 * (small renders are magnified by a whole factor, pixelated): the mouse wheel zooms and dragging pans all of them
 * together; two selectors and the space bar flip one large view between image A and image B, which shows the
 * grid's own images (so an embedded image is in the page once). */
void html_viewer(struct html_page *pg, int n, const char *const *labels, const char *const *srcs, int width,
                 int height);
/* The value of an src attribute for the image rel (a path relative to the page's folder): rel, escaped; with
 * embed a data: URI of the file's bytes (PNG, SVG or JPEG by the name's ending; a file that cannot be read makes
 * html_end fail naming it). */
void html_src(struct html_page *pg, const char *rel);
/* <img alt="alt" src="rel"> through html_src. */
void html_image(struct html_page *pg, const char *rel, const char *alt);
/* The heat-map colour bar (heat_color) from 0 to vmax. */
void html_colorbar(struct html_page *pg, float vmax, const char *what);
/* Writes the script, closes the page and renames it into place. Returns 0, or -1 with msg (and no page) when
 * writing failed or an image could not be embedded. */
int html_end(struct html_page *pg, char *msg);
/* Gives the page up: closes and removes its temporary file; path is left untouched. */
void html_abort(struct html_page *pg);

#endif
