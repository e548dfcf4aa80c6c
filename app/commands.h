/* commands.h: the entry points of the `restir` subcommands (cmd_*.c), which main.c and
 * `restir job` dispatch to. Must never hold state. */
#ifndef RESTIR_APP_COMMANDS_H
#define RESTIR_APP_COMMANDS_H

/* Each takes the arguments after its name and returns the process's exit code. */
int cmd_list(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_reference(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_study(int argc, char **argv);
int cmd_scene(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_job(int argc, char **argv);
int cmd_evaluate(int argc, char **argv);

#endif
