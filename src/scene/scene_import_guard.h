/* scene_import_guard.h: assimp run where its crash cannot take the process down. assimp asserts,
 * and can read out of bounds or loop, on some malformed files (docs/FUZZING.md lists what fuzzing
 * found); a renderer must refuse such a file, not die with the user's work. Internal to src/scene. */
#ifndef RESTIR_SCENE_SCENE_IMPORT_GUARD_H
#define RESTIR_SCENE_SCENE_IMPORT_GUARD_H

/* The longest assimp may take to read a file in the probe: IMPORT_GUARD_BASE_SECONDS plus
 * IMPORT_GUARD_SECONDS_PER_MB per MB of the file (assimp reads tens of MB a second; fuzzing found
 * 300-byte files it never finishes). */
#define IMPORT_GUARD_BASE_SECONDS 10
#define IMPORT_GUARD_SECONDS_PER_MB 2

/* Reads path with aiImportFile(path, flags) in a child process first. Returns 0 when the child
 * finished (whether assimp read the file or refused it: the caller's own import then says which),
 * or -1 with msg naming the file when assimp crashed (the signal) or ran past its time limit.
 * Without fork (not POSIX) it returns 0 at once. Call it from one thread at a time. */
int import_guard_probe(const char *path, unsigned flags, char *msg);

#endif
