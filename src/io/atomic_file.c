/* atomic_file.c: temporary sibling names and the rename that commits a finished output file.
 * Must never depend on image formats, scenes or render code. */
#include "io/image_io.h"

#include "core/check.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

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

void io_temp_path(const char *path, char *tmp, unsigned long tmp_len)
{
    if (!tmp || tmp_len == 0)
        return;
    snprintf(tmp, (size_t)tmp_len, "%s.tmp-%ld", path ? path : "", (long)getpid());
}

int io_commit(const char *tmp, const char *path, char *msg)
{
    if (rename(tmp, path) != 0) {
        int err = errno;
        if (msg)
            set_msg(msg, "%s: cannot move temporary file %s into place: %s", path,
                     tmp, strerror(err));
        remove(tmp);
        return -1;
    }
    return 0;
}
