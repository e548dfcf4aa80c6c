/* evaluate_check.c: `restir evaluate --check DIR` and `restir evaluate --tables DIR`
 * (evaluate_check.h): an evaluation's recorded steps checked against today's code, and its tables
 * written again from the steps' small files. Must never implement a method or measure an image. */
#include "experiments/evaluate_check.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/evaluate.h"
#include "experiments/evaluate_record.h"
#include "experiments/evaluate_tables.h"
#include "experiments/settings_file.h"
#include "methods/settings.h"
#include "scene/scene_hash.h"

#define PATH_LEN (PLAN_PATH_MAX + 200)
#define MAX_STEPS 1024 /* step folders one check reads */
#define MAX_DEPTH 6    /* folders below DIR it looks into (docs/evaluation/data/CAMPAIGN/STEP: 2) */

static int is_file(const char *dir, const char *name)
{
    char path[PATH_LEN + 32];
    snprintf(path, sizeof path, "%.*s/%s", PATH_LEN - 1, dir, name);
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* A folder holding what a merged step writes. */
static int is_step(const char *dir)
{
    return is_file(dir, "settings.json") || is_file(dir, "provenance.json") || is_file(dir, "study.csv") ||
           is_file(dir, "compare.csv");
}

struct step_list {
    int n;
    char (*path)[PATH_LEN];
};

static int by_path(const void *a, const void *b) { return strcmp(a, b); }

/* The step folders under dir (dir itself when it is one), not looking into a step's own folders or
 * into runs/. Returns 0, or -1 with msg when a folder cannot be read or there are too many. */
static int find_steps(const char *dir, int depth, struct step_list *l, char *msg)
{
    if (is_step(dir)) {
        if (l->n == MAX_STEPS) {
            snprintf(msg, RESTIR_MSG_LEN, "more than %d step folders", MAX_STEPS);
            return -1;
        }
        snprintf(l->path[l->n++], PATH_LEN, "%s", dir);
        return 0;
    }
    if (depth > MAX_DEPTH)
        return 0;
    DIR *d = opendir(dir);
    if (!d) {
        snprintf(msg, RESTIR_MSG_LEN, "%.400s: %s", dir, strerror(errno));
        return -1;
    }
    int rc = 0;
    for (struct dirent *e = readdir(d); e && rc == 0; e = readdir(d)) {
        if (e->d_name[0] == '.' || !strcmp(e->d_name, "runs"))
            continue;
        char sub[PATH_LEN];
        if (snprintf(sub, sizeof sub, "%s/%s", dir, e->d_name) >= (int)sizeof sub)
            continue;
        struct stat st;
        if (stat(sub, &st) == 0 && S_ISDIR(st.st_mode))
            rc = find_steps(sub, depth + 1, l, msg);
    }
    closedir(d);
    return rc;
}

/* The step's name in messages: its path below the checked folder (its own name when it is that folder). */
static const char *step_name(const char *root, const char *path)
{
    const size_t n = strlen(root);
    if (!strncmp(path, root, n) && path[n] == '/')
        return path + n + 1;
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static int positive_int(const cJSON *j, const char *key, int hi, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
    if (!cJSON_IsNumber(v) || v->valuedouble < 1 || v->valuedouble > hi || v->valuedouble != (int)v->valuedouble)
        return -1;
    *out = (int)v->valuedouble;
    return 0;
}

static int hex_u64(const cJSON *v, uint64_t *out)
{
    char *end = NULL;
    if (!cJSON_IsString(v) || !v->valuestring[0])
        return -1;
    errno = 0;
    *out = strtoull(v->valuestring, &end, 16);
    return *end || errno ? -1 : 0;
}

/* settings.json's shape, before anything is rendered. Returns 0, or -1 with msg. */
static int settings_shape(const cJSON *j, struct eval_hash_render *hr, char *msg)
{
    const cJSON *h = cJSON_GetObjectItemCaseSensitive(j, "hash_render");
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(j, "rows");
    const cJSON *seed = cJSON_GetObjectItemCaseSensitive(h, "seed");
    uint64_t scene_hash;
    char *end = NULL;
    if (!cJSON_IsString(cJSON_GetObjectItemCaseSensitive(j, "scene")) ||
        hex_u64(cJSON_GetObjectItemCaseSensitive(j, "scene_hash"), &scene_hash) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "\"scene\" and \"scene_hash\" (hex) are required");
        return -1;
    }
    if (positive_int(h, "width", 4096, &hr->width) != 0 || positive_int(h, "height", 4096, &hr->height) != 0 ||
        positive_int(h, "frames", 1000, &hr->frames) != 0 || !cJSON_IsString(seed) ||
        (hr->seed = strtoull(seed->valuestring, &end, 10), *end != '\0')) {
        snprintf(msg, RESTIR_MSG_LEN, "\"hash_render\" needs width, height, frames (counts) and seed (a string)");
        return -1;
    }
    if (!cJSON_IsArray(rows) || cJSON_GetArraySize(rows) == 0) {
        snprintf(msg, RESTIR_MSG_LEN, "\"rows\" must be a non-empty array");
        return -1;
    }
    const cJSON *row;
    int k = 0;
    cJSON_ArrayForEach(row, rows)
    {
        uint64_t hash;
        const cJSON *camera = cJSON_GetObjectItemCaseSensitive(row, "camera");
        if (!cJSON_IsString(cJSON_GetObjectItemCaseSensitive(row, "label")) ||
            !cJSON_IsString(cJSON_GetObjectItemCaseSensitive(row, "method")) ||
            !cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(row, "settings")) || !cJSON_IsString(camera) ||
            (strcmp(camera->valuestring, "path") && strcmp(camera->valuestring, "static")) ||
            hex_u64(cJSON_GetObjectItemCaseSensitive(row, "hash"), &hash) != 0) {
            snprintf(msg, RESTIR_MSG_LEN,
                     "row %d: label, method, camera (static or path), settings (an object) and hash (hex) are "
                     "required", k + 1);
            return -1;
        }
        k++;
    }
    return 0;
}

