/* method_json.h: the method registry as JSON, for `restir list --json` and the scripts and tests that read
 * it instead of keeping their own lists of methods (scripts/registry.py, scripts/check_lists.py).
 * Must never depend on the passes or the ray tracer. */
#ifndef RESTIR_METHODS_METHOD_JSON_H
#define RESTIR_METHODS_METHOD_JSON_H

#include <cjson/cJSON.h>

/* Adds to the object root:
 *   "capabilities": the names of enum method_caps' bits, in bit order ("direct-only", ...);
 *   "common_settings": what every method reads (method_common_settings, split at spaces);
 *   "methods": one object per registered method, in `restir list` order: name, description, capabilities
 *   (names), settings (its struct method.settings split: keys, and families ending in '.'), variants,
 *   roles (split the same way; empty arrays for NULL) and viewer_order (0: not in the viewer).
 * root stays the caller's (cJSON_Delete frees what was added). Aborts on allocation failure, and when a
 * row has a capability bit without a name here (a programming error: name it in method_json.c). Threads
 * may each fill their own root. */
void method_registry_to_json(cJSON *root);

#endif
