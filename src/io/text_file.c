/* text_file.c: whole small text files into memory (text_file.h).
 * Must never parse what it reads. */
#include "io/text_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "io/io_msg.h"

char *io_read_text(const char *path, size_t max, char *msg)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        io_msg(msg, "%.300s: %s", path, strerror(errno));
        return NULL;
    }
    char *buf = xmalloc(max + 1);
    size_t n = fread(buf, 1, max + 1, f);
    fclose(f);
    if (n > max) {
        io_msg(msg, "%.300s: larger than %zu bytes", path, max);
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    return buf;
}
