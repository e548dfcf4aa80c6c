/* out_dir.h: where a run writes, so that one folder never mixes two runs' files. A command without
 * --out gets a new folder each run (its default name, then NAME-2, NAME-3, ...); a given --out DIR
 * must be missing or empty, or is emptied first with --force; an output file (reference --out
 * FILE.exr) must not exist yet, or is replaced with --force. Checks touch nothing, so a refused
 * command leaves everything as it was. Must never render. */
#ifndef RESTIR_EXPERIMENTS_OUT_DIR_H
#define RESTIR_EXPERIMENTS_OUT_DIR_H

#include <stddef.h>

/* 0 when folder dir may take a new run: it does not exist, is an empty folder, or force is set and
 * out_dir_may_empty allows emptying it. Else EXIT_USAGE with msg naming option, dir and what it
 * holds, and saying to pass --force or give another folder. Touches nothing. */
int out_dir_check(const char *option, const char *dir, int force, char *msg);

/* Makes dir ready for a run out_dir_check accepted: with force, empties it first (out_dir_empty),
 * then creates it and its missing parents. Returns 0, or -1 with msg. */
int out_dir_prepare(const char *dir, int force, char *msg);

/* A new folder for a run without --out: creates base, else base-2, base-3, ... (the first name not
 * taken; mkdir decides, so two runs at once never share one), its parents made, into dir (len
 * bytes) and says so on stdout. Returns 0, or -1 with msg. */
int out_dir_fresh(const char *base, char *dir, size_t len, char *msg);

/* The name out_dir_fresh would take now, without making it (for a command that makes its folder
 * only once it has something to write), into dir. Returns 0, or -1 with msg. */
int out_dir_fresh_name(const char *base, char *dir, size_t len, char *msg);

/* out (a given --out, out_dir_prepare) or, when out is NULL, a fresh folder from base
 * (out_dir_fresh), into dir. Returns 0, or -1 with msg. */
int out_dir_open(const char *out, const char *base, int force, char *dir, size_t len, char *msg);

/* 0 when --force may empty folder dir, else -1 with msg saying why not: never the root folder, the
 * home folder ($HOME), the current folder or a folder above any of them, and only a folder that
 * holds what restir writes (at its top or one level down: summary.json, metrics.csv, frame_NNNN.*,
 * compare.csv, frames.csv, study.csv, plan.json, evaluation.md, reference.exr, screenshot_NNNN.*,
 * last_frame.*, camera.json, an exported scene NAME.json or NAME.mesh.json). */
int out_dir_may_empty(const char *dir, char *msg);

/* Removes everything inside folder dir (dir itself stays). A symbolic link is removed, never followed,
 * and no folder on another file system (a mount point) is entered. Returns 0, or -1 with msg naming
 * what could not be removed (what was removed before stays removed). */
int out_dir_empty(const char *dir, char *msg);

/* An output file (reference --out FILE.exr, scene export's DIR/NAME.json): 0 when path does not
 * exist, or force and it is no folder (the run replaces it); else EXIT_USAGE with msg, which starts
 * with what (an option or a command), names path and says to pass --force. Touches nothing. */
int out_file_check(const char *what, const char *path, int force, char *msg);

#endif
