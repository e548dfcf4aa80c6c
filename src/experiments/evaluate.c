/* evaluate.c: a paper's evaluation at its own scale as one plan of study / compare plans (evaluate.h):
 * its options, the plan of its steps (each planned through the study or compare harness), its jobs,
 * and the merge that writes the paper's tables and a verdict per claim (evaluate_tables.c).
 * Must never implement a method or measure an image: the steps do. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "experiments/evaluate.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_plan.h"
#include "experiments/compare_run.h"
#include "experiments/evaluate_record.h"
#include "experiments/evaluate_tables.h"
#include "experiments/options.h"
#include "experiments/out_dir.h"
#include "experiments/plan.h"
#include "experiments/study.h"
#include "io/atomic_file.h"

_Static_assert(sizeof((struct eval_options *)0)->scenes == sizeof((struct eval_options *)0)->configs,
               "parse() stores --scenes and --configs through one bound");

int evaluate_parse(int argc, char **argv, struct eval_options *o, const char **dir, int *mode, int *help)
{
    char msg[RESTIR_MSG_LEN];
    memset(o, 0, sizeof *o);
    char *options[EVAL_MAX_ARGS + 2];
    int n = 0;
    for (int i = 0; i < argc; i++) { /* the paper is the one argument that is not an option */
        const char *a = argv[i];
        if (a[0] == '-' || (i > 0 && cli_option_takes_value("evaluate", argv[i - 1]))) {
            if (n == EVAL_MAX_ARGS) {
                cli_error("evaluate: too many arguments");
                return EXIT_USAGE;
            }
            options[n++] = argv[i];
            continue;
        }
        if (o->paper[0]) {
            cli_error("evaluate: unexpected argument '%s' (one paper: 000, 004, 002 or all)", a);
            return EXIT_USAGE;
        }
        if (strlen(a) >= sizeof o->paper) {
            cli_error("evaluate: unknown paper '%.40s' (000, 004, 002 or all)", a);
            return EXIT_USAGE;
        }
        snprintf(o->paper, sizeof o->paper, "%s", a);
    }
    struct cli_options c;
    if (cli_parse_options("evaluate", n, options, &c, msg) != 0) {
        cli_error("%s%s (restir evaluate --help)", strncmp(msg, "evaluate: ", 10) ? "evaluate: " : "", msg);
        return EXIT_USAGE;
    }
    if (help)
        *help = c.help;
    if (c.help)
        return 0;
    o->threads = c.params.threads;
    o->partial = c.partial;
    o->force = c.force;
    o->resume = c.resume;
    if (c.check || c.tables) { /* the data of an evaluation already merged: no paper, no new plan */
        if (!(dir && mode)) {
            cli_error("evaluate: a plan's stored options name no folder");
            return EXIT_USAGE;
        }
        if (c.check && c.tables) {
            cli_error("evaluate: give one of --check DIR and --tables DIR");
            return EXIT_USAGE;
        }
        if (o->paper[0] || c.out || c.plan) {
            cli_error("evaluate: --%s DIR takes no paper, --out or --plan (it reads what DIR holds)",
                      c.check ? "check" : "tables");
            return EXIT_USAGE;
        }
        if (c.check && c.partial) {
            cli_error("evaluate: --partial goes with --tables DIR (or --merge DIR), not --check");
            return EXIT_USAGE;
        }
        *dir = c.check ? c.check : c.tables;
        *mode = c.check ? 'c' : 't';
        return 0;
    }
    if (c.partial) {
        cli_error("evaluate: --partial goes with --tables DIR or --merge DIR");
        return EXIT_USAGE;
    }
    if ((c.force || c.resume) && !c.out && !c.plan) {
        cli_error("evaluate: --%s goes with --out DIR or --plan DIR", c.force ? "force" : "resume");
        return EXIT_USAGE;
    }
    if (c.force && c.resume) {
        cli_error("evaluate: give one of --force (start over) and --resume (continue)");
        return EXIT_USAGE;
    }
    if ((c.out || c.plan) && !(dir && mode)) {
        cli_error("evaluate: a plan's stored options name no folder");
        return EXIT_USAGE;
    }
    if (c.out && c.plan) {
        cli_error("evaluate: give one of --out DIR and --plan DIR");
        return EXIT_USAGE;
    }
    if (dir && mode && (c.out || c.plan)) {
        *dir = c.out ? c.out : c.plan;
        *mode = c.out ? 'o' : 'p';
    }
    const char *lists[2] = {c.scenes, c.configs}, *names[2] = {"--scenes", "--configs"};
    char *fields[2] = {o->scenes, o->configs};
    for (int k = 0; k < 2; k++) {
        if (lists[k] && strlen(lists[k]) >= sizeof o->scenes) {
            cli_error("evaluate: %s is longer than %zu characters", names[k], sizeof o->scenes - 1);
            return EXIT_USAGE;
        }
        snprintf(fields[k], sizeof o->scenes, "%s", lists[k] ? lists[k] : "");
    }
    o->width = c.res_given ? c.params.width : EVAL_PAPER_WIDTH;
    o->height = c.res_given ? c.params.height : EVAL_PAPER_HEIGHT;
    o->runs = c.runs;
    o->frames = c.frames;
    o->warmup = c.warmup;
    o->ref_spp = c.ref_spp;
    o->report = c.report;
    if (!o->paper[0]) {
        cli_error("evaluate: which paper? (000, 004, 002 or all; restir evaluate --help)");
        return EXIT_USAGE;
    }
    const struct eval_paper *paper = eval_paper_find(o->paper);
    if (o->configs[0] && strcmp(o->paper, "all") && !(paper && paper->configs)) {
        char with[64] = ""; /* the papers whose recipes name configurations */
        for (int i = 0; eval_papers[i]; i++)
            if (eval_papers[i]->configs)
                snprintf(with + strlen(with), sizeof with - strlen(with), "%s%s", with[0] ? ", " : "",
                         eval_papers[i]->id);
        cli_error("evaluate: --configs chooses among %s's configurations; %s has none to choose", with, o->paper);
        return EXIT_USAGE;
    }
    return 0;
}

