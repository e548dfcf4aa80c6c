/* hash.h: FNV-1a 64, the project's content hash (scene fingerprints, plan ids, result checksums).
 * Not cryptographic: it detects change and corruption, not tampering. */
#ifndef RESTIR_CORE_HASH_H
#define RESTIR_CORE_HASH_H

#include <stddef.h>
#include <stdint.h>

#define FNV1A64_BASIS 0xcbf29ce484222325ull

static inline uint64_t fnv1a64(uint64_t h, const void *data, size_t n)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

#endif
