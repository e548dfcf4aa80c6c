/* plan.c: plan folders (plan.h): plan.json, jobs.txt, slurm.sh, job results and their checks.
 * Must never implement a method or know a command's results; it knows commands only by their kind. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "experiments/plan.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/check.h"
#include "core/hash.h"
#include "experiments/cli.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "io/atomic_file.h"
#include "io/report.h"
#include "io/text_file.h"

/* The plan's id: its kind, arguments and the build that made it, so results of another build's plan
 * of the same command (planned again into the same folder) are never taken as done. */
static uint64_t plan_hash(const char *kind, int argc, char **argv, const struct provenance *made_by)
{
    uint64_t h = fnv1a64(FNV1A64_BASIS, kind, strlen(kind) + 1);
    for (int i = 0; i < argc; i++)
        h = fnv1a64(h, argv[i], strlen(argv[i]) + 1);
    char build[PROVENANCE_COMMIT_LEN + 8];
    provenance_build_id(made_by, build, sizeof build);
    return fnv1a64(h, build, strlen(build) + 1);
}

static char *xstrdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = xmalloc(n);
    memcpy(c, s, n);
    return c;
}

/* Slurm's #SBATCH lines cannot quote, and jobs.txt is read by shells: keep the folder plain. */
static int plain_path(const char *s)
{
    for (; *s; s++)
        if (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\'' || *s == '"' || *s == '\\' || *s == '$' ||
            *s == '`' || *s == '%')
            return 0;
    return 1;
}

/* p->argv, p->argc, p->threads and p->id from the command's JSON description (options.h) and
 * p->made_by. Returns 0, or -1 with msg. */
static int plan_set_arguments(struct plan *p, const cJSON *desc, char *msg)
{
    if (cli_options_argv(p->kind, desc, &p->argc, &p->argv, msg) != 0)
        return -1;
    for (int i = 0; i + 1 < p->argc; i++)
        if (!strcmp(p->argv[i], "--threads"))
            p->threads = atoi(p->argv[i + 1]);
    p->id = plan_hash(p->kind, p->argc, p->argv, &p->made_by);
    return 0;
}

/* The plan's arguments and id from the command's: p->argv without --plan DIR, --force and --resume
 * (what to do with the folder is no part of the work), with --scene FILE and --ref FILE made
 * absolute. Returns 0, or -1 with msg. */
static int plan_identify(struct plan *p, const char *kind, int argc, char **argv, char *msg)
{
    snprintf(p->kind, sizeof p->kind, "%s", kind);
    p->argv = xcalloc((size_t)argc + 1, sizeof(char *));
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--plan")) { /* the jobs run the command itself */
            i++;
            continue;
        }
        if (!strcmp(argv[i], "--force") || !strcmp(argv[i], "--resume"))
            continue;
        const int path_value = i > 0 && (!strcmp(argv[i - 1], "--scene") || !strcmp(argv[i - 1], "--ref"));
        char abs[PATH_MAX];
        struct stat st;
        /* a scene name stays a name; a file is found again from any folder a job runs in */
        p->argv[p->argc++] = xstrdup(path_value && stat(argv[i], &st) == 0 && realpath(argv[i], abs) ? abs : argv[i]);
    }
    /* the arguments as the description plan.json keeps, and back: jobs and merges see the same */
    cJSON *desc = cli_options_describe(kind, p->argc, p->argv, msg);
    cli_options_free_argv(p->argc, p->argv);
    p->argc = 0;
    p->argv = NULL;
    if (!desc)
        return -1;
    provenance_now(&p->made_by, 0);
    const int rc = plan_set_arguments(p, desc, msg);
    cJSON_Delete(desc);
    p->made_by.threads = p->threads > 0 ? p->threads : p->made_by.threads;
    return rc;
}

/* Starts a plan of kind in dir (made, if missing) from the command's arguments (plan_identify).
 * Returns 0, or -1 with msg. */