/* The evaluation's options as arguments that do not name a folder: the plan's identity. */
static int canonical_args(const struct eval_options *o, char *text, size_t len, char **argv)
{
    int n = 0;
    size_t used = 0;
    char one[300];
#define ARG(...)                                                                                                   \
    do {                                                                                                           \
        snprintf(one, sizeof one, __VA_ARGS__);                                                                    \
        argv[n++] = text + used;                                                                                   \
        used += (size_t)snprintf(text + used, len - used, "%s", one) + 1;                                          \
    } while (0)
    ARG("%s", o->paper);
    ARG("--res");
    ARG("%dx%d", o->width, o->height);
    if (o->runs > 0 || strcmp(o->paper, "all")) { /* all: each paper's own default (eval_runs) */
        ARG("--runs");
        ARG("%d", eval_runs(o, o->paper));
    }
    ARG("--ref-spp");
    ARG("%d", eval_ref_spp(o));
    if (o->frames > 0) {
        ARG("--frames");
        ARG("%d", o->frames);
    }
    if (o->warmup > 0) {
        ARG("--warmup");
        ARG("%d", o->warmup);
    }
    if (o->scenes[0]) {
        ARG("--scenes");
        ARG("%s", o->scenes);
    }
    if (o->configs[0]) {
        ARG("--configs");
        ARG("%s", o->configs);
    }
    if (o->threads > 0) {
        ARG("--threads");
        ARG("%d", o->threads);
    }
    if (o->report)
        ARG("--report");
#undef ARG
    return n;
}

/* Plans step s into folder sub through the study or compare harness, as `restir KIND ARGS --plan sub`
 * would. Returns an exit code. */
