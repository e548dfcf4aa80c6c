/* import_notes.c: gathering what an import dropped or replaced (import_notes.h). assimp reports
 * through a process-wide logger whose messages read "Warn,  T0: text" or "Error, T0: text"; a log
 * stream attached for the length of one aiImportFile hands them to the notes of the import running
 * on this thread. */
#include "scene/import_notes.h"

#include <assimp/cimport.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* assimp messages that lose nothing of what we load, matched as substrings: vertices no face uses
 * (valid glTF files have them; the faces that dropped them have their own message), and 2D UVs
 * declared 3D. */
static const char *const benign[] = {"There are unreferenced vertices", "UVs are declared to be 3D", NULL};

static _Thread_local struct import_notes *listening;

/* Whether text, items separated by "; ", holds item whole (not as the start of a longer one). */
static int has_item(const char *text, const char *item)
{
    const size_t len = strlen(item);
    for (const char *at = strstr(text, item); at; at = strstr(at + 1, item))
        if ((at == text || (at >= text + 2 && at[-2] == ';' && at[-1] == ' ')) && (at[len] == '\0' || at[len] == ';'))
            return 1;
    return 0;
}

void import_notes_add(struct import_notes *n, int lossy, const char *fmt, ...)
{
    char item[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(item, sizeof item, fmt, ap);
    va_end(ap);
    if (has_item(n->text, item)) /* said already (assimp repeats a message per mesh) */
        return;
    const size_t used = strlen(n->text), room = sizeof(n->text) - used;
    const int w = snprintf(n->text + used, room, "%s%s", used ? "; " : "", item);
    if (w < 0 || (size_t)w >= room) /* full: end with an ellipsis */
        memcpy(n->text + sizeof(n->text) - 4, "...", 4);
    n->count++;
    n->lossy += lossy != 0;
}

static void on_log(const char *message, char *user)
{
    (void)user;
    if (!listening || (strncmp(message, "Warn", 4) != 0 && strncmp(message, "Error", 5) != 0))
        return;
    for (int k = 0; benign[k]; k++)
        if (strstr(message, benign[k]))
            return;
    const char *text = strstr(message, ": "); /* after "Warn,  T0" */
    text = text ? text + 2 : message;
    size_t len = strcspn(text, "\r\n");
    while (len > 0 && (text[len - 1] == '.' || text[len - 1] == ' ')) /* the item ends where the note does */
        len--;
    import_notes_add(listening, 1, "assimp: %.*s", (int)(len < 400 ? len : 400), text);
}

static struct aiLogStream stream = {on_log, NULL};

void import_notes_listen(struct import_notes *n)
{
    listening = n;
    aiAttachLogStream(&stream);
}

void import_notes_stop(void)
{
    aiDetachLogStream(&stream);
    listening = NULL;
}