static int plan_init(struct plan *p, const char *dir, const char *kind, int argc, char **argv, const char *command,
                     uint64_t scene_hash, char *msg)
{
    memset(p, 0, sizeof *p);
    if (io_make_dirs(dir, msg) != 0)
        return -1;
    if (!realpath(dir, p->dir)) {
        snprintf(msg, RESTIR_MSG_LEN, "--plan %.300s: %s", dir, strerror(errno));
        return -1;
    }
    if (!plain_path(p->dir)) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "--plan %.300s: the folder's path must not hold spaces, quotes, '$', '%%' or '\\' (Slurm's "
                 "#SBATCH lines cannot quote them)", p->dir);
        return -1;
    }
    snprintf(p->command, sizeof p->command, "%s", command);
    p->scene_hash = scene_hash;
    return plan_identify(p, kind, argc, argv, msg);
}

int plan_folder_claim(const char *dir, const char *kind, int argc, char **argv, int force)
{
    char msg[RESTIR_MSG_LEN], path[PLAN_PATH_MAX + 32];
    struct stat st;
    snprintf(path, sizeof path, "%s/plan.json", dir);
    int same = 0;
    char held[200] = "";
    if (stat(path, &st) == 0) {
        struct plan now, old;
        memset(&now, 0, sizeof now);
        if (plan_identify(&now, kind, argc, argv, msg) != 0) {
            cli_error("%s", msg);
            plan_free(&now);
            return EXIT_USAGE;
        }
        snprintf(held, sizeof held, "a plan.json restir cannot read");
        if (plan_load(dir, &old, msg) == 0) {
            same = !strcmp(old.kind, now.kind) && old.id == now.id;
            snprintf(held, sizeof held, "the plan of `%.150s`", old.command);
            plan_free(&old);
        }
        plan_free(&now);
    }
    if (same && !force) /* planned again: the jobs already done stay done */
        return 0;
    if (!held[0] || force) { /* no plan (the folder must be new or empty), or --force */
        if (out_dir_check("--plan", dir, force, msg) != 0) {
            cli_error("%s", msg);
            return EXIT_USAGE;
        }
        if (force && out_dir_prepare(dir, 1, msg) != 0) {
            cli_error("%s", msg);
            return EXIT_RUNTIME;
        }
        return 0;
    }
    cli_error("--plan %.200s holds %s, not this one (other options, or another build): pass --force to empty it "
              "first, or give a new folder",
              dir, held);
    return EXIT_USAGE;
}

