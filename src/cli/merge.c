/* cantact merge: the realisations CSVs of runs with --realisations a:b (the parts, e.g. the
 * tasks of a job array) read back, checked to be this scene's and to hold every realisation
 * once, and written as one run over all realisations would have written them. The parts print
 * every sample round-trip exact, so the merged outputs are the same bytes. */
#include "merge.h"
#include "args.h"
#include "ensemble_out.h"
#include "number.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const ct_cli_merge_help =
    "Usage: cantact merge SCENE.ini PART.csv... [--set section.key=value]... [-o FILE] [-q]\n"
    "\n"
    "Combines the realisations CSVs that runs of SCENE.ini with --realisations a:b wrote (e.g.\n"
    "the tasks of a job array) into what the scene's [output] what asks for (ensemble and/or\n"
    "realisations): the same bytes as one run over all realisations. Every realisation\n"
    "0 .. ensemble.realisations - 1 must be in exactly one part; the parts' speeds and impacts\n"
    "must be the scene's.\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (repeatable; as for the runs)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  -h, --help                this help\n";

/* Splits a line at commas into at most max fields, the error field (quoted, last) whole. */
static int split_fields(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        fields[n++] = p;
        if (*p == '"') { /* a quoted error: to the closing quote at the end */
            char *q = strrchr(p + 1, '"');
            if (!q)
                return -1;
            *q = '\0';
            fields[n - 1] = p + 1;
            return q[1] ? -1 : n;
        }
        char *c = strchr(p, ',');
        if (!c)
            return n;
        *c = '\0';
        p = c + 1;
    }
    return -1;
}

static int read_double(const char *s, double *x)
{
    char *end;
    if (!*s) {
        *x = NAN;
        return 0;
    }
    errno = 0;
    *x = strtod(s, &end);
    return *end || errno ? -1 : 0;
}

static int read_u64(const char *s, uint64_t *x)
{
    char *end;
    if (!(*s >= '0' && *s <= '9'))
        return -1;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    *x = (uint64_t)v;
    return *end || errno ? -1 : 0;
}

/* A row of a realisations CSV is a few numbers and an error message: longer is no part. */
#define PART_LINE_MAX 4096

/* The next line of f into buf (PART_LINE_MAX + 1 bytes) without its line end (\n or \r\n):
 * 1, 0 at the end, -1 when longer than PART_LINE_MAX (the rest of it is not read), -2 at a
 * NUL byte (no text cantact writes has one; read as a string, the line would end there). */
static int part_line(FILE *f, char *buf)
{
    size_t n = 0;
    int c;
    while ((c = getc_unlocked(f)) != EOF && c != '\n') {
        if (c == '\0') {
            buf[n] = '\0';
            return -2;
        }
        if (n == PART_LINE_MAX)
            return -1;
        buf[n++] = (char)c;
    }
    if (c == EOF && n == 0)
        return 0;
    if (n && buf[n - 1] == '\r')
        n--;
    buf[n] = '\0';
    return 1;
}

/* Up to 40 bytes of s from byte `from` on, for a message: bytes a terminal does not show
 * (a BOM, a tab, control characters) as \xHH, "..." where cut. */
static void excerpt(char *buf, size_t len, const char *s, size_t from)
{
    size_t n = 0, k = 0;
    if (from > 0)
        n += (size_t)snprintf(buf, len, "...");
    for (; s[from + k] && k < 40 && n + 8 < len; k++) {
        const unsigned char c = (unsigned char)s[from + k];
        n += (size_t)snprintf(buf + n, len - n, c >= 0x20 && c < 0x7f ? "%c" : "\\x%02X", c);
    }
    if (s[from + k] && n + 4 < len)
        snprintf(buf + n, len - n, "...");
    else if (n == 0 && len)
        buf[0] = '\0';
}

/* A line that is not the expected one, in one line: where they part and what follows in
 * each (two texts that look alike, or differ past what a message shows, are told apart). */
