/* view_script.h: timed input for `restir view --script FILE`, so a viewer session can be replayed
 * exactly (tests under Xvfb). One event per line, at a frame number, applied before that frame
 * renders; '#' starts a comment:
 *   FRAME press KEY        one press of KEY (a letter, or escape)
 *   FRAME hold KEY N       KEY held for N frames (movement keys)
 *   FRAME drag DX DY       the mouse dragged by DX, DY pixels (turns the camera)
 *   FRAME quit             ends the session after the frames before it
 *   FRAME screenshot FILE  the window as it shows then (the frame before FRAME, at the window's size)
 *                          as an 8-bit PNG: FILE under the viewer's --out DIR unless absolute; FRAME >= 1
 * Frames must not decrease from line to line. Must never depend on SDL. */
#ifndef RESTIR_VIEW_VIEW_SCRIPT_H
#define RESTIR_VIEW_VIEW_SCRIPT_H

enum view_event_kind { VIEW_PRESS, VIEW_HOLD, VIEW_DRAG, VIEW_QUIT, VIEW_SHOT };

struct view_event {
    int frame;
    enum view_event_kind kind;
    char key;   /* lower-case letter, or 27 for escape */
    int frames; /* hold: how many frames */
    int dx, dy; /* drag */
    char *file; /* screenshot: the PNG's path as written in the script (malloc'ed; view_script_fini frees it) */
};

struct view_script {
    int count;
    struct view_event *events;
};

/* Reads the script at path. Returns 0, or -1 with msg naming the file and line. */
int view_script_load(const char *path, struct view_script *s, char *msg);
void view_script_fini(struct view_script *s);

#endif
