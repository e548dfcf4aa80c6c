/* json_csv.c: atomic CSV and JSON report files for the command line (see report.h).
 * Must never depend on render code or scenes; only on cJSON and the C library. */
#include "io/report.h"

#include "core/check.h"
#include "io/image_io.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Formats a message into msg (RESTIR_MSG_LEN bytes, may be NULL), truncating long paths. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void set_msg(char *msg, const char *fmt, ...)
{
    if (!msg)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, RESTIR_MSG_LEN, fmt, ap);
    va_end(ap);
}

static int report_check_path(const char *path, char *msg)
{
    if (!path || !path[0]) {
        set_msg(msg, "(empty path): cannot write report");
        return -1;
    }
    if (strlen(path) >= REPORT_PATH_MAX) {
        set_msg(msg, "%.200s...: output path is too long", path);
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
    io_temp_path(path, w->tmp, sizeof w->tmp);
    w->f = fopen(w->tmp, "w");
    if (!w->f) {
        set_msg(msg, "%s: cannot create temporary file %.200s: %s", path, w->tmp, strerror(errno));
        return -1;
    }
    if (fprintf(w->f, "%s\n", header ? header : "") < 0) {
        set_msg(msg, "%s: cannot write CSV header: %s", path, strerror(errno));
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
        set_msg(msg, "%.400s: CSV writer is not open", w->path);
        return -1;
    }
    int bad = ferror(w->f) != 0;
    int err = bad ? EIO : 0;
    if (fclose(w->f) != 0 && !bad) {
        bad = 1;
        err = errno;
    }
    w->f = NULL;
    if (bad) {
        set_msg(msg, "%.400s: writing CSV failed: %s", w->path, strerror(err));
        remove(w->tmp);
        return -1;
    }
    return io_commit(w->tmp, w->path, msg);
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
        set_msg(msg, "%s: cannot format JSON", path);
        return -1;
    }
    char tmp[REPORT_PATH_MAX + 32];
    io_temp_path(path, tmp, sizeof tmp);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        set_msg(msg, "%s: cannot create temporary file %.200s: %s", path, tmp, strerror(errno));
        cJSON_free(text);
        return -1;
    }
    int bad = fputs(text, f) < 0 || fputc('\n', f) == EOF || ferror(f);
    int err = bad ? errno : 0;
    cJSON_free(text);
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        err = errno;
    }
    if (bad) {
        set_msg(msg, "%s: writing JSON failed: %s", path,
                 strerror(err ? err : EIO));
        remove(tmp);
        return -1;
    }
    return io_commit(tmp, path, msg);
}
