/* settings.c: the registry of settings blocks, and --set, the defaults, validation, help and the
 * BIASED list over it (settings.h). Must never depend on the passes or the ray tracer. */
#include "methods/settings.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

#include "core/check.h"
#include "methods/method.h"
#include "methods/passes.h"
#include "render/tiles.h"

/* At most this many blocks (toolkit and methods together) and method rows. */
#define MAX_BLOCKS 64
#define MAX_METHOD_ROWS 64

static const struct param_block *blocks[MAX_BLOCKS];
static size_t num_blocks;
static once_flag built = ONCE_FLAG_INIT;

/* Appends b to list (n entries, at most cap) unless it is there. Returns 0, or -1 when full. */
static int add_block(const struct param_block **list, size_t *n, size_t cap, const struct param_block *b)
{
    for (size_t k = 0; k < *n; k++)
        if (list[k] == b)
            return 0;
    if (*n >= cap)
        return -1;
    list[(*n)++] = b;
    return 0;
}

/* Every block of the toolkit and of methods[0..n) into list (cap entries), toolkit first. Returns the
 * count, or -1 with msg when there are more than cap. */
static long gather_blocks(const struct method *const *methods, int n, const struct param_block **list, size_t cap,
                          char *msg)
{
    size_t count = 0;
    for (size_t k = 0; k < render_params_toolkit_block_count; k++)
        if (add_block(list, &count, cap, render_params_toolkit_blocks[k]) != 0)
            goto full;
    for (int m = 0; m < n; m++)
        for (const struct param_block *const *b = methods[m]->blocks; b && *b; b++)
            if (add_block(list, &count, cap, *b) != 0)
                goto full;
    return (long)count;
full:
    snprintf(msg, RESTIR_MSG_LEN, "the registered methods declare more than %zu settings blocks", cap);
    return -1;
}

/* The method of methods[0..n) that lists block b first ("the toolkit" for a toolkit block). */
static const char *owner_of(const struct method *const *methods, int n, const struct param_block *b)
{
    for (int m = 0; m < n; m++)
        for (const struct param_block *const *x = methods[m]->blocks; x && *x; x++)
            if (*x == b && b->size > 0)
                return methods[m]->name;
    return "the toolkit";
}

/* A method's declared outputs (method.h): an output function with them, 3 channels (what the writers
 * take), names that are file-name suffixes and EXR layers ([A-Za-z0-9_], not "denoised", which the
 * denoised frame's files use), each once. Returns 0, or -1 with msg naming the method and output. */
static int check_outputs(const struct method *m, char *msg)
{
    const int n = method_output_count(m);
    if (n > 0 && !m->output) {
        snprintf(msg, RESTIR_MSG_LEN, "%s declares outputs but no output function", m->name);
        return -1;
    }
    for (int k = 0; k < n; k++) {
        const char *name = m->outputs[k].name;
        const size_t len = strlen(name);
        if (len == 0 || strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_") != len ||
            !strcmp(name, "denoised")) {
            snprintf(msg, RESTIR_MSG_LEN, "output '%s' of %s: a name is letters, digits and '_', not 'denoised'",
                     name, m->name);
            return -1;
        }
        if (m->outputs[k].channels != 3) {
            snprintf(msg, RESTIR_MSG_LEN, "output '%s' of %s has %d channels; the frame writers take 3 (RGB)", name,
                     m->name, m->outputs[k].channels);
            return -1;
        }
        for (int j = 0; j < k; j++)
            if (!strcmp(m->outputs[j].name, name)) {
                snprintf(msg, RESTIR_MSG_LEN, "%s declares output '%s' twice", m->name, name);
                return -1;
            }
    }
    return 0;
}

/* The methods' pass names (struct method.passes): [a-z0-9_], each once per method, not the renderer's
 * "denoise", and with today's ids at most PASS_MAX in all. Returns 0, or -1 with msg naming them. */
