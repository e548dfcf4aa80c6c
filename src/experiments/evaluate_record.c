/* evaluate_record.c: a merged step's provenance.json and settings.json, the tiny render whose hash
 * stands for what the code computes with a row's settings, and the provenance line of a paper's
 * section (evaluate_record.h). Must never measure an image or write a table. */
#include "experiments/evaluate_record.h"

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/hash.h"
#include "experiments/cli.h"
#include "experiments/compare_run.h"
#include "experiments/provenance.h"
#include "experiments/settings_file.h"
#include "experiments/study.h"
#include "io/report.h"
#include "io/text_file.h"
#include "methods/renderer.h"
#include "methods/settings.h"
#include "scene/scene_hash.h"

#define PATH_LEN (PLAN_PATH_MAX + 200)
#define MAX_MACHINES 16 /* distinct (CPU, threads) of a step's jobs named; more are counted as others */

int evaluate_hash_render(const struct scene *s, const struct method *m, const struct render_params *p,
                         int camera_path, const struct eval_hash_render *hr, int threads, uint64_t *hash, char *msg)
{
    struct render_params q = *p;
    q.width = hr->width;
    q.height = hr->height;
    q.seed = hr->seed;
    if (threads > 0)
        q.threads = threads;
    char why[RESTIR_MSG_LEN];
    if (render_params_validate(&q, why) != 0 || method_check_settings(m, &q, s, why) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.400s", why);
        return -1;
    }
    struct renderer r;
    renderer_init(&r, s, m, &q);
    const size_t n3 = 3 * (size_t)q.width * (size_t)q.height;
    uint64_t h = FNV1A64_BASIS;
    for (int f = 0; f < hr->frames; f++) {
        const struct camera cam = scene_camera_at(s, camera_path, (float)f);
        struct frame_stats st;
        renderer_render(&r, f, &cam, &st);
        h = fnv1a64(h, r.image, sizeof(float) * n3);
        if (r.denoised)
            h = fnv1a64(h, r.denoised, sizeof(float) * n3);
    }
    renderer_fini(&r);
    *hash = h;
    return 0;
}

cJSON *evaluate_read_json(const char *path, char *msg)
{
    char why[RESTIR_MSG_LEN];
    char *text = io_read_text(path, 16u << 20, why);
    if (!text) {
        snprintf(msg, RESTIR_MSG_LEN, "%.480s", why);
        return NULL;
    }
    cJSON *j = cJSON_Parse(text);
    free(text);
    if (!cJSON_IsObject(j)) {
        snprintf(msg, RESTIR_MSG_LEN, "%.400s: not a JSON object", path);
        cJSON_Delete(j);
        return NULL;
    }
    return j;
}

static void add_u64(cJSON *j, const char *key, uint64_t v, int hex)
{
    char text[32];
    snprintf(text, sizeof text, hex ? "%016llx" : "%llu", (unsigned long long)v);
    cJSON_AddStringToObject(j, key, text);
}

/* The machines of a step's jobs: (CPU, threads) and how many jobs ran on each. */
struct machines {
    int n, others, recorded, total;
    char cpu[MAX_MACHINES][128];
    int threads[MAX_MACHINES], count[MAX_MACHINES];
};

static void machines_add(struct machines *m, const char *cpu, int threads, int count)
{
    for (int i = 0; i < m->n; i++)
        if (m->threads[i] == threads && !strcmp(m->cpu[i], cpu)) {
            m->count[i] += count;
            return;
        }
    if (m->n == MAX_MACHINES) {
        m->others += count;
        return;
    }
    snprintf(m->cpu[m->n], sizeof m->cpu[0], "%s", cpu);
    m->threads[m->n] = threads;
    m->count[m->n++] = count;
}

/* Adds the machine recorded in path (plan_note_job_machine); 0 when there is none. */
static int machines_note(struct machines *m, const char *path)
{
    char msg[RESTIR_MSG_LEN];
    cJSON *j = evaluate_read_json(path, msg);
    struct provenance p;
    const int ok = j && provenance_from_json(j, &p, msg) == 0;
    cJSON_Delete(j);
    if (ok)
        machines_add(m, p.cpu, p.threads, 1);
    return ok;
}

/* Step job i's machine: as a line of the evaluation's plan (eval_line >= 0), else as a job of the
 * step's own plan (`restir job STEP K`). */