int plan_start(struct plan *p, const char *dir, const char *kind, int argc, char **argv, uint64_t scene_hash)
{
    char msg[RESTIR_MSG_LEN], command[8192];
    cli_command_line(kind, argc, argv, command, sizeof command);
    if (plan_init(p, dir, kind, argc, argv, command, scene_hash, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    return 0;
}

void plan_add_job(struct plan *p, const char *name, const char *output)
{
    RESTIR_CHECK(p->n_jobs < PLAN_MAX_JOBS);
    if (p->n_jobs == p->cap_jobs) { /* doubling: a plan of 100 000 jobs copies each entry about twice */
        p->cap_jobs = p->cap_jobs ? 2 * p->cap_jobs : 64;
        p->jobs = realloc(p->jobs, sizeof(struct plan_job) * (size_t)p->cap_jobs);
        RESTIR_CHECK(p->jobs != NULL);
    }
    struct plan_job *j = &p->jobs[p->n_jobs++];
    snprintf(j->name, sizeof j->name, "%s", name);
    snprintf(j->output, sizeof j->output, "%s", output);
}

void plan_output_path(const struct plan *p, int k, char *out, size_t len)
{
    snprintf(out, len, "%s/%s", p->dir, p->jobs[k].output);
}

/* Writes text to path through a temporary file. */
static int write_text(const char *path, const char *text, int executable, char *msg)
{
    char tmp[PLAN_PATH_MAX + 64];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "w", msg);
    if (!f)
        return -1;
    fputs(text, f);
    if (executable)
        chmod(tmp, 0755);
    return io_close_commit(f, tmp, path, msg);
}

/* The restir binary running now, so jobs run the same build from any folder. */
static void self_path(char *out, size_t len)
{
    ssize_t n = readlink("/proc/self/exe", out, len - 1);
    out[n > 0 ? n : 0] = '\0';
    if (n <= 0)
        snprintf(out, len, "restir");
}

int plan_write(const struct plan *p, char *msg)
{
    char path[PLAN_PATH_MAX + 64], exe[PLAN_PATH_MAX];
    self_path(exe, sizeof exe);
    if (!plain_path(exe)) {
        snprintf(msg, RESTIR_MSG_LEN, "the restir binary's path %.300s holds spaces or quotes; jobs.txt could not "
                 "name it", exe);
        return -1;
    }
    snprintf(path, sizeof path, "%s/runs/logs", p->dir);
    if (io_make_dirs(path, msg) != 0)
        return -1;

    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "restir_plan", PLAN_FORMAT);
    cJSON_AddStringToObject(j, "kind", p->kind);
    cJSON_AddStringToObject(j, "command", p->command);
    cJSON *desc = cli_options_describe(p->kind, p->argc, p->argv, msg);
    if (!desc) {
        cJSON_Delete(j);
        return -1;
    }
    cJSON_AddItemToObject(j, "options", desc);
    char hex[32];
    snprintf(hex, sizeof hex, "%016llx", (unsigned long long)p->scene_hash);
    cJSON_AddStringToObject(j, "scene_hash", hex);
    cJSON_AddStringToObject(j, "binary", exe);
    cJSON_AddItemToObject(j, "provenance", provenance_to_json(&p->made_by));
    cJSON *jobs = cJSON_AddArrayToObject(j, "jobs");
    for (int k = 0; k < p->n_jobs; k++) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "line", k + 1);
        cJSON_AddStringToObject(o, "name", p->jobs[k].name);
        cJSON_AddStringToObject(o, "output", p->jobs[k].output);
        cJSON_AddItemToArray(jobs, o);
    }
    snprintf(path, sizeof path, "%s/plan.json", p->dir);
    int rc = json_write_file(path, j, msg);
    cJSON_Delete(j);
    if (rc != 0)
        return -1;

    size_t cap = (size_t)p->n_jobs * (strlen(exe) + strlen(p->dir) + 140) + 1, used = 0;
    char *text = xmalloc(cap);
    text[0] = '\0';
    for (int k = 0; k < p->n_jobs; k++)
        used += (size_t)snprintf(text + used, cap - used, "%s job %s %d  # %s\n", exe, p->dir, k + 1, p->jobs[k].name);
    snprintf(path, sizeof path, "%s/jobs.txt", p->dir);
    rc = write_text(path, text, 0, msg);
    free(text);
    if (rc != 0)
        return -1;

    char script[8 * PLAN_PATH_MAX + 2048];
    snprintf(script, sizeof script,
             "#!/bin/sh\n"
             "# A Slurm job array over the %d jobs of this plan (restir %s): array task K runs line K of\n"
             "# jobs.txt. Submit: sbatch %s/slurm.sh; when every task is done: restir %s --merge %s%s\n"
             "#SBATCH --job-name=restir-%s\n"
             "#SBATCH --array=1-%d\n"
             "#SBATCH --cpus-per-task=%d\n"
             "#SBATCH --output=%s/runs/logs/%%A_%%a.out\n"
             "set -eu\n"
             "line=$(sed -n \"${SLURM_ARRAY_TASK_ID}p\" %s/jobs.txt)\n"
             "if [ -z \"$line\" ]; then\n"
             "    echo \"slurm.sh: %s/jobs.txt has no line $SLURM_ARRAY_TASK_ID\" >&2\n"
             "    exit 1\n"
             "fi\n"
             "export OMP_NUM_THREADS=\"${SLURM_CPUS_PER_TASK:-1}\"\n"
             "exec /bin/sh -c \"$line\"\n",
             p->n_jobs, p->kind, p->dir, p->kind, p->dir, strcmp(p->kind, "reference") ? "" : " --out FILE.exr",
             p->kind, p->n_jobs, p->threads > 0 ? p->threads : 1, p->dir, p->dir, p->dir);
    snprintf(path, sizeof path, "%s/slurm.sh", p->dir);
    return write_text(path, script, 1, msg);
}

