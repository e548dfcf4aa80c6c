/* plan.h: plan folders: long commands split into independent jobs, run anywhere, then merged.
 * Must never implement a method or know a command's results. */
#ifndef RESTIR_EXPERIMENTS_PLAN_H
#define RESTIR_EXPERIMENTS_PLAN_H

#include <stddef.h>
#include <stdint.h>

#include "experiments/provenance.h"

/* A plan folder holds plan.json (the command's kind, its JSON description (options.h) and its jobs), jobs.txt (one
 * shell command per job: `restir job DIR K`, for GNU parallel), slurm.sh (an `sbatch --array`
 * script that runs line $SLURM_ARRAY_TASK_ID of jobs.txt) and runs/, the only place jobs write,
 * each its own output, atomically. */

/* plan.json's "restir_plan": 2 stores the command's JSON description ("options"); 3 adds "provenance",
 * the build that made the plan: a campaign runs on one commit, and plans without it are refused */
#define PLAN_FORMAT 3
#define PLAN_MAX_JOBS 100000
#define PLAN_PATH_MAX 4096
#define PLAN_NAME_MAX 256 /* a job's name: an evaluate step, a spec of up to SPEC_MAX characters, a run */

struct plan_job {
    char name[PLAN_NAME_MAX]; /* what the job computes, for messages ("config compat, run 3") */
    char output[160]; /* its result, relative to the plan folder (under runs/) */
};

struct plan {
    char dir[PLAN_PATH_MAX]; /* absolute */
    char kind[16];           /* "study", "reference", "compare" or "evaluate": the command whose jobs these are */
    char command[8192];      /* the command as it was given, for reports */
    int argc;
    char **argv;             /* the command's arguments without --plan DIR, file paths made absolute */
    uint64_t id;             /* hash of kind, arguments and build: every result file carries it */
    uint64_t scene_hash;     /* scene_content_hash when planned: jobs refuse a changed scene */
    int threads;             /* --threads of the command (0: not given): Slurm's CPUs per task */
    struct provenance made_by; /* the build (and machine, date) that made the plan */
    int n_jobs, cap_jobs;
    struct plan_job *jobs;
};

/* Starts a plan of `restir kind` in dir (made, if missing) from the command's arguments, copying
 * them without --plan DIR and with --scene FILE and --ref FILE made absolute; the command line is
 * kept for reports. Returns 0, or an exit code having said why. */
int plan_start(struct plan *p, const char *dir, const char *kind, int argc, char **argv, uint64_t scene_hash);
/* Before `restir KIND ... --plan dir`: dir may be new, empty, or hold this very plan (the same
 * arguments, --force and --resume aside, and build), which is planned again with its finished jobs
 * kept. Any other folder is refused (EXIT_USAGE, said why, nothing touched). With force any folder
 * is emptied first, so the plan starts over (out_dir.h: only a folder restir wrote, never / or
 * $HOME or the current folder). Returns 0 or an exit code. */
int plan_folder_claim(const char *dir, const char *kind, int argc, char **argv, int force);
void plan_add_job(struct plan *p, const char *name, const char *output);
/* Writes dir/plan.json, dir/jobs.txt, dir/slurm.sh and makes dir/runs/logs. Returns 0, or -1 with
 * msg. */
int plan_write(const struct plan *p, char *msg);
/* plan_write, then says how to run the jobs and merge them, and frees p. Returns an exit code. */
int plan_finish(struct plan *p);
/* Reads dir/plan.json. Returns 0, or -1 with msg naming the folder and the problem (a plan.json
 * without "provenance", written before the one-commit rule, is refused: plan again). */
int plan_load(const char *dir, struct plan *p, char *msg);
void plan_free(struct plan *p);
/* plan_load for a merge, which needs a plan of kind (what: "a study" ...) made by this binary's
 * build (plan_check_build). Returns 0, or an exit code having said why (p is then freed). */
int plan_load_kind(const char *dir, const char *kind, const char *what, struct plan *p);
/* The one-commit rule: a campaign's jobs and merges run on the build that made its plan. 0 when
 * p->made_by is this binary's build (commit and dirty flag); else it says so, naming the plan and
 * both builds, and returns EXIT_USAGE. */
int plan_check_build(const struct plan *p);
/* After job k (0-based) succeeded: records the machine that ran it (provenance.h: CPU, threads,
 * date; threads: the job's --threads, 0: OpenMP's) as dir/runs/logs/job_K.json (K 1-based), unless
 * a record is there already (the machine that first computed it). Best effort: a record that
 * cannot be written is left out silently. */
void plan_note_job_machine(const struct plan *p, int k, int threads);
/* Absolute path of job k's (0-based) output. */
void plan_output_path(const struct plan *p, int k, char *out, size_t len);
/* Checks that every job finished: valid(p, k, why, ctx) says whether job k's output is there and
 * sound (0) or not (-1, why: RESTIR_MSG_LEN). Returns 0, or -1 with msg naming the missing or
 * corrupt jobs by line of jobs.txt (the first few, and how many in all). */
int plan_check_jobs(const struct plan *p, int (*valid)(const struct plan *p, int k, char *why, void *ctx), void *ctx,
                    char *msg);

/* 0 when scene_hash (scene_content_hash of what a job or merge loaded) is the plan's; else it says
 * the scene changed since planning and returns EXIT_RUNTIME. */
int plan_check_scene(const struct plan *p, uint64_t scene_hash);
/* Copies src to dst through a temporary name. Returns 0, or -1 with msg. */
int plan_copy_file(const char *src, const char *dst, char *msg);

/* A job's binary result: an 8-byte magic, the plan id, the payload size, the payload (parts
 * concatenated) and an FNV-1a 64 checksum of everything before it; written to a temporary name
 * and renamed. Returns 0, or -1 with msg. */
int plan_blob_write(const char *path, const char magic[8], uint64_t id, const void *const *parts, const size_t *sizes,
                    int n, char *msg);
/* Reads such a file into a new malloc'ed payload. Returns 0; 1 when the file does not exist; -1
 * with msg when it is of another kind or plan, truncated, or fails its checksum. */
int plan_blob_read(const char *path, const char magic[8], uint64_t id, void **payload, size_t *size, char *msg);

#endif
