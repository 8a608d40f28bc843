/* Output files written atomically (temporary file, then rename) and a progress bar. */
#ifndef CT_CLI_OUTPUT_H
#define CT_CLI_OUTPUT_H

#include <stdio.h>

typedef struct {
    char *path;     /* final path, or NULL for stdout */
    char *tmp_path; /* temporary file beside it */
    FILE *f;        /* where rows go */
    char *special;  /* a path that is no regular file (a device, a FIFO), written in place */
    char *mem;      /* stdout and special paths: rows are held here until commit */
    size_t mem_size;
} ct_out;

/* Opens an output: "-" buffers in memory for stdout, anything else a temporary file in the
 * target's directory. Returns 0, or -1 with a message in err. */
int ct_out_open(ct_out *o, const char *path, char *err, size_t errlen);
/* Publishes the rows: rename into place, or write to stdout. Returns 0 or -1. */
int ct_out_commit(ct_out *o, char *err, size_t errlen);
/* Drops everything written: no file is left behind. */
void ct_out_abort(ct_out *o);

typedef struct {
    int enabled;
    size_t total, done;
    int last_shown;
} ct_progress;

void ct_progress_start(ct_progress *p, size_t total);
void ct_progress_step(ct_progress *p);
void ct_progress_end(ct_progress *p);

#endif
