/* cli_util.h: helpers for tests driving the `restir` binary ($RESTIR_BIN) via the shell: capture, temp folders, files.
 * Must never include renderer headers: these tests see the program from outside, as a user does. */
#ifndef RESTIR_TEST_CLI_UTIL_H
#define RESTIR_TEST_CLI_UTIL_H

#include <dirent.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define CLI_PATH_MAX 4096
#define CLI_ERR_MAX 32768 /* captured stdout or stderr, bytes */

/* The binary under test, or NULL (and a message) when RESTIR_BIN is unset. */
static inline const char *cli_bin(void)
{
    const char *b = getenv("RESTIR_BIN");
    if (!b || !*b) {
        printf("RESTIR_BIN is not set (run through ctest, or export RESTIR_BIN=path/to/restir)\n");
        return NULL;
    }
    return b;
}

/* Creates a fresh folder /tmp/restir-test-XXXXXX (under $TMPDIR when set) into dir. */
static inline int cli_make_temp_dir(char *dir)
{
    const char *t = getenv("TMPDIR");
    snprintf(dir, CLI_PATH_MAX, "%s/restir-test-XXXXXX", t && *t ? t : "/tmp");
    return mkdtemp(dir) ? 0 : -1;
}

/* Runs `$RESTIR_BIN args` with stdout and stderr captured into out and err (NUL terminated,
 * truncated to CLI_ERR_MAX; out may be NULL to discard stdout). args is pasted into a shell command
 * line: callers quote paths. Returns the exit code; a crash reads as 128 + signal (the shell's
 * convention), and a failure to run the shell as -1. */
static inline int cli_run_capture(const char *tmp_dir, const char *args, char *out, char *err)
{
    const char *bin = cli_bin();
    char out_path[CLI_PATH_MAX + 16], err_path[CLI_PATH_MAX + 16], cmd[3 * CLI_PATH_MAX];
    char *bufs[2] = {out, err};
    const char *paths[2] = {out_path, err_path};
    err[0] = '\0';
    if (out)
        out[0] = '\0';
    if (!bin)
        return -1;
    if (snprintf(out_path, sizeof(out_path), "%s/stdout.txt", tmp_dir) >= (int)sizeof(out_path) ||
        snprintf(err_path, sizeof(err_path), "%s/stderr.txt", tmp_dir) >= (int)sizeof(err_path) ||
        snprintf(cmd, sizeof(cmd), "'%s' %s >'%s' 2>'%s'", bin, args, out ? out_path : "/dev/null", err_path) >=
            (int)sizeof(cmd))
        return -1;
    int st = system(cmd);
    for (int k = 0; k < 2; k++) {
        if (!bufs[k])
            continue;
        FILE *f = fopen(paths[k], "rb");
        if (f) {
            size_t n = fread(bufs[k], 1, CLI_ERR_MAX - 1, f);
            bufs[k][n] = '\0';
            fclose(f);
        }
        remove(paths[k]);
    }
    if (st == -1 || !WIFEXITED(st))
        return -1;
    return WEXITSTATUS(st);
}

static inline int cli_run(const char *tmp_dir, const char *args, char *err)
{
    return cli_run_capture(tmp_dir, args, NULL, err);
}

/* Number of entries of dir whose name contains `part` ("" counts every entry); -1 when dir does
 * not exist or is not a folder. */
/* Runs the shell command fmt with a and b put in (two %s); returns its exit code, -1 when it did not exit. */
static inline int cli_sh(const char *fmt, const char *a, const char *b)
{
    char cmd[6 * CLI_PATH_MAX];
    snprintf(cmd, sizeof cmd, fmt, a, b);
    const int st = system(cmd);
    return st == -1 || !WIFEXITED(st) ? -1 : WEXITSTATUS(st);
}

/* 1 when path exists. */
static inline int cli_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

static inline int cli_count_entries(const char *dir, const char *part)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (strstr(e->d_name, part))
            n++;
    }
    closedir(d);
    return n;
}

/* Removes path: a file, or a folder with everything below it. Returns 0 when nothing is left. */
static inline int cli_remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return 0;
    if (S_ISDIR(st.st_mode)) {
        DIR *d = opendir(path);
        if (d) {
            struct dirent *e;
            char child[CLI_PATH_MAX];
            while ((e = readdir(d)) != NULL) {
                if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                    continue;
                if (snprintf(child, sizeof(child), "%s/%s", path, e->d_name) < (int)sizeof(child))
                    cli_remove_tree(child);
            }
            closedir(d);
        }
        return rmdir(path);
    }
    return remove(path);
}

/* 1 when both files exist and have the same bytes, 0 when they differ, -1 when one cannot be
 * read. *size gets the first file's size. */
static inline int cli_files_equal(const char *a, const char *b, long *size)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    *size = 0;
    if (!fa || !fb) {
        if (fa)
            fclose(fa);
        if (fb)
            fclose(fb);
        return -1;
    }
    int same = 1;
    for (;;) {
        int ca = fgetc(fa), cb = fgetc(fb);
        if (ca != cb) {
            same = 0;
            break;
        }
        if (ca == EOF)
            break;
        (*size)++;
    }
    fclose(fa);
    fclose(fb);
    return same;
}

