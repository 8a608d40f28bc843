/* `cantact run` (src/cli/run.c). */
#ifndef CT_CLI_RUN_H
#define CT_CLI_RUN_H

/* Returns the exit status; help is the text of --help. */
int ct_cli_run(int argc, char **argv, const char *help);

#endif