static void step_machines(const struct plan *eval, const struct plan *sp, const char *name, struct machines *m)
{
    memset(m, 0, sizeof *m);
    int first = -1;
    const size_t len = strlen(name);
    for (int j = 0; j < eval->n_jobs && first < 0; j++)
        if (!strncmp(eval->jobs[j].output, name, len) && eval->jobs[j].output[len] == '/')
            first = j;
    char path[PATH_LEN];
    m->total = sp->n_jobs;
    for (int i = 0; i < sp->n_jobs; i++) {
        int found = 0;
        if (first >= 0 && first + i < eval->n_jobs) {
            snprintf(path, sizeof path, "%s/runs/logs/job_%d.json", eval->dir, first + i + 1);
            found = machines_note(m, path);
        }
        if (!found) {
            snprintf(path, sizeof path, "%s/runs/logs/job_%d.json", sp->dir, i + 1);
            found = machines_note(m, path);
        }
        m->recorded += found;
    }
}

static cJSON *machines_json(const struct machines *m)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < m->n; i++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "cpu", m->cpu[i]);
        cJSON_AddNumberToObject(o, "threads", m->threads[i]);
        cJSON_AddNumberToObject(o, "count", m->count[i]);
        cJSON_AddItemToArray(a, o);
    }
    if (m->others) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "cpu", "other machines");
        cJSON_AddNumberToObject(o, "threads", 0);
        cJSON_AddNumberToObject(o, "count", m->others);
        cJSON_AddItemToArray(a, o);
    }
    return a;
}

/* A step's setup, loaded again from its plan: the study's or the comparison's (large: static). */
static struct study_setup study_st;
static struct compare_setup compare_st;

/* One row of settings.json: the label its table gives it, the method, every setting in effect and
 * the hash of the tiny render. Returns the row, or NULL with msg. */
static cJSON *settings_row(const struct scene *s, const char *label, const struct method *m,
                           const struct render_params *p, int camera_path, int instances, char *msg)
{
    const struct eval_hash_render hr = {EVAL_HASH_WIDTH, EVAL_HASH_HEIGHT, EVAL_HASH_FRAMES, EVAL_HASH_SEED};
    uint64_t hash = 0;
    char why[RESTIR_MSG_LEN];
    if (evaluate_hash_render(s, m, p, camera_path, &hr, 0, &hash, why) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "row %.200s: the tiny render is refused: %.250s", label, why);
        return NULL;
    }
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "label", label);
    cJSON_AddStringToObject(row, "method", m->name);
    cJSON_AddStringToObject(row, "camera", camera_path ? "path" : "static");
    cJSON_AddNumberToObject(row, "instances", instances);
    cJSON_AddItemToObject(row, "settings", settings_json(p));
    add_u64(row, "hash", hash, 1);
    return row;
}

/* settings.json's rows for the loaded step. Returns the array, or NULL with msg. */
static cJSON *settings_rows(int study, char *msg)
{
    cJSON *rows = cJSON_CreateArray();
    const int n = study ? study_st.ncfg : compare_st.n;
    for (int k = 0; k < n; k++) {
        cJSON *row;
        if (study) { /* a configuration renders with the study's settings and its own (study_run_unit) */
            struct render_params p = study_st.o.params;
            study_config_apply(&study_st.cfg[k], &p);
            row = settings_row(&study_st.s, study_st.cfg[k].name, study_st.method, &p, 0, 1, msg);
        } else {
            const struct compare_spec *c = &compare_st.specs[k];
            row = settings_row(&compare_st.s, c->label, c->method, &c->p, c->p.camera_path, c->instances, msg);
        }
        if (!row) {
            cJSON_Delete(rows);
            return NULL;
        }
        cJSON_AddItemToArray(rows, row);
    }
    return rows;
}

/* The run parameters, scene and seeds of the loaded step into j (provenance.json's and settings.json's
 * common part). */
static void add_setup(cJSON *j, int study, uint64_t scene_hash)
{
    const struct cli_options *o = study ? &study_st.o : &compare_st.o;
    cJSON_AddStringToObject(j, "scene", o->scene ? o->scene : "many-lights");
    if (o->env)
        cJSON_AddStringToObject(j, "env", o->env);
    add_u64(j, "scene_hash", scene_hash, 1);
    cJSON_AddNumberToObject(j, "width", o->params.width);
    cJSON_AddNumberToObject(j, "height", o->params.height);
}

