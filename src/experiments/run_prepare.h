/* run_prepare.h: the checks every command runs before its first frame (run_prepare.c), in one order:
 * the method, the scene, the settings against the method and the scene, the memory. render, compare,
 * study, reference and view call these instead of each keeping its own subset. Must never implement
 * a method: what a method reads and needs is asked of the registry (method_check_*). */
#ifndef RESTIR_EXPERIMENTS_RUN_PREPARE_H
#define RESTIR_EXPERIMENTS_RUN_PREPARE_H

#include "experiments/options.h"
#include "methods/renderer.h"
#include "scene/scene.h"

/* What run_prepare checks besides the method's settings against the scene (method_check_settings,
 * always). */
enum run_prepare_checks {
    RUN_CHECK_SETS = 1,   /* every --set key is one the method reads (method_check_assignments) */
    RUN_CHECK_MEMORY = 2, /* a renderer fits in --max-memory or what the system has (cli_check_memory) */
};

/* The method named `name` (a --method), or NULL having said on stderr "--method is required (see
 * restir list)" when name is NULL, "unknown method 'NAME' (see restir list)" when no method has that
 * name. */
const struct method *run_find_method(const char *name);

/* Checks method m with parameters p on the loaded scene s, `checks` (enum run_prepare_checks) saying
 * which besides its settings: the --set keys of sets (n of them; may be NULL when n is 0), then the
 * memory against max_memory_mb. Returns 0, or an exit code with msg: EXIT_USAGE for a setting,
 * EXIT_RUNTIME for memory. Writes nothing else; any thread. */
int run_check_method(const struct scene *s, const struct method *m, const struct render_params *p,
                     const char *const *sets, int n_sets, long long max_memory_mb, unsigned checks, char *msg);

/* For a command that renders method m with the description o: loads o->scene (o->params' scene
 * settings, o->env) into *s, then run_check_method with o->params, o->sets and o->max_memory_mb.
 * Returns 0 with *s to destroy (scene_destroy), or an exit code having said why on stderr (EXIT_USAGE
 * for the scene or a setting, EXIT_RUNTIME for memory), *s destroyed. */
int run_prepare(const struct cli_options *o, const struct method *m, unsigned checks, struct scene *s);

#endif
