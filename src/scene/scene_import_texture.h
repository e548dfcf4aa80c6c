/* scene_import_texture.h: the textures of an assimp material as texture maps of the builder.
 * Internal to scene_import*.c: must never be included outside them (it exposes assimp types). */
#ifndef RESTIR_SCENE_SCENE_IMPORT_TEXTURE_H
#define RESTIR_SCENE_SCENE_IMPORT_TEXTURE_H

#include <assimp/material.h>
#include <assimp/scene.h>

#include "scene/scene.h"

/* The map id (>= 1) of the first texture of m among types[0 .. ntypes-1], decoded as sRGB or
 * linear and added to the builder on first use (keyed by its resolved file, or the model's path and
 * the embedded reference, so instances of one model share its textures); 0 when m has none.
 * Embedded textures ("*N", or a name matching an embedded texture's) come from ai->mTextures;
 * others are files relative to the model file's folder. Returns -1 with msg naming the model and
 * the texture when it cannot be read. */
int import_texture_map(struct scene_builder *b, const struct aiScene *ai, const struct aiMaterial *m,
                       const char *model_path, const enum aiTextureType *types, int ntypes, int srgb, char *msg);

#endif