static void mismatch(char *err, size_t errlen, const char *where, const char *what,
                     const char *line, const char *want)
{
    size_t at = 0;
    while (line[at] && line[at] == want[at])
        at++;
    const size_t from = at > 20 ? at - 20 : 0;
    char got[150], exp[150];
    excerpt(got, sizeof got, line, from);
    excerpt(exp, sizeof exp, want, from);
    snprintf(err, errlen, "%.160s: %.60s: from byte %zu it says '%s', expected '%s'", where, what,
             at + 1, got, exp);
}

/* Reads and checks a part's first two lines (into line): this scene's identity, after a
 * UTF-8 byte order mark if one comes first (an editor's), then the header. 0, or -1 with
 * the message in err. */
static int part_head(FILE *f, const char *path, const ct_scene *sc, char *line, char *err,
                     size_t errlen)
{
    char id[800], where[300];
    ct_ens_identity(sc, id, sizeof id);
    for (long lineno = 1; lineno <= 2; lineno++) {
        const int got = part_line(f, line);
        snprintf(where, sizeof where, "%s:%ld", path, lineno);
        if (got == 0 && ferror(f))
            snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        else if (got == 0)
            snprintf(err, errlen, "%s: %s: not a realisations CSV", path,
                     lineno == 1 ? "empty" : "no header");
        else if (got == -1)
            snprintf(err, errlen, "%s: a line longer than %d bytes: not a realisations CSV", where,
                     PART_LINE_MAX);
        else if (got == -2 && lineno == 1 &&
                 ((line[0] == '\xFF' && line[1] == '\xFE') ||
                  (line[0] == '\xFE' && line[1] == '\xFF')))
            snprintf(err, errlen, "%s: UTF-16 text: a part is the UTF-8 that cantact writes", path);
        else if (got == -2)
            snprintf(err, errlen, "%s: a NUL byte: not a realisations CSV", where);
        if (got <= 0)
            return -1;
        const char *text = line;
        if (lineno == 1 && !strncmp(text, "\xEF\xBB\xBF", 3))
            text += 3;
        if (lineno == 1 && !strcmp(text, id))
            continue;
        if (lineno == 2 && !strcmp(text, ct_ens_realisations_header(sc->skip_failed)))
            return 0;
        if (lineno == 1 && strncmp(text, CT_ENS_ID_HEAD, strlen(CT_ENS_ID_HEAD)))
            snprintf(err, errlen,
                     "%s: not a part of an ensemble run (its first line is not '" CT_ENS_ID_HEAD
                     "...', which cantact run --realisations a:b writes first)",
                     path);
        else if (lineno == 1)
            mismatch(err, errlen, where, "not a part of this scene", text, id);
        else
            mismatch(err, errlen, where, "not a realisations CSV of this scene", text,
                     ct_ens_realisations_header(sc->skip_failed));
        return -1;
    }
    return 0;
}

/* The values of one row as the run would have written them: e in [0, 1], u_max and V*_c
 * finite and >= 0, u_max below H*, clip counts at most the draws; empty only for a failed impact (a
 * row with its error), and failed impacts only in a scene with solver.on_error = skip. NULL or why
 * not. */
static const char *row_values(const ct_scene *sc, double u, double e, double vc, uint64_t cx,
                              uint64_t cz, const char *error)
{
    ct_random_cantor rc;
    ct_surface_random_cantor(sc->surface, &rc, NULL);
    const uint64_t draws = ((uint64_t)2 << rc.depth) - 2;
    if (cx > draws || cz > draws)
        return "more clipped ratios than draws";
    if (error && *error)
        return isnan(e) && isnan(u) && isnan(vc) ? NULL : "a failed impact with numbers";
    if (isnan(e) || isnan(u) || isnan(vc))
        return sc->skip_failed ? "empty numbers without an error"
                               : "empty numbers in a part of a "
                                 "scene that stops on errors";
    if (!(e >= 0.0 && e <= 1.0))
        return "e outside [0, 1]";
    if (!(isfinite(u) && u >= 0.0) || !(isfinite(vc) && vc >= 0.0))
        return "u_max_over_h0 or V_star_crit not a finite number >= 0";
    const ct_layer *L = &sc->scales.layer;
    if (!(u < L->Hstar / L->h0)) /* u_max >= H* is a crushed layer: refused, never a row */
        return "u_max_over_h0 not below H*/h0 (a crushed layer)";
    return NULL;
}