static const char *str_of(const cJSON *j, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(j, key)->valuestring;
}

/* Renders step j's rows and compares. Returns 0 (all as recorded), 1 (some row stale: said), or 2
 * having said why (the scene cannot be loaded). */
static int check_step(const char *name, const char *path, const cJSON *j, const struct eval_hash_render *hr,
                      int threads)
{
    const cJSON *rows = cJSON_GetObjectItemCaseSensitive(j, "rows"), *row;
    const cJSON *by = cJSON_GetObjectItemCaseSensitive(j, "recorded_by");
    const cJSON *env = cJSON_GetObjectItemCaseSensitive(j, "env");
    const char *since = cJSON_IsString(by) ? by->valuestring : "(not recorded)";
    char msg[RESTIR_MSG_LEN];
    /* the scene is loaded with the first row's scene.* settings, as the step loaded it */
    struct render_params p0;
    render_params_defaults(&p0);
    if (settings_apply_object(path, cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(rows, 0), "settings"), &p0,
                              msg) != 0) {
        printf("STALE: table %s, row %s: its settings are not today's: %s (recorded by commit %s)\n", name,
               str_of(cJSON_GetArrayItem(rows, 0), "label"), msg, since);
        return 1;
    }
    struct scene s;
    if (cli_scene_load(&p0, cJSON_IsString(env) ? env->valuestring : NULL, str_of(j, "scene"), &s, msg) != 0) {
        cli_error("evaluate --check: table %s: its scene cannot be loaded: %s", name, msg);
        return 2;
    }
    uint64_t recorded_scene = 0;
    hex_u64(cJSON_GetObjectItemCaseSensitive(j, "scene_hash"), &recorded_scene);
    if (scene_content_hash(&s) != recorded_scene) {
        printf("STALE: table %s: the content of scene %s changed since commit %s\n", name, str_of(j, "scene"), since);
        scene_destroy(&s);
        return 1;
    }
    int stale = 0, n = 0;
    cJSON_ArrayForEach(row, rows)
    {
        const char *label = str_of(row, "label"), *method = str_of(row, "method");
        const struct method *m = method_find(method);
        struct render_params p;
        render_params_defaults(&p);
        uint64_t recorded = 0, now = 0;
        hex_u64(cJSON_GetObjectItemCaseSensitive(row, "hash"), &recorded);
        n++;
        if (!m) {
            printf("STALE: table %s, row %s: method %s no longer exists (recorded by commit %s)\n", name, label,
                   method, since);
            stale = 1;
        } else if (settings_apply_object(path, cJSON_GetObjectItemCaseSensitive(row, "settings"), &p, msg) != 0 ||
                   evaluate_hash_render(&s, m, &p, !strcmp(str_of(row, "camera"), "path"), hr, threads, &now,
                                        msg) != 0) {
            printf("STALE: table %s, row %s: its settings are not today's: %s (recorded by commit %s)\n", name,
                   label, msg, since);
            stale = 1;
        } else if (now != recorded) {
            printf("STALE: table %s, row %s renders differently since commit %s (hash %016llx, recorded %016llx)\n",
                   name, label, since, (unsigned long long)now, (unsigned long long)recorded);
            stale = 1;
        }
    }
    scene_destroy(&s);
    return stale;
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int evaluate_check(const char *dir, int threads)
{
    char msg[RESTIR_MSG_LEN], path[PATH_LEN + 32];
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        cli_error("evaluate --check: %s is not a folder", dir);
        return EXIT_USAGE;
    }
    struct step_list l = {0, xcalloc(MAX_STEPS, PATH_LEN)};
    int rc = find_steps(dir, 0, &l, msg) == 0 ? 0 : EXIT_USAGE;
    if (rc != 0)
        cli_error("evaluate --check: %s", msg);
    else if (l.n == 0) {
        cli_error("evaluate --check: no step under %s (a folder with settings.json, provenance.json, study.csv or "
                  "compare.csv)", dir);
        rc = EXIT_USAGE;
    }
    qsort(l.path, (size_t)l.n, PATH_LEN, by_path);
    cJSON **rec = xcalloc((size_t)l.n + 1, sizeof *rec);
    struct eval_hash_render *hr = xcalloc((size_t)l.n + 1, sizeof *hr);
    for (int k = 0; k < l.n && rc == 0; k++) { /* every record read and checked before anything renders */
        snprintf(path, sizeof path, "%s/settings.json", l.path[k]);
        if (!is_file(l.path[k], "settings.json")) {
            cli_error("evaluate --check: table %s has no settings.json (%s): merge it with this restir, or export "
                      "it with scripts/evaluation_export.sh", step_name(dir, l.path[k]), path);
            rc = EXIT_USAGE;
        } else if (!(rec[k] = evaluate_read_json(path, msg))) {
            cli_error("evaluate --check: table %s: %s", step_name(dir, l.path[k]), msg);
            rc = EXIT_USAGE;
        } else if (settings_shape(rec[k], &hr[k], msg) != 0) {
            cli_error("evaluate --check: table %s: %s: %s", step_name(dir, l.path[k]), path, msg);
            rc = EXIT_USAGE;
        }
    }
    if (threads > 0)
        omp_set_num_threads(threads);
    int stale = 0, bad = 0;
    for (int k = 0; k < l.n && rc == 0; k++) {
        const double t0 = seconds_now();
        snprintf(path, sizeof path, "%s/settings.json", l.path[k]);
        const int r = check_step(step_name(dir, l.path[k]), path, rec[k], &hr[k], threads);
        stale |= r == 1;
        bad |= r == 2;
        if (r == 0)
            printf("ok: table %s, %d rows render as recorded (%.2f s)\n", step_name(dir, l.path[k]),
                   cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(rec[k], "rows")), seconds_now() - t0);
    }
    if (rc == 0)
        rc = bad ? EXIT_USAGE : stale ? EXIT_RUNTIME : 0;
    if (rc == 0)
        printf("evaluate --check: %d table%s under %s render as recorded\n", l.n, l.n == 1 ? "" : "s", dir);
    else if (rc == EXIT_RUNTIME)
        printf("evaluate --check: stale tables under %s: today's code renders their settings differently; run "
               "their evaluations again\n", dir);
    for (int k = 0; k < l.n; k++)
        cJSON_Delete(rec[k]);
    free(rec);
    free(hr);
    free(l.path);
    return rc;
}

