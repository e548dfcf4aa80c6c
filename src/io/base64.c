/* base64.c: base64 encoding (base64.h), RFC 4648 Sec. 4: each 3 bytes become 4 characters of the
 * 64-letter alphabet; a last group of 1 or 2 bytes is padded with '='. */
#include "io/base64.h"

static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

size_t base64_encode(const unsigned char *in, size_t n, char *out)
{
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        const unsigned long v = (unsigned long)in[i] << 16 | (i + 1 < n ? (unsigned long)in[i + 1] << 8 : 0ul) |
                                (i + 2 < n ? (unsigned long)in[i + 2] : 0ul);
        out[o++] = alphabet[v >> 18 & 63];
        out[o++] = alphabet[v >> 12 & 63];
        out[o++] = i + 1 < n ? alphabet[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? alphabet[v & 63] : '=';
    }
    out[o] = '\0';
    return o;
}

long long base64_copy(FILE *in, FILE *out)
{
    enum { CHUNK = 3 * 4096 }; /* a multiple of 3: only the last chunk is padded */
    unsigned char buf[CHUNK];
    char text[BASE64_LEN(CHUNK) + 1];
    long long total = 0;
    for (;;) {
        size_t got = 0;
        while (got < CHUNK) { /* fill the chunk whole, so that no padding falls inside the stream */
            const size_t r = fread(buf + got, 1, CHUNK - got, in);
            if (r == 0)
                break;
            got += r;
        }
        if (ferror(in))
            return -1;
        if (got == 0)
            break;
        const size_t len = base64_encode(buf, got, text);
        if (fwrite(text, 1, len, out) != len)
            return -1;
        total += (long long)got;
        if (got < CHUNK)
            break;
    }
    return total;
}
