/* atomic_file.c: temporary sibling names, the rename that commits a finished output file, and
 * output folders (atomic_file.h). Must never depend on image formats, scenes or render code. */
#include "io/atomic_file.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/io_msg.h"

void io_temp_path(const char *path, char *tmp, unsigned long tmp_len)
{
    if (!tmp || tmp_len == 0)
        return;
    snprintf(tmp, (size_t)tmp_len, "%s.tmp-%ld", path ? path : "", (long)getpid());
}

FILE *io_open_temp(const char *path, char *tmp, unsigned long tmp_len, const char *mode, char *msg)
{
    io_temp_path(path, tmp, tmp_len);
    FILE *f = fopen(tmp, mode);
    if (!f)
        io_msg(msg, "%s: cannot create temporary file %.200s: %s", path, tmp, strerror(errno));
    return f;
}

int io_commit(const char *tmp, const char *path, char *msg)
{
    if (rename(tmp, path) != 0) {
        int err = errno;
        io_msg(msg, "%s: cannot move temporary file %s into place: %s", path, tmp, strerror(err));
        remove(tmp);
        return -1;
    }
    return 0;
}

int io_close_commit(FILE *f, const char *tmp, const char *path, char *msg)
{
    int err = ferror(f) ? (errno ? errno : EIO) : 0;
    if (fclose(f) != 0 && !err)
        err = errno ? errno : EIO;
    if (err) {
        io_msg(msg, "%s: writing failed: %s", path, strerror(err));
        remove(tmp);
        return -1;
    }
    return io_commit(tmp, path, msg);
}

int io_write_file(const char *path, const void *data, size_t len, char *msg)
{
    char tmp[4200];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "wb", msg);
    if (!f)
        return -1;
    if (len > 0 && fwrite(data, 1, len, f) != len) {
        int err = errno ? errno : EIO;
        fclose(f);
        remove(tmp);
        io_msg(msg, "%s: writing failed: %s", path, strerror(err));
        return -1;
    }
    return io_close_commit(f, tmp, path, msg);
}

int io_remove_stale_temporaries(const char *path)
{
    char dir[4096];
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) : 1, slash ? path : ".");
    if (slash == path)
        snprintf(dir, sizeof dir, "/");
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    const size_t n = strlen(base);
    int removed = 0;
    for (struct dirent *e = readdir(d); e; e = readdir(d)) {
        const char *name = e->d_name;
        if (strncmp(name, base, n) != 0 || strncmp(name + n, ".tmp-", 5) != 0)
            continue;
        char *end = NULL;
        long pid = strtol(name + n + 5, &end, 10);
        if (end == name + n + 5 || *end != '\0' || pid <= 0 || pid == (long)getpid())
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue; /* its writer may still be running */
        char full[8400];
        snprintf(full, sizeof full, "%s/%s", dir, name);
        removed += remove(full) == 0;
    }
    closedir(d);
    return removed;
}

int io_make_dirs(const char *dir, char *msg)
{
    char path[4096];
    if (snprintf(path, sizeof(path), "%s", dir) >= (int)sizeof(path)) {
        io_msg(msg, "output folder name is too long");
        return -1;
    }
    for (char *p = path + 1;; p++) {
        char c = *p;
        if (c == '/' || c == '\0') {
            *p = '\0';
            if (mkdir(path, 0777) != 0 && errno != EEXIST) {
                io_msg(msg, "cannot create folder '%.300s': %s", path, strerror(errno));
                return -1;
            }
            *p = c;
        }
        if (c == '\0')
            break;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        io_msg(msg, "'%.300s' is not a folder", dir);
        return -1;
    }
    return 0;
}