/* The data rows of a part (its lines after the identity and the header), its head checked:
 * -1 with the message in err when it is no part of this scene, cannot be read or has a line
 * that no part has (too long, a NUL byte). */
static long long part_rows(const char *path, const ct_scene *sc, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    char *line = malloc(PART_LINE_MAX + 1);
    long long n = -1,
              blank = 0; /* empty lines: harmless at the end (an editor's), not among rows */
    int got = 0;
    if (!line)
        snprintf(err, errlen, "out of memory");
    else if (!part_head(f, path, sc, line, err, errlen)) {
        n = 0;
        while ((got = part_line(f, line)) > 0 && !(line[0] && blank))
            line[0] ? n++ : blank++;
        const long long lineno = n + blank + 3;
        if (got > 0)
            snprintf(err, errlen, "%s:%lld: an empty line among the rows: not a realisations CSV",
                     path, lineno - 1);
        else if (got == -1)
            snprintf(err, errlen, "%s:%lld: a line longer than %d bytes: not a realisations CSV",
                     path, lineno, PART_LINE_MAX);
        else if (got == -2)
            snprintf(err, errlen, "%s:%lld: a NUL byte: not a realisations CSV", path, lineno);
        else if (ferror(f))
            snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
        if (got != 0 || ferror(f))
            n = -1;
    }
    fclose(f);
    free(line);
    return n;
}

/* One data row of a part, as read. */
typedef struct {
    char *fields[9]; /* into the line; fields[8]: the error (solver.on_error = skip) */
    uint64_t r, impact, cx, cz;
    double V, u, e, vc;
} part_row;

/* Splits a data row into its nf fields and reads their numbers: 0, or -1 when malformed. */
static int parse_row(char *line, int nf, part_row *row)
{
    char **fields = row->fields;
    if (split_fields(line, fields, nf) != nf || read_u64(fields[0], &row->r) ||
        read_u64(fields[1], &row->impact) || read_double(fields[2], &row->V) ||
        read_double(fields[3], &row->u) || read_double(fields[4], &row->e) ||
        read_double(fields[5], &row->vc) || read_u64(fields[6], &row->cx) ||
        read_u64(fields[7], &row->cz))
        return -1;
    return 0;
}

/* A part being read into the table t: where it is (for messages) and which realisation it is
 * in. */
typedef struct {
    const char *path;
    long lineno;
    const ct_scene *sc;
    ct_ens_table *t;
    unsigned char *seen; /* seen[r]: realisation r was read, in this part or an earlier one */
    uint64_t r_cur;      /* the realisation being read (UINT64_MAX: none yet) */
    size_t q_next;       /* its next row */
    char *err;
    size_t errlen;
} part_reader;

/* Where a row goes in the table (*k): a realisation of the scene, its rows together, whole and
 * once, in the scene's order of speeds and impacts. 0, or -1 with the message in p->err. */
static int place_row(part_reader *p, const part_row *row, size_t *k)
{
    const size_t impacts = (size_t)p->sc->impacts, nrows = p->t->nrows;
    const uint64_t r = row->r;
    if (r >= p->t->count) {
        snprintf(p->err, p->errlen,
                 "%s:%ld: realisation %llu: the scene has ensemble.realisations = %llu", p->path,
                 p->lineno, (unsigned long long)r, (unsigned long long)p->t->count);
        return -1;
    }
    if (r != p->r_cur) {
        if (p->r_cur != UINT64_MAX && p->q_next != nrows) {
            snprintf(p->err, p->errlen, "%s:%ld: realisation %llu has %zu rows, the scene %zu",
                     p->path, p->lineno, (unsigned long long)p->r_cur, p->q_next, nrows);
            return -1;
        }
        if (p->seen[r]) {
            snprintf(p->err, p->errlen, "%s:%ld: realisation %llu appears twice", p->path,
                     p->lineno, (unsigned long long)r);
            return -1;
        }
        p->seen[r] = 1;
        p->r_cur = r;
        p->q_next = 0;
    }
    const size_t q = p->q_next++;
    if (q >= nrows || row->impact != q % impacts + 1 || row->V != p->sc->V_star[q / impacts]) {
        snprintf(p->err, p->errlen,
                 "%s:%ld: V* = %s, impact %s: not the scene's row %zu of realisation %llu "
                 "(the parts must come from runs of this scene)",
                 p->path, p->lineno, row->fields[2], row->fields[1], q + 1, (unsigned long long)r);
        return -1;
    }
    *k = (size_t)r * nrows + q;
    return 0;
}

