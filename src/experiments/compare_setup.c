/* compare_setup.c: a comparison's description into its specs (method, settings, instances, folder),
 * common parameters and integrand, with its scene loaded and memory checked (compare_run.h).
 * Must never render. */
#include "experiments/compare_run.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/reference_size.h"
#include "experiments/run_prepare.h"
#include "methods/settings.h"
#include "scene/scene_file.h"

/* msg of render_params_set without its "--set" prefix, which
 * would name an option the user did not give. */
static const char *strip_set_prefix(const char *m)
{
    if (!strncmp(m, "--set: ", 7))
        return m + 7;
    if (!strncmp(m, "--set ", 6))
        return m + 6;
    return m;
}

/* Removes every "instances=N" from a spec's key=value list (colon separated, in place) into *n: the
 * row averages N independently seeded renderers (as --equal-time's instances; 002 Sec. 5 gives its
 * baselines fixed counts). Returns 0, or -1 with msg. */
static int take_instances(char *list, int *n, char *msg)
{
    char out[SPEC_MAX + 1] = "";
    size_t used = 0;
    for (char *tok = list, *next; tok; tok = next) {
        next = strchr(tok, ':');
        if (next)
            *next++ = '\0';
        if (!strncmp(tok, "instances=", 10)) {
            long long v = 0;
            if (cli_parse_int("instances", tok + 10, 1, MAX_INSTANCES, &v, msg) != 0)
                return -1;
            *n = (int)v;
            continue;
        }
        used += (size_t)snprintf(out + used, sizeof out - used, "%s%s", used ? ":" : "", tok);
    }
    memcpy(list, out, used + 1);
    return 0;
}

/* Parses spec "NAME[:key=value]..." onto common parameters. Returns 0, or -1 with msg naming the
 * spec and the problem (an unknown method, key or value). */
static int parse_spec(const char *spec, const struct render_params *common, struct compare_spec *c, char *msg)
{
    char sub[RESTIR_MSG_LEN];
    if (strlen(spec) > SPEC_MAX) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.40s...' is longer than %d characters", spec, SPEC_MAX);
        return -1;
    }
    snprintf(c->label, sizeof(c->label), "%s", spec);
    char buf[SPEC_MAX + 1];
    snprintf(buf, sizeof(buf), "%s", spec);
    char *rest = strchr(buf, ':');
    if (rest)
        *rest++ = '\0';
    const struct method *m = method_find(buf);
    if (!m) {
        if (rest)
            snprintf(msg, RESTIR_MSG_LEN, "unknown method '%s' in --methods spec '%s' (see restir list)", buf, spec);
        else
            snprintf(msg, RESTIR_MSG_LEN, "unknown method '%s' in --methods (see restir list)", buf);
        return -1;
    }
    c->method = m;
    c->p = *common;
    c->instances = 1;
    if (rest && take_instances(rest, &c->instances, sub) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.200s': %.280s", spec, sub);
        return -1;
    }
    if (rest && *rest && render_params_set_list(&c->p, rest, sub) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.200s': %.280s", spec, strip_set_prefix(sub));
        return -1;
    }
    const char *own = rest; /* known keys and values: does the method read them? */
    if (rest && *rest && method_check_assignments(m, &own, 1, sub) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "--methods spec '%.200s': %.280s", spec, strip_set_prefix(sub));
        return -1;
    }
    /* One reference serves every row, so no row may change the integral it is measured against. */
    if (c->p.max_bounces != common->max_bounces || c->p.jitter != common->jitter ||
        c->p.camera_shutter != common->camera_shutter || c->p.camera_aperture != common->camera_aperture ||
        c->p.camera_focus != common->camera_focus) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--methods spec '%.200s' changes the integrand (pt.max_bounces, jitter or a camera.* setting), "
                 "which every row "
                 "shares with the reference: give it to all rows with --set",
                 spec);
        return -1;
    }
    return 0;
}

/* Folder names from labels: every character outside [A-Za-z0-9._-] becomes '_', and a name an
 * earlier spec already took gets _2, _3, ... appended. */
