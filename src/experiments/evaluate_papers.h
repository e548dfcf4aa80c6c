/* evaluate_papers.h: the papers' evaluations as `restir study` / `restir compare` commands (evaluate_papers.c):
 * which scenes, configurations and parameters each paper's tables need. Must never run a
 * command or read results: cmd_evaluate.c runs the steps, evaluate_tables.c reads their tables. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_PAPERS_H
#define RESTIR_EXPERIMENTS_EVALUATE_PAPERS_H

#define EVAL_MAX_STEPS 24
#define EVAL_MAX_ARGS 48
#define EVAL_PAPER_WIDTH 1920 /* every paper evaluates at 1920x1080 */
#define EVAL_PAPER_HEIGHT 1080

/* What `restir evaluate` was asked for; 0 / "" fields take the papers' values. */
struct eval_options {
    char paper[8]; /* 000, 004, 002 or all */
    int width, height, runs, frames, warmup, ref_spp, threads;
    char scenes[256]; /* comma-separated scenes instead of each paper's defaults */
    char configs[256]; /* 000: comma-separated configurations to run, a subset of eval_000_configs ("": all) */
    int report;       /* --report: the steps' pages and the evaluation's index.html */
    int partial;      /* --tables --partial: steps without their tables are named, not refused */
    int force;        /* --force: empty a folder that holds anything but this evaluation first */
    int resume;       /* --resume: the folder must hold this evaluation, to continue it */
};

/* One command of an evaluation: `restir KIND ARGS...` planned into DIR/NAME. */
struct eval_step {
    char paper[4]; /* 000, 004 or 002 */
    char name[64]; /* its folder: e.g. 004-pillars-restir-pt */
    char kind[8];  /* study or compare */
    char scene[32];
    char base[24]; /* the method the paper's variants modify (restir-pt, restir-di) or "" */
    int table2;    /* 000: this study also holds Table 2's R x K grid */
    int ablation;  /* 004: SPMIS's own variants (Figures 2, 6, 7) */
    int argc;
    char *argv[EVAL_MAX_ARGS];
    char text[4096]; /* the arguments' storage */
};

/* The paper a scene of ours stands in for (e.g. forest for EMERALD SQUARE), and why. */
struct eval_scene_note {
    const char *paper, *scene, *stands_for, *why;
};
extern const struct eval_scene_note eval_scene_notes[];

/* 000's configurations in the order its study runs them: Table 1's four (Bitterli R = 30 and the
 * presets; every scene), then Table 2's R x K grid and Figure 3's radii (the first scene only). */
extern const char *const eval_000_configs[];
#define EVAL_000_TABLE1_CONFIGS 4

/* 004's main table: the reuse variants each step runs, as suffixes of the base method's spec (the
 * first, "", is standard reuse), in the order of the table's rows. */
#define EVAL_004_ROWS 5
extern const char *const eval_004_suffixes[EVAL_004_ROWS];

/* The steps of o->paper ("all": 000, 004 and 002 in turn) into steps (at most EVAL_MAX_STEPS).
 * Returns 0, or -1 with msg (RESTIR_MSG_LEN): an unknown paper, a resolution below what the
 * paper's pixel radii allow (named), or --configs naming what 000 does not run or leaving out its
 * baseline. */
int eval_steps(const struct eval_options *o, struct eval_step *steps, int *n, char *msg);
/* The parameters a step runs with that its tables state: frames, warm-up, runs, reference paths. */
int eval_frames(const struct eval_options *o, const char *paper);
int eval_warmup(const struct eval_options *o);
/* Runs per configuration of paper ("000", "004", "002"): --runs, else the paper's default (002: 8, the others 4). */
int eval_runs(const struct eval_options *o, const char *paper);
int eval_ref_spp(const struct eval_options *o);

#endif