static int plan_step(const struct eval_step *s, const char *sub)
{
    char *argv[EVAL_MAX_ARGS + 2], msg[RESTIR_MSG_LEN];
    int argc = 0;
    for (int i = 0; i < s->argc; i++)
        argv[argc++] = s->argv[i];
    argv[argc++] = (char *)"--plan";
    argv[argc++] = (char *)sub;
    struct cli_options desc;
    if (cli_parse_options(s->kind, argc, argv, &desc, msg) != 0) {
        cli_error("evaluate: step %s: %s", s->name, msg);
        return EXIT_USAGE;
    }
    int rc;
    if (!strcmp(s->kind, "study")) {
        static struct study_setup st;
        if ((rc = study_setup(&desc, 1, &st)) != 0)
            return rc;
        rc = study_plan(&st, argc, argv);
        scene_destroy(&st.s);
    } else {
        static struct compare_setup st;
        if ((rc = compare_setup(&desc, &st)) != 0)
            return rc;
        rc = compare_plan(&st, argc, argv);
        scene_destroy(&st.s);
    }
    return rc;
}

/* Merges step s's plan in folder sub. Returns an exit code. */
static int merge_step(const struct eval_step *s, const char *sub)
{
    return !strcmp(s->kind, "study") ? study_merge(sub) : compare_merge(sub);
}

static void step_dir(const char *dir, const struct eval_step *s, char *out, size_t len)
{
    snprintf(out, len, "%s/%s", dir, s->name);
}

/* 1 when dir exists and holds anything. */
static int has_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int any = 0;
    for (struct dirent *e = readdir(d); e && !any; e = readdir(d))
        any = strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return any;
}

/* The folder may hold nothing, or this very evaluation, continued; with resume only the latter. With
 * force it is emptied first, whatever it holds (out_dir.h says which folders --force may empty).
 * Returns 0, or EXIT_USAGE having said why (nothing touched). */
static int check_folder(const char *dir, uint64_t id, const char *command, int force, int resume)
{
    char path[PLAN_PATH_MAX + 32], msg[RESTIR_MSG_LEN];
    static const char *const hint = "; pass --force to empty it first, or give another folder";
    if (force) {
        if (has_entries(dir) && (out_dir_may_empty(dir, msg) != 0 || out_dir_empty(dir, msg) != 0)) {
            cli_error("evaluate: %s", msg);
            return EXIT_USAGE;
        }
        return 0;
    }
    snprintf(path, sizeof path, "%s/plan.json", dir);
    struct stat st;
    if (stat(path, &st) == 0) {
        struct plan old;
        if (plan_load(dir, &old, msg) != 0) {
            cli_error("evaluate: %s: %s%s", dir, msg, hint);
            return EXIT_USAGE;
        }
        int rc = 0;
        if (strcmp(old.kind, "evaluate") != 0) {
            cli_error("evaluate: %s is the plan of `%s`, not an evaluation%s", dir, old.command, hint);
            rc = EXIT_USAGE;
        } else if (plan_check_build(&old) != 0) { /* planned again, its done jobs would mix two builds */
            rc = EXIT_USAGE;
        } else if (old.id != id) {
            cli_error("evaluate: %s holds another evaluation (`%s`), not `%s`%s", dir, old.command, command, hint);
            rc = EXIT_USAGE;
        }
        plan_free(&old);
        return rc; /* 0: this evaluation; its jobs not yet done run, the others stay done */
    }
    if (resume) {
        cli_error("evaluate: --resume: %s holds no evaluation to continue (drop --resume to start one)", dir);
        return EXIT_USAGE;
    }
    if (has_entries(dir)) {
        cli_error("evaluate: %s is not empty and holds no evaluation%s", dir, hint);
        return EXIT_USAGE;
    }
    return 0;
}

