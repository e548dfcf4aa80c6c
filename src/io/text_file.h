/* text_file.h: reading a whole small text file (plans, settings) into memory, with a size limit.
 * Must never parse what it reads. */
#ifndef RESTIR_IO_TEXT_FILE_H
#define RESTIR_IO_TEXT_FILE_H

#include <stddef.h>

/* The file at path, NUL-terminated, in a malloc'ed buffer; NULL with msg ("PATH: reason", or
 * "PATH: larger than MAX bytes") when it cannot be read or holds more than max bytes. */
char *io_read_text(const char *path, size_t max, char *msg);

#endif
