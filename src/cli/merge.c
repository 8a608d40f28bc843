/* cantact merge: the realisations (or landings) CSVs of runs with --realisations a:b (--landings
 * a:b) (the parts, e.g. the tasks of a job array) read back, checked to be this scene's and to
 * hold every sample once, and written as one run over all realisations would have written them. The
 * parts print every sample round-trip exact, so the merged outputs are the same bytes. */
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
    "must be the scene's. The same for the landings CSVs of runs with --landings a:b (a scene\n"
    "with body.landings; each landing's apex is checked against the one the scene draws).\n"
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

/* What the parts hold: realisations of a random surface, or landings of a curved body (their
 * apexes checked against the ones drawn: the parts must come from runs of this scene). */
typedef struct {
    int landings, plane; /* landings; on a plane (x and y) */
    uint64_t N;          /* ensemble.realisations or body.landings */
    const char *word;    /* "realisation" or "landing" */
    ct_plan_info info;   /* landings: the surface's rods as built (the identity line) */
    double lo[2], hi[2]; /* landings: the region they are drawn from */
} merge_kind;

/* Reads and checks a part's first two lines (into line): this scene's identity, after a
 * UTF-8 byte order mark if one comes first (an editor's), then the header. 0, or -1 with
 * the message in err. */
static int part_head(FILE *f, const char *path, const ct_scene *sc, const merge_kind *mk,
                     char *line, char *err, size_t errlen)
{
    char id[800], where[300];
    const char *head = mk->landings ? CT_ENS_LANDINGS_HEAD : CT_ENS_ID_HEAD;
    ct_ens_identity(sc, &mk->info, id, sizeof id);
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
        if (lineno == 2 && !strcmp(text, ct_ens_samples_header(sc)))
            return 0;
        if (lineno == 1 && strncmp(text, head, strlen(head)))
            snprintf(err, errlen,
                     "%s: not a part of an ensemble run (its first line is not '%s...', which "
                     "cantact run --%ss a:b writes first)",
                     path, head, mk->word);
        else if (lineno == 1)
            mismatch(err, errlen, where, "not a part of this scene", text, id);
        else
            mismatch(err, errlen, where, "not a realisations CSV of this scene", text,
                     ct_ens_samples_header(sc));
        return -1;
    }
    return 0;
}

/* The values of one row as the run would have written them: e in [0, 1], u_max and V*_c
 * finite and >= 0, u_max below H*, clip counts at most the draws; empty only for a failed impact (a
 * row with its error), and failed impacts only in a scene with solver.on_error = skip. NULL or why
 * not. */
