/* file_name.h: file-name helpers every scene reader shares (stem, suffix, whole-file read).
 * Must never depend on the scene or on any file format: the readers depend on it, not back. */
#ifndef RESTIR_SCENE_FILE_NAME_H
#define RESTIR_SCENE_FILE_NAME_H

#include <stddef.h>

/* The file name without folders and extension ("scenes/Box.gltf" -> "Box"), cut to len. */
void scene_file_stem(const char *path, char *out, size_t len);
/* 1 when path ends with suffix (lower-case ".json"), ignoring the case of path. */
int scene_path_has_suffix(const char *path, const char *suffix);
/* The whole file at path (at most 1 GiB), malloc'ed with a NUL after its *len bytes, or NULL with
 * msg naming the file and the problem. */
char *scene_read_whole_file(const char *path, long *len, char *msg);

#endif
