/* fuzz_env_map.c: libFuzzer harness for the environment-map readers (scene/environment.c): .hdr
 * through our header check and stb_image, .exr through OpenEXR, then our texel validation. The
 * first byte picks the format, the rest is the file. Any input gives a map or a message naming the
 * file, never a crash, a hang, a sanitizer report or a leak. */
#include <stdint.h>
#include <stdlib.h>

#include "core/check.h"
#include "fuzz_file.h"
#include "scene/environment.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > (4u << 20))
        return 0;
    const char *name = data[0] & 1 ? "env.exr" : "env.hdr";
    const char *path = fuzz_write(name, data + 1, size - 1);
    struct environment env;
    char msg[RESTIR_MSG_LEN];
    if (environment_load(NULL, path, 1.0f, 0.0f, &env, msg) == 0)
        environment_fini(&env);
    else
        fuzz_check_refusal(msg, sizeof msg, name);
    return 0;
}
