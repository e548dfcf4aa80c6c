/* settings_file.c: settings to and from JSON (settings_file.h), so that `restir render --params
 * DIR/summary.json` reproduces a run bit for bit. Must never run a render. */
#include "experiments/settings_file.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "io/text_file.h"
#include "methods/settings.h"

/* Largest summary or settings file read: far above any real one, small enough to refuse junk. */
#define SETTINGS_FILE_MAX (1u << 20)

cJSON *settings_json(const struct render_params *p)
{
    cJSON *j = cJSON_CreateObject();
    for (size_t i = 0; render_params_key(i); i++) {
        const char *key = render_params_key(i);
        char val[64], *end = NULL;
        render_params_get(p, key, val, sizeof(val));
        (void)strtod(val, &end);
        if (end != val && *end == '\0') /* a number: written in the spelling --set reads back exactly */
            cJSON_AddItemToObject(j, key, cJSON_CreateRaw(val));
        else
            cJSON_AddStringToObject(j, key, val);
    }
    return j;
}

/* One --set key from its JSON value: a string as it is, a number in full precision, a bool as
 * on/off. */
static int apply_setting(const char *path, const cJSON *item, struct render_params *p, char *msg)
{
    char assignment[256], why[RESTIR_MSG_LEN];
    if (cJSON_IsString(item))
        snprintf(assignment, sizeof(assignment), "%s=%s", item->string, item->valuestring);
    else if (cJSON_IsNumber(item))
        snprintf(assignment, sizeof(assignment), "%s=%.17g", item->string, item->valuedouble);
    else if (cJSON_IsBool(item))
        snprintf(assignment, sizeof(assignment), "%s=%s", item->string, cJSON_IsTrue(item) ? "on" : "off");
    else {
        snprintf(msg, RESTIR_MSG_LEN, "--params %.300s: \"%.100s\" must be a string, number or bool", path,
                 item->string);
        return -1;
    }
    if (render_params_set(p, assignment, why) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--params %.250s: %.250s", path, why);
        return -1;
    }
    return 0;
}

int settings_apply_object(const char *path, const cJSON *settings, struct render_params *p, char *msg)
{
    const cJSON *item;
    cJSON_ArrayForEach(item, settings)
        if (apply_setting(path, item, p, msg) != 0)
            return -1;
    return 0;
}

cJSON *settings_read_file(const char *path, char *msg)
{
    char why[RESTIR_MSG_LEN];
    char *text = io_read_text(path, SETTINGS_FILE_MAX, why);
    if (!text) {
        snprintf(msg, RESTIR_MSG_LEN, "--params %.500s", why);
        return NULL;
    }
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!cJSON_IsObject(root)) {
        snprintf(msg, RESTIR_MSG_LEN, "--params %.300s: not a JSON object (a summary.json or {\"key\": value})",
                 path);
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}
