/* evaluate_papers.h: the papers' evaluations as `restir study` / `restir compare` commands. Each paper
 * is a recipe, struct eval_paper (its rows live in evaluate_recipes.c): its defaults, scenes,
 * configurations, steps with their method specs and settings, and the writer of each step's table.
 * evaluate_papers.c plans the steps from the recipes. Must never run a command or read results:
 * cmd_evaluate.c runs the steps, the recipes' table writers (evaluate_tables.c) read their tables. */
#ifndef RESTIR_EXPERIMENTS_EVALUATE_PAPERS_H
#define RESTIR_EXPERIMENTS_EVALUATE_PAPERS_H

#define EVAL_MAX_STEPS 24
#define EVAL_MAX_ARGS 48
#define EVAL_MAX_VARIANTS 8
#define EVAL_PAPER_WIDTH 1920 /* every paper evaluates at 1920x1080 */
#define EVAL_PAPER_HEIGHT 1080

/* What `restir evaluate` was asked for; 0 / "" fields take the papers' values. */
struct eval_options {
    char paper[8]; /* 000, 004, 002 or all */
    int width, height, runs, frames, warmup, ref_spp, threads;
    char scenes[256]; /* comma-separated scenes instead of each paper's defaults */
    char configs[256]; /* a subset of the paper's named configurations (eval_paper.configs; "": all) */
    int report;       /* --report: the steps' pages and the evaluation's index.html */
    int partial;      /* --tables --partial: steps without their tables are named, not refused */
    int force;        /* --force: empty a folder that holds anything but this evaluation first */
    int resume;       /* --resume: the folder must hold this evaluation, to continue it */
};

struct eval_step;
struct eval_paper;
struct md_text;
struct claims;
struct step_tables;

/* Writes one merged step's tables into md and its claims into cl, reading d (the step's
 * study.csv / compare.csv and runs.csv) and, where it needs more, files of DIR/STEP. Returns 0, or
 * an exit code having said why. Single-threaded. */
typedef int eval_table_writer(struct md_text *md, struct claims *cl, const struct eval_options *o, const char *dir,
                              const struct eval_step *s, const struct step_tables *d);

/* A row of a compare step's table: the method spec's suffix after the step's base method (or the
 * whole spec when the step has no base), the row's name in the table, and for the variants the
 * paper's claims compare, the claim's short name. */
struct eval_variant {
    const char *spec, *name, *claim;
};

/* The paper a scene of ours stands in for (e.g. forest for EMERALD SQUARE), and why. */
struct eval_scene_note {
    const char *scene, *stands_for, *why;
};

/* One command of a paper's recipe, planned once per scene (or once, on the first scene). Its
 * arguments are the options every step shares, then in this order those its fields give:
 * --camera path (a paper without warm-up), --method, --warmup, --configs, --methods, extra, --set. */
struct eval_step_recipe {
    const char *kind;   /* study or compare */
    const char *folder; /* the folder's name after PAPER-SCENE- ("": PAPER-SCENE) */
    const char *base;   /* the method the variants modify (restir-pt, restir-di) or "": whole specs */
    int paper_ran_base; /* 1: the paper itself evaluated base; 0: its claims are carried over to it */
    int first_scene_only; /* once, on the first scene, after every scene's other steps */
    const char *method;   /* a study's --method, or NULL */
    int configs;          /* a study of the paper's named configurations (--warmup, --configs) */
    const struct eval_variant *variants; /* a compare's --methods: base + each spec, in table order */
    int nvariants;
    const char *const *extra;    /* further arguments as given, NULL-terminated (NULL: none) */
    const char *const *settings; /* --set KEY=VALUE of every method, NULL-terminated (NULL: none) */
    eval_table_writer *table;    /* writes its tables and claims once merged */
};

/* A paper's evaluation: what `restir evaluate ID` plans and how its section of evaluation.md reads. */
struct eval_paper {
    const char *id;    /* 000, 004, 002 */
    const char *title; /* its section's heading */
    int runs;          /* independent runs per configuration unless --runs */
    int frames;        /* measured frames unless --frames */
    int warmup;        /* frames before measuring with a static camera unless --warmup; 0: a camera path, whose
                          last frame's error is measured */
    const char *default_scenes; /* comma-separated, unless --scenes */
    int radius;                 /* its largest pixel radius: the image must hold its disk */
    const char *radius_what;    /* what reaches that radius, for the refusal */
    /* its named configurations in the order its study runs them (NULL: none; NULL-terminated): the
     * first configs_every_scene on every scene, all of them on the first */
    const char *const *configs;
    int configs_every_scene;
    const char *baseline, *baseline_why; /* the configuration --configs must keep, and why */
    const char *configs_whole; /* what the whole evaluation runs, said when --configs keeps a subset */
    const struct eval_scene_note *scenes; /* the scenes of ours that stand in for its own, {NULL} last */
    const char *setup_note; /* its claims' departures from the paper beyond resolution and scene */
    int where_names_base;   /* its claims' "where" names the step's base method with the scene */
    const struct eval_step_recipe *steps;
    int nsteps;
};

/* The papers in the order `restir evaluate all` runs them (NULL-terminated). */
extern const struct eval_paper *const eval_papers[];
/* The paper of that id, or NULL for an unknown id (or NULL). */
const struct eval_paper *eval_paper_find(const char *id);

/* One command of an evaluation: `restir KIND ARGS...` planned into DIR/NAME. */
struct eval_step {
    char paper[4]; /* 000, 004 or 002 */
    char name[64]; /* its folder: e.g. 004-pillars-restir-pt */
    char kind[8];  /* study or compare */
    char scene[32];
    char base[24]; /* the method the paper's variants modify (restir-pt, restir-di) or "" */
    int all_configs; /* a study of the paper's configurations on its first scene: all of them, not only
                        those of every scene (000: Table 2's R x K grid) */
    const struct eval_paper *recipe;           /* the paper's recipe (static storage) */
    const struct eval_step_recipe *step_recipe; /* the recipe's step it was planned from */
    int argc;
    char *argv[EVAL_MAX_ARGS];
    char text[4096]; /* the arguments' storage */
};

/* The steps of o->paper ("all": every paper of eval_papers in turn) into steps (at most
 * EVAL_MAX_STEPS). Returns 0, or -1 with msg (RESTIR_MSG_LEN): an unknown paper, a resolution
 * below what the paper's pixel radii allow (named), or --configs naming what the paper does not
 * run or leaving out its baseline. */
int eval_steps(const struct eval_options *o, struct eval_step *steps, int *n, char *msg);
/* The parameters a step runs with that its tables state: frames, warm-up, runs, reference paths;
 * --frames / --warmup / --runs when given, else the paper's (an unknown paper id: the defaults of
 * the last paper, as before recipes existed; callers pass ids of planned steps). */
int eval_frames(const struct eval_options *o, const char *paper);
int eval_warmup(const struct eval_options *o, const char *paper);
int eval_runs(const struct eval_options *o, const char *paper);
int eval_ref_spp(const struct eval_options *o);

#endif
