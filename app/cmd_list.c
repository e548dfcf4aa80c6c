/* cmd_list.c: `restir list`: the built-in scenes and the registered methods, as lines for people or
 * (--json) as one JSON document for scripts and tests (scripts/registry.py reads it), so that no script
 * keeps a list of methods of its own. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "methods/method.h"
#include "methods/method_json.h"
#include "scene/scenes_builtin.h"

static void list_usage(FILE *out)
{
    fprintf(out,
            "usage: restir list [--json]\n"
            "Prints the built-in scenes and the registered methods, one per line:\n"
            "scene NAME<tab>description, then method NAME<tab>description.\n"
            "--json prints one JSON object instead, for scripts (scripts/registry.py reads it):\n"
            "  scenes: [{name, description}], in the order above;\n"
            "  capabilities: the names a method's capabilities are spelled with;\n"
            "  common_settings: the setting keys (and families ending in '.') every method reads;\n"
            "  methods: [{name, description, capabilities, settings (the keys and families it reads beyond\n"
            "    the common ones), variants (settings that exercise its own code paths, each key=value or\n"
            "    key=value:key=value; scripts/render_hashes.sh and scripts/tsan.sh render each), roles\n"
            "    (reference: the method every reference integrates; demo: the one scripts/demo.sh shows),\n"
            "    viewer_order (its place in the viewer's M cycle; 0: not there)}], in the order above.\n");
}

static int list_json(void)
{
    cJSON *root = cJSON_CreateObject();
    RESTIR_CHECK(root != NULL);
    cJSON *scenes = cJSON_AddArrayToObject(root, "scenes");
    RESTIR_CHECK(scenes != NULL);
    for (int i = 0; scene_builtins[i].name; i++) {
        cJSON *o = cJSON_CreateObject();
        RESTIR_CHECK(o != NULL);
        RESTIR_CHECK(cJSON_AddStringToObject(o, "name", scene_builtins[i].name) != NULL);
        RESTIR_CHECK(cJSON_AddStringToObject(o, "description", scene_builtins[i].description) != NULL);
        cJSON_AddItemToArray(scenes, o);
    }
    method_registry_to_json(root);
    char *text = cJSON_Print(root);
    RESTIR_CHECK(text != NULL);
    puts(text);
    cJSON_free(text);
    cJSON_Delete(root);
    return 0;
}

int cmd_list(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "--help") || !strcmp(argv[0], "-h"))) {
        list_usage(stdout);
        return 0;
    }
    if (argc == 1 && !strcmp(argv[0], "--json"))
        return list_json();
    if (argc > 0) {
        cli_error("list takes no arguments but --json, got '%s'", argv[0]);
        return EXIT_USAGE;
    }
    for (int i = 0; scene_builtins[i].name; i++)
        printf("scene %s\t%s\n", scene_builtins[i].name, scene_builtins[i].description);
    for (int k = 0; k < method_count(); k++)
        printf("method %s\t%s\n", method_at(k)->name, method_at(k)->description);
    return 0;
}
