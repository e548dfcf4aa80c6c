/* provenance.h: where a result comes from (provenance.c): the build (commit, whether its tracked
 * files differed from the commit, build type) and the machine (CPU model, threads) and time that
 * made it, to and from JSON and as one line of markdown. Plans record the build that made them
 * (a campaign runs on one commit, plan.h); an evaluation's steps record it with their settings
 * (evaluate_record.h). Must never run a render or read a command's results. */
#ifndef RESTIR_EXPERIMENTS_PROVENANCE_H
#define RESTIR_EXPERIMENTS_PROVENANCE_H

#include <stddef.h>

struct cJSON;

#define PROVENANCE_COMMIT_LEN 48

/* A value type: no pointers, copied freely; every string NUL-terminated. */
struct provenance {
    char commit[PROVENANCE_COMMIT_LEN]; /* git rev-parse --short=12 HEAD at build time, or "unknown" */
    int dirty;                          /* 1: tracked files differed from the commit when it was built */
    char build_type[24];                /* CMake's build type (Release, Debug, ...), or "unknown" */
    char cpu[128];                      /* /proc/cpuinfo's model name, or "unknown CPU" */
    int threads;                        /* OpenMP threads it ran with */
    char date[32];                      /* UTC, ISO 8601: 2026-12-06T14:03:59Z */
};

/* This binary's build, this machine and now: threads > 0 as given (a command's --threads), else
 * omp_get_max_threads(). Reads /proc/cpuinfo; safe from any thread (no shared state). */
void provenance_now(struct provenance *p, int threads);
/* "abc123def456" or "abc123def456-dirty": the build's identity, which the one-commit rule compares
 * (out: at least PROVENANCE_COMMIT_LEN + 8 bytes). */
void provenance_build_id(const struct provenance *p, char *out, size_t len);
/* 1 when a and b are the same build (commit and dirty flag), else 0. */
int provenance_same_build(const struct provenance *a, const struct provenance *b);

/* A new JSON object {"version" (this binary's, restir --version), "commit", "dirty", "build_type",
 * "cpu", "threads", "date"} (the caller owns it; cJSON_Delete). */
struct cJSON *provenance_to_json(const struct provenance *p);
/* Reads such an object: commit is required, the other keys default to unknown / 0 when absent.
 * Returns 0, or -1 with msg (RESTIR_MSG_LEN) when j is not an object, commit is missing or a
 * value has the wrong type or does not fit. p is left zeroed on failure; j may be NULL (an error). */
int provenance_from_json(const struct cJSON *j, struct provenance *p, char *msg);
/* One line of markdown: "commit abc123def456 (clean), Release, AMD EPYC 7B13, 2 threads,
 * 2026-12-06" (out: len bytes, truncated to fit). */
void provenance_text(const struct provenance *p, char *out, size_t len);

#endif
