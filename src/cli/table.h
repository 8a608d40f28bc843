/* `cantact table SCENE`: an e(V*) table with a checked interpolation error (src/cli/table.c). */
#ifndef CT_CLI_TABLE_H
#define CT_CLI_TABLE_H

#include "scene.h"

/* Returns the exit status. */
int ct_cli_table(int argc, char **argv);

extern const char *const ct_cli_table_help;

#endif