static void assign_dirs(struct compare_spec *c, int n)
{
    for (int k = 0; k < n; k++) {
        char base[SPEC_MAX + 1];
        size_t len = strlen(c[k].label);
        for (size_t i = 0; i <= len; i++) {
            char ch = c[k].label[i];
            int ok = ch == '\0' || (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') ||
                     ch == '.' || ch == '_' || ch == '-';
            base[i] = ok ? ch : '_';
        }
        snprintf(c[k].dir, sizeof(c[k].dir), "%s", base);
        for (int suffix = 2;; suffix++) {
            int taken = 0;
            for (int j = 0; j < k && !taken; j++)
                taken = !strcmp(c[j].dir, c[k].dir);
            if (!taken)
                break;
            snprintf(c[k].dir, sizeof(c[k].dir), "%s_%d", base, suffix);
        }
    }
}

int compare_setup(const struct cli_options *desc, struct compare_setup *st)
{
    char msg[RESTIR_MSG_LEN];
    st->o = *desc;
    struct cli_options *o = &st->o;
    if (!o->methods) {
        cli_error("--methods SPEC,SPEC,... is required (see restir list)");
        return EXIT_USAGE;
    }
    char list[MAX_METHODS * (SPEC_MAX + 1) + 64];
    if (strlen(o->methods) >= sizeof(list)) {
        cli_error("--methods is longer than %zu characters", sizeof(list) - 1);
        return EXIT_USAGE;
    }
    /* --ref without --res: the reference's size, which every spec copies */
    if (o->ref && reference_size_adopt(o->ref, o->res_given, &o->params, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    snprintf(list, sizeof(list), "%s", o->methods);
    st->n = 0;
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        if (st->n == MAX_METHODS) {
            cli_error("--methods lists more than %d methods", MAX_METHODS);
            return EXIT_USAGE;
        }
        if (parse_spec(tok, &o->params, &st->specs[st->n], msg) != 0) {
            cli_error("%s", msg);
            return EXIT_USAGE;
        }
        st->n++;
    }
    if (st->n == 0) {
        cli_error("--methods lists no method (see restir list)");
        return EXIT_USAGE;
    }
    for (int k = 0; k < o->n_sets; k++) { /* a common setting must be read by some row's method */
        int used = 0;
        for (int j = 0; j < st->n && !used; j++)
            used = method_check_assignments(st->specs[j].method, &o->sets[k], 1, msg) == 0;
        if (!used) {
            cli_error("%s; nor does any other method of --methods", msg);
            return EXIT_USAGE;
        }
    }
    for (int k = 0; k < st->n && o->equal_time; k++)
        if (st->specs[k].instances != 1) {
            cli_error("--methods spec '%s': instances= and --equal-time both set a row's instances; give one",
                      st->specs[k].label);
            return EXIT_USAGE;
        }
    st->p = o->params;
    st->integrand = st->specs[0].method;
    for (int k = st->n - 1; k >= 0; k--)
        if (method_has(st->specs[k].method, METHOD_DIRECT_ONLY))
            st->integrand = st->specs[k].method;
    method_reference_params(st->integrand, &st->p); /* pt estimates the same integral */
    for (int k = 0; k < st->n; k++) {
        method_reference_params(st->integrand, &st->specs[k].p); /* as for --set */
        if (render_params_validate(&st->specs[k].p, msg) != 0) {
            cli_error("--methods spec '%s': %s", st->specs[k].label, msg);
            return EXIT_USAGE;
        }
    }
    assign_dirs(st->specs, st->n);
    if (cli_scene_load(&o->params, o->env, o->scene, &st->s, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    for (int k = 0; k < st->n; k++) { /* each method's renderers exist one at a time */
        /* the --set keys were checked against the specs above, as a key may be any spec's */
        int rc = run_check_method(&st->s, st->specs[k].method, &st->specs[k].p, NULL, 0, o->max_memory_mb,
                                  RUN_CHECK_MEMORY, msg);
        if (rc != 0) {
            cli_error("--methods spec '%s': %s", st->specs[k].label, msg);
            scene_destroy(&st->s);
            return rc;
        }
    }
    if (o->params.threads > 0)
        omp_set_num_threads(o->params.threads);
    return 0;
}
