/* scene_import_gltf.c: a glTF material's emissive strength and texture lookups read from the file's
 * own JSON (scene_import_gltf.h). Must never depend on assimp: it reads the file beside it. */
#include "scene/scene_import_gltf.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

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

/* The material named name, when exactly one has that name (else NULL). */
static const cJSON *material_by_name(const cJSON *materials, const char *name)
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
    return count == 1 ? found : NULL;
}

static double strength_by_name(const cJSON *materials, const char *name)
{
    const cJSON *found = material_by_name(materials, name);
    if (!found)
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

/* A glTF sampler wrap mode as enum texture_wrap (REPEAT 10497 and anything unknown: repeat). */
static int wrap_of(const cJSON *v)
{
    if (!cJSON_IsNumber(v))
        return WRAP_REPEAT;
    return v->valueint == 33071 ? WRAP_CLAMP : v->valueint == 33648 ? WRAP_MIRROR : WRAP_REPEAT;
}

/* Number `key` of obj, or def; -1 when present but not a finite number. */
static int number_or(const cJSON *obj, const char *key, int index, double def, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (index >= 0)
        v = cJSON_IsArray(v) ? cJSON_GetArrayItem(v, index) : NULL;
    *out = def;
    if (!v)
        return 0;
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble) || fabs(v->valuedouble) > 1e6)
        return -1;
    *out = v->valuedouble;
    return 0;
}

/* One textureInfo: its texCoord, its texture's sampler, its KHR_texture_transform. */
static int read_lookup(const cJSON *gltf, const cJSON *info, const char *mname, const char *which,
                       struct texture_lookup *l, char *msg)
{
    if (!cJSON_IsObject(info))
        return 0;
    double tc = 0.0, ox, oy, rot, sx, sy;
    const cJSON *ext = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(info, "extensions"),
                                                        "KHR_texture_transform");
    if (number_or(info, "texCoord", -1, 0.0, &tc) != 0 || number_or(ext, "texCoord", -1, tc, &tc) != 0 ||
        number_or(ext, "offset", 0, 0.0, &ox) != 0 || number_or(ext, "offset", 1, 0.0, &oy) != 0 ||
        number_or(ext, "rotation", -1, 0.0, &rot) != 0 || number_or(ext, "scale", 0, 1.0, &sx) != 0 ||
        number_or(ext, "scale", 1, 1.0, &sy) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "material '%.200s': %s: texCoord or KHR_texture_transform is not a finite number",
                 mname, which);
        return -1;
    }
    if (tc != 0.0 && tc != 1.0) {
        snprintf(msg, RESTIR_MSG_LEN, "material '%.200s': %s: texCoord %g (sets 0 and 1 are read)", mname, which, tc);
        return -1;
    }
    l->uv_set = (int)tc;
    if (ext) { /* glTF: uv' = T R S uv with v down; assimp's v_a = 1 - v (see the header) */
        const double a = cos(rot) * sx, b = sin(rot) * sy, c = -sin(rot) * sx, d = cos(rot) * sy;
        const double m[6] = {a, -b, b + ox, -c, d, 1.0 - d - oy};
        l->has_xform = 1;
        for (int i = 0; i < 6; i++)
            l->xform[i] = (float)m[i];
    }
    const cJSON *index = cJSON_GetObjectItemCaseSensitive(info, "index");
    const cJSON *tex = cJSON_IsNumber(index) ? cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "textures"),
                                                                  index->valueint)
                                             : NULL;
    const cJSON *sampler = cJSON_GetObjectItemCaseSensitive(tex, "sampler");
    const cJSON *smp = cJSON_IsNumber(sampler)
                           ? cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "samplers"), sampler->valueint)
                           : NULL;
    l->wrap_u = wrap_of(cJSON_GetObjectItemCaseSensitive(smp, "wrapS"));
    l->wrap_v = wrap_of(cJSON_GetObjectItemCaseSensitive(smp, "wrapT"));
    return 0;
}

