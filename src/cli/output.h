/* Output files written atomically (temporary file, then rename), and a progress bar.
 *
 * A regular file (new, or existing: then its mode is kept; a symbolic link: then its target)
 * is written to a temporary file beside it and renamed into place at commit; a new file gets
 * 0666 less the umask. Standard output ("-") and paths that are no regular file (a device, a
 * FIFO) are spooled to an unlinked temporary file and copied there at commit: memory does not
 * grow with the output, and nothing reaches them from a failed run. Temporary files are
 * removed on abort, at exit and on every signal whose default action ends the process;
 * SIGXFSZ is ignored (a write beyond ulimit -f fails, and is said). */
#ifndef CT_CLI_OUTPUT_H
#define CT_CLI_OUTPUT_H

#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

typedef struct {
    char *shown;    /* the path as given, for messages ("-": standard output) */
    char *path;     /* where the rows land: the path, or a symbolic link's target; NULL: stdout */
    char *tmp_path; /* regular files: the temporary file beside the target */
    FILE *f;        /* where rows go */
    int spooled;    /* stdout or a special file: f is an unlinked spool, copied at commit */
    mode_t mode;    /* the mode the committed file gets */
    char *buf;      /* f's buffer (1 MiB: a 2000-row CSV in one write, not 67) */
} ct_out;

/* Opens /dev/null read-only on any of descriptors 0-2 that is closed, so that no file the
 * program opens takes their place (a temporary output on descriptor 2 would receive the
 * notes); writing to a closed standard output then fails, as it did (exit 2), and an output
 * "-" is refused up front. Called first thing in main. */
void ct_out_guard_std(void);

/* Opens an output: "-" for standard output, else a path (checked now: a directory, an
 * unwritable place or a dangling symbolic link fail before any work is done). Returns 0, or
 * -1 with a message in err. */
int ct_out_open(ct_out *o, const char *path, char *err, size_t errlen);
/* Publishes one output: ct_out_commit_all of one. */
int ct_out_commit(ct_out *o, char *err, size_t errlen);
/* Publishes several outputs together: every one is written and checked first, and only if
 * all succeeded are they copied to their special files, then renamed into place; a rename
 * that fails puts back the files the earlier ones replaced (kept as hard links until all
 * landed). Otherwise all are dropped. Returns 0 or -1 with a message in err. */
int ct_out_commit_all(ct_out *const *outs, size_t n, char *err, size_t errlen);
/* Drops everything written: no file is left behind. */
void ct_out_abort(ct_out *o);
/* 1 when output names the regular file input (hard links and symbolic links included): an
 * output that would replace an input. */
int ct_out_is_input(const char *output, const char *input);
/* 1 when both paths name one existing file (hard links and symbolic links included). */
int ct_out_same_file(const char *a, const char *b);

/* A progress bar on stderr, drawn only when stderr is a terminal (DESIGN.md: long work shows
 * progress there and nothing otherwise). */
typedef struct {
    int enabled;
    size_t total, done;
    int last_shown;
    const char *unit; /* NULL: a bar of done/total; else for a total that grows, the counts
                         "done of total unit" */
} ct_progress;

void ct_progress_start(ct_progress *p, size_t total);
void ct_progress_step(ct_progress *p);
/* done of total (a total that grows is redrawn at once); a no-op off a terminal */
void ct_progress_to(ct_progress *p, size_t done, size_t total);
void ct_progress_end(ct_progress *p);

#endif
