/* `cantact fit FILE|SCENE.ini` (src/cli/fit.c). */
#ifndef CT_CLI_FIT_H
#define CT_CLI_FIT_H

/* Returns the exit status. */
int ct_cli_fit(int argc, char **argv);

#endif
