/* io_msg.c: io_msg (io_msg.h), the message formatter every file of src/io shares.
 * Must never depend on image formats, report files, scenes or render code. */
#include "io/io_msg.h"

#include <stdarg.h>
#include <stdio.h>

#include "core/check.h"

void io_msg(char *msg, const char *fmt, ...)
{
    if (!msg)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, RESTIR_MSG_LEN, fmt, ap);
    va_end(ap);
}
