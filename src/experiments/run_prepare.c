/* run_prepare.c: the checks before a command's first frame (run_prepare.h). */
#include "experiments/run_prepare.h"

#include "core/check.h"
#include "experiments/cli.h"
#include "methods/settings.h"

const struct method *run_find_method(const char *name)
{
    const struct method *m = name ? method_find(name) : NULL;
    if (!name)
        cli_error("--method is required (see restir list)");
    else if (!m)
        cli_error("unknown method '%s' (see restir list)", name);
    return m;
}

int run_check_method(const struct scene *s, const struct method *m, const struct render_params *p,
                     const char *const *sets, int n_sets, long long max_memory_mb, unsigned checks, char *msg)
{
    if (((checks & RUN_CHECK_SETS) && method_check_assignments(m, sets, n_sets, msg) != 0) ||
        method_check_settings(m, p, s, msg) != 0)
        return EXIT_USAGE;
    if ((checks & RUN_CHECK_MEMORY) && cli_check_memory(s, m, p, max_memory_mb, msg) != 0)
        return EXIT_RUNTIME;
    return 0;
}

int run_prepare(const struct cli_options *o, const struct method *m, unsigned checks, struct scene *s)
{
    char msg[RESTIR_MSG_LEN];
    if (cli_scene_load(&o->params, o->env, o->scene, s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    int rc = run_check_method(s, m, &o->params, o->sets, o->n_sets, o->max_memory_mb, checks, msg);
    if (rc != 0) {
        cli_error("%s", msg);
        scene_destroy(s);
    }
    return rc;
}
