/* scene_file.c: the one entry point every command takes a scene (or a camera file) through.
 * Must never be included by the format readers it dispatches to (scene_json, scene_import). */
#include "scene/scene_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "scene/file_name.h"
#include "scene/scene_import.h"
#include "scene/scene_json.h"
#include "scene/scenes_builtin.h"

int scene_load(const char *name_or_path, struct scene *s, char *msg)
{
    return scene_load_with(name_or_path, NULL, s, msg);
}

int scene_load_with(const char *name_or_path, const struct scene_load_desc *d, struct scene *s, char *msg)
{
    memset(s, 0, sizeof(*s));
    if (scene_is_builtin(name_or_path))
        return scene_create_builtin_with(name_or_path, d, s, msg);
    FILE *f = fopen(name_or_path, "rb");
    if (!f) {
        if (!strchr(name_or_path, '/') && !strchr(name_or_path, '.'))
            return scene_create_builtin_with(name_or_path, d, s, msg); /* names the built-in scenes */
        snprintf(msg, RESTIR_MSG_LEN, "scene '%s': no built-in scene of that name and cannot open it as a file: %s",
                 name_or_path, strerror(errno));
        return -1;
    }
    fclose(f);
    if (scene_path_has_suffix(name_or_path, ".json"))
        return scene_json_load(name_or_path, d, s, msg);
    return scene_import_file_with(name_or_path, d, s, msg);
}

int scene_cameras_load(const char *path, struct camera **cams, int *n, char *msg)
{
    *cams = NULL;
    *n = 0;
    long len = 0;
    char *text = scene_read_whole_file(path, &len, msg);
    if (!text)
        return -1;
    int rc = scene_json_cameras_parse(text, (size_t)len, path, cams, n, msg);
    free(text);
    return rc;
}