static const char *row_values(const ct_scene *sc, const merge_kind *mk, double u, double e,
                              double vc, uint64_t cx, uint64_t cz, const char *error)
{
    if (!mk->landings) {
        ct_random_cantor rc;
        ct_surface_random_cantor(sc->surface, &rc, NULL);
        const uint64_t draws = ((uint64_t)2 << rc.depth) - 2;
        if (cx > draws || cz > draws)
            return "more clipped ratios than draws";
    }
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
static long long part_rows(const char *path, const ct_scene *sc, const merge_kind *mk, char *err,
                           size_t errlen)
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
    else if (!part_head(f, path, sc, mk, line, err, errlen)) {
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
    char *fields[10]; /* into the line; the last: the error (solver.on_error = skip) */
    uint64_t r, impact, cx, cz;
    double x, y, V, u, e, vc;
    const char *V_text, *impact_text;
} part_row;

/* Splits a data row into its nf fields and reads their numbers: 0, or -1 when malformed. A
 * realisation's row: realisation, impact, V*, u, e, V*_c, fx and fz clipped; a landing's:
 * landing, x (and y on a plane), impact, V*, u, e, V*_c. */
static int parse_row(char *line, int nf, const merge_kind *mk, part_row *row)
{
    char **f = row->fields;
    if (split_fields(line, f, nf) != nf || read_u64(f[0], &row->r))
        return -1;
    row->x = row->y = NAN;
    row->cx = row->cz = 0;
    const int a = mk->landings ? 1 + mk->plane : 0; /* the position's fields */
    if (mk->landings && (read_double(f[1], &row->x) || (mk->plane && read_double(f[2], &row->y))))
        return -1;
    row->impact_text = f[a + 1];
    row->V_text = f[a + 2];
    if (read_u64(f[a + 1], &row->impact) || read_double(f[a + 2], &row->V) ||
        read_double(f[a + 3], &row->u) || read_double(f[a + 4], &row->e) ||
        read_double(f[a + 5], &row->vc))
        return -1;
    if (!mk->landings && (read_u64(f[6], &row->cx) || read_u64(f[7], &row->cz)))
        return -1;
    return 0;
}

/* A part being read into the table t: where it is (for messages) and which realisation it is
 * in. */
typedef struct {
    const char *path;
    long lineno;
    const ct_scene *sc;
    const merge_kind *mk;
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
    const char *w = p->mk->word;
    if (r >= p->t->count) {
        snprintf(p->err, p->errlen, "%s:%ld: %s %llu: the scene has %s = %llu", p->path, p->lineno,
                 w, (unsigned long long)r,
                 p->mk->landings ? "body.landings" : "ensemble.realisations",
                 (unsigned long long)p->t->count);
        return -1;
    }
    if (r != p->r_cur) {
        if (p->r_cur != UINT64_MAX && p->q_next != nrows) {
            snprintf(p->err, p->errlen, "%s:%ld: %s %llu has %zu rows, the scene %zu", p->path,
                     p->lineno, w, (unsigned long long)p->r_cur, p->q_next, nrows);
            return -1;
        }
        if (p->seen[r]) {
            snprintf(p->err, p->errlen, "%s:%ld: %s %llu appears twice", p->path, p->lineno, w,
                     (unsigned long long)r);
            return -1;
        }
        p->seen[r] = 1;
        p->r_cur = r;
        p->q_next = 0;
    }
    const size_t q = p->q_next++;
    if (q >= nrows || row->impact != q % impacts + 1 || row->V != p->sc->V_star[q / impacts]) {
        snprintf(p->err, p->errlen,
                 "%s:%ld: V* = %s, impact %s: not the scene's row %zu of %s %llu "
                 "(the parts must come from runs of this scene)",
                 p->path, p->lineno, row->V_text, row->impact_text, q + 1, w,
                 (unsigned long long)r);
        return -1;
    }
    if (p->mk->landings) { /* the apex drawn for this landing, to the bit */
        double pos[2];
        ct_body_landing(p->mk->lo, p->mk->hi, p->sc->body.seed, r, pos);
        if (!(row->x == pos[0] && (!p->mk->plane || row->y == pos[1]))) {
            snprintf(p->err, p->errlen,
                     "%s:%ld: landing %llu at x = %.17g: this scene draws it at x = %.17g%s (the "
                     "parts must come from runs of this scene)",
                     p->path, p->lineno, (unsigned long long)r, row->x, pos[0],
                     p->mk->plane ? " (and y as drawn)" : "");
            return -1;
        }
    }
    *k = (size_t)r * nrows + q;
    return 0;
}

/* One data row of a part into the table: its fields, its values and its place checked. 0, or
 * -1 with the message in p->err. */
static int read_row(part_reader *p, char *line)
{
    const ct_scene *sc = p->sc;
    const int nf = (p->mk->landings ? 7 + p->mk->plane : 8) + (sc->skip_failed != 0);
    part_row row;
    if (parse_row(line, nf, p->mk, &row)) {
        snprintf(p->err, p->errlen, "%s:%ld: malformed row (expected %s)", p->path, p->lineno,
                 ct_ens_samples_header(sc));
        return -1;
    }
    const char *error = sc->skip_failed ? row.fields[nf - 1] : NULL;
    const char *why = row_values(sc, p->mk, row.u, row.e, row.vc, row.cx, row.cz, error);
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
    t->x[row.r] = row.x;
    t->y[row.r] = row.y;
    if (error && error[0] && !(t->err[k] = strdup(error))) {
        snprintf(p->err, p->errlen, "out of memory");
        return -1;
    }
    return 0;
}

/* Reads one part into t; seen[r] marks the realisations read. Returns 0 or -1 (err set). */
static int read_part(const char *path, const ct_scene *sc, const merge_kind *mk, ct_ens_table *t,
                     unsigned char *seen, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    part_reader p = {.path = path,
                     .lineno = 2,
                     .sc = sc,
                     .mk = mk,
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
    if (part_head(f, path, sc, mk, line, err, errlen))
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
        snprintf(err, errlen, "%s: %s %llu has %zu rows, the scene %zu", path, mk->word,
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
static int count_rows(const char *const *parts, size_t nparts, const ct_scene *sc,
                      const merge_kind *mk, char *err, size_t errlen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    const char *w = mk->word, *key = mk->landings ? "body.landings" : "ensemble.realisations";
    long long rows = 0;
    for (size_t p = 0; p < nparts; p++) {
        long long n = part_rows(parts[p], sc, mk, err, errlen);
        if (n < 0)
            return -1;
        rows += n;
    }
    if ((unsigned long long)rows != (unsigned long long)mk->N * nrows) {
        if (rows % (long long)nrows == 0)
            snprintf(err, errlen,
                     "merge: the parts hold %lld rows, %lld %ss of %zu rows; the scene has %s = "
                     "%llu (every %s must be in exactly one part)",
                     rows, rows / (long long)nrows, w, nrows, key, (unsigned long long)mk->N, w);
        else
            snprintf(err, errlen,
                     "merge: the parts hold %lld rows, not whole %ss of %zu rows (the scene's "
                     "%zu speeds x %ld impacts); %s = %llu needs %llu (every %s must be in "
                     "exactly one part)",
                     rows, w, nrows, sc->nvel, sc->impacts, key, (unsigned long long)mk->N,
                     (unsigned long long)mk->N * nrows, w);
        return -1;
    }
    return 0;
}

/* Every realisation's samples are held: refuse up front what would not fit, as run does. 0, or
 * -1 with the message in err. */
static int check_memory(const ct_scene *sc, const merge_kind *mk, char *err, size_t errlen)
{
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    const double bytes = (double)mk->N * ((double)nrows * 4.0 + 5.0) * sizeof(double);
    if (bytes > 0.5 * (double)ct_available_memory()) {
        snprintf(err, errlen,
                 "merge: %llu %ss x %zu rows need %.3g GiB, more than half the %.3g GiB "
                 "of memory available",
                 (unsigned long long)mk->N, mk->word, nrows, bytes / 1073741824.0,
                 (double)ct_available_memory() / 1073741824.0);
        return -1;
    }
    return 0;
}

/* What the scene's parts hold; for landings the surface built (as the runs build it) for the
 * identity line and the region the apexes are drawn from. 0, or -1 with the message in err. */
static int kind_of(const ct_scene *sc, merge_kind *mk, char *err, size_t errlen)
{
    memset(mk, 0, sizeof *mk);
    mk->landings = sc->body.landings != 0;
    mk->N = mk->landings ? sc->body.landings : sc->realisations;
    mk->word = mk->landings ? "landing" : "realisation";
    if (!mk->landings)
        return 0;
    mk->plane = ct_ens_landings_plane(sc);
    ct_build_request req;
    ct_bundle *b = NULL;
    ct_scene_request(sc, 0, &req);
    int st = ct_surface_build_unmet(sc->surface, &req, &b, &mk->info);
    if (!st)
        st = ct_body_landing_region(&sc->body, &sc->scales, b, mk->lo, mk->hi);
    ct_bundle_free(b);
    if (st)
        snprintf(err, errlen, "%s", ct_error_message());
    return st ? -1 : 0;
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
    merge_kind mk;
    if (!sc->realisations && !sc->body.landings) {
        snprintf(err, sizeof err, "merge: %s has no [ensemble] realisations or body.landings",
                 scene);
        ct_cli_fail("%s", err);
        goto done;
    }
    if (kind_of(sc, &mk, err, sizeof err)) {
        ct_cli_fail_scene(sc, CT_EINVAL, err);
        goto done;
    }
    /* the table is sized by what the parts hold: they must hold every sample once */
    if (count_rows(parts, nparts, sc, &mk, err, sizeof err) ||
        check_memory(sc, &mk, err, sizeof err)) {
        ct_cli_fail("%s", err);
        goto done;
    }
    const size_t nrows = sc->nvel * (size_t)sc->impacts;
    if (ct_ens_table_alloc(&t, 0, mk.N, nrows, mk.landings) || !(seen = calloc((size_t)mk.N, 1))) {
        ct_cli_fail("merge: out of memory");
        rc = EXIT_FAILED;
        goto done;
    }
    t.owns_err = 1;
    t.info = mk.info;
    for (size_t k = 0; k < (size_t)mk.N * nrows; k++)
        t.e[k] = t.u[k] = t.vc[k] = NAN;
    /* open the outputs first: an unwritable path fails before any reading */
    int opened = ct_ens_open_outputs(&o, sc, sc->what, parts, nparts, err, sizeof err);
    if (opened) {
        if (opened == -1)
            ct_cli_fail("%s", err);
        goto done;
    }
    for (size_t p = 0; p < nparts; p++)
        if (read_part(parts[p], sc, &mk, &t, seen, err, sizeof err)) {
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
