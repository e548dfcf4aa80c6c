/* settings_file.h: a run's settings as JSON: what summary.json records, and `--params FILE`, which
 * reads a summary.json (or a plain object of --set keys) back. Must never run a render. */
#ifndef RESTIR_EXPERIMENTS_SETTINGS_FILE_H
#define RESTIR_EXPERIMENTS_SETTINGS_FILE_H

#include <cjson/cJSON.h>

#include "render/params.h"

/* Every setting of p (render_params_key order) as --set spells it: numbers as JSON numbers in the
 * spelling --set parses back exactly, names and on/off as strings. */
cJSON *settings_json(const struct render_params *p);

/* Reads FILE as a JSON object (a summary.json or a plain object of --set keys). Returns it, or NULL
 * with msg naming the file. */
cJSON *settings_read_file(const char *path, char *msg);
/* Applies every member of settings as `--set key=value` (strings as they are, numbers in full
 * precision, bools as on/off). Returns 0, or -1 with msg naming path and the key. */
int settings_apply_object(const char *path, const cJSON *settings, struct render_params *p, char *msg);

#endif
