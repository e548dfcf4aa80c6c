/* fuzz_file.h: for the harnesses whose reader takes a path, not bytes: the input written to a file
 * of the given name in a folder of this process's own (made on first use, under TMPDIR or /tmp).
 * Header-only: every harness is one translation unit with its own main (libFuzzer's). */
#ifndef RESTIR_FUZZ_FUZZ_FILE_H
#define RESTIR_FUZZ_FUZZ_FILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* libFuzzer's entry point, which every harness defines. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char fuzz_dir_path[256];

static void fuzz_dir_remove(void)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", fuzz_dir_path);
    if (system(cmd) != 0)
        fprintf(stderr, "fuzz: could not remove %s\n", fuzz_dir_path);
}

/* The folder, made once and removed at exit; aborts when it cannot be made (the harness could test
 * nothing). */
static const char *fuzz_dir(void)
{
    char *dir = fuzz_dir_path;
    if (!dir[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof fuzz_dir_path, "%s/restir-fuzz-%ld", tmp && *tmp ? tmp : "/tmp", (long)getpid());
        char cmd[300];
        snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
        if (system(cmd) != 0)
            abort();
        atexit(fuzz_dir_remove);
    }
    return dir;
}

/* Writes data to fuzz_dir()/name and returns the path (a static buffer); aborts on a write error. */
static const char *fuzz_write(const char *name, const uint8_t *data, size_t size)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", fuzz_dir(), name);
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0)
        abort();
    return path;
}

/* A refusal must say why, in a terminated message that names the file. */
static void fuzz_check_refusal(const char *msg, size_t cap, const char *name)
{
    if (!memchr(msg, '\0', cap) || !msg[0] || (name && !strstr(msg, name)))
        abort();
}

#endif
