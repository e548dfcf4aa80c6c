/* html_report.c: the pieces of a report page (html_report.h), its style and script inline, its images beside it
 * or embedded.
 * Must never depend on render code. */
#include "io/html_report.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "io/atomic_file.h"
#include "io/base64.h"
#include "io/io_msg.h"
#include "io/png.h"

static const char *const page_style =
    "body{font-family:sans-serif;margin:1.5em;background:#fafafa;color:#222}"
    "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}"
    "th{background:#eee}td:first-child,th:first-child{text-align:left}"
    ".grid{display:flex;flex-wrap:wrap;gap:10px}.pane{margin:0}.pane figcaption{font-size:0.85em;text-align:center}"
    ".frame{overflow:hidden;border:1px solid #999;cursor:grab;background:#000;position:relative}"
    ".frame img{transform-origin:0 0;image-rendering:pixelated;display:block;user-select:none}"
    ".bar{display:inline-block;width:260px;height:14px;vertical-align:middle;border:1px solid #999}"
    ".crops img{image-rendering:pixelated}code{background:#eee;padding:1px 3px}";

/* One script for every viewer on the page: every image of a viewer shares one zoom and pan (wheel
 * about the cursor, drag), and the A/B view shows one image at a time, the space bar flipping
 * between the two selected (its options' values index the viewer's grid, whose images it shows).
 * A viewer is a .viewer element holding .frame elements; its A/B part is an element with data-ab.
 * Once the page has loaded, the body records how many of its images and SVG plots there are, how
 * many images failed to load and how many script errors occurred (data-images, data-broken,
 * data-errors), so a headless browser can check the page. */
static const char *const page_script =
    "var restirErrors=0;window.addEventListener('error',function(e){if(!(e instanceof ErrorEvent))return;restirErrors++;"
    "document.body.dataset.errors=restirErrors;},true);"
    "window.addEventListener('load',function(){var im=document.images,bad=0;"
    "for(var i=0;i<im.length;i++)if(!im[i].complete||im[i].naturalWidth===0)bad++;"
    "document.body.dataset.images=im.length;document.body.dataset.plots=document.querySelectorAll('svg').length;"
    "document.body.dataset.broken=bad;document.body.dataset.errors=restirErrors;});"
    "document.querySelectorAll('.viewer').forEach(function(v){"
    "var s={z:1,x:0,y:0},imgs=v.querySelectorAll('.frame img');"
    "function apply(){imgs.forEach(function(i){i.style.transform='translate('+s.x+'px,'+s.y+'px) scale('+s.z+')';});}"
    "v.querySelectorAll('.frame').forEach(function(f){var d=null;"
    "f.addEventListener('wheel',function(e){e.preventDefault();var r=f.getBoundingClientRect(),"
    "mx=e.clientX-r.left,my=e.clientY-r.top,k=e.deltaY<0?1.25:0.8;s.x=mx-(mx-s.x)*k;s.y=my-(my-s.y)*k;s.z*=k;apply();});"
    "f.addEventListener('mousedown',function(e){d=[e.clientX-s.x,e.clientY-s.y];e.preventDefault();});"
    "window.addEventListener('mouseup',function(){d=null;});"
    "window.addEventListener('mousemove',function(e){if(d){s.x=e.clientX-d[0];s.y=e.clientY-d[1];apply();}});});"
    "var ab=v.querySelector('[data-ab]');if(!ab)return;"
    "var a=ab.querySelector('.a'),b=ab.querySelector('.b'),img=ab.querySelector('img'),"
    "grid=v.querySelectorAll('.grid img'),lab=ab.querySelector('.which'),showA=true;"
    "function show(){var sel=showA?a:b;img.src=grid[+sel.value].src;lab.textContent=(showA?'A: ':'B: ')+"
    "sel.options[sel.selectedIndex].text;}"
    "a.onchange=b.onchange=show;ab.querySelector('button').onclick=function(){showA=!showA;show();};"
    "document.addEventListener('keydown',function(e){if(e.code==='Space'&&e.target.tagName!=='SELECT'){"
    "e.preventDefault();showA=!showA;show();}});show();});";

