/* `cantact merge SCENE PART.csv...` (src/cli/merge.c): the realisations CSVs of runs with
 * --realisations a:b combined into the outputs of one run over all realisations. */
#ifndef CT_CLI_MERGE_H
#define CT_CLI_MERGE_H

/* Returns the exit status. */
int ct_cli_merge(int argc, char **argv);

extern const char *const ct_cli_merge_help;

#endif
