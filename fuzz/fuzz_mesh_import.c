/* fuzz_mesh_import.c: libFuzzer harness for the mesh import path, the entry `restir scene info FILE`
 * takes (scene_import_file_with: our header precheck, assimp, our glTF JSON reader, material,
 * texture and camera import, the builder). The first byte picks the format, the rest is the file:
 * glTF 2.0 JSON, OBJ, PLY, OFF or binary glTF. Any input gives a scene or a message naming the
 * file; never a crash, a sanitizer report or a leak in our code (assimp's own findings are in
 * docs/FUZZING.md). */
#include <stdint.h>
#include <stdlib.h>

#include "core/check.h"
#include "fuzz_file.h"
#include "scene/scene_import.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"in.gltf", "in.obj", "in.ply", "in.off", "in.glb"};
    if (size < 1 || size > (1u << 20))
        return 0;
    const char *name = names[data[0] % 5];
    const char *path = fuzz_write(name, data + 1, size - 1);
    const struct scene_load_desc desc = {.max_triangles = 1 << 18};
    struct scene s;
    char msg[RESTIR_MSG_LEN];
    if (scene_import_file_with(path, &desc, &s, msg) == 0)
        scene_destroy(&s);
    else
        fuzz_check_refusal(msg, sizeof msg, name);
    return 0;
}
