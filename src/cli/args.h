/* One argument parser for every subcommand: the options all share (-h, -q, --set, -o) and a
 * subcommand's own, from a table. */
#ifndef CT_CLI_ARGS_H
#define CT_CLI_ARGS_H

#include "scene.h"

#include <stddef.h>

enum { EXIT_DONE = 0, EXIT_FAILED = 1, EXIT_USAGE = 2 };

/* A subcommand's own option: its spelling and what --set it stands for ("surface.unit"; NULL:
 * the option is kept as it is, in ct_args.extra). */
typedef struct {
    const char *name;
    const char *key; /* "section.key" it sets, NULL: kept */
} ct_opt;

typedef struct {
    const char *positional[64];
    size_t npos;
    const char **sets; /* "section.key=value", -o last as output.file */
    const char **set_where;
    size_t nsets;
    int quiet, help;
    const char *extra_name[16], *extra_value[16];
    size_t nextra;
    char **owned; /* strings made here */
    size_t nowned;
} ct_args;

/* Parses argv (the subcommand's arguments) with the shared options and opts (may be NULL).
 * max_pos: the most positional arguments taken (more is an error naming them). Returns -1
 * when the caller goes on, else an exit status (the error printed as one line). */
int ct_args_parse(ct_args *a, int argc, char **argv, const char *cmd, const ct_opt *opts,
                  size_t max_pos);
void ct_args_free(ct_args *a);
/* The value of a kept option, NULL when not given. */
const char *ct_args_extra(const ct_args *a, const char *name);

/* Prints "cantact: msg" on stderr (rank 0 only under MPI). */
void ct_cli_fail(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
/* A library failure of a prepared scene's computation, one line as ct_cli_fail: in a scene
 * given by mass and speed, the V* it names also as the impact speed in m/s, and a crushed
 * layer adds the unit material.E is read in (E given in GPa gives speeds a million times too
 * strong). */
void ct_cli_fail_scene(const ct_scene *sc, int st, const char *msg);
/* Exit status of a library status: 2 for bad input, 1 for a failed computation. */
int ct_cli_status_exit(int st);

/* Prints the surface's notes (one line each, "cantact: " first) unless quiet, and clears them. */
void ct_cli_notes(ct_surface *s, int quiet);
/* FILE_tag.ext beside FILE.ext (FILE_tag without an extension), where a run writes its
 * outputs beyond the first; malloc'ed, NULL when out of memory. */
char *ct_cli_derived_path(const char *path, const char *tag);
/* The one check of every subcommand before it computes anything: no output (outputs, n of
 * them, derived ones included) may be one of the run's inputs (the scene and the surface's
 * files in sc, when not NULL, and extra, e.g. merge's parts). EXIT_USAGE with one line naming
 * both, or -1 when they are all distinct. */
int ct_cli_outputs_not_inputs(const ct_scene *sc, const char *const *outputs, size_t n,
                              const char *const *extra, size_t nextra);
/* Loads the scene of a subcommand's first positional argument with the --set overrides,
 * refuses an output that is the scene itself, and prepares it (files read, speeds as V*,
 * outputs made ready). Returns -1 when the caller goes on, else an exit status. */
int ct_cli_load_scene(const ct_args *a, const char *cmd, ct_scene *sc);

#endif
