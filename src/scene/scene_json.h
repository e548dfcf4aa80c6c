/* scene_json.h: the readers of our JSON scene format (docs/SCENES.md; the writer is
 * src/io/scene_export.c) and of camera files. Must never depend on the loader entry (scene_file.h). */
#ifndef RESTIR_SCENE_SCENE_JSON_H
#define RESTIR_SCENE_SCENE_JSON_H

#include <stddef.h>

#include "scene/scene.h"

/* Reads a JSON scene as d says (scene.h; NULL: the defaults). Paths inside it are relative to the
 * file. Every error names the file and the key (e.g. "shapes[3].radius"). Returns 0, or -1 with
 * msg filled and s left empty. */
int scene_json_load(const char *path, const struct scene_load_desc *d, struct scene *s, char *msg);
/* The same from memory: text[0 .. len-1] followed by a NUL at text[len]; file names the text in
 * messages and dir is where relative mesh paths start ("" or NULL: the current folder). */
int scene_json_parse_with(const char *text, size_t len, const char *file, const char *dir,
                          const struct scene_load_desc *d, struct scene *s, char *msg);
/* scene_json_parse_with with the defaults. */
int scene_json_parse(const char *text, size_t len, const char *file, const char *dir, struct scene *s, char *msg);

/* A camera file (format in scene_file.h: scene_cameras_load) from memory: text[0 .. len-1]
 * followed by a NUL at text[len]; file names the text in messages. Returns 0 with *cams
 * (malloc'ed) and *n, or -1 with msg naming the file and the key, *cams NULL and *n 0. */
int scene_json_cameras_parse(const char *text, size_t len, const char *file, struct camera **cams, int *n,
                             char *msg);

#endif
