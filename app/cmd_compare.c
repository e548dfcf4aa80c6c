/* cmd_compare.c: `restir compare`: method specs (NAME[:key=value]...) run on the same frames against one
 * reference, optionally at equal time, into a table and compare.csv. Parses the options into the
 * harness's description (src/experiments/compare_command.h), which runs it. Must never implement a
 * method. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "core/check.h"
#include "experiments/cli.h"
#include "experiments/compare_command.h"
#include "experiments/compare_plan.h"
#include "experiments/options.h"

int cmd_compare(int argc, char **argv)
{
    for (int i = 0; i + 1 < argc; i++)
        if (!strcmp(argv[i], "--merge")) {
            if (argc != 2) {
                cli_error("compare --merge DIR takes no other option (the plan holds them)");
                return EXIT_USAGE;
            }
            return compare_merge(argv[i + 1]);
        }
    char msg[RESTIR_MSG_LEN];
    struct cli_options desc;
    if (cli_parse_options("compare", argc, argv, &desc, msg) != 0) {
        cli_error("%s", msg);
        return EXIT_USAGE;
    }
    if (desc.help) {
        compare_usage(stdout);
        return 0;
    }
    return compare_command(&desc, argc, argv);
}
