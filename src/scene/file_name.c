/* file_name.c: file-name helpers every scene reader shares (stem, suffix, whole-file read).
 * Must never depend on the scene or on any file format: the readers depend on it, not back. */
#include "scene/file_name.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

/* Largest scene file read into memory (the JSON itself; meshes it names are read by assimp). */
#define SCENE_JSON_MAX_BYTES (1L << 30)

char *scene_read_whole_file(const char *path, long *len, char *msg)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    char *buf = NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (*len = ftell(f)) >= 0 && *len <= SCENE_JSON_MAX_BYTES &&
        fseek(f, 0, SEEK_SET) == 0) {
        buf = xmalloc((size_t)*len + 1);
        if (fread(buf, 1, (size_t)*len, f) != (size_t)*len) {
            free(buf);
            buf = NULL;
        }
    }
    fclose(f);
    if (!buf)
        snprintf(msg, RESTIR_MSG_LEN, "%s: cannot read (not a regular file, or over %ld bytes)", path,
                 SCENE_JSON_MAX_BYTES);
    else
        buf[*len] = '\0';
    return buf;
}

void scene_file_stem(const char *path, char *out, size_t len)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, len, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out)
        *dot = '\0';
    if (!out[0] && len > 5)
        snprintf(out, len, "scene");
}

int scene_path_has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    if (n < k)
        return 0;
    for (size_t i = 0; i < k; i++) {
        char c = s[n - k + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != suffix[i])
            return 0;
    }
    return 1;
}