/* Step s's provenance checked against the evaluation's: its build (as plan_build), resolution and
 * runs. Returns 0, or EXIT_USAGE having said why. */
static int step_provenance(const char *dir, const struct eval_options *o, const struct eval_step *s,
                           const char *plan_build)
{
    char path[PATH_LEN], msg[RESTIR_MSG_LEN], build[PROVENANCE_COMMIT_LEN + 8];
    snprintf(path, sizeof path, "%s/%s/provenance.json", dir, s->name);
    cJSON *j = evaluate_read_json(path, msg);
    struct provenance planned;
    int rc = 0;
    if (!j) {
        cli_error("evaluate --tables: step %s has no provenance: %s (merge it again with this restir)", s->name, msg);
        rc = EXIT_USAGE;
    } else if (provenance_from_json(cJSON_GetObjectItemCaseSensitive(j, "planned"), &planned, msg) != 0) {
        cli_error("evaluate --tables: step %s: %s: %s", s->name, path, msg);
        rc = EXIT_USAGE;
    } else {
        provenance_build_id(&planned, build, sizeof build);
        const cJSON *w = cJSON_GetObjectItemCaseSensitive(j, "width"),
                    *h = cJSON_GetObjectItemCaseSensitive(j, "height");
        const cJSON *runs = cJSON_GetObjectItemCaseSensitive(j, "runs");
        if (strcmp(build, plan_build) != 0) {
            cli_error("evaluate --tables: step %s was made by commit %s, the evaluation (plan.json) by %s: a "
                      "campaign's tables come from one commit; run the step again on %s", s->name, build, plan_build,
                      plan_build);
            rc = EXIT_USAGE;
        } else if (!cJSON_IsNumber(w) || !cJSON_IsNumber(h) || (int)w->valuedouble != o->width ||
                   (int)h->valuedouble != o->height) {
            cli_error("evaluate --tables: step %s is of another resolution (%gx%g) than the evaluation (%dx%d)",
                      s->name, cJSON_IsNumber(w) ? w->valuedouble : 0.0, cJSON_IsNumber(h) ? h->valuedouble : 0.0,
                      o->width, o->height);
            rc = EXIT_USAGE;
        } else if (!cJSON_IsNumber(runs) || (int)runs->valuedouble != eval_runs(o, s->paper)) {
            cli_error("evaluate --tables: step %s has %g runs per configuration, the evaluation %d", s->name,
                      cJSON_IsNumber(runs) ? runs->valuedouble : 0.0, eval_runs(o, s->paper));
            rc = EXIT_USAGE;
        }
    }
    cJSON_Delete(j);
    return rc;
}