/* Plans every step into DIR/NAME and the evaluation into DIR (plan.json, jobs.txt, slurm.sh).
 * Returns 0 or an exit code. */
static int plan_evaluation(const char *dir, const struct eval_options *o, struct eval_step *steps, int n,
                           struct plan *pl)
{
    static char text[4096];
    char *argv[32], msg[RESTIR_MSG_LEN], command[8192];
    const int argc = canonical_args(o, text, sizeof text, argv);
    cli_command_line("evaluate", argc, argv, command, sizeof command);
    struct stat st;
    if (o->resume && stat(dir, &st) != 0) {
        cli_error("evaluate: --resume: %s does not exist, so there is no evaluation to continue", dir);
        return EXIT_USAGE;
    }
    int rc = io_make_dirs(dir, msg) == 0 ? 0 : EXIT_RUNTIME;
    if (rc != 0) {
        cli_error("%s", msg);
        return rc;
    }
    char abs[PLAN_PATH_MAX];
    if (!realpath(dir, abs)) {
        cli_error("evaluate: cannot resolve %s", dir);
        return EXIT_RUNTIME;
    }
    struct plan probe;
    if ((rc = plan_start(&probe, abs, "evaluate", argc, argv, 0)) != 0)
        return rc;
    rc = check_folder(abs, probe.id, command, o->force, o->resume);
    plan_free(&probe);
    if (rc != 0)
        return rc;
    for (int k = 0; k < n && rc == 0; k++) {
        char sub[PLAN_PATH_MAX + 80];
        step_dir(abs, &steps[k], sub, sizeof sub);
        printf("evaluate: step %d of %d: %s\n", k + 1, n, steps[k].name);
        rc = plan_step(&steps[k], sub);
    }
    if (rc != 0)
        return rc;
    if ((rc = plan_start(pl, abs, "evaluate", argc, argv, 0)) != 0)
        return rc;
    for (int k = 0; k < n && rc == 0; k++) {
        char sub[PLAN_PATH_MAX + 80], name[PLAN_NAME_MAX], out[160];
        step_dir(abs, &steps[k], sub, sizeof sub);
        struct plan sp;
        if (plan_load(sub, &sp, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
            break;
        }
        for (int j = 0; j < sp.n_jobs; j++) {
            snprintf(name, sizeof name, "%.40s: %.210s", steps[k].name, sp.jobs[j].name);
            snprintf(out, sizeof out, "%.60s/%.95s", steps[k].name, sp.jobs[j].output);
            plan_add_job(pl, name, out);
        }
        plan_free(&sp);
    }
    if (rc != 0)
        plan_free(pl);
    return rc;
}

int evaluate_plan_steps(const struct plan *pl, struct eval_options *o, struct eval_step *steps, int *n)
{
    char msg[RESTIR_MSG_LEN];
    int rc = evaluate_parse(pl->argc, pl->argv, o, NULL, NULL, NULL);
    if (rc != 0)
        return rc;
    if (eval_steps(o, steps, n, msg) != 0) {
        cli_error("%s/plan.json: %s", pl->dir, msg);
        return EXIT_USAGE;
    }
    return 0;
}

int evaluate_run_job(const struct plan *pl, int k)
{
    static struct eval_step steps[EVAL_MAX_STEPS];
    struct eval_options o;
    int n = 0;
    int rc = evaluate_plan_steps(pl, &o, steps, &n);
    if (rc != 0)
        return rc;
    char msg[RESTIR_MSG_LEN], sub[PLAN_PATH_MAX + 80];
    for (int s = 0; s < n; s++) {
        step_dir(pl->dir, &steps[s], sub, sizeof sub);
        struct plan sp;
        if (plan_load(sub, &sp, msg) != 0) {
            cli_error("%s", msg);
            return EXIT_RUNTIME;
        }
        if (k < sp.n_jobs) {
            rc = plan_check_build(&sp); /* a step planned again by another build */
            if (rc == 0)
                rc = !strcmp(sp.kind, "study") ? study_run_job(&sp, k) : compare_run_job(&sp, k);
            plan_free(&sp);
            return rc;
        }
        k -= sp.n_jobs;
        plan_free(&sp);
    }
    cli_error("%s: no job %d in its steps' plans", pl->dir, k + 1);
    return EXIT_RUNTIME;
}

/* Merges every step, then writes the tables. partial: a step that cannot be merged yet (jobs not
 * done) is left out of the tables, which say so, instead of failing the merge. Returns an exit code. */
int evaluate_merge(const char *dir, int partial)
{
    struct plan pl;
    int rc = plan_load_kind(dir, "evaluate", "an evaluation", &pl);
    if (rc != 0)
        return rc;
    static struct eval_step steps[EVAL_MAX_STEPS];
    struct eval_options o;
    int n = 0;
    rc = evaluate_plan_steps(&pl, &o, steps, &n);
    char sub[PLAN_PATH_MAX + 80], msg[RESTIR_MSG_LEN];
    int merged[EVAL_MAX_STEPS], any = 0;
    for (int k = 0; k < n && rc == 0; k++) { /* one commit: a step of another build fails even --partial */
        step_dir(pl.dir, &steps[k], sub, sizeof sub);
        struct plan sp;
        if (plan_load(sub, &sp, msg) != 0) {
            cli_error("%s", msg);
            rc = EXIT_RUNTIME;
        } else {
            rc = plan_check_build(&sp);
            plan_free(&sp);
        }
    }
    for (int k = 0; k < n && rc == 0; k++) {
        step_dir(pl.dir, &steps[k], sub, sizeof sub);
        printf("evaluate: merging %s\n", steps[k].name);
        int step_rc = merge_step(&steps[k], sub);
        if (step_rc == 0) /* what its table was computed with: provenance.json, settings.json */
            step_rc = evaluate_record_step(&pl, &steps[k], sub);
        merged[k] = step_rc == 0;
        any |= merged[k];
        if (step_rc != 0 && partial)
            printf("evaluate: %s is left out (--partial)\n", steps[k].name);
        else
            rc = step_rc;
    }
    if (rc == 0 && !any) {
        cli_error("evaluate: no step of %s can be merged yet", pl.dir);
        rc = EXIT_RUNTIME;
    }
    if (rc == 0)
        rc = evaluate_write_tables(pl.dir, pl.command, &o, steps, n, merged);
    plan_free(&pl);
    return rc;
}

int evaluate_run(const struct eval_options *o_in, const char *dir, int mode)
{
    struct eval_options o = *o_in;
    int rc = 0;
    if (!mode) {
        cli_error("evaluate: give --out DIR (plan, run and merge) or --plan DIR (plan only)");
        return EXIT_USAGE;
    }
    static struct eval_step steps[EVAL_MAX_STEPS];
    int n = 0;
    char msg[RESTIR_MSG_LEN];
    if (eval_steps(&o, steps, &n, msg) != 0) {
        cli_error("evaluate: %s", msg);
        return EXIT_USAGE;
    }
    struct plan pl;
    if ((rc = plan_evaluation(dir, &o, steps, n, &pl)) != 0)
        return rc;
    if (mode == 'p')
        return plan_finish(&pl);
    if (plan_write(&pl, msg) != 0) {
        cli_error("%s", msg);
        plan_free(&pl);
        return EXIT_RUNTIME;
    }
    for (int k = 0; k < pl.n_jobs && rc == 0; k++) { /* finished jobs say so and return at once */
        rc = evaluate_run_job(&pl, k);
        if (rc == 0)
            plan_note_job_machine(&pl, k, o.threads);
    }
    char abs[PLAN_PATH_MAX];
    snprintf(abs, sizeof abs, "%s", pl.dir);
    plan_free(&pl);
    return rc != 0 ? rc : evaluate_merge(abs, 0);
}