static int check_passes(const struct method *const *methods, int n, char *msg)
{
    int ids = PASS_COUNT; /* today's, then the names none of them is */
    for (int a = 0; a < n; a++)
        for (const char *const *p = methods[a]->passes; p && *p; p++) {
            const size_t len = strlen(*p);
            if (len == 0 || strspn(*p, "abcdefghijklmnopqrstuvwxyz0123456789_") != len || !strcmp(*p, "denoise")) {
                snprintf(msg, RESTIR_MSG_LEN, "pass '%s' of %s: a pass name is [a-z0-9_], and not the renderer's "
                         "'denoise'", *p, methods[a]->name);
                return -1;
            }
            for (const char *const *q = methods[a]->passes; q != p; q++)
                if (!strcmp(*q, *p)) {
                    snprintf(msg, RESTIR_MSG_LEN, "%s lists pass '%s' twice", methods[a]->name, *p);
                    return -1;
                }
            int seen = 0;
            for (int k = 0; k < PASS_COUNT && !seen; k++)
                seen = !strcmp(pass_toolkit_names[k], *p);
            for (int b = 0; b < a && !seen; b++)
                for (const char *const *q = methods[b]->passes; q && *q && !seen; q++)
                    seen = !strcmp(*q, *p);
            if (!seen && ++ids > PASS_MAX) {
                snprintf(msg, RESTIR_MSG_LEN, "pass '%s' of %s is one more than PASS_MAX (%d) in methods/passes.h",
                         *p, methods[a]->name, PASS_MAX);
                return -1;
            }
        }
    return 0;
}

int settings_registry_check(const struct method *const *methods, int n, char *msg)
{
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++)
            if (!strcmp(methods[a]->name, methods[b]->name)) {
                snprintf(msg, RESTIR_MSG_LEN, "two registered methods are called '%s' (rows %d and %d of the table)",
                         methods[a]->name, a, b);
                return -1;
            }
    const struct param_block *list[MAX_BLOCKS];
    long count = gather_blocks(methods, n, list, MAX_BLOCKS, msg);
    if (count < 0)
        return -1;
    size_t bytes = 0;
    for (long a = 0; a < count; a++) {
        for (size_t i = 0; i < list[a]->count; i++)
            for (long b = a; b < count; b++)
                for (size_t j = b == a ? i + 1 : 0; j < list[b]->count; j++)
                    if (!strcmp(list[a]->rows[i].key, list[b]->rows[j].key)) {
                        snprintf(msg, RESTIR_MSG_LEN,
                                 "setting '%s' is declared twice: by block '%s' (%s) and by block '%s' (%s)",
                                 list[a]->rows[i].key, list[a]->name, owner_of(methods, n, list[a]), list[b]->name,
                                 owner_of(methods, n, list[b]));
                        return -1;
                    }
        if (list[a]->size > 0)
            bytes = (bytes + list[a]->align - 1) / list[a]->align * list[a]->align + list[a]->size;
    }
    if (bytes > RENDER_PARAMS_METHOD_BYTES) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "the methods' settings blocks need %zu bytes, more than RENDER_PARAMS_METHOD_BYTES (%d) in "
                 "render/params.h",
                 bytes, RENDER_PARAMS_METHOD_BYTES);
        return -1;
    }
    for (int a = 0; a < n; a++)
        if (check_outputs(methods[a], msg) != 0)
            return -1;
    if (check_passes(methods, n, msg) != 0)
        return -1;
    for (int a = 0; a < n; a++)
        for (const char *const *s = methods[a]->streams; s && *s; s++) {
            const uint64_t id = rng_stream_id(*s);
            if (id < RNG_PASS_COUNT) {
                snprintf(msg, RESTIR_MSG_LEN, "random stream '%s' of %s has the id of a toolkit pass (%llu)", *s,
                         methods[a]->name, (unsigned long long)id);
                return -1;
            }
            for (int b = a; b < n; b++)
                for (const char *const *t = b == a ? s + 1 : methods[b]->streams; t && *t; t++)
                    if (rng_stream_id(*t) == id) {
                        snprintf(msg, RESTIR_MSG_LEN,
                                 "random streams '%s' of %s and '%s' of %s have one id (%016llx): rename one", *s,
                                 methods[a]->name, *t, methods[b]->name, (unsigned long long)id);
                        return -1;
                    }
        }
    return 0;
}

/* Builds the registry once: checks it (a failure is a bug in a method's row: abort, naming it) and
 * places the methods' blocks in the method storage, in table order. */
