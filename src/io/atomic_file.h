/* atomic_file.h: atomic output files (a temporary sibling, then a rename) and output folders.
 * Must never depend on image formats, report formats, scenes or render code. */
#ifndef RESTIR_IO_ATOMIC_FILE_H
#define RESTIR_IO_ATOMIC_FILE_H

#include <stdio.h>

/* Temporary sibling name for atomic writes: "<path>.tmp-<pid>". */
void io_temp_path(const char *path, char *tmp, unsigned long tmp_len);
/* Removes path's temporaries ("<path>.tmp-<pid>") whose writer process no longer exists, left by a
 * process that was killed mid-write. Returns how many were removed. */
int io_remove_stale_temporaries(const char *path);
/* Renames tmp over path; returns 0, or -1 with msg (and removes tmp). */
int io_commit(const char *tmp, const char *path, char *msg);
/* Finishes a file written through io_open_temp: closes f and renames tmp over path when every write
 * succeeded (no ferror, fclose succeeded), otherwise removes tmp. Returns 0, or -1 with msg
 * naming path and the reason. */
int io_close_commit(FILE *f, const char *tmp, const char *path, char *msg);
/* Writes len bytes of data to path through a temporary sibling (io_open_temp, io_close_commit).
 * Returns 0, or -1 with msg; path is never left half-written. */
int io_write_file(const char *path, const void *data, size_t len, char *msg);
/* Creates folder dir and its missing parents (mkdir -p). Returns 0, or -1 with msg naming the
 * folder that could not be made, or dir when it exists but is not a folder. */
int io_make_dirs(const char *dir, char *msg);
/* Creates path's temporary sibling (io_temp_path into tmp, tmp_len bytes) and opens it with fopen
 * mode. Returns the file, or NULL with msg naming path, the temporary and the reason. */
FILE *io_open_temp(const char *path, char *tmp, unsigned long tmp_len, const char *mode, char *msg);

#endif