int evaluate_tables(const char *dir, int partial)
{
    char msg[RESTIR_MSG_LEN], sub[PATH_LEN];
    struct plan pl;
    if (plan_load(dir, &pl, msg) != 0) {
        cli_error("evaluate --tables: %s", msg);
        return EXIT_USAGE;
    }
    if (strcmp(pl.kind, "evaluate") != 0) {
        cli_error("evaluate --tables: %s holds a plan of `restir %s`, not an evaluation", pl.dir, pl.kind);
        plan_free(&pl);
        return EXIT_USAGE;
    }
    static struct eval_step steps[EVAL_MAX_STEPS];
    struct eval_options o;
    int n = 0, merged[EVAL_MAX_STEPS], any = 0;
    int rc = evaluate_plan_steps(&pl, &o, steps, &n);
    char plan_build[PROVENANCE_COMMIT_LEN + 8];
    provenance_build_id(&pl.made_by, plan_build, sizeof plan_build);
    for (int k = 0; k < n && rc == 0; k++) {
        snprintf(sub, sizeof sub, "%s/%s", pl.dir, steps[k].name);
        char table[16];
        snprintf(table, sizeof table, "%s.csv", steps[k].kind);
        const char *missing = !is_file(sub, table)                                            ? table
                              : !strcmp(steps[k].kind, "compare") && !is_file(sub, "passes.csv") ? "passes.csv"
                                                                                                  : NULL;
        merged[k] = !missing;
        if (missing && partial) {
            printf("evaluate: %s is left out (--partial): it has no %s\n", steps[k].name, missing);
            continue;
        }
        if (missing) {
            cli_error("evaluate --tables: step %s has no %s (%s/%s): merge or export it, or give --partial",
                      steps[k].name, missing, sub, missing);
            rc = EXIT_USAGE;
            break;
        }
        any = 1;
        rc = step_provenance(pl.dir, &o, &steps[k], plan_build);
    }
    if (rc == 0 && !any) {
        cli_error("evaluate --tables: no step of %s has its table", pl.dir);
        rc = EXIT_USAGE;
    }
    o.report = 0; /* the steps' pages are not part of the data */
    if (rc == 0)
        rc = evaluate_write_tables(pl.dir, pl.command, &o, steps, n, merged);
    plan_free(&pl);
    return rc;
}