int plan_finish(struct plan *p)
{
    char msg[RESTIR_MSG_LEN];
    int rc = plan_write(p, msg) == 0 ? 0 : EXIT_RUNTIME;
    if (rc != 0)
        cli_error("%s", msg);
    else
        printf("planned %d jobs in %s: run them with `parallel -j N < %s/jobs.txt` or `sbatch %s/slurm.sh`, then "
               "`restir %s --merge %s%s`\n",
               p->n_jobs, p->dir, p->dir, p->dir, p->kind, p->dir, strcmp(p->kind, "reference") ? "" : " --out FILE.exr");
    plan_free(p);
    return rc;
}

/* A job writes under runs/ of its plan, or of a step's plan one folder down (an evaluation's). */
static int output_in_runs(const char *out)
{
    if (strstr(out, "..") || out[0] == '/')
        return 0;
    if (!strncmp(out, "runs/", 5))
        return 1;
    const char *slash = strchr(out, '/');
    return slash && slash > out && !strncmp(slash + 1, "runs/", 5);
}

int plan_load(const char *dir, struct plan *p, char *msg)
{
    memset(p, 0, sizeof *p);
    char path[PLAN_PATH_MAX + 64], why[RESTIR_MSG_LEN];
    if (!realpath(dir, p->dir)) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: not a plan folder (%s)", dir, strerror(errno));
        return -1;
    }
    snprintf(path, sizeof path, "%s/plan.json", p->dir);
    char *text = io_read_text(path, 64u << 20, why);
    if (!text) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s is not a plan folder: %.180s", dir, why);
        return -1;
    }
    cJSON *j = cJSON_Parse(text);
    free(text);
    const cJSON *kind = cJSON_GetObjectItemCaseSensitive(j, "kind");
    const cJSON *options = cJSON_GetObjectItemCaseSensitive(j, "options");
    const cJSON *jobs = cJSON_GetObjectItemCaseSensitive(j, "jobs");
    const cJSON *hash = cJSON_GetObjectItemCaseSensitive(j, "scene_hash");
    const cJSON *command = cJSON_GetObjectItemCaseSensitive(j, "command");
    const cJSON *made_by = cJSON_GetObjectItemCaseSensitive(j, "provenance");
    if (j && !options && cJSON_GetObjectItemCaseSensitive(j, "args")) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "%.300s: planned by an older restir, which stored the command's arguments instead of its JSON "
                 "description; plan the command again", path);
        cJSON_Delete(j);
        return -1;
    }
    if (!j || !cJSON_IsString(kind) || !cJSON_IsObject(options) || !cJSON_IsArray(jobs) || !cJSON_IsString(hash) ||
        !cJSON_IsString(command) || strlen(kind->valuestring) >= sizeof p->kind ||
        cJSON_GetArraySize(jobs) > PLAN_MAX_JOBS) {
        snprintf(msg, RESTIR_MSG_LEN,
                 "%.300s: not a plan (kind, options, jobs, scene_hash and command are required)", path);
        cJSON_Delete(j);
        return -1;
    }
    if (!made_by) { /* the commit its jobs must run on is unknown: accepting it would let builds mix */
        snprintf(msg, RESTIR_MSG_LEN,
                 "%.300s: planned by a restir without build provenance (before the one-commit rule), so the "
                 "commit its jobs must run on is unknown; plan the command again", path);
        cJSON_Delete(j);
        return -1;
    }
    if (provenance_from_json(made_by, &p->made_by, why) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: %.180s", path, why);
        cJSON_Delete(j);
        return -1;
    }
    snprintf(p->kind, sizeof p->kind, "%s", kind->valuestring);
    snprintf(p->command, sizeof p->command, "%s", command->valuestring);
    p->scene_hash = strtoull(hash->valuestring, NULL, 16);
    char why_options[RESTIR_MSG_LEN];
    if (plan_set_arguments(p, options, why_options) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.200s: %.280s", path, why_options);
        cJSON_Delete(j);
        plan_free(p);
        return -1;
    }
    int bad = 0;
    const cJSON *o;
    cJSON_ArrayForEach(o, jobs)
    {
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(o, "name");
        const cJSON *out = cJSON_GetObjectItemCaseSensitive(o, "output");
        if (!cJSON_IsString(name) || !cJSON_IsString(out) || !output_in_runs(out->valuestring)) {
            bad = 1;
            break;
        }
        plan_add_job(p, name->valuestring, out->valuestring);
    }
    cJSON_Delete(j);
    if (bad) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: a job entry is malformed", path);
        plan_free(p);
        return -1;
    }
    return 0;
}

