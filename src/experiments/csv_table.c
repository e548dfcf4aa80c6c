/* csv_table.c: CSV files read back into cells (csv_table.h). Must never write files. */
#include "experiments/csv_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "io/io_msg.h"
#include "io/text_file.h"

/* Splits one line (in place) into at most max fields; unquotes "..." fields. Returns the count. */
static int split_line(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        char *start = p, *out = p;
        if (*p == '"') { /* quoted: "" is a quote */
            p++;
            while (*p && !(*p == '"' && p[1] != '"')) {
                if (*p == '"')
                    p++;
                *out++ = *p++;
            }
            if (*p == '"')
                p++;
        } else {
            while (*p && *p != ',')
                *out++ = *p++;
        }
        const int more = *p == ',';
        if (n < max)
            fields[n] = start;
        n++;
        *out = '\0';
        if (!more)
            return n;
        p++;
    }
}

int csv_table_read(const char *path, struct csv_table *t, char *msg)
{
    memset(t, 0, sizeof *t);
    char why[RESTIR_MSG_LEN];
    t->text = io_read_text(path, 64u << 20, why);
    if (!t->text) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s", why);
        return -1;
    }
    int lines = 0;
    for (const char *c = t->text; *c; c++)
        lines += *c == '\n';
    t->cell = NULL;
    char *save = NULL;
    int row = 0;
    for (char *line = strtok_r(t->text, "\n", &save); line; line = strtok_r(NULL, "\n", &save), row++) {
        char *fields[256];
        const int n = split_line(line, fields, 256);
        if (row == 0) {
            t->ncol = n < 256 ? n : 256;
            t->cell = xcalloc((size_t)(lines + 1) * (size_t)t->ncol, sizeof(char *));
        } else if (n != t->ncol) {
            snprintf(msg, RESTIR_MSG_LEN, "%.300s: row %d has %d fields, the header %d", path, row, n, t->ncol);
            csv_table_free(t);
            return -1;
        }
        memcpy(t->cell + (size_t)row * t->ncol, fields, sizeof(char *) * (size_t)t->ncol);
    }
    if (row == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: empty", path);
        csv_table_free(t);
        return -1;
    }
    t->nrow = row - 1;
    return 0;
}

void csv_table_free(struct csv_table *t)
{
    free(t->cell);
    free(t->text);
    memset(t, 0, sizeof *t);
}

int csv_table_find(const struct csv_table *t, const char *key)
{
    for (int r = 0; r < t->nrow; r++)
        if (!strcmp(t->cell[(size_t)(r + 1) * t->ncol], key))
            return r;
    return -1;
}

double csv_table_num(const struct csv_table *t, int row, const char *col)
{
    if (row < 0 || row >= t->nrow)
        return NAN;
    for (int c = 0; c < t->ncol; c++)
        if (!strcmp(t->cell[c], col)) {
            const char *s = t->cell[(size_t)(row + 1) * t->ncol + c];
            char *end;
            const double v = strtod(s, &end);
            return end != s && *end == '\0' ? v : NAN;
        }
    return NAN;
}