/* Starts `$RESTIR_BIN args` in the background (the shell execs it, so signals reach restir
 * itself), stdout to /dev/null and stderr to err_path. Returns its pid, or -1. */
static inline pid_t cli_spawn(const char *args, const char *err_path)
{
    const char *bin = cli_bin();
    char cmd[3 * CLI_PATH_MAX];
    if (!bin || snprintf(cmd, sizeof cmd, "exec '%s' %s >/dev/null 2>'%s'", bin, args, err_path) >= (int)sizeof cmd)
        return -1;
    pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    return pid;
}

/* Waits until path exists (polling every 10 ms), at most timeout_ms. Returns 1 when it does. */
static inline int cli_wait_for_file(const char *path, int timeout_ms)
{
    struct stat st;
    for (int waited = 0; waited < timeout_ms; waited += 10) {
        if (stat(path, &st) == 0)
            return 1;
        nanosleep(&(struct timespec){0, 10000000L}, NULL);
    }
    return stat(path, &st) == 0;
}

/* Runs `$RESTIR_BIN args` (stderr into err, n bytes, through err_path) and, once `started` exists,
 * makes a folder (folder 1) or an empty file at `blocker`, so that a write the run makes later fails
 * there (a non-empty --out is refused before anything runs: a blocker made beforehand would stop
 * the run at the door). Returns the exit status, or -1 when the run never started or was killed. */
static inline int cli_run_blocked(const char *args, const char *err_path, const char *started, const char *blocker,
                                  int folder, char *err, size_t n)
{
    const pid_t pid = cli_spawn(args, err_path);
    int status = 0;
    if (pid < 0)
        return -1;
    int ok = cli_wait_for_file(started, 60000);
    if (ok && folder)
        ok = mkdir(blocker, 0777) == 0;
    else if (ok) {
        FILE *f = fopen(blocker, "w");
        ok = f && fclose(f) == 0;
    }
    if (!ok)
        kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FILE *f = fopen(err_path, "rb");
    const size_t len = f ? fread(err, 1, n - 1, f) : 0;
    if (f)
        fclose(f);
    err[len] = '\0';
    return ok && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* Signals pid with sig and waits for it; returns the raw wait status. */
static inline int cli_signal_and_wait(pid_t pid, int sig)
{
    int status = 0;
    kill(pid, sig);
    waitpid(pid, &status, 0);
    return status;
}

/* Reads the CSV file path into out (n bytes) without its columns first..last (0-based, first >= 1;
 * fields hold no quoted commas): how tests compare tables whose timing columns are measurements. */
static inline void cli_csv_without_columns(const char *path, int first, int last, char *out, size_t n)
{
    static char text[1 << 16];
    FILE *f = fopen(path, "rb");
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[len] = '\0';
    size_t o = 0;
    int col = 0;
    for (const char *c = text; *c && o + 2 < n; c++) {
        col = *c == '\n' ? 0 : col + (*c == ',');
        if (col < first || col > last) /* a column's leading comma goes with it */
            out[o++] = *c;
    }
    out[o] = '\0';
}

/* Drops columns first .. last of every line of the CSV text in place (as cli_csv_without_columns). */
static inline void cli_csv_drop_columns(char *text, int first, int last)
{
    size_t o = 0;
    int col = 0;
    for (const char *c = text; *c; c++) {
        col = *c == '\n' ? 0 : col + (*c == ',');
        if (col < first || col > last)
            text[o++] = *c;
    }
    text[o] = '\0';
}

/* Reads path into buf (NUL terminated, truncated to n - 1 bytes); empty when it cannot be read. */
static inline void cli_read_text(const char *path, char *buf, size_t n)
{
    buf[0] = '\0';
    FILE *f = fopen(path, "rb");
    if (!f)
        return;
    size_t k = fread(buf, 1, n - 1, f);
    buf[k] = '\0';
    fclose(f);
}

/* Writes text to path (replacing it). Returns 0, or -1 when it cannot be written. */
static inline int cli_write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int ok = fputs(text, f) >= 0;
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* Index of column name in a comma-separated header line (up to the first newline), or -1. */
static inline int cli_csv_column(const char *header, const char *name)
{
    size_t len = strlen(name);
    int col = 0;
    const char *p = header;
    for (;;) {
        const char *e = p;
        while (*e && *e != ',' && *e != '\n' && *e != '\r')
            e++;
        if ((size_t)(e - p) == len && strncmp(p, name, len) == 0)
            return col;
        if (*e != ',')
            return -1;
        p = e + 1;
        col++;
    }
}

/* Field col of the line starting at line, as a double (NAN when absent or not a number). */
static inline double cli_csv_number(const char *line, int col)
{
    const char *p = line;
    for (int k = 0; k < col; k++) {
        while (*p && *p != ',' && *p != '\n')
            p++;
        if (*p != ',')
            return NAN;
        p++;
    }
    char *end;
    double v = strtod(p, &end);
    if (end == p || (*end && *end != ',' && *end != '\n' && *end != '\r'))
        return NAN;
    return v;
}

/* Start of the line after p, or NULL at the end of the text. */
static inline const char *cli_next_line(const char *p)
{
    const char *e = strchr(p, '\n');
    return e && e[1] ? e + 1 : NULL;
}

#endif
