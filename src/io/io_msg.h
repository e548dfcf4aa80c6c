/* io_msg.h: io_msg, the one formatter of the messages src/io's functions return in msg.
 * Must never depend on other io headers: every file of src/io may include it. */
#ifndef RESTIR_IO_IO_MSG_H
#define RESTIR_IO_IO_MSG_H

/* Formats a message into msg (RESTIR_MSG_LEN bytes, may be NULL), truncating long paths. */
void io_msg(char *msg, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#endif