int plan_load_kind(const char *dir, const char *kind, const char *what, struct plan *p)
{
    char msg[RESTIR_MSG_LEN];
    if (plan_load(dir, p, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_RUNTIME;
    }
    if (strcmp(p->kind, kind) != 0) {
        cli_error("%s holds a plan of `restir %s`, not of %s", p->dir, p->kind, what);
        plan_free(p);
        return EXIT_USAGE;
    }
    const int rc = plan_check_build(p);
    if (rc != 0)
        plan_free(p);
    return rc;
}

int plan_check_build(const struct plan *p)
{
    struct provenance self;
    provenance_now(&self, 0);
    if (provenance_same_build(&p->made_by, &self))
        return 0;
    char planned[PROVENANCE_COMMIT_LEN + 8], binary[PROVENANCE_COMMIT_LEN + 8];
    provenance_build_id(&p->made_by, planned, sizeof planned);
    provenance_build_id(&self, binary, sizeof binary);
    cli_error("%s/plan.json: a campaign runs on one commit: this plan was made by %s, this binary is %s; re-plan "
              "or build %s", p->dir, planned, binary, p->made_by.commit);
    return EXIT_USAGE;
}

void plan_note_job_machine(const struct plan *p, int k, int threads)
{
    char path[PLAN_PATH_MAX + 64], logs[PLAN_PATH_MAX + 32], msg[RESTIR_MSG_LEN];
    snprintf(path, sizeof path, "%s/runs/logs/job_%d.json", p->dir, k + 1);
    struct stat st;
    if (stat(path, &st) == 0)
        return;
    snprintf(logs, sizeof logs, "%s/runs/logs", p->dir);
    if (io_make_dirs(logs, msg) != 0)
        return;
    struct provenance m;
    provenance_now(&m, threads);
    cJSON *j = provenance_to_json(&m);
    (void)json_write_file(path, j, msg);
    cJSON_Delete(j);
}

void plan_free(struct plan *p)
{
    for (int i = 0; i < p->argc; i++)
        free(p->argv[i]);
    free(p->argv);
    free(p->jobs);
    p->argv = NULL;
    p->jobs = NULL;
    p->argc = p->n_jobs = p->cap_jobs = 0;
}

int plan_check_jobs(const struct plan *p, int (*valid)(const struct plan *p, int k, char *why, void *ctx), void *ctx,
                    char *msg)
{
    char list[RESTIR_MSG_LEN] = "", why[RESTIR_MSG_LEN], first_why[RESTIR_MSG_LEN] = "";
    int missing = 0;
    for (int k = 0; k < p->n_jobs; k++) {
        if (valid(p, k, why, ctx) == 0)
            continue;
        if (missing == 0)
            snprintf(first_why, sizeof first_why, "%s", why);
        if (missing < 8)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%sline %d (%s)", missing ? ", " : "", k + 1,
                     p->jobs[k].name);
        missing++;
    }
    if (missing == 0)
        return 0;
    snprintf(msg, RESTIR_MSG_LEN, "%d of %d jobs of %.80s are missing or corrupt: %.200s%s; first: %.140s", missing,
             p->n_jobs, p->dir, list, missing > 8 ? ", ..." : "", first_why);
    return -1;
}

