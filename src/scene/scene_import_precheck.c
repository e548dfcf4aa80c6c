/* scene_import_precheck.c: PLY and OFF headers checked against the file's size before assimp reads
 * them. Must never depend on assimp or the scene: it runs before either sees the file. */
#include "scene/scene_import_precheck.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

/* assimp 5.2 trusts the element counts of PLY and OFF headers and allocates (and zero-fills) that
 * many vertices and faces before reading any: the 309-byte invalid/OutOfMemory.off of
 * assimp-testmodels, whose vertex count wraps to 1.3e9, costs 16 GB and half a minute, and a
 * 200-byte PLY claiming 1e9 vertices 12 GB. Every element takes at least one byte of the file, so
 * a count above the file's size is refused before assimp sees the file. */

#define PRECHECK_HEAD 65536 /* how much of the file's start the headers are looked for in */

/* Next whitespace-separated token of [*p, end), '#' comments skipped (OFF allows them). */
static int next_token(const char **p, const char *end, const char **tok, size_t *len)
{
    const char *q = *p;
    for (;;) {
        while (q < end && (*q == ' ' || *q == '\t' || *q == '\r' || *q == '\n'))
            q++;
        if (q < end && *q == '#') {
            while (q < end && *q != '\n')
                q++;
            continue;
        }
        break;
    }
    if (q >= end)
        return 0;
    *tok = q;
    while (q < end && *q != ' ' && *q != '\t' && *q != '\r' && *q != '\n')
        q++;
    *len = (size_t)(q - *tok);
    *p = q;
    return 1;
}

/* A decimal token as a count, saturating: these headers overflow 32 bits on purpose. */
static int token_count(const char *tok, size_t len, unsigned long long *out)
{
    unsigned long long v = 0;
    if (len == 0)
        return 0;
    for (size_t i = 0; i < len; i++) {
        if (tok[i] < '0' || tok[i] > '9')
            return 0;
        v = v > ULLONG_MAX / 10 - 1 ? ULLONG_MAX / 10 : v * 10 + (unsigned long long)(tok[i] - '0');
    }
    *out = v;
    return 1;
}

/* What a PLY header declares ("element <name> <count>" lines up to end_header; read line by line
 * so that comment lines never count): the largest count (0 when none), and the first element
 * name declared twice, copied into repeated (empty when none). */
struct ply_header_scan {
    unsigned long long most;
    char repeated[32];
};

#define PLY_MAX_ELEMENTS 64 /* names remembered; a header with more is not looked at further */

static void ply_scan_header(const char *p, const char *end, struct ply_header_scan *out)
{
    const char *names[PLY_MAX_ELEMENTS];
    size_t lens[PLY_MAX_ELEMENTS];
    int n_names = 0;
    memset(out, 0, sizeof *out);
    while (p < end) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        const char *line_end = eol ? eol : end, *q = p, *tok, *name;
        size_t len, name_len;
        if (next_token(&q, line_end, &tok, &len)) {
            unsigned long long n;
            if (len == 10 && memcmp(tok, "end_header", 10) == 0)
                break;
            if (len == 7 && memcmp(tok, "element", 7) == 0 && next_token(&q, line_end, &name, &name_len)) {
                for (int k = 0; k < n_names && !out->repeated[0]; k++)
                    if (lens[k] == name_len && memcmp(names[k], name, name_len) == 0)
                        snprintf(out->repeated, sizeof out->repeated, "%.*s", (int)(name_len < 31 ? name_len : 31),
                                 name);
                if (n_names < PLY_MAX_ELEMENTS) {
                    names[n_names] = name;
                    lens[n_names++] = name_len;
                }
                if (next_token(&q, line_end, &tok, &len) && token_count(tok, len, &n) && n > out->most)
                    out->most = n;
            }
        }
        p = eol ? eol + 1 : end;
    }
}

/* The larger of an OFF header's vertex and face counts ([ST][C][N][4][n]OFF [dim] nv nf ne), 0
 * when the header is not of that form. */
static unsigned long long off_max_count(const char *p, const char *end)
{
    const char *tok;
    size_t len;
    if (!next_token(&p, end, &tok, &len) || len < 3 || memcmp(tok + len - 3, "OFF", 3) != 0)
        return 0;
    unsigned long long nv, nf, dim;
    const int has_dim = len >= 4 && tok[len - 4] == 'n'; /* nOFF: the dimension comes first */
    if (has_dim && !(next_token(&p, end, &tok, &len) && token_count(tok, len, &dim)))
        return 0;
    if (!(next_token(&p, end, &tok, &len) && token_count(tok, len, &nv)))
        return 0;
    if (!(next_token(&p, end, &tok, &len) && token_count(tok, len, &nf)))
        return nv;
    return nv > nf ? nv : nf;
}

int import_precheck_counts(const char *path, char *msg)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0)
        size = ftell(f);
    char *head = NULL;
    size_t n = 0;
    if (size > 0 && fseek(f, 0, SEEK_SET) == 0) {
        head = xmalloc(PRECHECK_HEAD);
        n = fread(head, 1, PRECHECK_HEAD, f);
    }
    fclose(f);
    unsigned long long most = 0;
    const char *kind = NULL;
    struct ply_header_scan ply = {0, ""};
    if (n >= 4 && memcmp(head, "ply", 3) == 0 && (head[3] == '\n' || head[3] == '\r')) {
        ply_scan_header(head + 3, head + n, &ply);
        most = ply.most;
        kind = "PLY";
    } else if (n > 0) {
        most = off_max_count(head, head + n);
        kind = "OFF";
    }
    free(head);
    if (ply.repeated[0]) {
        /* assimp 5.2 sizes the mesh by the first declaration and then writes the elements of every
         * one into it, past its end (PlyLoader.cpp LoadVertex; a heap overflow that need not crash,
         * found by fuzz/fuzz_mesh_import.c with an ASan build of assimp; fixed upstream in 2024). */
        snprintf(msg, RESTIR_MSG_LEN,
                 "%s: the PLY header declares element '%s' twice (a broken or repeated header), which the mesh "
                 "importer cannot read safely",
                 path, ply.repeated);
        return -1;
    }
    if (most > (unsigned long long)size) {
        snprintf(msg, RESTIR_MSG_LEN, "%s: the %s header claims %llu elements, more than the file's %ld bytes can hold",
                 path, kind, most, size);
        return -1;
    }
    return 0;
}
