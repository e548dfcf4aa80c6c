/* scene_import_precheck.h: PLY and OFF headers checked against the file's size before assimp reads
 * them. Must never depend on assimp or the scene: it runs before either sees the file. */
#ifndef RESTIR_SCENE_SCENE_IMPORT_PRECHECK_H
#define RESTIR_SCENE_SCENE_IMPORT_PRECHECK_H

/* 0, or -1 with msg when a PLY or OFF header claims more elements than the file has bytes, or a
 * PLY header declares one element twice (assimp 5.2 writes past its buffer on those). Files that
 * cannot be opened are left to assimp, which says why. */
int import_precheck_counts(const char *path, char *msg);

#endif