static void build_registry(void)
{
    const struct method *methods[MAX_METHOD_ROWS];
    const int n = method_count() < MAX_METHOD_ROWS ? method_count() : MAX_METHOD_ROWS;
    for (int k = 0; k < n; k++)
        methods[k] = method_at(k);
    char msg[RESTIR_MSG_LEN];
    long count = -1;
    if (method_count() > MAX_METHOD_ROWS)
        snprintf(msg, sizeof msg, "more than %d registered methods", MAX_METHOD_ROWS);
    else if (settings_registry_check(methods, n, msg) == 0)
        count = gather_blocks(methods, n, blocks, MAX_BLOCKS, msg);
    if (count < 0) {
        fprintf(stderr, "restir: the method registry is inconsistent: %s\n", msg);
        abort();
    }
    num_blocks = (size_t)count;
    size_t at = 0;
    for (size_t k = 0; k < num_blocks; k++) {
        if (blocks[k]->size == 0)
            continue;
        at = (at + blocks[k]->align - 1) / blocks[k]->align * blocks[k]->align;
        /* the one write to a block: its place, before any parameters exist */
        ((struct param_block *)(uintptr_t)blocks[k])->base = offsetof(struct render_params, method_settings) + at;
        at += blocks[k]->size;
    }
}

static void registry(void) { call_once(&built, build_registry); }

size_t settings_block_count(void)
{
    registry();
    return num_blocks;
}

const struct param_block *settings_block_at(size_t k)
{
    registry();
    return k < num_blocks ? blocks[k] : NULL;
}

/* The row of key and its block (*block), or NULL. klen: the key's length in key. */
static const struct param_def *find_row(const char *key, size_t klen, const struct param_block **block)
{
    registry();
    for (size_t b = 0; b < num_blocks; b++)
        for (size_t i = 0; i < blocks[b]->count; i++)
            if (strlen(blocks[b]->rows[i].key) == klen && !strncmp(blocks[b]->rows[i].key, key, klen)) {
                *block = blocks[b];
                return &blocks[b]->rows[i];
            }
    return NULL;
}

const struct param_block *settings_block_of(const char *key)
{
    const struct param_block *b = NULL;
    return find_row(key, strlen(key), &b) ? b : NULL;
}

int method_reads_block(const struct method *m, const struct param_block *b)
{
    if (b->common)
        return 1;
    for (const struct param_block *const *x = m->blocks; x && *x; x++)
        if (*x == b)
            return 1;
    return 0;
}

static int reads_key(const struct method *m, const void *key) { return method_uses_setting(m, key); }

void settings_readers(const char *key, char *out, size_t n) { method_names_where(reads_key, key, out, n); }

void render_params_defaults(struct render_params *p)
{
    registry();
    memset(p, 0, sizeof(*p));
    /* What the command line sets by options of its own (--res, --seed, --threads, --camera). */
    p->width = 640;
    p->height = 360;
    p->seed = 1;
    p->threads = 0;
    p->camera_path = 0;
    char msg[RESTIR_MSG_LEN];
    for (size_t b = 0; b < num_blocks; b++)
        for (size_t i = 0; i < blocks[b]->count; i++)
            if (blocks[b]->rows[i].def)
                RESTIR_CHECK(param_parse(blocks[b], &blocks[b]->rows[i], blocks[b]->rows[i].def,
                                         param_block_in_mut(p, blocks[b]), msg) == 0);
}

int render_params_set(struct render_params *p, const char *assignment, char *msg)
{
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment) {
        snprintf(msg, RESTIR_MSG_LEN, "--set expects key=value, got '%s'", assignment);
        return -1;
    }
    size_t klen = (size_t)(eq - assignment);
    const struct param_block *b = NULL;
    const struct param_def *d = find_row(assignment, klen, &b);
    if (d)
        return param_parse(b, d, eq + 1, param_block_in_mut(p, b), msg);
    snprintf(msg, RESTIR_MSG_LEN, "--set: unknown key '%.*s' (see restir render --help)", (int)klen, assignment);
    return -1;
}

int render_params_set_list(struct render_params *p, const char *list, char *msg)
{
    char buf[1024];
    if (strlen(list) >= sizeof(buf)) {
        snprintf(msg, RESTIR_MSG_LEN, "settings '%.40s...' are longer than %zu characters", list, sizeof(buf) - 1);
        return -1;
    }
    snprintf(buf, sizeof(buf), "%s", list);
    char *save = NULL;
    for (char *tok = strtok_r(buf, ":", &save); tok; tok = strtok_r(NULL, ":", &save))
        if (render_params_set(p, tok, msg) != 0)
            return -1;
    return 0;
}

