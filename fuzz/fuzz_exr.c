/* fuzz_exr.c: libFuzzer harness for the OpenEXR reader behind --ref and compare (io/exr.c): any
 * bytes as a .exr file give an image or a message naming the file, never a crash, a sanitizer
 * report or a leak. Reads it both ways: RGB, and the layer "denoised" (a compare folder's). */
#include <stdint.h>
#include <stdlib.h>

#include "core/check.h"
#include "fuzz_file.h"
#include "io/exr.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (4u << 20))
        return 0;
    const char *path = fuzz_write("in.exr", data, size);
    char msg[RESTIR_MSG_LEN];
    float *rgb = NULL;
    int w = 0, h = 0;
    if (exr_read_rgb(path, &rgb, &w, &h, msg) == 0) {
        if (!rgb || w < 1 || h < 1)
            abort();
        free(rgb);
    } else
        fuzz_check_refusal(msg, sizeof msg, "in.exr");
    rgb = NULL;
    if (exr_read_layer(path, "denoised", &rgb, &w, &h, msg) == 0)
        free(rgb);
    else
        fuzz_check_refusal(msg, sizeof msg, "in.exr");
    return 0;
}
