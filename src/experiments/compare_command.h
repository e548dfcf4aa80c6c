/* compare_command.h: `restir compare` as a harness function (compare_command.c) and its usage
 * (compare_help.c). The subcommand (app/cmd_compare.c) only parses the options. Must never implement
 * a method. */
#ifndef RESTIR_EXPERIMENTS_COMPARE_COMMAND_H
#define RESTIR_EXPERIMENTS_COMPARE_COMMAND_H

#include <stdio.h>

#include "experiments/options.h"

/* The comparison desc describes (struct cli_options as the option table parsed it from argc, argv,
 * which go into a plan and the table's command line): its --out checked (new or empty, or --force),
 * the specs set up (compare_setup), then with --plan the plan written (compare_plan), else the
 * reference rendered or read, every spec run (compare_schedule) and the table written. Returns an exit
 * code, having said what went wrong (0; 2 for bad input, nothing written; 1 for a failure; 128 + the
 * signal after SIGINT / SIGTERM, what is kept said). Not thread-safe (one comparison per process). */
int compare_command(const struct cli_options *desc, int argc, char **argv);

/* Writes `restir compare --help` to out: the usage, the files written, then the option table's help. */
void compare_usage(FILE *out);

#endif
