/* test_base64.c: base64_encode gives RFC 4648 Sec. 10's test vectors, and base64_copy streams a file
 * longer than its chunk to the same text as base64_encode of the whole (padding only at the end). */
#include <stdlib.h>
#include <string.h>

#include "io/base64.h"
#include "test_util.h"

int main(void)
{
    static const char *const plain[] = {"", "f", "fo", "foo", "foob", "fooba", "foobar"};
    static const char *const coded[] = {"", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy"};
    for (int k = 0; k < 7; k++) {
        char out[16];
        const size_t n = strlen(plain[k]);
        const size_t len = base64_encode((const unsigned char *)plain[k], n, out);
        EXPECT(len == BASE64_LEN(n) && !strcmp(out, coded[k]), "base64('%s') = '%s', want '%s'", plain[k], out,
               coded[k]);
    }
    /* every byte value, over several of base64_copy's chunks and a last group of 2 bytes */
    enum { N = 3 * 4096 * 3 + 2 };
    unsigned char *bytes = malloc(N);
    char *whole = malloc(BASE64_LEN(N) + 1), *streamed = calloc(BASE64_LEN(N) + 2, 1);
    for (int i = 0; i < N; i++)
        bytes[i] = (unsigned char)(i * 7 + i / 256);
    base64_encode(bytes, N, whole);
    FILE *in = tmpfile(), *out = tmpfile();
    EXPECT(in && out, "no temporary files");
    if (in && out) {
        fwrite(bytes, 1, N, in);
        rewind(in);
        EXPECT(base64_copy(in, out) == N, "base64_copy did not read %d bytes", N);
        rewind(out);
        const size_t got = fread(streamed, 1, BASE64_LEN(N) + 1, out);
        EXPECT(got == BASE64_LEN(N) && !strcmp(streamed, whole), "base64_copy wrote %zu characters, not the %zu of "
               "base64_encode", got, (size_t)BASE64_LEN(N));
    }
    if (in)
        fclose(in);
    if (out)
        fclose(out);
    free(bytes);
    free(whole);
    free(streamed);
    return test_finish();
}
