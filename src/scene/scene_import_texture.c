/* scene_import_texture.c: resolving and decoding the textures an assimp material names: embedded
 * ones (glTF binary buffers, data URIs: compressed images or raw BGRA texels) and files beside the
 * model. Must never build geometry. */
#include "scene_import_texture.h"

#include <assimp/texture.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/check.h"

void import_texture_cache_fini(struct import_texture_cache *c)
{
    free(c->entries);
    memset(c, 0, sizeof(*c));
}

/* The embedded texture a reference names: "*N", or (assimp 5.1+) the file name of one. */
static const struct aiTexture *embedded(const struct aiScene *ai, const char *ref)
{
    if (!ai->mTextures || ai->mNumTextures == 0)
        return NULL;
    if (ref[0] == '*') {
        char *end = NULL;
        long i = strtol(ref + 1, &end, 10);
        return end != ref + 1 && *end == '\0' && i >= 0 && (unsigned long)i < ai->mNumTextures ? ai->mTextures[i]
                                                                                               : NULL;
    }
    const char *base = strrchr(ref, '/');
    base = base ? base + 1 : ref;
    for (unsigned i = 0; i < ai->mNumTextures; i++) {
        const struct aiTexture *t = ai->mTextures[i];
        if (t && t->mFilename.length > 0 && t->mFilename.length < MAXLEN) {
            const char *tb = strrchr(t->mFilename.data, '/');
            tb = tb ? tb + 1 : t->mFilename.data;
            if (strcmp(tb, base) == 0)
                return t;
        }
    }
    return NULL;
}

static int decode(const struct aiScene *ai, const char *model_path, const char *ref, int srgb, struct texture *t,
                  char *msg)
{
    char label[320]; /* long names are cut: the message must fit RESTIR_MSG_LEN */
    snprintf(label, sizeof label, "%.150s (of %.150s)", ref, model_path);
    const struct aiTexture *e = embedded(ai, ref);
    if (e && e->pcData) {
        if (e->mHeight == 0) /* compressed: mWidth bytes of PNG, JPEG, ... */
            return texture_load_memory((const unsigned char *)e->pcData, (int)e->mWidth, srgb, label, t, msg);
        if (e->mWidth > 32768 || e->mHeight > 32768) {
            snprintf(msg, RESTIR_MSG_LEN, "texture %s: %ux%u is out of range", label, e->mWidth, e->mHeight);
            return -1;
        }
        texture_from_bgra8((const unsigned char *)e->pcData, (int)e->mWidth, (int)e->mHeight, srgb, t);
        return 0;
    }
    if (ref[0] == '*') {
        snprintf(msg, RESTIR_MSG_LEN, "texture %s: the file has no such embedded texture", label);
        return -1;
    }
    char path[2200];
    const char *slash = strrchr(model_path, '/');
    if (ref[0] == '/' || !slash)
        snprintf(path, sizeof path, "%s", ref);
    else
        snprintf(path, sizeof path, "%.*s/%s", (int)(slash - model_path), model_path, ref);
    return texture_load_file(path, srgb, t, msg);
}

int import_texture_map(struct scene_builder *b, const struct aiScene *ai, const struct aiMaterial *m,
                       const char *model_path, const enum aiTextureType *types, int ntypes, int srgb,
                       struct import_texture_cache *cache, char *msg)
{
    struct aiString ref;
    int found = 0;
    for (int k = 0; k < ntypes && !found; k++)
        found = aiGetMaterialTextureCount(m, types[k]) > 0 &&
                aiGetMaterialTexture(m, types[k], 0, &ref, NULL, NULL, NULL, NULL, NULL, NULL) == aiReturn_SUCCESS &&
                ref.length > 0 && ref.length < MAXLEN;
    if (!found)
        return 0;
    const char *key = ref.data;
    for (int i = 0; i < cache->count; i++)
        if (cache->entries[i].srgb == srgb && strcmp(cache->entries[i].key, key) == 0)
            return cache->entries[i].map;
    struct texture t;
    if (decode(ai, model_path, key, srgb, &t, msg) != 0)
        return -1;
    if (cache->count == cache->cap) {
        cache->cap = cache->cap ? 2 * cache->cap : 8;
        struct import_texture_entry *grown = realloc(cache->entries, sizeof(*grown) * (size_t)cache->cap);
        RESTIR_CHECK(grown != NULL);
        cache->entries = grown;
    }
    struct import_texture_entry *e = &cache->entries[cache->count++];
    snprintf(e->key, sizeof e->key, "%s", key);
    e->srgb = srgb;
    e->map = scene_add_texture(b, t);
    return e->map;
}
