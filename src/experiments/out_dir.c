/* out_dir.c: output folders of their own for every run, --force's careful emptying, and output
 * files that are never silently replaced (out_dir.h). Must never render. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "experiments/out_dir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "io/atomic_file.h"
#include "scene/scenes_builtin.h"

/* How many entries folder dir holds (-1: it cannot be read), and the first of them by name into first. */
static int count_entries(const char *dir, char *first, size_t len)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    first[0] = '\0';
    for (struct dirent *e = readdir(d); e; e = readdir(d)) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (n++ == 0 || strcmp(e->d_name, first) < 0)
            snprintf(first, len, "%s", e->d_name);
    }
    closedir(d);
    return n;
}

/* 1 when name is something restir writes into an output folder. */
static int restir_name(const char *name)
{
    static const char *const exact[] = {"summary.json", "metrics.csv", "compare.csv", "frames.csv", "study.csv",
                                        "plan.json",    "evaluation.md", "reference.exr", "camera.json", NULL};
    static const char *const prefix[] = {"frame_", "screenshot_", "last_frame.", NULL};
    for (int k = 0; exact[k]; k++)
        if (!strcmp(name, exact[k]))
            return 1;
    for (int k = 0; prefix[k]; k++)
        if (!strncmp(name, prefix[k], strlen(prefix[k])))
            return 1;
    const size_t n = strlen(name);
    if (n > 10 && !strcmp(name + n - 10, ".mesh.json"))
        return 1;
    for (int k = 0; scene_builtins[k].name; k++) { /* scene export NAME: NAME.json */
        const size_t s = strlen(scene_builtins[k].name);
        if (n == s + 5 && !strncmp(name, scene_builtins[k].name, s) && !strcmp(name + s, ".json"))
            return 1;
    }
    return 0;
}

/* 1 when folder dir holds a name restir writes, at its top or (depth 1) one folder down. */
static int holds_restir_output(const char *dir, int depth)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int found = 0;
    for (struct dirent *e = readdir(d); e && !found; e = readdir(d)) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        found = restir_name(e->d_name);
        char sub[PATH_MAX + 260];
        struct stat st;
        if (!found && depth > 0 && snprintf(sub, sizeof sub, "%s/%s", dir, e->d_name) < (int)sizeof sub &&
            lstat(sub, &st) == 0 && S_ISDIR(st.st_mode))
            found = holds_restir_output(sub, depth - 1);
    }
    closedir(d);
    return found;
}

/* 1 when folder abs (absolute, resolved) is path or a folder above it. */
static int is_or_holds(const char *abs, const char *path)
{
    char real[PATH_MAX];
    if (!path || !*path || !realpath(path, real))
        return 0;
    const size_t n = strlen(abs);
    return !strcmp(abs, real) || (!strncmp(real, abs, n) && real[n] == '/');
}

int out_dir_may_empty(const char *dir, char *msg)
{
    char abs[PATH_MAX], cwd[PATH_MAX];
    if (!realpath(dir, abs)) {
        snprintf(msg, RESTIR_MSG_LEN, "--force: cannot resolve %.300s: %s", dir, strerror(errno));
        return -1;
    }
    const char *why = NULL;
    if (!strcmp(abs, "/"))
        why = "it is the root folder";
    else if (is_or_holds(abs, getenv("HOME")))
        why = "it is the home folder or holds it";
    else if (getcwd(cwd, sizeof cwd) && is_or_holds(abs, cwd))
        why = "it is the current folder or holds it";
    else if (!holds_restir_output(abs, 1))
        why = "it holds no restir output (summary.json, metrics.csv, frame_NNNN.*, compare.csv, study.csv, "
              "plan.json, evaluation.md, an exported scene, ...)";
    if (!why)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN, "--force will not empty %.200s: %s; empty it yourself or give another folder", dir,
             why);
    return -1;
}

/* Removes every entry of the open folder fd (taken over and closed here), shown as `shown` in
 * messages, staying on file system dev. Returns 0, or -1 with msg. */
static int remove_children(int fd, const char *shown, dev_t dev, char *msg)
{
    DIR *d = fdopendir(fd);
    if (!d) {
        snprintf(msg, RESTIR_MSG_LEN, "--force: cannot read %.300s: %s", shown, strerror(errno));
        close(fd);
        return -1;
    }
    int rc = 0, left = 1;
    while (rc == 0 && left) { /* again from the start: removing entries while reading may skip some */
        left = 0;
        rewinddir(d);
        for (struct dirent *e = readdir(d); e && rc == 0; e = readdir(d)) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            left = 1;
            char path[PATH_MAX + 260];
            snprintf(path, sizeof path, "%s/%s", shown, e->d_name);
            struct stat st;
            if (fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0) {
                snprintf(msg, RESTIR_MSG_LEN, "--force: cannot remove %.300s: %s", path, strerror(errno));
                rc = -1;
            } else if (S_ISDIR(st.st_mode)) {
                if (st.st_dev != dev) {
                    snprintf(msg, RESTIR_MSG_LEN, "--force: %.300s is another file system's mount point; not removed",
                             path);
                    rc = -1;
                    break;
                }
                const int sub = openat(dirfd(d), e->d_name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
                if (sub < 0) {
                    snprintf(msg, RESTIR_MSG_LEN, "--force: cannot open %.300s: %s", path, strerror(errno));
                    rc = -1;
                } else if ((rc = remove_children(sub, path, dev, msg)) == 0 &&
                           unlinkat(dirfd(d), e->d_name, AT_REMOVEDIR) != 0) {
                    snprintf(msg, RESTIR_MSG_LEN, "--force: cannot remove %.300s: %s", path, strerror(errno));
                    rc = -1;
                }
            } else if (unlinkat(dirfd(d), e->d_name, 0) != 0) { /* a file, or a link (never followed) */
                snprintf(msg, RESTIR_MSG_LEN, "--force: cannot remove %.300s: %s", path, strerror(errno));
                rc = -1;
            }
        }
    }
    closedir(d);
    return rc;
}

