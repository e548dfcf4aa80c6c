/* options.h: the options the subcommands share, parsed once into struct cli_options.
 * Must never run a render. */
#ifndef RESTIR_EXPERIMENTS_OPTIONS_H
#define RESTIR_EXPERIMENTS_OPTIONS_H

#include <stdio.h>

#include "render/params.h"

struct cli_options {
    const char *scene;
    const char *method;
    const char *methods; /* compare: comma-separated */
    const char *ref;
    const char *out;
    int frames;
    int frame;           /* reference: camera of this frame */
    int equal_time;
    int report;          /* compare, study: write DIR/index.html */
    int self_contained;  /* compare, study: the report holds its images (data: URIs) */
    const char *camera_file; /* render: --camera FILE, one camera per frame (restir view records them) */
    const char *env;         /* --env FILE|none: the environment light replacing the scene's own */
    const char *script;      /* view: timed input (src/view/view_script.h) */
    long long max_memory_mb; /* --max-memory: refuse renders estimated above it (0: what the system has) */
    int frames_given;
    int ref_spp;         /* compare: spp of the reference rendered when --ref is absent */
    int save_all;        /* render: write every frame (1) or only the last (0) */
    int help;
    int spp_given;
    int res_given;
    const char *configs; /* study, evaluate: comma-separated configurations */
    const char *scenes;  /* evaluate: comma-separated scenes */
    const char *radii;   /* study: comma-separated radii */
    int runs;            /* study: independent sequences per configuration; compare: per spec */
    int ref_every;       /* compare: also measure frames K-1, 2K-1, ... against their own references */
    int warmup;          /* study: frames before measuring */
    int hard_neighbors;  /* study: enum restir_hard_neighbors, which neighbors the hard-pixel ratio counts */
    double checkpoint_every; /* reference: seconds between checkpoints (< 0: none, 0: every chunk) */
    double target_relmse;    /* reference: stop at this estimated relMSE (0: render --spp samples) */
    const char *plan;        /* study, reference, compare: write jobs into this folder instead of running */
    const char *merge;       /* study, reference, compare: merge the finished jobs of this plan folder */
    const char *check;       /* evaluate: check the recorded settings of the steps under this folder */
    const char *tables;      /* evaluate: write the tables of this evaluation from its steps' small files */
    int partial;             /* evaluate --tables: leave out the steps without tables */
    int shards;              /* reference --plan: jobs the samples are split into (0: not given) */
    int force;               /* --force: empty a non-empty --out (or --plan) folder first, replace an --out file */
    int resume;              /* --resume: continue the run --out holds (reference, evaluate), never start anew */
    struct render_params params;
    /* the --set assignments as given, in order (checked against the method that reads them) */
#define CLI_MAX_SETS 128
    const char *sets[CLI_MAX_SETS];
    int n_sets;
    /* options that stand for a setting (--denoise X): their "key=value" texts, which sets points at */
#define CLI_MAX_SETTING_TEXTS 8
    char setting_texts[CLI_MAX_SETTING_TEXTS][80];
    int n_setting_texts;
    /* --params FILE: the strings it names (scene, method, camera file) live here */
    char params_scene[4096], params_method[128], params_camera[4096], params_env[4096];
};

/* The defaults of `command`'s options (the option table's, then the settings table's). */
void cli_options_defaults(const char *command, struct cli_options *o);
/* Parses argv[0..argc) for `command` through the option table (options.c): each option's
 * commands, value kind, range and default are one row there. Returns 0, or -1 with msg naming the
 * bad option or value. */
int cli_parse_options(const char *command, int argc, char **argv, struct cli_options *o, char *msg);
/* 1 when `name` is an option of `command` that takes a value (the next argument is not a
 * positional one), or, when `command` does not read it, an option of another command that takes a
 * value there (so that the option with its value reaches cli_parse_options, which refuses it). Each
 * command accepts only the options that it reads: cli_parse_options refuses another command's
 * option by name, naming the commands that read it, and suggests the nearest option of `command`
 * for a misspelt one. */
int cli_option_takes_value(const char *command, const char *name);
/* A command's arguments as a JSON description, through the option table: an object whose keys are
 * option names without "--" with typed values (numbers for counts and seconds, true for flags,
 * strings otherwise; seeds as strings, which keep all 64 bits), "set": an array of "key=value" in
 * the order given, and "positional": the arguments that are no option (evaluate's paper). An option
 * given twice keeps its last value. Returns a new object, or NULL with msg naming an unknown option
 * or a missing value. */
struct cJSON *cli_options_describe(const char *command, int argc, char **argv, char *msg);
/* The arguments a description stands for, in the table's order (options, then settings, then
 * positionals): *argv is malloc'ed with its strings (cli_options_free_argv). Returns 0, or -1 with
 * msg naming an unknown key or a value of the wrong type. */
int cli_options_argv(const char *command, const struct cJSON *desc, int *argc, char ***argv, char *msg);
void cli_options_free_argv(int argc, char **argv);
/* Prints the options `command` takes, from the table, with their defaults. */
void cli_options_help(FILE *out, const char *command);

#endif
