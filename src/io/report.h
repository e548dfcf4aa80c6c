/* report.h: atomic CSV and JSON report writers for the command line (temp file, then rename).
 * Must never depend on render code or scenes; only on cJSON and the C library. */
#ifndef RESTIR_IO_REPORT_H
#define RESTIR_IO_REPORT_H

#include <cjson/cJSON.h>
#include <stdio.h>

#define REPORT_PATH_MAX 4096

/* A CSV file being written; rows go to tmp until csv_close commits it to path. */
struct csv_writer {
    FILE *f;
    char path[REPORT_PATH_MAX];
    char tmp[REPORT_PATH_MAX + 32];
};

/* Creates the temporary file and writes header (without newline) and a newline.
 * Returns 0, or -1 with msg (RESTIR_MSG_LEN) naming the file; w is then closed. */
int csv_open(struct csv_writer *w, const char *path, const char *header, char *msg);
/* Writes one printf-formatted row and a newline. Returns 0 or -1 (write error, seen at close). */
int csv_row(struct csv_writer *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Flushes, closes and renames into place. Returns 0, or -1 with msg; the temp file is removed. */
int csv_close(struct csv_writer *w, char *msg);
/* Closes and removes the temporary file; path is left untouched. Safe on a closed writer. */
void csv_abort(struct csv_writer *w);

/* s as one CSV field into out (n bytes): verbatim, or quoted (quotes doubled) when it holds a
 * comma, a quote or a line break. */
void csv_field(char *out, size_t n, const char *s);

/* Writes cJSON_Print(root) and a newline to path atomically. Returns 0, or -1 with msg. */
int json_write_file(const char *path, const cJSON *root, char *msg);

#endif
