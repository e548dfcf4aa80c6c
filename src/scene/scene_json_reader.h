/* scene_json_reader.h: typed getters for our JSON files (scenes, camera files) whose every error
 * names the file and the key. Must never depend on what the values mean (the builder, formats). */
#ifndef RESTIR_SCENE_SCENE_JSON_READER_H
#define RESTIR_SCENE_SCENE_JSON_READER_H

#include <cjson/cJSON.h>
#include <stddef.h>

#include "core/vec3.h"
#include "scene/scene.h"

struct scene_builder;

/* One read of one file. The getters use only file and msg; the rest is the scene reader's
 * (scene_json.c), kept here so that one pointer carries everything through its recursion. */
struct json_reader {
    const char *file;
    char dir[4096]; /* directory of file, for relative mesh paths ("" = current) */
    char *msg;
    struct scene_builder *b;
    cJSON *materials; /* the "materials" array (names resolve through it) */
    struct environment *env; /* the "environment", read (attached after the build), or NULL */
};

/* Material id's "animation" (scene_json_animation.c; m is its JSON object, mkey its key), read,
 * checked and given to the builder (scene_animate_material); nothing without one. Returns 0, or -1
 * with the message naming the key. */
int json_animate_material(struct json_reader *r, const cJSON *m, const char *mkey, int id);

/* vsnprintf into out: a message too long for the buffer is cut, never left unterminated. */
void json_msgf(char *out, size_t len, const char *fmt, ...);
/* Fills r->msg with "file: key: what" ("file: what" without a key) and returns -1. */
int json_fail(struct json_reader *r, const char *key, const char *fmt, ...);
/* key of a child: "parent.name" or "parent[i]" */
void json_child_key(char *out, size_t len, const char *parent, const char *name, int index);
/* An object whose keys must all be among allowed (NULL-terminated). */
int json_check_keys(struct json_reader *r, const cJSON *obj, const char *key, const char *const *allowed);

/* Member name of obj (key names obj): absent and optional gives fallback and 0; absent and
 * required, of the wrong type or out of [lo, hi] gives -1 with the message. */
int json_get_number(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int required,
                    double lo, double hi, float fallback, float *out);
int json_get_int(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int lo, int hi,
                 int fallback, int *out);
/* Absent: 0 (false). */
int json_get_bool(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int *out);
int json_get_vec3(struct json_reader *r, const cJSON *obj, const char *key, const char *name, int required,
                  double lo, double hi, vec3 fallback, vec3 *out);
/* A 3-vector from an array value v (key names it). */
int json_vec3_value(struct json_reader *r, const cJSON *v, const char *key, double lo, double hi, vec3 *out);
/* The array member name of obj, or NULL when absent; *ok is 0 (with the message) when it is
 * required and absent, or not an array. */
const cJSON *json_get_array(struct json_reader *r, const cJSON *obj, const char *key, const char *name,
                            int required, int *ok);

/* Line of the position where cJSON stopped parsing. */
int json_line_of(const char *text, const char *at);

#endif
