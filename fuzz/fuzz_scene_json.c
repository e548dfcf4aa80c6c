/* fuzz_scene_json.c: libFuzzer harness for the JSON scene reader (`make fuzz`). Any input must
 * give a scene or a message, never a crash, a sanitizer report or a leak. Relative mesh paths
 * point into a folder that does not exist, so inputs exercise our reader, not the file system. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/scene_json.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (1u << 20)) /* scenes larger than 1 MB say nothing new about the reader */
        return 0;
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    /* a sphere of 4096 segments must not exhaust the fuzzer's memory */
    const struct scene_load_desc desc = {.max_triangles = 1 << 18};
    if (scene_json_parse_with(text, size, "fuzz.json", "/nonexistent-restir-fuzz", &desc, &s, msg) == 0)
        scene_destroy(&s);
    else if (msg[0] == '\0' || memchr(msg, '\0', sizeof msg) == NULL)
        abort(); /* a refusal must say why, in a terminated message */
    free(text);
    return 0;
}
