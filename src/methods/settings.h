/* settings.h: the settings of every registered method, read through their blocks (render/settings_block.h):
 * the toolkit's blocks (render/params.h) and the blocks the method rows list (struct method.blocks). The
 * registry is built on first use: it places the methods' blocks in struct render_params' method storage
 * and refuses, naming both owners, a key two blocks declare, two methods of one name, storage the blocks
 * outgrow and two random streams of one id. `--set`, the defaults, validation, `--help` and summary.json
 * all go through these functions. Threads: the first call must come from one thread (every entry point
 * calls render_params_defaults before it starts others); later calls may run concurrently. */
#ifndef RESTIR_METHODS_SETTINGS_H
#define RESTIR_METHODS_SETTINGS_H

#include <stddef.h>
#include <stdio.h>

#include "render/params.h"

struct method;

/* Every setting at its default, and --res 640x360, --seed 1, all threads, a static camera. */
void render_params_defaults(struct render_params *p);
/* Applies one "key=value". Returns 0, or -1 with msg (RESTIR_MSG_LEN bytes) naming the key or the bad value. */
int render_params_set(struct render_params *p, const char *assignment, char *msg);
/* Applies "key=value:key=value..." in order (the settings part of a method spec such as
 * `restir-pt:spatial.reuse=spmis:spmis.candidates=8`). Returns 0, or -1 with msg. */
int render_params_set_list(struct render_params *p, const char *list, char *msg);
/* Checks ranges (resolution, counts, ...) and what each block checks across its keys. Returns 0, or -1 with
 * msg naming the problem. */
int render_params_validate(const struct render_params *p, char *msg);
/* The value of key in p as --set spells it ("l2", "on", "0.2", ...) into val (n bytes). Returns 0,
 * or -1 (val empty) for an unknown key. */
int render_params_get(const struct render_params *p, const char *key, char *val, size_t n);
/* Prints every key with its default, meaning, and the value that makes it BIASED, block by block, each
 * block after a line naming the methods that read it (from the registry). */
void render_params_help(FILE *out);
/* The i-th key that has a value of its own (every key --set takes but shorthands such as
 * spatial.preset), in registry order; NULL past the last. With render_params_get this lists every
 * setting of a run, as summary.json records it. */
const char *render_params_key(size_t i);
/* Writes "key=value, ..." of the settings in p whose value makes the estimator BIASED into out
 * (n bytes) and returns how many there are (0: every setting in p is unbiased). */
int render_params_biased(const struct render_params *p, char *out, size_t n);

/* The block that declares key (a full key, "spatial.radius"), or NULL for an unknown key. */
const struct param_block *settings_block_of(const char *key);
/* The registry's blocks, toolkit first, then the methods' in table order: settings_block_at(0 ..
 * settings_block_count() - 1). */
size_t settings_block_count(void);
const struct param_block *settings_block_at(size_t k);
/* 1 when method m reads block b: b is common or listed in m's row. */
int method_reads_block(const struct method *m, const struct param_block *b);

/* 1 when m reads setting `key`: the block that declares it is common or in m's blocks. */
int method_uses_setting(const struct method *m, const char *key);
/* Checks that m reads the key of every "key=value" or "key=value:key=value..." in assignments (n of
 * them). Returns 0, or -1 with msg naming the first key m does not read and the method. */
int method_check_assignments(const struct method *m, const char *const *assignments, int n, char *msg);

/* Writes the names of the methods that read setting key, ", "-separated, into out (n bytes): for help
 * texts that say who a setting is for without a list kept by hand. */
void settings_readers(const char *key, char *out, size_t n);

/* Checks that methods[0..n) and the toolkit's blocks can form a registry: method names distinct, every
 * key declared by one block only, the methods' blocks fit RENDER_PARAMS_METHOD_BYTES, the methods'
 * random streams of distinct ids (and none of them a toolkit pass id), their outputs well formed (3
 * channels, file-safe names, each once, an output function), their pass names well formed and, with
 * today's pass ids, at most PASS_MAX (methods/passes.h). Returns 0, or -1 with msg naming
 * both owners of what collides. Pure: for the registry's own build and for tests with rows of their own. */
int settings_registry_check(const struct method *const *methods, int n, char *msg);

#endif
