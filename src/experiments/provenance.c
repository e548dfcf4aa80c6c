/* provenance.c: the build, machine and time a result comes from (provenance.h).
 * Must never run a render or read a command's results. */
#include "experiments/provenance.h"

#include <cjson/cJSON.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <restir/version.h>

#include "core/check.h"
#include "experiments/report_commit.h"

/* The first "model name" of /proc/cpuinfo into out, else "unknown CPU". */
static void cpu_model(char *out, size_t len)
{
    snprintf(out, len, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        const char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) != 0 || !colon)
            continue;
        colon++;
        while (*colon == ' ' || *colon == '\t')
            colon++;
        snprintf(out, len, "%s", colon);
        out[strcspn(out, "\n")] = '\0';
        break;
    }
    fclose(f);
}

void provenance_now(struct provenance *p, int threads)
{
    memset(p, 0, sizeof *p);
    snprintf(p->commit, sizeof p->commit, "%s", RESTIR_GIT_COMMIT);
    p->dirty = RESTIR_GIT_DIRTY ? 1 : 0;
    snprintf(p->build_type, sizeof p->build_type, "%s", RESTIR_BUILD_TYPE);
    cpu_model(p->cpu, sizeof p->cpu);
    p->threads = threads > 0 ? threads : omp_get_max_threads();
    const time_t now = time(NULL);
    struct tm utc;
    gmtime_r(&now, &utc);
    strftime(p->date, sizeof p->date, "%Y-%m-%dT%H:%M:%SZ", &utc);
}

void provenance_build_id(const struct provenance *p, char *out, size_t len)
{
    snprintf(out, len, "%s%s", p->commit, p->dirty ? "-dirty" : "");
}

int provenance_same_build(const struct provenance *a, const struct provenance *b)
{
    return !strcmp(a->commit, b->commit) && !a->dirty == !b->dirty;
}

cJSON *provenance_to_json(const struct provenance *p)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "version", RESTIR_VERSION_STRING); /* restir --version's; not read back */
    cJSON_AddStringToObject(j, "commit", p->commit);
    cJSON_AddBoolToObject(j, "dirty", p->dirty);
    cJSON_AddStringToObject(j, "build_type", p->build_type);
    cJSON_AddStringToObject(j, "cpu", p->cpu);
    cJSON_AddNumberToObject(j, "threads", p->threads);
    cJSON_AddStringToObject(j, "date", p->date);
    return j;
}

/* String member key of j into out (len bytes) when present; -1 with msg when it is not a string
 * or does not fit. */
static int read_string(const cJSON *j, const char *key, char *out, size_t len, char *msg)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(j, key);
    if (!v)
        return 0;
    if (!cJSON_IsString(v) || strlen(v->valuestring) >= len) {
        snprintf(msg, RESTIR_MSG_LEN, "provenance: \"%s\" must be a string of at most %zu characters", key, len - 1);
        return -1;
    }
    snprintf(out, len, "%s", v->valuestring);
    return 0;
}

int provenance_from_json(const cJSON *j, struct provenance *p, char *msg)
{
    memset(p, 0, sizeof *p);
    snprintf(p->build_type, sizeof p->build_type, "unknown");
    snprintf(p->cpu, sizeof p->cpu, "unknown CPU");
    if (!cJSON_IsObject(j)) {
        snprintf(msg, RESTIR_MSG_LEN, "provenance: not a JSON object");
        return -1;
    }
    const cJSON *commit = cJSON_GetObjectItemCaseSensitive(j, "commit");
    const cJSON *dirty = cJSON_GetObjectItemCaseSensitive(j, "dirty");
    const cJSON *threads = cJSON_GetObjectItemCaseSensitive(j, "threads");
    int rc = 0;
    if (!cJSON_IsString(commit) || !commit->valuestring[0]) {
        snprintf(msg, RESTIR_MSG_LEN, "provenance: \"commit\" is required (a string)");
        rc = -1;
    } else if (dirty && !cJSON_IsBool(dirty)) {
        snprintf(msg, RESTIR_MSG_LEN, "provenance: \"dirty\" must be true or false");
        rc = -1;
    } else if (threads && (!cJSON_IsNumber(threads) || threads->valuedouble < 0 || threads->valuedouble > 1e6)) {
        snprintf(msg, RESTIR_MSG_LEN, "provenance: \"threads\" must be a count");
        rc = -1;
    }
    if (rc == 0)
        rc = read_string(j, "commit", p->commit, sizeof p->commit, msg) != 0 ||
                     read_string(j, "build_type", p->build_type, sizeof p->build_type, msg) != 0 ||
                     read_string(j, "cpu", p->cpu, sizeof p->cpu, msg) != 0 ||
                     read_string(j, "date", p->date, sizeof p->date, msg) != 0
                 ? -1
                 : 0;
    if (rc != 0) {
        memset(p, 0, sizeof *p);
        return -1;
    }
    p->dirty = cJSON_IsTrue(dirty);
    p->threads = threads ? (int)threads->valuedouble : 0;
    return 0;
}

void provenance_text(const struct provenance *p, char *out, size_t len)
{
    char day[16];
    if (p->date[0])
        snprintf(day, sizeof day, "%.10s", p->date);
    else
        snprintf(day, sizeof day, "unknown date");
    snprintf(out, len, "commit %s (%s), %s, %s, %d thread%s, %s", p->commit, p->dirty ? "dirty" : "clean",
             p->build_type, p->cpu, p->threads, p->threads == 1 ? "" : "s", day);
}