int html_begin(struct html_page *pg, const char *path, const char *title, char *msg)
{
    memset(pg, 0, sizeof(*pg));
    snprintf(pg->path, sizeof pg->path, "%s", path);
    pg->f = io_open_temp(path, pg->tmp, sizeof pg->tmp, "wb", msg);
    if (!pg->f)
        return -1;
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>", pg->f);
    html_text(pg, title);
    fprintf(pg->f, "</title><style>%s</style></head><body>\n", page_style);
    return 0;
}

void html_text(struct html_page *pg, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", pg->f); break;
        case '<': fputs("&lt;", pg->f); break;
        case '>': fputs("&gt;", pg->f); break;
        case '"': fputs("&quot;", pg->f); break;
        default: fputc(*s, pg->f);
        }
    }
}

void html_raw(struct html_page *pg, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(pg->f, fmt, ap);
    va_end(ap);
}

void html_machine_name(char *out, size_t len)
{
    char model[256] = "unknown CPU";
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        if (!strncmp(line, "model name", 10)) {
            const char *c = strchr(line, ':');
            if (c) {
                snprintf(model, sizeof model, "%s", c + 2);
                model[strcspn(model, "\n")] = '\0';
            }
            break;
        }
    }
    if (f)
        fclose(f);
    snprintf(out, len, "%s, %ld cores", model, sysconf(_SC_NPROCESSORS_ONLN));
}

void html_run_info(struct html_page *pg, const char *command, const char *commit)
{
    char machine[400], when[64];
    html_machine_name(machine, sizeof machine);
    time_t now = time(NULL);
    strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", gmtime(&now));
    html_raw(pg, "<p>Command: <code>");
    html_text(pg, command);
    html_raw(pg, "</code><br>Commit: <code>");
    html_text(pg, commit);
    html_raw(pg, "</code> (at build time). Machine: ");
    html_text(pg, machine);
    html_raw(pg, ". Written %s.</p>\n", when);
}

void html_table(struct html_page *pg, int cols, const char *const *header, int rows, const char *const *cells)
{
    fputs("<table><tr>", pg->f);
    for (int c = 0; c < cols; c++) {
        fputs("<th>", pg->f);
        html_text(pg, header[c]);
        fputs("</th>", pg->f);
    }
    fputs("</tr>\n", pg->f);
    for (int r = 0; r < rows; r++) {
        fputs("<tr>", pg->f);
        for (int c = 0; c < cols; c++) {
            fputs("<td>", pg->f);
            html_text(pg, cells[r * cols + c]);
            fputs("</td>", pg->f);
        }
        fputs("</tr>\n", pg->f);
    }
    fputs("</table>\n", pg->f);
}

