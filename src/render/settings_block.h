/* settings_block.h: a block of settings, the unit in which a layer or a method declares what `--set`
 * may change. A block is a struct of values and a table of rows, one per key: key, type, offset in
 * the block's struct, default, range or names, the value that makes the estimator BIASED, and help.
 * The toolkit's blocks (image, scene, path walk, lights, reuse, SPMIS cells, shift) live at fixed
 * places in struct render_params; a method's own block (ReSTIR DI's candidates, the gradient
 * methods' pair search, ...) is declared in the method's folder and lives in the parameters' method
 * storage, where the registry (methods/settings.h) places it when it is built. Which settings a
 * method reads is the union of the blocks its row lists and the blocks every method reads.
 * Must never depend on the ray tracer or render passes. */
#ifndef RESTIR_RENDER_SETTINGS_BLOCK_H
#define RESTIR_RENDER_SETTINGS_BLOCK_H

#include <stddef.h>

/* P_NAMES: an enum stored as int, spelled by the row's names; P_COUNT: an int where "M" means 0
 * (all M pixels of a reuse cell); P_PRESET: a shorthand that sets other keys of its block through
 * the block's preset function and has no value of its own. */
enum param_type { P_INT, P_COUNT, P_FLOAT, P_BOOL, P_MIS, P_SHIFT, P_NAMES, P_PRESET };

/* One row per setting: everything about it is said here, once. */
struct param_def {
    const char *key;
    enum param_type type;
    size_t offset;       /* of the value in the block's struct */
    double lo, hi;       /* accepted range for numbers */
    const char *def;     /* the default, as --set spells it (NULL: a shorthand that sets other keys) */
    const char *biased;  /* the value that makes the estimator BIASED, as --set spells it (NULL: none) */
    const char *help;
    const char *const *names; /* P_NAMES and P_PRESET: the spellings of values 0, 1, ..., NULL-terminated */
};

struct render_params;

struct param_block {
    const char *name;  /* for messages and `restir list`: "di", "reuse", "recon", ... */
    const struct param_def *rows;
    size_t count;
    /* Where the block's struct lives, in bytes from the start of struct render_params. A toolkit
     * block says it (offsetof); a method block (size > 0) gets it when the registry is built, and
     * 0 means not placed yet. */
    size_t base;
    size_t size, align; /* a method block's struct: bytes and alignment in the method storage; 0 for a toolkit block */
    int common;         /* 1: every method reads it (the scene, ray tracing, the camera, the denoiser) */
    /* Checks what depends on several values of the block, or on the shared settings (p), beyond each row's range
     * (NULL: nothing). Returns 0, or -1 with msg (RESTIR_MSG_LEN bytes) naming the keys. */
    int (*validate)(const struct render_params *p, const void *block, char *msg);
    /* Its P_PRESET row (NULL: none): sets the block's other values for names[k]. */
    void (*preset)(void *block, int k);
};

/* The initializer of a method's own block: its name, its rows (an array), the struct its values live in
 * and its validate function (or NULL); the registry places it.
 *   struct param_block ris_gi_block = PARAM_METHOD_BLOCK("ris-gi", ris_gi_rows, struct ris_gi_settings, NULL); */
#define PARAM_METHOD_BLOCK(name, rows, type, validate)                                                               \
    {(name), (rows), sizeof(rows) / sizeof((rows)[0]), 0, sizeof(type), _Alignof(type), 0, (validate), NULL}

/* Aborts, naming b: a method block read before the registry placed it (it places every registered
 * method's blocks before the first parameters exist). */
_Noreturn void param_block_unplaced(const struct param_block *b);

/* The block's struct in p: a constant offset, so passes may read it per pixel. */
static inline const void *param_block_in(const struct render_params *p, const struct param_block *b)
{
    if (b->size > 0 && b->base == 0)
        param_block_unplaced(b);
    return (const char *)p + b->base;
}
static inline void *param_block_in_mut(struct render_params *p, const struct param_block *b)
{
    if (b->size > 0 && b->base == 0)
        param_block_unplaced(b);
    return (char *)p + b->base;
}

/* Parses val for row d of block b into the block's struct at block. Returns 0, or -1 with msg naming the key
 * and what was wrong (the value is then unchanged). */
int param_parse(const struct param_block *b, const struct param_def *d, const char *val, void *block, char *msg);
/* The value of row d in the block's struct as --set spells it ("l2", "on", "0.2", "M", ...) into val (n bytes). */
void param_format(const struct param_def *d, const void *block, char *val, size_t n);
/* Checks the value of row d against its range or names (for values set other than through --set).
 * Returns 0, or -1 with msg. */
int param_check(const struct param_def *d, const void *block, char *msg);

#endif
