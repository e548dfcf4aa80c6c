/* scene_hash.h: scene_content_hash, which tells a resumed reference whether its scene is the one
 * its checkpoint was rendered from. Must never hash what rendering does not read. */
#ifndef RESTIR_SCENE_SCENE_HASH_H
#define RESTIR_SCENE_SCENE_HASH_H

#include <stdint.h>

#include "scene/scene_types.h"

/* A 64-bit FNV-1a hash of everything rendering reads: vertices, triangles, their materials,
 * objects and uvs, the materials and the textures' texels. Equal scenes hash equally on every
 * machine and run; a changed vertex, material or texel changes it (up to hash collisions). */
uint64_t scene_content_hash(const struct scene *s);

#endif