int plan_check_scene(const struct plan *p, uint64_t scene_hash)
{
    if (scene_hash == p->scene_hash)
        return 0;
    cli_error("the scene of %s/plan.json changed since the plan was made (its content hash differs); plan again",
              p->dir);
    return EXIT_RUNTIME;
}

int plan_copy_file(const char *src, const char *dst, char *msg)
{
    FILE *in = fopen(src, "rb");
    if (!in) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: %s", src, strerror(errno));
        return -1;
    }
    char tmp[PLAN_PATH_MAX + 400];
    FILE *out = io_open_temp(dst, tmp, sizeof tmp, "wb", msg);
    if (!out) {
        fclose(in);
        return -1;
    }
    char buf[1 << 16];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, in)) > 0)
        fwrite(buf, 1, n, out);
    const int bad = ferror(in);
    fclose(in);
    if (bad) {
        fclose(out);
        remove(tmp);
        snprintf(msg, RESTIR_MSG_LEN, "%.200s: reading failed while copying to %.200s", src, dst);
        return -1;
    }
    return io_close_commit(out, tmp, dst, msg);
}

int plan_blob_write(const char *path, const char magic[8], uint64_t id, const void *const *parts, const size_t *sizes,
                    int n, char *msg)
{
    char tmp[PLAN_PATH_MAX + 64];
    FILE *f = io_open_temp(path, tmp, sizeof tmp, "wb", msg);
    if (!f)
        return -1;
    uint64_t size = 0;
    for (int i = 0; i < n; i++)
        size += sizes[i];
    uint64_t h = FNV1A64_BASIS;
    h = fnv1a64(h, magic, 8);
    h = fnv1a64(h, &id, sizeof id);
    h = fnv1a64(h, &size, sizeof size);
    fwrite(magic, 1, 8, f);
    fwrite(&id, sizeof id, 1, f);
    fwrite(&size, sizeof size, 1, f);
    for (int i = 0; i < n; i++) {
        fwrite(parts[i], 1, sizes[i], f);
        h = fnv1a64(h, parts[i], sizes[i]);
    }
    fwrite(&h, sizeof h, 1, f);
    return io_close_commit(f, tmp, path, msg);
}

int plan_blob_read(const char *path, const char magic[8], uint64_t id, void **payload, size_t *size, char *msg)
{
    *payload = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: %s", path, strerror(errno));
        return errno == ENOENT ? 1 : -1;
    }
    char m[8];
    uint64_t fid = 0, n = 0, stored = 0;
    int ok = fread(m, 1, 8, f) == 8 && fread(&fid, sizeof fid, 1, f) == 1 && fread(&n, sizeof n, 1, f) == 1;
    if (!ok || memcmp(m, magic, 8) != 0) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: not a %.8s result", path, magic);
        fclose(f);
        return -1;
    }
    if (fid != id) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: written for another plan (its arguments differ)", path);
        fclose(f);
        return -1;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || (uint64_t)st.st_size != 8 + 2 * sizeof(uint64_t) + n + sizeof(uint64_t)) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: truncated or padded (%lld bytes for a payload of %llu)", path,
                 (long long)st.st_size, (unsigned long long)n);
        fclose(f);
        return -1;
    }
    unsigned char *data = xmalloc(n ? (size_t)n : 1);
    ok = fread(data, 1, (size_t)n, f) == n && fread(&stored, sizeof stored, 1, f) == 1;
    fclose(f);
    uint64_t h = FNV1A64_BASIS;
    h = fnv1a64(h, m, 8);
    h = fnv1a64(h, &fid, sizeof fid);
    h = fnv1a64(h, &n, sizeof n);
    h = fnv1a64(h, data, (size_t)n);
    if (!ok || h != stored) {
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: checksum mismatch (corrupt)", path);
        free(data);
        return -1;
    }
    *payload = data;
    *size = (size_t)n;
    return 0;
}