int evaluate_record_step(const struct plan *eval, const struct eval_step *s, const char *step_dir)
{
    char msg[RESTIR_MSG_LEN], path[PATH_LEN];
    struct plan sp;
    if (plan_load(step_dir, &sp, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    struct cli_options desc;
    const int study = !strcmp(sp.kind, "study");
    int rc = 0;
    if (cli_parse_options(sp.kind, sp.argc, sp.argv, &desc, msg) != 0) {
        cli_error("%s/plan.json: %s", sp.dir, msg);
        rc = EXIT_USAGE;
    } else
        rc = study ? study_setup(&desc, 0, &study_st) : compare_setup(&desc, &compare_st);
    if (rc != 0) {
        plan_free(&sp);
        return rc;
    }
    const struct cli_options *o = study ? &study_st.o : &compare_st.o;
    struct scene *scene = study ? &study_st.s : &compare_st.s;
    const uint64_t scene_hash = scene_content_hash(scene);
    char build[PROVENANCE_COMMIT_LEN + 8];
    provenance_build_id(&sp.made_by, build, sizeof build);

    cJSON *set = cJSON_CreateObject();
    cJSON_AddStringToObject(set, "step", s->name);
    cJSON_AddStringToObject(set, "kind", sp.kind);
    cJSON_AddStringToObject(set, "recorded_by", build);
    add_setup(set, study, scene_hash);
    cJSON *hr = cJSON_AddObjectToObject(set, "hash_render");
    cJSON_AddNumberToObject(hr, "width", EVAL_HASH_WIDTH);
    cJSON_AddNumberToObject(hr, "height", EVAL_HASH_HEIGHT);
    cJSON_AddNumberToObject(hr, "frames", EVAL_HASH_FRAMES);
    add_u64(hr, "seed", EVAL_HASH_SEED, 0);
    cJSON *rows = settings_rows(study, msg);
    if (!rows) {
        cli_error("evaluate: step %s: %s", s->name, msg);
        rc = EXIT_RUNTIME;
    } else {
        cJSON_AddItemToObject(set, "rows", rows);
        snprintf(path, sizeof path, "%s/settings.json", sp.dir);
        if (json_write_file(path, set, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        }
    }
    cJSON_Delete(set);

    if (rc == 0) {
        struct machines m;
        step_machines(eval, &sp, s->name, &m);
        struct provenance merged;
        provenance_now(&merged, 0);
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "step", s->name);
        cJSON_AddStringToObject(j, "paper", s->paper);
        cJSON_AddStringToObject(j, "kind", sp.kind);
        cJSON_AddStringToObject(j, "command", sp.command);
        cJSON_AddStringToObject(j, "evaluation", eval->command);
        cJSON_AddStringToObject(j, "commit", sp.made_by.commit);
        cJSON_AddBoolToObject(j, "dirty", sp.made_by.dirty);
        cJSON_AddStringToObject(j, "build_type", sp.made_by.build_type);
        cJSON_AddItemToObject(j, "planned", provenance_to_json(&sp.made_by));
        cJSON_AddItemToObject(j, "merged", provenance_to_json(&merged));
        cJSON_AddItemToObject(j, "jobs", machines_json(&m));
        cJSON_AddNumberToObject(j, "jobs_total", m.total);
        cJSON_AddNumberToObject(j, "jobs_recorded", m.recorded);
        cJSON_AddNumberToObject(j, "threads_per_job", o->params.threads);
        add_setup(j, study, scene_hash);
        cJSON_AddNumberToObject(j, "runs", o->runs);
        cJSON_AddNumberToObject(j, "frames", o->frames);
        cJSON_AddNumberToObject(j, "warmup", study ? o->warmup : 0);
        cJSON_AddNumberToObject(j, "reference_spp", o->ref_spp);
        cJSON_AddStringToObject(j, "camera", !study && o->params.camera_path ? "path" : "static");
        add_u64(j, "seed", o->params.seed, 0);
        add_u64(j, "run_seed_stride", study ? STUDY_RUN_SEED_STRIDE : COMPARE_RUN_SEED_STRIDE, 0);
        if (!study)
            add_u64(j, "instance_seed_stride", COMPARE_INSTANCE_SEED_STRIDE, 0);
        snprintf(path, sizeof path, "%s/provenance.json", sp.dir);
        if (json_write_file(path, j, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        }
        cJSON_Delete(j);
    }
    scene_destroy(scene);
    plan_free(&sp);
    return rc;
}

/* The number member key of j, or fallback. */
static double num_of(const cJSON *j, const char *key, double fallback)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
    return cJSON_IsNumber(v) ? v->valuedouble : fallback;
}

static const char *str_of(const cJSON *j, const char *key, const char *fallback)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
    return cJSON_IsString(v) ? v->valuestring : fallback;
}

/* Appends to out (len bytes) what fmt says. */
static void append(char *out, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void append(char *out, size_t len, const char *fmt, ...)
{
    const size_t used = strlen(out);
    if (used + 1 >= len)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out + used, len - used, fmt, ap);
    va_end(ap);
}

void evaluate_provenance_text(const char *dir, const struct eval_step *steps, int n, const int *merged,
                              const char *paper, char *out, size_t len)
{
    struct machines jobs;
    memset(&jobs, 0, sizeof jobs);
    struct provenance build, last_merge;
    char seeds[2][120] = {"", ""}, first_commit[PROVENANCE_COMMIT_LEN + 8] = "", other_commit[200] = "";
    int found = 0, width = 0, height = 0, runs = 0, ref_spp = 0;
    memset(&last_merge, 0, sizeof last_merge);
    for (int k = 0; k < n; k++) {
        if (!merged[k] || strcmp(steps[k].paper, paper) != 0)
            continue;
        char path[PATH_LEN], msg[RESTIR_MSG_LEN];
        snprintf(path, sizeof path, "%s/%s/provenance.json", dir, steps[k].name);
        cJSON *j = evaluate_read_json(path, msg);
        struct provenance planned, m;
        if (!j || provenance_from_json(cJSON_GetObjectItemCaseSensitive(j, "planned"), &planned, msg) != 0) {
            cJSON_Delete(j);
            continue;
        }
        char id[PROVENANCE_COMMIT_LEN + 8];
        provenance_build_id(&planned, id, sizeof id);
        if (!found++) {
            build = planned;
            snprintf(first_commit, sizeof first_commit, "%s", id);
            width = (int)num_of(j, "width", 0);
            height = (int)num_of(j, "height", 0);
            runs = (int)num_of(j, "runs", 0);
            ref_spp = (int)num_of(j, "reference_spp", 0);
        } else if (strcmp(id, first_commit) != 0 && !other_commit[0])
            snprintf(other_commit, sizeof other_commit, "%s (step %.60s)", id, steps[k].name);
        if (provenance_from_json(cJSON_GetObjectItemCaseSensitive(j, "merged"), &m, msg) == 0 &&
            strcmp(m.date, last_merge.date) > 0)
            last_merge = m;
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(j, "jobs"), *e;
        cJSON_ArrayForEach(e, list)
            machines_add(&jobs, str_of(e, "cpu", "unknown CPU"), (int)num_of(e, "threads", 0),
                         (int)num_of(e, "count", 0));
        jobs.total += (int)num_of(j, "jobs_total", 0);
        jobs.recorded += (int)num_of(j, "jobs_recorded", 0);
        const int study = !strcmp(str_of(j, "kind", ""), "study");
        const unsigned long long stride = strtoull(str_of(j, "run_seed_stride", "0"), NULL, 10);
        snprintf(seeds[study], sizeof seeds[0], stride >> 32 ? "%s + 0x%llx r (%s)" : "%s + %llu r (%s)",
                 str_of(j, "seed", "?"), stride, study ? "study" : "compare");
        cJSON_Delete(j);
    }
    if (!found) {
        snprintf(out, len, "Provenance: not recorded (no merged step of %s has a provenance.json).", paper);
        return;
    }
    out[0] = '\0';
    append(out, len, "Provenance: commit %s (%s), %s build", build.commit, build.dirty ? "dirty" : "clean",
           build.build_type);
    if (other_commit[0])
        append(out, len, " (but %s: steps of several commits)", other_commit);
    append(out, len, "; jobs:");
    for (int i = 0; i < jobs.n; i++)
        append(out, len, "%s %d on %s with %d thread%s", i ? "," : "", jobs.count[i], jobs.cpu[i], jobs.threads[i],
               jobs.threads[i] == 1 ? "" : "s");
    if (jobs.others)
        append(out, len, "%s %d on other machines", jobs.n ? "," : "", jobs.others);
    if (jobs.total > jobs.recorded)
        append(out, len, "%s %d without a record", jobs.n || jobs.others ? "," : "", jobs.total - jobs.recorded);
    append(out, len, "; merged %.10s on %s with %d thread%s; %dx%d, %d runs per configuration, run r seeded %s%s%s, "
           "references of %d paths per pixel. Frame times are those of the jobs' machines.",
           last_merge.date[0] ? last_merge.date : "(unknown date)", last_merge.cpu[0] ? last_merge.cpu : "unknown CPU",
           last_merge.threads, last_merge.threads == 1 ? "" : "s", width, height, runs, seeds[1],
           seeds[0][0] && seeds[1][0] ? " or " : "", seeds[0], ref_spp);
}
