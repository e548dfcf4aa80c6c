/* view_script.c: the --script reader of `restir view` (format in view_script.h). */
#include "view/view_script.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

/* KEY as the viewer's key code: a single letter, or "escape". */
static int parse_key(const char *word, char *key)
{
    if (!strcmp(word, "escape")) {
        *key = 27;
        return 0;
    }
    if (strlen(word) == 1 && isalpha((unsigned char)word[0])) {
        *key = (char)tolower((unsigned char)word[0]);
        return 0;
    }
    return -1;
}

static int parse_line(char *line, struct view_event *e)
{
    char verb[16], a[32];
    int frame, n = 0, x, y;
    if (sscanf(line, "%d %15s%n", &frame, verb, &n) != 2 || frame < 0 || frame > 10000000)
        return -1;
    const char *rest = line + n;
    memset(e, 0, sizeof(*e));
    e->frame = frame;
    if (!strcmp(verb, "quit")) {
        e->kind = VIEW_QUIT;
        return sscanf(rest, " %31s", a) == 1 ? -1 : 0;
    }
    if (!strcmp(verb, "press")) {
        e->kind = VIEW_PRESS;
        return sscanf(rest, " %31s", a) == 1 ? parse_key(a, &e->key) : -1;
    }
    if (!strcmp(verb, "hold")) {
        e->kind = VIEW_HOLD;
        return sscanf(rest, " %31s %d", a, &e->frames) == 2 && e->frames > 0 && e->frames <= 100000
                   ? parse_key(a, &e->key)
                   : -1;
    }
    if (!strcmp(verb, "screenshot")) { /* the rest of the line, trimmed: a path may hold spaces */
        e->kind = VIEW_SHOT;
        while (isspace((unsigned char)*rest))
            rest++;
        size_t len = strlen(rest);
        while (len > 0 && isspace((unsigned char)rest[len - 1]))
            len--;
        if (len == 0 || frame < 1) /* frame 0: the window has shown nothing yet */
            return -1;
        e->file = xmalloc(len + 1);
        memcpy(e->file, rest, len);
        e->file[len] = '\0';
        return 0;
    }
    if (!strcmp(verb, "drag")) {
        e->kind = VIEW_DRAG;
        if (sscanf(rest, " %d %d", &x, &y) != 2 || abs(x) > 100000 || abs(y) > 100000)
            return -1;
        e->dx = x;
        e->dy = y;
        return 0;
    }
    return -1;
}

int view_script_load(const char *path, struct view_script *s, char *msg)
{
    memset(s, 0, sizeof(*s));
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: cannot open the script", path);
        return -1;
    }
    char line[512];
    int cap = 0, lineno = 0, rc = 0;
    while (rc == 0 && fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char probe[2];
        if (sscanf(line, " %1s", probe) != 1)
            continue; /* blank */
        struct view_event e;
        if (parse_line(line, &e) != 0) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "%.300s:%d: expected 'FRAME press KEY', 'FRAME hold KEY N', 'FRAME drag DX DY', 'FRAME quit' "
                     "or 'FRAME screenshot FILE' (FRAME >= 1)",
                     path, lineno);
            rc = -1;
        } else if (s->count > 0 && e.frame < s->events[s->count - 1].frame) {
            snprintf(msg, RESTIR_MSG_LEN, "%.300s:%d: frame %d comes before the previous line's", path, lineno,
                     e.frame);
            free(e.file);
            rc = -1;
        } else {
            if (s->count == cap) {
                cap = cap ? 2 * cap : 16;
                struct view_event *grown = realloc(s->events, sizeof(*grown) * (size_t)cap);
                RESTIR_CHECK(grown != NULL);
                s->events = grown;
            }
            s->events[s->count++] = e;
        }
    }
    fclose(f);
    if (rc != 0)
        view_script_fini(s);
    return rc;
}

void view_script_fini(struct view_script *s)
{
    for (int k = 0; k < s->count; k++)
        free(s->events[k].file);
    free(s->events);
    memset(s, 0, sizeof(*s));
}