int out_dir_empty(const char *dir, char *msg)
{
    const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--force: cannot open %.300s: %s", dir, strerror(errno));
        if (fd >= 0)
            close(fd);
        return -1;
    }
    return remove_children(fd, dir, st.st_dev, msg);
}

int out_dir_check(const char *option, const char *dir, int force, char *msg)
{
    struct stat st;
    if (stat(dir, &st) != 0)
        return 0; /* a new folder */
    if (!S_ISDIR(st.st_mode))
        return 0; /* not a folder: making it fails, and says so, when the run starts writing */
    char first[256];
    const int n = count_entries(dir, first, sizeof first);
    if (n < 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%s %.300s cannot be read: %s", option, dir, strerror(errno));
        return EXIT_USAGE;
    }
    if (n == 0)
        return 0;
    if (force)
        return out_dir_may_empty(dir, msg) == 0 ? 0 : EXIT_USAGE;
    char more[48] = "";
    if (n > 1)
        snprintf(more, sizeof more, " and %d more", n - 1);
    snprintf(msg, RESTIR_MSG_LEN,
             "%s %.250s is not empty (it holds %.100s%s, perhaps an earlier run's): pass --force to empty it first, "
             "or give a new folder",
             option, dir, first, more);
    return EXIT_USAGE;
}

int out_dir_prepare(const char *dir, int force, char *msg)
{
    struct stat st;
    if (force && stat(dir, &st) == 0 && S_ISDIR(st.st_mode)) {
        char first[256];
        if (count_entries(dir, first, sizeof first) > 0 &&
            (out_dir_may_empty(dir, msg) != 0 || out_dir_empty(dir, msg) != 0))
            return -1;
    }
    return io_make_dirs(dir, msg);
}

int out_dir_fresh(const char *base, char *dir, size_t len, char *msg)
{
    char parent[PATH_MAX];
    snprintf(parent, sizeof parent, "%s", base);
    char *slash = strrchr(parent, '/');
    if (slash && slash != parent) {
        *slash = '\0';
        if (io_make_dirs(parent, msg) != 0)
            return -1;
    }
    for (int k = 1; k < 100000; k++) {
        if ((k == 1 ? snprintf(dir, len, "%s", base) : snprintf(dir, len, "%s-%d", base, k)) >= (int)len) {
            snprintf(msg, RESTIR_MSG_LEN, "output folder name %.300s is too long", base);
            return -1;
        }
        if (mkdir(dir, 0777) == 0) {
            printf("writing into %s (a new folder; --out DIR chooses another)\n", dir);
            fflush(stdout);
            return 0;
        }
        if (errno != EEXIST) {
            snprintf(msg, RESTIR_MSG_LEN, "cannot create folder %.300s: %s", dir, strerror(errno));
            return -1;
        }
    }
    snprintf(msg, RESTIR_MSG_LEN, "%.300s-2 to -99999 are all taken; give --out DIR", base);
    return -1;
}

int out_dir_fresh_name(const char *base, char *dir, size_t len, char *msg)
{
    struct stat st;
    for (int k = 1; k < 100000; k++) {
        if ((k == 1 ? snprintf(dir, len, "%s", base) : snprintf(dir, len, "%s-%d", base, k)) >= (int)len) {
            snprintf(msg, RESTIR_MSG_LEN, "output folder name %.300s is too long", base);
            return -1;
        }
        if (lstat(dir, &st) != 0)
            return 0;
    }
    snprintf(msg, RESTIR_MSG_LEN, "%.300s-2 to -99999 are all taken; give --out DIR", base);
    return -1;
}

int out_dir_open(const char *out, const char *base, int force, char *dir, size_t len, char *msg)
{
    if (!out)
        return out_dir_fresh(base, dir, len, msg);
    if (snprintf(dir, len, "%s", out) >= (int)len) {
        snprintf(msg, RESTIR_MSG_LEN, "output folder name %.300s is too long", out);
        return -1;
    }
    return out_dir_prepare(dir, force, msg);
}

int out_file_check(const char *what, const char *path, int force, char *msg)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return 0;
    if (S_ISDIR(st.st_mode)) {
        snprintf(msg, RESTIR_MSG_LEN, "%s %.300s is a folder; give a file name (FILE.exr)", what, path);
        return EXIT_USAGE;
    }
    if (force)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN,
             "%s %.300s exists (an earlier run's): pass --force to replace it, or give another --out", what, path);
    return EXIT_USAGE;
}