int import_gltf_lookups(const cJSON *gltf, const char *name, struct material *m, char *msg)
{
    const cJSON *mat = material_by_name(cJSON_GetObjectItemCaseSensitive(gltf, "materials"), name);
    if (!mat)
        return 0;
    const cJSON *pbr = cJSON_GetObjectItemCaseSensitive(mat, "pbrMetallicRoughness");
    return read_lookup(gltf, cJSON_GetObjectItemCaseSensitive(pbr, "baseColorTexture"), name, "baseColorTexture",
                       &m->base_color_lookup, msg) != 0 ||
                   read_lookup(gltf, cJSON_GetObjectItemCaseSensitive(pbr, "metallicRoughnessTexture"), name,
                               "metallicRoughnessTexture", &m->metal_rough_lookup, msg) != 0 ||
                   read_lookup(gltf, cJSON_GetObjectItemCaseSensitive(mat, "emissiveTexture"), name, "emissiveTexture",
                               &m->emission_lookup, msg) != 0 ||
                   read_lookup(gltf, cJSON_GetObjectItemCaseSensitive(mat, "normalTexture"), name, "normalTexture",
                               &m->normal_lookup, msg) != 0
               ? -1
               : 0;
}

/* The count of accessor index a in gltf's accessors, or -1. */
static long accessor_count(const cJSON *gltf, const cJSON *a)
{
    const cJSON *acc = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "accessors"),
                                          cJSON_IsNumber(a) ? a->valueint : -1);
    const cJSON *c = cJSON_GetObjectItemCaseSensitive(acc, "count");
    return cJSON_IsNumber(c) && c->valuedouble >= 0 && c->valuedouble < 1e12 ? (long)c->valuedouble : -1;
}

/* The triangles of mesh m, or -1. */
static long mesh_triangles(const cJSON *gltf, int m)
{
    const cJSON *mesh = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "meshes"), m);
    const cJSON *prims = cJSON_GetObjectItemCaseSensitive(mesh, "primitives"), *p;
    if (!cJSON_IsArray(prims))
        return -1;
    long total = 0;
    cJSON_ArrayForEach(p, prims)
    {
        const cJSON *mode = cJSON_GetObjectItemCaseSensitive(p, "mode");
        const int md = cJSON_IsNumber(mode) ? mode->valueint : 4;
        const cJSON *ix = cJSON_GetObjectItemCaseSensitive(p, "indices");
        const long n = ix ? accessor_count(gltf, ix)
                          : accessor_count(gltf, cJSON_GetObjectItemCaseSensitive(
                                                     cJSON_GetObjectItemCaseSensitive(p, "attributes"), "POSITION"));
        if (md < 4 || md > 6) /* points and lines */
            continue;
        if (n < 0)
            return -1;
        total += md == 4 ? n / 3 : n >= 2 ? n - 2 : 0;
    }
    return total;
}

/* The triangles node n and its descendants place, or -1. */
static long node_triangles(const cJSON *gltf, int n, int depth)
{
    const cJSON *node = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "nodes"), n), *c;
    if (!node || depth > 64)
        return -1;
    const cJSON *mesh = cJSON_GetObjectItemCaseSensitive(node, "mesh");
    long total = cJSON_IsNumber(mesh) ? mesh_triangles(gltf, mesh->valueint) : 0;
    cJSON_ArrayForEach(c, cJSON_GetObjectItemCaseSensitive(node, "children"))
    {
        const long k = cJSON_IsNumber(c) && total >= 0 ? node_triangles(gltf, c->valueint, depth + 1) : -1;
        total = k < 0 ? -1 : total + k;
    }
    return total;
}

long import_gltf_declared_triangles(const cJSON *gltf)
{
    const cJSON *which = cJSON_GetObjectItemCaseSensitive(gltf, "scene"), *n;
    const cJSON *scene = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(gltf, "scenes"),
                                            cJSON_IsNumber(which) ? which->valueint : 0);
    const cJSON *roots = cJSON_GetObjectItemCaseSensitive(scene, "nodes");
    if (!cJSON_IsArray(roots))
        return -1;
    long total = 0;
    cJSON_ArrayForEach(n, roots)
    {
        const long k = cJSON_IsNumber(n) && total >= 0 ? node_triangles(gltf, n->valueint, 0) : -1;
        total = k < 0 ? -1 : total + k;
    }
    return total;
}