void html_viewer(struct html_page *pg, int n, const char *const *labels, const char *const *srcs, int width,
                 int height)
{
    pg->viewers++;
    const int zoom = width > 0 && width < 320 ? (320 + width - 1) / width : 1; /* grid */
    const int ab_zoom = width > 0 && 2 * zoom * width <= 1280 ? 2 * zoom : zoom; /* the A/B view */
    fputs("<div class=\"viewer\"><p>Wheel: zoom (all images together); drag: pan; space or the button: flip the "
          "A/B view.</p><div class=\"grid\">\n", pg->f);
    for (int k = 0; k < n; k++) {
        fprintf(pg->f, "<figure class=\"pane\"><div class=\"frame\" style=\"width:%dpx;height:%dpx\"><img width=\"%d\" "
                       "height=\"%d\" alt=\"",
                zoom * width, zoom * height, zoom * width, zoom * height);
        html_text(pg, labels[k]);
        fputs("\" src=\"", pg->f);
        html_src(pg, srcs[k]);
        fputs("\"></div><figcaption>", pg->f);
        html_text(pg, labels[k]);
        fputs("</figcaption></figure>\n", pg->f);
    }
    fputs("</div><div data-ab=\"1\"><p>A <select class=\"a\">", pg->f);
    for (int pass = 0; pass < 2; pass++) {
        for (int k = 0; k < n; k++) {
            fprintf(pg->f, "<option value=\"%d", k);
            fputs(pass == 0 ? (k == 0 ? "\" selected>" : "\">") : (k == (n > 1 ? 1 : 0) ? "\" selected>" : "\">"),
                  pg->f);
            html_text(pg, labels[k]);
            fputs("</option>", pg->f);
        }
        fputs(pass == 0 ? "</select> B <select class=\"b\">" : "</select> <button type=\"button\">flip A/B</button> "
                                                               "<b class=\"which\"></b></p>",
              pg->f);
    }
    fprintf(pg->f, "<div class=\"frame\" style=\"width:%dpx;height:%dpx\"><img width=\"%d\" height=\"%d\" alt=\"A/B\"",
            ab_zoom * width, ab_zoom * height, ab_zoom * width, ab_zoom * height);
    if (!pg->embed && n > 0) { /* embedded, the script gives it the grid's image (a second copy otherwise) */
        fputs(" src=\"", pg->f);
        html_src(pg, srcs[0]);
        fputs("\"", pg->f);
    }
    fputs("></div></div></div>\n", pg->f);
}

/* The MIME type of an image file by its name's ending. */
static const char *image_type(const char *name)
{
    const char *dot = strrchr(name, '.');
    if (dot && !strcmp(dot, ".svg"))
        return "image/svg+xml";
    if (dot && (!strcmp(dot, ".jpg") || !strcmp(dot, ".jpeg")))
        return "image/jpeg";
    return "image/png";
}

void html_src(struct html_page *pg, const char *rel)
{
    if (!pg->embed) {
        html_text(pg, rel);
        return;
    }
    char path[8400];
    const char *slash = strrchr(pg->path, '/');
    if (slash)
        snprintf(path, sizeof path, "%.*s/%s", (int)(slash - pg->path), pg->path, rel);
    else
        snprintf(path, sizeof path, "%s", rel);
    FILE *in = fopen(path, "rb");
    const int open_errno = errno;
    fprintf(pg->f, "data:%s;base64,", image_type(rel));
    const long long got = in ? base64_copy(in, pg->f) : -1;
    if (in)
        fclose(in);
    if (got <= 0 && !pg->failed) {
        pg->failed = 1;
        snprintf(pg->why, sizeof pg->why, "cannot embed %.300s: %s", path,
                 !in ? strerror(open_errno) : got == 0 ? "empty" : "read error");
    }
}

void html_image(struct html_page *pg, const char *rel, const char *alt)
{
    fputs("<img alt=\"", pg->f);
    html_text(pg, alt);
    fputs("\" src=\"", pg->f);
    html_src(pg, rel);
    fputs("\">", pg->f);
}

void html_colorbar(struct html_page *pg, float vmax, const char *what)
{
    fputs("<p>", pg->f);
    html_text(pg, what);
    fputs(": 0 <span class=\"bar\" style=\"background:linear-gradient(to right", pg->f);
    for (int k = 0; k < HEAT_STOPS; k++)
        fprintf(pg->f, ",rgb(%d,%d,%d)", heat_stops[k][0], heat_stops[k][1], heat_stops[k][2]);
    fprintf(pg->f, ")\"></span> %g and above</p>\n", (double)vmax);
}

int html_end(struct html_page *pg, char *msg)
{
    if (pg->failed) {
        io_msg(msg, "%s: %s", pg->path, pg->why);
        html_abort(pg);
        return -1;
    }
    fprintf(pg->f, "<script>%s</script>\n</body></html>\n", page_script);
    FILE *f = pg->f;
    pg->f = NULL;
    return io_close_commit(f, pg->tmp, pg->path, msg);
}

void html_abort(struct html_page *pg)
{
    fclose(pg->f);
    pg->f = NULL;
    remove(pg->tmp);
}