/* One data row of a part into the table: its fields, its values and its place checked. 0, or
 * -1 with the message in p->err. */
static int read_row(part_reader *p, char *line)
{
    const ct_scene *sc = p->sc;
    const int nf = sc->skip_failed ? 9 : 8;
    part_row row;
    if (parse_row(line, nf, &row)) {
        snprintf(p->err, p->errlen, "%s:%ld: malformed row (expected %s)", p->path, p->lineno,
                 ct_ens_realisations_header(sc->skip_failed));
        return -1;
    }
    const char *error = nf == 9 ? row.fields[8] : NULL;
    const char *why = row_values(sc, row.u, row.e, row.vc, row.cx, row.cz, error);
    if (why) {
        snprintf(p->err, p->errlen, "%s:%ld: %s: not what a run writes", p->path, p->lineno, why);
        return -1;
    }
    size_t k;
    if (place_row(p, &row, &k))
        return -1;
    ct_ens_table *t = p->t;
    t->e[k] = row.e;
    t->u[k] = row.u;
    t->vc[k] = row.vc;
    t->cx[row.r] = row.cx;
    t->cz[row.r] = row.cz;
    if (error && error[0] && !(t->err[k] = strdup(error))) {
        snprintf(p->err, p->errlen, "out of memory");
        return -1;
    }
    return 0;
}

/* Reads one part into t; seen[r] marks the realisations read. Returns 0 or -1 (err set). */
static int read_part(const char *path, const ct_scene *sc, ct_ens_table *t, unsigned char *seen,
                     char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    part_reader p = {.path = path,
                     .lineno = 2,
                     .sc = sc,
                     .t = t,
                     .seen = seen,
                     .r_cur = UINT64_MAX,
                     .err = err,
                     .errlen = errlen};
    char *line = malloc(PART_LINE_MAX + 1);
    int rc = -1, got;
    if (!line) {
        snprintf(err, errlen, "out of memory");
        goto done;
    }
    if (part_head(f, path, sc, line, err, errlen))
        goto done;
    while ((got = part_line(f, line)) != 0) {
        p.lineno++;
        if (got == -1) {
            snprintf(err, errlen, "%s:%ld: a line longer than %d bytes: not a realisations CSV",
                     path, p.lineno, PART_LINE_MAX);
            goto done;
        }
        if (got == -2) {
            snprintf(err, errlen, "%s:%ld: a NUL byte: not a realisations CSV", path, p.lineno);
            goto done;
        }
        /* an empty line is one at the end: part_rows refused one among the rows */
        if (line[0] && read_row(&p, line))
            goto done;
    }
    if (p.r_cur != UINT64_MAX && p.q_next != t->nrows) {
        snprintf(err, errlen, "%s: realisation %llu has %zu rows, the scene %zu", path,
                 (unsigned long long)p.r_cur, p.q_next, t->nrows);
        goto done;
    }
    if (ferror(f)) {
        snprintf(err, errlen, "%s: read error", path);
        goto done;
    }
    rc = 0;
done:
    free(line);
    fclose(f);
    return rc;
}

/* The parts' data rows (their heads checked) against the scene: they must hold every
 * realisation once, R x nrows rows in all. 0, or -1 with the message in err. */
static int count_rows(const char *const *parts, size_t nparts, const ct_scene *sc, char *err,
                      size_t errlen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    long long rows = 0;
    for (size_t p = 0; p < nparts; p++) {
        long long n = part_rows(parts[p], sc, err, errlen);
        if (n < 0)
            return -1;
        rows += n;
    }
    if ((unsigned long long)rows != (unsigned long long)sc->realisations * nrows) {
        if (rows % (long long)nrows == 0)
            snprintf(err, errlen,
                     "merge: the parts hold %lld rows, %lld realisations of %zu rows; the scene "
                     "has ensemble.realisations = %llu (every realisation must be in exactly one "
                     "part)",
                     rows, rows / (long long)nrows, nrows, (unsigned long long)sc->realisations);
        else
            snprintf(err, errlen,
                     "merge: the parts hold %lld rows, not whole realisations of %zu rows (the "
                     "scene's %zu speeds x %ld impacts); ensemble.realisations = %llu needs %llu "
                     "(every realisation must be in exactly one part)",
                     rows, nrows, sc->nvel, sc->impacts, (unsigned long long)sc->realisations,
                     (unsigned long long)sc->realisations * nrows);
        return -1;
    }
    return 0;
}

