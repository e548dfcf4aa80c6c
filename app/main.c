/* main.c: the `restir` command: dispatches to list, render, reference, compare, study, evaluate, scene, view
 * and job.
 * Must never parse method parameters itself (options.c and params.c do). */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "experiments/cli.h"
#include "experiments/provenance.h"
#include <restir/version.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: restir <command> [options]\n"
            "commands:\n"
            "  list        scenes and methods, one per line (--json: one JSON document, for scripts)\n"
            "  render      render frames of one method (restir render --help)\n"
            "  reference   render a converged reference of what a method estimates\n"
            "  compare     run several methods on the same frames, optionally at equal time\n"
            "  study       the error-correlation study of neighbor selection (000 Sec. 6-7)\n"
            "  evaluate    a paper's evaluation at its own scale, with a verdict per claim (000, 004, 002)\n"
            "  scene       scene info NAME|FILE; scene export NAME --out DIR (restir scene --help)\n"
            "  view        an interactive window rendering frame after frame (restir view --help)\n"
            "  job         job K of a plan folder (study, reference, compare, evaluate --plan DIR): restir job DIR K\n"
            "restir help COMMAND: what restir COMMAND --help prints\n"
            "restir --version: the version, the commit it was built from and the build type\n"
            "Progress goes to stderr: a bar on a terminal, else a line at most every %.0f s (the environment's\n"
            "RESTIR_PROGRESS_SECONDS sets the interval; off: none).\n",
            PROGRESS_LINE_SECONDS);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    static char help_flag[] = "--help";
    char *help_argv[] = {argv[0], NULL, help_flag, NULL};
    if (argc == 3 && !strcmp(argv[1], "help")) { /* restir help CMD: restir CMD --help */
        help_argv[1] = argv[2];
        argc = 3;
        argv = help_argv;
    } else if (argc > 3 && !strcmp(argv[1], "help")) {
        cli_error("usage: restir help COMMAND");
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "list"))
        return cmd_list(argc - 2, argv + 2);
    if (!strcmp(cmd, "render"))
        return cmd_render(argc - 2, argv + 2);
    if (!strcmp(cmd, "reference"))
        return cmd_reference(argc - 2, argv + 2);
    if (!strcmp(cmd, "compare"))
        return cmd_compare(argc - 2, argv + 2);
    if (!strcmp(cmd, "study"))
        return cmd_study(argc - 2, argv + 2);
    if (!strcmp(cmd, "evaluate"))
        return cmd_evaluate(argc - 2, argv + 2);
    if (!strcmp(cmd, "scene"))
        return cmd_scene(argc - 2, argv + 2);
    if (!strcmp(cmd, "view"))
        return cmd_view(argc - 2, argv + 2);
    if (!strcmp(cmd, "job"))
        return cmd_job(argc - 2, argv + 2);
    if (!strcmp(cmd, "--version")) {
        struct provenance p;
        provenance_now(&p, 0);
        printf("restir %s (commit %s%s, %s)\n", RESTIR_VERSION_STRING, p.commit, p.dirty ? "-dirty" : "",
               p.build_type);
        return 0;
    }
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        usage(stdout);
        return 0;
    }
    cli_error("unknown command '%s'", cmd);
    usage(stderr);
    return EXIT_USAGE;
}
