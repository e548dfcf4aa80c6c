/* scene_import_gltf.c: KHR_materials_emissive_strength read from a glTF file's own JSON, for
 * assimp versions that drop it. Must never depend on assimp: it reads the file beside it. */
#include "scene/scene_import_gltf.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* assimp 5.2 reads glTF's emissiveFactor (at most 1) but drops KHR_materials_emissive_strength;
 * 5.3 reports it as AI_MATKEY_EMISSIVE_INTENSITY. Without the strength every glTF emitter would be
 * capped at radiance 1, so when assimp reports no intensity we read the strength from the file's
 * JSON ourselves. Materials are matched by name: assimp orders them by first use, not by their
 * index in the file, so only uniquely named materials can be matched (exporters name them). */

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The JSON text of a .gltf (the whole file) or .glb (its first chunk, which the format requires
 * to be JSON), malloc'ed, or NULL when it cannot be read. */
static char *read_gltf_text(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = NULL;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    if (size <= 0 || size > (1L << 30) || fseek(f, 0, SEEK_SET) != 0)
        goto done;
    unsigned char head[20];
    size_t got = fread(head, 1, sizeof head, f);
    size_t start = 0, n = (size_t)size;
    if (got == sizeof head && le32(head) == 0x46546C67u) { /* "glTF": binary container */
        uint32_t chunk = le32(head + 12);
        if (le32(head + 16) != 0x4E4F534Au || chunk > (uint32_t)size - 20u) /* "JSON" */
            goto done;
        start = 20;
        n = chunk;
    }
    if (fseek(f, (long)start, SEEK_SET) != 0)
        goto done;
    text = malloc(n + 1);
    if (!text)
        goto done;
    if (fread(text, 1, n, f) != n) {
        free(text);
        text = NULL;
        goto done;
    }
    text[n] = '\0';
    *len = n;
done:
    fclose(f);
    return text;
}

static double strength_by_name(const cJSON *materials, const char *name)
{
    const cJSON *found = NULL;
    int count = 0;
    const cJSON *m;
    cJSON_ArrayForEach(m, materials)
    {
        const cJSON *nm = cJSON_GetObjectItemCaseSensitive(m, "name");
        if (cJSON_IsString(nm) && strcmp(nm->valuestring, name) == 0) {
            found = m;
            count++;
        }
    }
    if (count != 1)
        return 1.0;
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(found, "extensions");
    const cJSON *es = cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_emissive_strength");
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(es, "emissiveStrength");
    return cJSON_IsNumber(v) ? v->valuedouble : 1.0;
}

cJSON *import_gltf_read(const char *path)
{
    size_t len = 0;
    char *text = read_gltf_text(path, &len);
    cJSON *gltf = text ? cJSON_ParseWithLength(text, len) : NULL;
    free(text);
    return gltf;
}

double import_gltf_strength(const cJSON *gltf, const char *name)
{
    const cJSON *materials = cJSON_GetObjectItemCaseSensitive(gltf, "materials");
    return cJSON_IsArray(materials) ? strength_by_name(materials, name) : 1.0;
}
