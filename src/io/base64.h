/* base64.h: the base64 encoding of RFC 4648 Sec. 4 (the data: URIs of self-contained report pages).
 * Must never depend on other io headers. */
#ifndef RESTIR_IO_BASE64_H
#define RESTIR_IO_BASE64_H

#include <stddef.h>
#include <stdio.h>

/* Characters base64_encode writes for n bytes, without the terminating NUL: 4 per 3 bytes, padded. */
#define BASE64_LEN(n) (4 * (((size_t)(n) + 2) / 3))

/* Encodes n bytes of in into out (BASE64_LEN(n) + 1 bytes), '=' padded and NUL-terminated. Returns
 * the characters written. */
size_t base64_encode(const unsigned char *in, size_t n, char *out);
/* Writes the encoding of the whole of `in` (read to its end) to out. Returns the bytes read, or -1 when
 * reading or writing failed. */
long long base64_copy(FILE *in, FILE *out);

#endif
