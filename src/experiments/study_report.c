/* study_report.c: `restir study --report` (study_report.h): DIR/index.html beside what the study wrote, its
 * images loaded from there or, with --self-contained, embedded.
 * Must never render or compute a study's numbers: the page is built from the files the study wrote. */
#include "experiments/study_report.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/report_commit.h"
#include "io/html_report.h"
#include "io/png.h"

/* The page shows study.csv as the table, pareto.svg (and pareto_denoised.svg where --denoise wrote it),
 * hard_pixels.png, strip.png and the reference the study measured against, so it shows exactly the
 * study's numbers. */

#define STUDY_REPORT_MAX_CELLS 4096

/* study.csv as a table: the header line names the columns. Config names hold no commas. */
static int csv_table(struct html_page *pg, const char *dir, char *msg)
{
    char path[4300];
    snprintf(path, sizeof path, "%s/study.csv", dir);
    static char text[1 << 18];
    FILE *f = fopen(path, "rb");
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[len] = '\0';
    if (!text[0]) {
        snprintf(msg, RESTIR_MSG_LEN, "%.400s: missing or empty", path);
        return -1;
    }
    const char *cells[STUDY_REPORT_MAX_CELLS];
    int cols = 0, n = 0;
    for (char *line = strtok(text, "\n"); line && n < STUDY_REPORT_MAX_CELLS - 64; line = strtok(NULL, "\n")) {
        int in_line = 0;
        for (char *c = line;; c++) {
            char *comma = strchr(c, ',');
            if (comma)
                *comma = '\0';
            cells[n++] = c;
            in_line++;
            if (!comma)
                break;
            c = comma;
        }
        if (!cols)
            cols = in_line;
        else if (in_line != cols) {
            snprintf(msg, RESTIR_MSG_LEN, "%.400s: a row has %d fields, the header %d", path, in_line, cols);
            return -1;
        }
    }
    html_table(pg, cols, cells, n / cols - 1, cells + cols);
    return 0;
}

int study_write_report(const struct study_report_run *run, char *msg)
{
    char path[4300];
    snprintf(path, sizeof path, "%s/reference.png", run->out_dir);
    if (png_write_srgb(path, run->reference, run->width, run->height, 0.0f, msg) != 0)
        return -1;
    struct html_page pg;
    snprintf(path, sizeof path, "%s/index.html", run->out_dir);
    if (html_begin(&pg, path, "restir study", msg) != 0)
        return -1;
    pg.embed = run->self_contained;
    html_raw(&pg, "<h1>restir study: ");
    html_text(&pg, run->method);
    html_raw(&pg, " on ");
    html_text(&pg, run->scene);
    html_raw(&pg, "</h1>\n");
    html_run_info(&pg, run->command, RESTIR_GIT_COMMIT);
    html_raw(&pg,
             "<p>%dx%d, %d independently seeded runs per configuration, %d warm-up and %d measured frames, static "
             "camera; %d hard pixels (000 Sec. 7).</p>\n<h2>Results (study.csv)</h2>\n",
             run->width, run->height, run->runs, run->warmup, run->frames, run->hard_pixels);
    if (csv_table(&pg, run->out_dir, msg) != 0) {
        html_abort(&pg);
        return -1;
    }
    html_raw(&pg, "<h2>Pareto plot (000 Figure 3)</h2>\n<p>SMAPE against spatial covariance over radii: every "
                  "Bitterli configuration, and every compat one with K = 32.</p>");
    html_image(&pg, "pareto.svg", "Pareto plot");
    snprintf(path, sizeof path, "%s/pareto_denoised.svg", run->out_dir);
    FILE *dn = fopen(path, "rb");
    if (dn) { /* --denoise: the same after denoising */
        fclose(dn);
        html_raw(&pg, "<p>After denoising (BIASED; study_denoised.md):</p>");
        html_image(&pg, "pareto_denoised.svg", "Pareto plot after denoising");
    }
    html_raw(&pg, "\n<h2>Hard pixels</h2>\n<p>In red, the pixels whose neighbors within the radius rarely look alike "
                  "(the hardest 10%%), over the reference:</p>\n");
    const char *labels[2] = {"reference", "hard pixels"}, *srcs[2] = {"reference.png", "hard_pixels.png"};
    html_viewer(&pg, 2, labels, srcs, run->width, run->height);
    html_raw(&pg, "<h2>Strip (000 Figure 5)</h2>\n<p>Row %d of run 0 over the measured frames (time downward), one "
                  "panel per configuration (up to four), luminance over the reference (mid grey = exact):</p>",
             run->strip_row);
    html_image(&pg, "strip.png", "strip");
    html_raw(&pg, "\n");
    return html_end(&pg, msg);
}