int render_params_validate(const struct render_params *p, char *msg)
{
    registry();
    if (p->width < 1 || p->height < 1 || p->width > 16384 || p->height > 16384 ||
        (long long)p->width * p->height > 64ll * 1024 * 1024) {
        snprintf(msg, RESTIR_MSG_LEN, "resolution %dx%d is out of range (1..16384 per side, 64 Mpixel total)",
                 p->width, p->height);
        return -1;
    }
    for (size_t b = 0; b < num_blocks; b++)
        if (blocks[b]->validate && blocks[b]->validate(p, param_block_in(p, blocks[b]), msg) != 0)
            return -1;
    /* Every key's range or names, also for values set other than through --set (options of their
     * own such as --spp, a study's radii, a method's defaults). */
    for (size_t b = 0; b < num_blocks; b++)
        for (size_t i = 0; i < blocks[b]->count; i++)
            if (param_check(&blocks[b]->rows[i], param_block_in(p, blocks[b]), msg) != 0)
                return -1;
    return 0;
}

int render_params_get(const struct render_params *p, const char *key, char *val, size_t n)
{
    const struct param_block *b = NULL;
    const struct param_def *d = find_row(key, strlen(key), &b);
    if (!d) {
        val[0] = '\0';
        return -1;
    }
    param_format(d, param_block_in(p, b), val, n);
    return 0;
}

void render_params_help(FILE *out)
{
    struct render_params d;
    render_params_defaults(&d);
    for (size_t b = 0; b < num_blocks; b++) {
        char readers[512] = "";
        if (blocks[b]->common)
            snprintf(readers, sizeof readers, "every method");
        for (int k = 0; !blocks[b]->common && k < method_count(); k++)
            if (method_reads_block(method_at(k), blocks[b]))
                snprintf(readers + strlen(readers), sizeof readers - strlen(readers), "%s%s", readers[0] ? ", " : "",
                         method_at(k)->name);
        fprintf(out, "  [%s] read by %s\n", blocks[b]->name, readers[0] ? readers : "no method");
        for (size_t i = 0; i < blocks[b]->count; i++) {
            const struct param_def *r = &blocks[b]->rows[i];
            char val[32];
            param_format(r, param_block_in(&d, blocks[b]), val, sizeof(val));
            fprintf(out, "  %-26s %-11s %s", r->key, val, r->help);
            if (r->biased)
                fprintf(out, " [%s=%s is BIASED]", r->key, r->biased);
            fputc('\n', out);
        }
    }
}

const char *render_params_key(size_t i)
{
    registry();
    /* shorthands (spatial.preset) set other keys and have no value of their own */
    for (size_t b = 0; b < num_blocks; b++)
        for (size_t k = 0; k < blocks[b]->count; k++)
            if (blocks[b]->rows[k].def && i-- == 0)
                return blocks[b]->rows[k].key;
    return NULL;
}

int render_params_biased(const struct render_params *p, char *out, size_t n)
{
    registry();
    int count = 0;
    if (n > 0)
        out[0] = '\0';
    for (size_t b = 0; b < num_blocks; b++)
        for (size_t i = 0; i < blocks[b]->count; i++) {
            const struct param_def *r = &blocks[b]->rows[i];
            if (!r->biased)
                continue;
            char val[32];
            param_format(r, param_block_in(p, blocks[b]), val, sizeof(val));
            if (strcmp(val, r->biased) != 0)
                continue;
            size_t used = strlen(out);
            snprintf(out + used, n - used, "%s%s=%s", count ? ", " : "", r->key, val);
            count++;
        }
    return count;
}

int method_uses_setting(const struct method *m, const char *key)
{
    const struct param_block *b = settings_block_of(key);
    return b && method_reads_block(m, b);
}

int method_check_assignments(const struct method *m, const char *const *assignments, int n, char *msg)
{
    for (int i = 0; i < n; i++) {
        for (const char *a = assignments[i]; a && *a;) {
            char key[96];
            size_t len = strcspn(a, "=:");
            snprintf(key, sizeof key, "%.*s", (int)(len < sizeof key - 1 ? len : sizeof key - 1), a);
            if (key[0] && settings_block_of(key) && !method_uses_setting(m, key)) { /* unknown keys: --set says so */
                snprintf(msg, RESTIR_MSG_LEN, "--set %s: %s does not read this setting (restir render --help lists "
                         "what each setting is for)", key, m->name);
                return -1;
            }
            a = strchr(a, ':');
            a = a ? a + 1 : NULL;
        }
    }
    return 0;
}
