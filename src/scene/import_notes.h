/* import_notes.h: what an import dropped or replaced (faces assimp could not read, materials it
 * made up, our own skipped triangles), gathered into one line per file, so that a file that loads
 * only in part says so (scene_import.c; scene_load_partial in scene.h decides what to do with it).
 * Internal to src/scene. */
#ifndef RESTIR_SCENE_IMPORT_NOTES_H
#define RESTIR_SCENE_IMPORT_NOTES_H

#define IMPORT_NOTES_LEN 1024

struct import_notes {
    char text[IMPORT_NOTES_LEN]; /* the items, "; "-separated, truncated with "..." when too long */
    int count;                   /* items added (repeats of a text are added once) */
    int lossy;                   /* of which lost or replaced something of the file's */
};

/* Appends one item (printf format); lossy 0 for what loses nothing (triangles of zero area). */
void import_notes_add(struct import_notes *n, int lossy, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Until import_notes_stop, the warnings and errors assimp logs on this thread become items
 * ("assimp: ..."), but for those that lose nothing (import_notes.c lists them). Not reentrant: one
 * import at a time per thread. */
void import_notes_listen(struct import_notes *n);
void import_notes_stop(void);

#endif
