/* report.c: atomic CSV and JSON report files for the command line (report.h).
 * Must never depend on render code or scenes; only on cJSON and the C library. */
#include "io/report.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"
#include "io/io_msg.h"

static int report_check_path(const char *path, char *msg)
{
    if (!path || !path[0]) {
        io_msg(msg, "(empty path): cannot write report");
        return -1;
    }
    if (strlen(path) >= REPORT_PATH_MAX) {
        io_msg(msg, "%.200s...: output path is too long", path);
        return -1;
    }
    return 0;
}

int csv_open(struct csv_writer *w, const char *path, const char *header, char *msg)
{
    memset(w, 0, sizeof *w);
    if (report_check_path(path, msg) != 0)
        return -1;
    snprintf(w->path, sizeof w->path, "%s", path);
    w->f = io_open_temp(path, w->tmp, sizeof w->tmp, "w", msg);
    if (!w->f)
        return -1;
    if (fprintf(w->f, "%s\n", header ? header : "") < 0) {
        io_msg(msg, "%s: cannot write CSV header: %s", path, strerror(errno));
        csv_abort(w);
        return -1;
    }
    return 0;
}

int csv_row(struct csv_writer *w, const char *fmt, ...)
{
    if (!w->f)
        return -1;
    va_list ap;
    va_start(ap, fmt);
    int n = vfprintf(w->f, fmt, ap);
    va_end(ap);
    if (n < 0 || fputc('\n', w->f) == EOF)
        return -1;
    return 0;
}

int csv_close(struct csv_writer *w, char *msg)
{
    if (!w->f) {
        io_msg(msg, "%.400s: CSV writer is not open", w->path);
        return -1;
    }
    FILE *f = w->f;
    w->f = NULL;
    return io_close_commit(f, w->tmp, w->path, msg);
}

void csv_abort(struct csv_writer *w)
{
    if (w->f) {
        fclose(w->f);
        w->f = NULL;
        remove(w->tmp);
    }
}

int json_write_file(const char *path, const cJSON *root, char *msg)
{
    if (report_check_path(path, msg) != 0)
        return -1;
    char *text = cJSON_Print(root);
    if (!text) {
        io_msg(msg, "%s: cannot format JSON", path);
        return -1;
    }
    const size_t len = strlen(text);
    text[len] = '\n'; /* cJSON_Print's terminator becomes the file's last line break */
    int rc = io_write_file(path, text, len + 1, msg);
    cJSON_free(text);
    return rc;
}

/* Writes s as one CSV field: verbatim, or quoted (quotes doubled) when it holds a comma, a quote
 * or a line break. */
void csv_field(char *out, size_t n, const char *s)
{
    int quote = strpbrk(s, ",\"\r\n") != NULL;
    size_t o = 0;
    if (quote)
        out[o++] = '"';
    for (; *s && o + 3 < n; s++) {
        if (*s == '"')
            out[o++] = '"';
        out[o++] = *s;
    }
    if (quote)
        out[o++] = '"';
    out[o] = '\0';
}
