/* method_json.c: the registry as JSON (method_json.h). The capability names below are the one place
 * enum method_caps is spelled for readers outside C; a new bit gets its name here. */
#include "methods/method_json.h"

#include <string.h>

#include "core/check.h"
#include "methods/method.h"
#include "methods/settings.h"

static const struct {
    unsigned bit;
    const char *name;
} cap_names[] = {
    {METHOD_DIRECT_ONLY, "direct-only"},       {METHOD_GRADIENT, "gradient"},
    {METHOD_HISTORY, "history"},               {METHOD_CAMERA_EFFECTS, "camera-effects"},
    {METHOD_PATH_RESERVOIRS, "path-reservoirs"}, {METHOD_BUDGET_BY_SPP, "budget-by-spp"},
    {METHOD_SELECTION_STUDY, "selection-study"}, {METHOD_ANIMATED_EMITTERS, "animated-emitters"},
    {METHOD_TEMPORAL_GRADIENT, "temporal-gradient"},
};
enum { N_CAPS = sizeof cap_names / sizeof cap_names[0] };

/* Checked cJSON: every item is allocated, and cJSON returns NULL only when malloc does. */
static cJSON *checked(cJSON *item)
{
    RESTIR_CHECK(item != NULL);
    return item;
}

/* The words of a space-separated list (NULL: none) as an array of strings. */
static cJSON *words(const char *list)
{
    cJSON *a = checked(cJSON_CreateArray());
    for (const char *s = list; s && *s;) {
        s += strspn(s, " ");
        const size_t n = strcspn(s, " ");
        if (n > 0) {
            char word[256];
            RESTIR_CHECK(n < sizeof word);
            memcpy(word, s, n);
            word[n] = '\0';
            cJSON_AddItemToArray(a, checked(cJSON_CreateString(word)));
        }
        s += n;
    }
    return a;
}

/* The keys of the blocks that every method reads (common = 1), or that m reads beyond them (common = 0). */
static cJSON *setting_keys(const struct method *m, int common)
{
    cJSON *a = checked(cJSON_CreateArray());
    for (size_t b = 0; b < settings_block_count(); b++) {
        const struct param_block *block = settings_block_at(b);
        if (block->common != common || (!common && !method_reads_block(m, block)))
            continue;
        for (size_t i = 0; i < block->count; i++)
            cJSON_AddItemToArray(a, checked(cJSON_CreateString(block->rows[i].key)));
    }
    return a;
}

/* The NULL-terminated strings of list (NULL: none) as an array. */
static cJSON *strings(const char *const *list)
{
    cJSON *a = checked(cJSON_CreateArray());
    for (const char *const *x = list; x && *x; x++)
        cJSON_AddItemToArray(a, checked(cJSON_CreateString(*x)));
    return a;
}

/* The names of the blocks m lists in its row. */
static cJSON *block_names(const struct method *m)
{
    cJSON *a = checked(cJSON_CreateArray());
    for (const struct param_block *const *b = m->blocks; b && *b; b++)
        cJSON_AddItemToArray(a, checked(cJSON_CreateString((*b)->name)));
    return a;
}

static cJSON *method_json(const struct method *m)
{
    cJSON *o = checked(cJSON_CreateObject());
    checked(cJSON_AddStringToObject(o, "name", m->name));
    checked(cJSON_AddStringToObject(o, "description", m->description));
    cJSON *caps = checked(cJSON_AddArrayToObject(o, "capabilities"));
    unsigned named = 0;
    for (int i = 0; i < N_CAPS; i++) {
        named |= cap_names[i].bit;
        if (m->caps & cap_names[i].bit)
            cJSON_AddItemToArray(caps, checked(cJSON_CreateString(cap_names[i].name)));
    }
    RESTIR_CHECK((m->caps & ~named) == 0); /* a bit of enum method_caps without a name in cap_names */
    cJSON_AddItemToObject(o, "blocks", block_names(m));
    cJSON_AddItemToObject(o, "settings", setting_keys(m, 0));
    cJSON_AddItemToObject(o, "variants", words(m->variants));
    cJSON_AddItemToObject(o, "roles", words(m->roles));
    cJSON_AddItemToObject(o, "streams", strings(m->streams));
    cJSON_AddItemToObject(o, "passes", strings(m->passes));
    checked(cJSON_AddNumberToObject(o, "viewer_order", m->viewer_order));
    return o;
}

void method_registry_to_json(cJSON *root)
{
    cJSON *caps = checked(cJSON_AddArrayToObject(root, "capabilities"));
    for (int i = 0; i < N_CAPS; i++)
        cJSON_AddItemToArray(caps, checked(cJSON_CreateString(cap_names[i].name)));
    cJSON_AddItemToObject(root, "common_settings", setting_keys(NULL, 1));
    cJSON *methods = checked(cJSON_AddArrayToObject(root, "methods"));
    for (int k = 0; k < method_count(); k++)
        cJSON_AddItemToArray(methods, method_json(method_at(k)));
}