/* Every realisation's samples are held: refuse up front what would not fit, as run does. 0, or
 * -1 with the message in err. */
static int check_memory(const ct_scene *sc, char *err, size_t errlen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    const double bytes = (double)sc->realisations * ((double)nrows * 4.0 + 3.0) * sizeof(double);
    if (bytes > 0.5 * (double)ct_available_memory()) {
        snprintf(err, errlen,
                 "merge: %llu realisations x %zu rows need %.3g GiB, more than half the %.3g GiB "
                 "of memory available",
                 (unsigned long long)sc->realisations, nrows, bytes / 1073741824.0,
                 (double)ct_available_memory() / 1073741824.0);
        return -1;
    }
    return 0;
}

/* The parts (nparts of them) of the scene sc (read from the file scene) into its outputs.
 * Returns the exit status. */
static int merge_parts(const ct_scene *sc, const char *scene, const char *const *parts,
                       size_t nparts, int quiet)
{
    char err[600];
    int rc = EXIT_USAGE;
    ct_ens_table t;
    memset(&t, 0, sizeof t);
    unsigned char *seen = NULL;
    ct_ens_outputs o;
    memset(&o, 0, sizeof o);
    if (!sc->realisations) {
        snprintf(err, sizeof err, "merge: %s has no [ensemble] realisations", scene);
        ct_cli_fail("%s", err);
        goto done;
    }
    /* the table is sized by what the parts hold: they must hold every realisation once */
    if (count_rows(parts, nparts, sc, err, sizeof err) || check_memory(sc, err, sizeof err)) {
        ct_cli_fail("%s", err);
        goto done;
    }
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    if (ct_ens_table_alloc(&t, 0, sc->realisations, nrows) ||
        !(seen = calloc((size_t)sc->realisations, 1))) {
        ct_cli_fail("merge: out of memory");
        rc = EXIT_FAILED;
        goto done;
    }
    t.owns_err = 1;
    for (size_t k = 0; k < (size_t)sc->realisations * nrows; k++)
        t.e[k] = t.u[k] = t.vc[k] = NAN;
    /* open the outputs first: an unwritable path fails before any reading */
    int opened = ct_ens_open_outputs(&o, sc, sc->what, parts, nparts, err, sizeof err);
    if (opened) {
        if (opened == -1)
            ct_cli_fail("%s", err);
        goto done;
    }
    for (size_t p = 0; p < nparts; p++)
        if (read_part(parts[p], sc, &t, seen, err, sizeof err)) {
            ct_cli_fail("%s", err);
            goto done;
        }
    /* every realisation is now in exactly one part: the parts held R x nrows rows, none twice,
     * each with nrows rows of an index below R */
    rc = ct_ens_write_outputs(&o, sc, &t, quiet);
done:
    ct_ens_close_outputs(&o);
    ct_ens_table_free(&t);
    free(seen);
    return rc;
}

int ct_cli_merge(int argc, char **argv)
{
    ct_args a;
    ct_scene sc;
    int rc = ct_args_parse(&a, argc, argv, "merge", NULL, 64);
    if (rc < 0 && a.help) {
        fputs(ct_cli_merge_help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0 && a.npos < 2) {
        ct_cli_fail("merge: needs SCENE.ini and at least one PART.csv (see cantact merge --help)");
        rc = EXIT_USAGE;
    }
    if (rc < 0)
        rc = ct_cli_load_scene(&a, "merge", &sc);
    if (rc < 0) {
        rc = merge_parts(&sc, a.positional[0], a.positional + 1, a.npos - 1, a.quiet);
        ct_scene_free(&sc);
    }
    ct_args_free(&a);
    return rc;
}
