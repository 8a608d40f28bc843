/* Scene files (INI, parsed with inih) -> a surface of some kind and the run's settings. The
 * keys are rows: the CLI's own below, each kind's in the library (src/surface/). Values are
 * stored as text while the file and the --set overrides are read (a later override replaces
 * an earlier value), then parsed through their rows; every error names file:line, the key,
 * its value and the valid range. */
#include "scene.h"

#include <ini.h>
#include <stdarg.h>

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static _Thread_local char scene_message[512];

/* Marks a value held aside by the line reader (a line longer than inih's buffer). */
#define LONG_VALUE_MARK '\x01'

/* Scenes larger than this are refused: a scene is a few hundred bytes, a long speed list a
 * few megabytes. */
#define CT_MAX_SCENE_BYTES (64u << 20)

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int
scene_error(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(scene_message, sizeof scene_message, fmt, ap);
    va_end(ap);
    return status;
}

const char *ct_scene_message(void)
{
    return scene_message;
}

/* ---- the CLI's keys ---- */

#define AT(field) offsetof(ct_scene_keys, field)
static const ct_key cli_keys[] = {
    {"surface", "type", CT_KEY_TEXT, 0, 0, 0, NULL, "must be a kind of surface", "cantor",
     "the kind of surface that makes the rods (cantact kinds lists them)", AT(type)},
    {"output", "file", CT_KEY_TEXT, 0, 0, 0, NULL, "must be a path or -", "-",
     "where the e table goes (-: standard output); other outputs beside it", AT(file)},
    {"output", "what", CT_KEY_WORDS, 0, 0, 0, CT_OUTPUT_WORDS,
     "each item must be e, time, curve, history, profile, compare, bearing, bounce, ensemble, "
     "realisations or landings",
     "e", "the outputs (cantact kinds: which each kind of surface gives)", AT(what)},
    {"output", "history_points", CT_KEY_INTEGER, 0, 100000000, 0, NULL,
     "must satisfy 0 <= history_points <= 1e8", "200",
     "uniform time points of each impact's history, beside its breakpoints", AT(history_points)},
};
#undef AT
#define NCLI (sizeof cli_keys / sizeof cli_keys[0])

const ct_key *ct_scene_key_row(size_t i)
{
    static const char *const sections[] = {"surface", "body",  "impact",  "solver",
                                           "output",  "table", "ensemble"};
    size_t n[3];
    const ct_key *table[3] = {cli_keys, ct_body_keys_table(&n[1]), ct_run_keys_table(&n[2])};
    n[0] = NCLI;
    for (size_t s = 0; s < sizeof sections / sizeof sections[0]; s++)
        for (size_t t = 0; t < 3; t++)
            for (size_t r = 0; r < n[t]; r++)
                if (!strcmp(table[t][r].section, sections[s]) && i-- == 0)
                    return &table[t][r];
    return NULL;
}

/* ---- the values as read: text, where it came from ---- */

typedef struct {
    char section[64], key[64];
    char *value;
    char where[300]; /* "file:line" or "--set" */
} entry;

typedef struct {
    const char *name;
    entry *entries;
    size_t n, cap;
    int line;
    int section_line; /* line of the latest [section] header */
    int error_line;   /* line of the handler's first error */
    int status;
    const char *text;   /* what is left to read */
    char **long_values; /* values of lines longer than inih's buffer, by placeholder index */
    size_t nlong;
} parse_state;

static const ct_key *cli_key(const char *section, const char *key)
{
    const ct_key *row;
    for (size_t k = 0; (row = ct_scene_key_row(k)); k++)
        if (!strcmp(row->section, section) && !strcmp(row->name, key))
            return row;
    return NULL;
}

/* The rows of every kind of surface and the CLI's, in that order: row i of n. */
static const ct_key *any_row(size_t i)
{
    for (size_t k = 0; k < ct_surface_kind_count(); k++) {
        size_t n;
        const ct_key *rows = ct_surface_kind_keys(k, &n);
        if (i < n)
            return &rows[i];
        i -= n;
    }
    return ct_scene_key_row(i);
}

static int key_known(const char *section, const char *key)
{
    for (size_t i = 0;; i++) {
        const ct_key *r = any_row(i);
        if (!r)
            return 0;
        if (!strcmp(r->section, section) && !strcmp(r->name, key))
            return 1;
    }
}

/* The sections: the usual ones in their usual order, then any other a table has. */
static void section_list(char *buf, size_t len)
{
    static const char *const usual[] = {"surface", "body",     "material", "impact", "solver",
                                        "output",  "ensemble", "table",    "fit"};
    size_t n = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < sizeof usual / sizeof usual[0]; k++)
        for (size_t i = 0; any_row(i); i++)
            if (!strcmp(any_row(i)->section, usual[k])) {
                n += (size_t)snprintf(buf + n, len > n ? len - n : 0, "%s%s", n ? ", " : "",
                                      usual[k]);
                break;
            }
    for (size_t i = 0; any_row(i) && n < len; i++) {
        const char *sec = any_row(i)->section;
        int seen = 0;
        for (size_t k = 0; k < sizeof usual / sizeof usual[0] && !seen; k++)
            seen = !strcmp(usual[k], sec);
        for (size_t j = 0; j < i && !seen; j++)
            seen = !strcmp(any_row(j)->section, sec);
        if (!seen)
            n += (size_t)snprintf(buf + n, len - n, ", %s", sec);
    }
}

static int section_known(const char *section)
{
    for (size_t i = 0; any_row(i); i++)
        if (!strcmp(any_row(i)->section, section))
            return 1;
    return 0;
}

/* " did you mean X?" for the known key (any kind's or the CLI's: "surface.fz") or, key NULL,
 * the known section ("[surface]") nearest to what was given (ct_nearest_name); "" when none is
 * that close. */
static void did_you_mean(const char *section, const char *key, char *buf, size_t len)
{
    enum { CAP = 512 };
    static _Thread_local char names[CAP][80];
    const char *list[CAP];
    char given[160];
    size_t n = 0;
    buf[0] = '\0';
    for (size_t i = 0; any_row(i) && n < CAP; i++) {
        const ct_key *r = any_row(i);
        if (key)
            snprintf(names[n], sizeof names[n], "%s.%s", r->section, r->name);
        else
            snprintf(names[n], sizeof names[n], "%s", r->section);
        list[n] = names[n];
        n++;
    }
    snprintf(given, sizeof given, key ? "%s.%s" : "%s", section, key ? key : "");
    const size_t k = ct_nearest_name(given, list, n);
    if (k < n)
        snprintf(buf, len, key ? " (did you mean %s?)" : " (did you mean [%s]?)", list[k]);
}

static entry *find_entry(parse_state *s, const char *section, const char *key)
{
    for (size_t k = 0; k < s->n; k++)
        if (!strcmp(s->entries[k].section, section) && !strcmp(s->entries[k].key, key))
            return &s->entries[k];
    return NULL;
}

static int store(parse_state *s, const char *section, const char *key, const char *value,
                 const char *where)
{
    char known[200], hint[200];
    if (!section_known(section)) {
        section_list(known, sizeof known);
        did_you_mean(section, NULL, hint, sizeof hint);
        if (strcmp(where, "--set"))
            return scene_error(CT_EINVAL, "%s:%d: [%s]: unknown section%s (known: %s)", s->name,
                               s->section_line, section, hint, known);
        return scene_error(CT_EINVAL, "--set: [%s]: unknown section%s (known: %s)", section, hint,
                           known);
    }
    if (!key_known(section, key) || strlen(key) >= sizeof s->entries[0].key) {
        did_you_mean(section, key, hint, sizeof hint);
        return scene_error(CT_EINVAL, "%s: %s.%s: unknown key%s", where, section, key, hint);
    }
    entry *e = find_entry(s, section, key);
    if (e && strcmp(where, "--set") && strncmp(e->where, "--set", 5))
        return scene_error(CT_EINVAL, "%s: %s.%s: duplicate key (first set at %s)", where, section,
                           key, e->where);
    char *copy = strdup(value);
    if (!copy)
        return scene_error(CT_ENOMEM, "scene: out of memory");
    if (!e) {
        if (s->n == s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 32;
            entry *grown = realloc(s->entries, cap * sizeof *grown);
            if (!grown) {
                free(copy);
                return scene_error(CT_ENOMEM, "scene: out of memory");
            }
            s->entries = grown;
            s->cap = cap;
        }
        e = &s->entries[s->n++];
        memset(e, 0, sizeof *e);
        snprintf(e->section, sizeof e->section, "%s", section);
        snprintf(e->key, sizeof e->key, "%s", key);
    }
    free(e->value);
    e->value = copy;
    snprintf(e->where, sizeof e->where, "%s", where);
    return CT_OK;
}

static int handler(void *user, const char *section, const char *key, const char *value)
{
    parse_state *s = user;
    char where[300];
    if (s->status != CT_OK)
        return 0; /* inih goes on after an error; the first one is reported */
    s->error_line = s->line;
    snprintf(where, sizeof where, "%s:%d", s->name, s->line);
    if (value[0] == LONG_VALUE_MARK) { /* a value too long for inih's buffer, held aside */
        unsigned long k = strtoul(value + 1, NULL, 10);
        value = k < s->nlong ? s->long_values[k] : "";
    }
    if (!section[0])
        s->status = scene_error(CT_EINVAL, "%s: %s: key outside any section", where, key);
    else
        s->status = store(s, section, key, value, where);
    return s->status == CT_OK;
}

/* inih reads line by line through this reader, which hands it every line in a normal form
 * and counts lines, so that every key has its line: line ends \n, \r\n or a lone \r; a UTF-8
 * byte-order mark dropped; leading white space dropped (inih would read an indented line as
 * the continuation of the previous value); section headers checked whole ("[name]", then
 * only a comment) against the known sections, empty ones included. inih cuts lines at its
 * buffer size (200 bytes) and would read the rest as a new line: a longer comment is handed
 * over empty, and a longer key line as "key = <mark><index>" with its value held aside. */
/* Records a reader error (fmt takes the file, the line and arg) and ends the reading. */
static char *reader_error(parse_state *s, const char *fmt, const char *arg)
{
    char msg[400];
    snprintf(msg, sizeof msg, fmt, s->name, s->line, arg);
    s->error_line = s->line;
    s->status = scene_error(CT_EINVAL, "%s", msg);
    return NULL;
}

static int is_comment_start(char c)
{
    return c == ';' || c == '#';
}

/* A section header line "[name]" (then only a comment): its name, known, handed to inih. */
static char *section_line(parse_state *s, const char *p, size_t n, char *buf, int size)
{
    const char *close = memchr(p, ']', n), *end = p + n;
    char name[64], shown[64];
    snprintf(shown, sizeof shown, "%.*s", (int)(n < 60 ? n : 60), p);
    if (!close)
        return reader_error(s, "%s:%d: %s: malformed section header (expected [name])", shown);
    const char *after = close + 1;
    while (after < end && isspace((unsigned char)*after))
        after++;
    if (after < end && !is_comment_start(*after))
        return reader_error(s, "%s:%d: %s: text after the section header", shown);
    const char *a = p + 1, *b = close;
    while (a < b && isspace((unsigned char)*a))
        a++;
    while (b > a && isspace((unsigned char)b[-1]))
        b--;
    if (b == a || (size_t)(b - a) >= sizeof name || memchr(a, '[', (size_t)(b - a)))
        return reader_error(s, "%s:%d: %s: not a section name", shown);
    memcpy(name, a, (size_t)(b - a));
    name[b - a] = '\0';
    if (!section_known(name)) {
        char msg[500], known[200], hint[200];
        section_list(known, sizeof known);
        did_you_mean(name, NULL, hint, sizeof hint);
        snprintf(msg, sizeof msg, "%%s:%%d: [%%s]: unknown section%s (known: %s)", hint, known);
        return reader_error(s, msg, name);
    }
    s->section_line = s->line;
    snprintf(buf, (size_t)size, "[%s]\n", name);
    return buf;
}

/* A key line longer than inih's buffer: split here as inih would (at the first '=' or ':',
 * an inline comment starts at ';' after white space), the value held aside and handed over
 * as "key = <mark><index>". */
static char *long_key_line(parse_state *s, const char *p, size_t n, char *buf, int size)
{
    const char *sep = p;
    while (sep < p + n && *sep != '=' && *sep != ':')
        sep++;
    if (sep == p + n)
        return reader_error(s, "%s:%d: malformed line (expected [section] or key = value)%s", "");
    const char *kend = sep;
    while (kend > p && isspace((unsigned char)kend[-1]))
        kend--;
    if ((size_t)(kend - p) + 32 > (size_t)size)
        return reader_error(s, "%s:%d: key longer than %s characters", "160");
    const char *v = sep + 1, *vend = p + n;
    while (v < vend && isspace((unsigned char)*v))
        v++;
    for (const char *c = v + 1; c < vend; c++)
        if (*c == ';' && isspace((unsigned char)c[-1])) {
            vend = c;
            break;
        }
    while (vend > v && isspace((unsigned char)vend[-1]))
        vend--;
    char **grown = realloc(s->long_values, (s->nlong + 1) * sizeof *grown);
    char *value = grown ? malloc((size_t)(vend - v) + 1) : NULL;
    if (grown)
        s->long_values = grown;
    if (!value) {
        s->status = scene_error(CT_ENOMEM, "scene: out of memory");
        return NULL;
    }
    memcpy(value, v, (size_t)(vend - v));
    value[vend - v] = '\0';
    s->long_values[s->nlong] = value;
    snprintf(buf, (size_t)size, "%.*s = %c%zu\n", (int)(kend - p), p, LONG_VALUE_MARK, s->nlong);
    s->nlong++;
    return buf;
}

static char *read_string_line(char *buf, int size, void *stream)
{
    parse_state *s = stream;
    if (s->status != CT_OK || !*s->text)
        return NULL;
    const char *p = s->text;
    size_t n = 0;
    while (p[n] && p[n] != '\n' && p[n] != '\r')
        n++;
    const char *next = p + n;
    if (next[0] == '\r' && next[1] == '\n')
        next += 2;
    else if (*next)
        next++;
    s->text = next;
    s->line++;
    if (s->line == 1 && n >= 3 && !memcmp(p, "\xEF\xBB\xBF", 3)) {
        p += 3;
        n -= 3;
    }
    /* a text scene holds no control characters but tab (and the line ends above); the
     * mark of a held-aside value is one, so it cannot be forged */
    for (size_t k = 0; k < n; k++)
        if ((unsigned char)p[k] < 0x20 && p[k] != '\t') {
            char code[8];
            snprintf(code, sizeof code, "0x%02x", (unsigned char)p[k]);
            return reader_error(s, "%s:%d: control character %s: not a scene file", code);
        }
    while (n && isspace((unsigned char)*p))
        p++, n--;
    while (n && isspace((unsigned char)p[n - 1]))
        n--;
    if (n == 0 || is_comment_start(*p)) {
        snprintf(buf, (size_t)size, "\n");
        return buf;
    }
    if (*p == '[')
        return section_line(s, p, n, buf, size);
    if (n + 2 > (size_t)size)
        return long_key_line(s, p, n, buf, size);
    memcpy(buf, p, n);
    buf[n] = '\n';
    buf[n + 1] = '\0';
    return buf;
}

/* ---- interpreting the values ---- */

static int bad(const entry *e, const char *why)
{
    size_t n = strlen(e->value);
    return scene_error(CT_EINVAL, "%s: %s.%s = %.*s%s: %s", e->where, e->section, e->key,
                       (int)(n > 80 ? 72 : n), e->value, n > 80 ? "..." : "", why);
}

/* Parses every entry of the CLI's own keys into k, in file order. */
static int cli_values(parse_state *s, ct_scene_keys *k, ct_body *body)
{
    ct_body_defaults(body);
    for (size_t i = 0; i < s->n; i++) {
        entry *e = &s->entries[i];
        const ct_key *row = cli_key(e->section, e->key);
        size_t nbody;
        const ct_key *body_rows = ct_body_keys_table(&nbody);
        const int of_body = row >= body_rows && row < body_rows + nbody;
        if (!row || (!strcmp(e->section, "surface") && !of_body)) /* surface.type: the kind's */
            continue;
        /* the body's rows (surface.periodic too) point into the body, the others into the keys */
        int st = ct_key_parse(row, e->value, of_body ? (void *)body : k);
        if (st == CT_ENOMEM)
            return scene_error(st, "scene: out of memory");
        if (st)
            return bad(e, ct_error_message());
    }
    /* a radius or an apex without a shape: the shape was forgotten (the flat strip would run,
     * ignoring them); a shape given as flat may keep a curved body's keys (to compare) */
    entry *er = find_entry(s, "body", "radius"), *ep = find_entry(s, "body", "position");
    if ((er || ep) && !find_entry(s, "body", "shape"))
        return bad(er ? er : ep, "without body.shape the body is the flat strip, which has no "
                                 "radius or apex: give body.shape = cylinder or sphere");
    return CT_OK;
}

/* The kind named by surface.type, and every key the surface takes given to it. */
static int surface_values(parse_state *s, ct_scene *sc)
{
    entry *et = find_entry(s, "surface", "type");
    int st = ct_surface_new(&sc->surface, et ? et->value : "cantor");
    if (st == CT_ENOMEM)
        return scene_error(st, "scene: out of memory");
    if (st)
        return bad(et, ct_error_message());
    /* keys of other kinds first: a scene of the wrong kind says so before anything else */
    for (size_t i = 0; i < s->n; i++) {
        entry *e = &s->entries[i];
        if (cli_key(e->section, e->key) || ct_surface_key(sc->surface, e->section, e->key))
            continue;
        if ((st = ct_surface_set(sc->surface, e->section, e->key, e->value, e->where)))
            return scene_error(st, "%s", ct_error_message());
    }
    size_t nrows;
    const ct_key *rows = ct_surface_kind_keys(ct_surface_kind_index(sc->surface), &nrows);
    for (size_t r = 0; r < nrows; r++) {
        entry *e = find_entry(s, rows[r].section, rows[r].name);
        if (e && (st = ct_surface_set(sc->surface, e->section, e->key, e->value, e->where)))
            return scene_error(st, "%s", ct_error_message());
    }
    if ((st = ct_surface_check(sc->surface, s->name)))
        return scene_error(st, "%s", ct_error_message());
    return CT_OK;
}

/* [impact]: V* given, or mass with velocity or drop_height; a bounce sequence. */
static int impact_values(parse_state *s, ct_scene *sc, ct_scene_keys *k)
{
    entry *ev = find_entry(s, "impact", "V_star"), *em = find_entry(s, "impact", "mass"),
          *evel = find_entry(s, "impact", "velocity"),
          *edrop = find_entry(s, "impact", "drop_height");
    if (edrop) { /* a body dropped from rest: v1 = sqrt(2 g h), as the velocity list */
        if (evel || ev)
            return bad(edrop, "give either drop_height or velocity / V_star, not both");
        if (!em)
            return bad(edrop, "needs impact.mass");
        free(k->run.velocity.v);
        if (!(k->run.velocity.v = malloc(sizeof(double))))
            return scene_error(CT_ENOMEM, "scene: out of memory");
        k->run.velocity.v[0] = sqrt(2.0 * k->run.gravity * k->run.drop_height);
        k->run.velocity.n = 1;
        evel = edrop;
    }
    if (ev && (em || evel))
        return bad(ev, "give either V_star or mass + velocity, not both");
    if (!ev && !(em && evel))
        return scene_error(CT_EINVAL, "%s: [impact]: needs V_star, or both mass and velocity",
                           s->name);
    ct_speeds *sp = ev ? &k->run.V_star : &k->run.velocity;
    sc->V_star = sp->v;
    sc->nvel = sp->n;
    sp->v = NULL;
    sp->n = 0;
    sc->mass = ev ? 0.0 : k->run.mass;
    sc->speeds_are_velocities = !ev;
    sc->speeds_key = ev ? "V_star" : edrop ? "drop_height" : "velocity";
    snprintf(sc->where_speeds, sizeof sc->where_speeds, "%s", (ev ? ev : evel)->where);
    sc->bounce = k->run.sequence == 1;
    entry *e = find_entry(s, "impact", "stop_speed");
    if (e && !sc->bounce)
        return bad(e, "only with sequence = bounce");
    sc->stop_speed = k->run.stop_speed;
    sc->gravity = k->run.gravity;
    if (sc->bounce && !(sc->mass > 0.0 && sc->nvel == 1))
        return scene_error(CT_EINVAL,
                           "%s: impact.sequence = bounce: needs impact.mass and one first speed "
                           "(impact.velocity or impact.drop_height)",
                           s->name);
    sc->impacts = find_entry(s, "impact", "impacts") ? k->run.impacts : sc->bounce ? 20 : 1;
    return CT_OK;
}

static int solver_values(parse_state *s, ct_scene *sc, const ct_scene_keys *k)
{
    ct_run_solver r;
    if (ct_run_keys_solver(&k->run, &r)) /* only a tolerance given below doubles' reach */
        return bad(find_entry(s, "solver", "tolerance"), ct_error_message());
    sc->opts = r.opts;
    sc->skip_failed = r.skip_failed;
    sc->path = r.path;
    sc->depth_tolerance = r.depth_tolerance;
    sc->threads = r.threads;
    return CT_OK;
}

/* [output] what under body.landings: e (the statistics over the landings, as an ensemble's,
 * also named ensemble) and landings (one row per landing, speed and impact). */
static int landings_what(parse_state *s, ct_scene *sc, entry *e)
{
    entry *el = find_entry(s, "body", "landings");
    const char *why;
    if (sc->bounce)
        return bad(el, "impact.sequence = bounce follows one body through its bounces: landings "
                       "sample separate impacts (impact.sequence = repeat)");
    if (sc->body.shape == 0)
        return bad(el, "the flat strip lands everywhere alike: landings need a curved body "
                       "(body.shape = cylinder or sphere)");
    if (sc->realisations)
        return bad(el, "a sample is a landing or a realisation, not both: drop [ensemble] "
                       "realisations (or body.landings)");
    if (!ct_surface_kind_supports(ct_surface_kind_index(sc->surface), "landings", &why))
        return bad(el, why);
    const unsigned allowed = CT_OUT_E | CT_OUT_ENSEMBLE | CT_OUT_LANDINGS;
    if (e && (sc->what & ~allowed))
        return bad(e, "with body.landings each item must be e (the statistics over the landings), "
                      "ensemble (the same) or landings (every landing's rows)");
    const unsigned what = e ? sc->what : CT_OUT_E;
    sc->what =
        (what & (CT_OUT_E | CT_OUT_ENSEMBLE) ? CT_OUT_ENSEMBLE : 0) | (what & CT_OUT_LANDINGS);
    return CT_OK;
}

/* [output] what: compare and time alone mean e with them; a bounce sequence and an ensemble
 * write their own tables. */
static int output_values(parse_state *s, ct_scene *sc, ct_scene_keys *k)
{
    entry *e = find_entry(s, "output", "what"), *ef = find_entry(s, "output", "file");
    sc->output = k->file ? k->file : strdup("-");
    k->file = NULL;
    if (!sc->output)
        return scene_error(CT_ENOMEM, "scene: out of memory");
    (void)ef;
    sc->what = e ? k->what : CT_OUT_E;
    sc->what_given = e != NULL;
    if (e && !(sc->what & ~(unsigned)(CT_OUT_COMPARE | CT_OUT_TIME)))
        sc->what |= CT_OUT_E;
    if (sc->bounce) {
        if (e && (sc->what & ~(unsigned)CT_OUT_BOUNCE))
            return bad(e, "with impact.sequence = bounce it must be bounce");
        sc->what = CT_OUT_BOUNCE;
    } else if (sc->what & CT_OUT_BOUNCE) {
        return bad(e, "bounce needs impact.sequence = bounce");
    }
    sc->history_points = (size_t)k->history_points;
    const unsigned ens = CT_OUT_ENSEMBLE | CT_OUT_REALISATIONS;
    if (sc->body.landings) /* e is the statistics over the landings, as an ensemble's */
        return landings_what(s, sc, e);
    if (sc->what & CT_OUT_LANDINGS)
        return bad(e, "landings needs body.landings (the number of apex positions to draw)");
    if (sc->realisations && !e)
        sc->what = CT_OUT_ENSEMBLE;
    else if (sc->realisations && (sc->what & ~ens))
        return bad(e, "with [ensemble] each item must be ensemble or realisations");
    else if (!sc->realisations && (sc->what & ens))
        return bad(e, "ensemble and realisations need [ensemble] realisations");
    /* what the kind of surface does not give: its reason */
    for (unsigned bit = 0; bit < CT_OUTPUT_NWORDS; bit++) {
        if (!(sc->what & (1u << bit)))
            continue;
        char word[32];
        const char *w = CT_OUTPUT_WORDS;
        for (unsigned j = 0; j < bit; j++)
            w = strchr(w, '|') + 1;
        snprintf(word, sizeof word, "%.*s", (int)strcspn(w, "|"), w);
        const char *why;
        if (!ct_surface_kind_supports(ct_surface_kind_index(sc->surface), word, &why)) {
            char msg[400];
            snprintf(msg, sizeof msg, "%s: %s", word, why);
            return e ? bad(e, msg) : scene_error(CT_EINVAL, "%s: output.what: %s", s->name, msg);
        }
    }
    /* the comparisons (the paper's laws, a profile's fitted Cantor surface) are the flat strip's:
     * beside a curved body's e they would compare different bodies */
    if ((sc->what & CT_OUT_COMPARE) && sc->body.shape != 0)
        return bad(e, "compare: the paper's laws and a fitted Cantor surface are the flat strip's, "
                      "not a curved body's (body.shape): compare with the flat strip in a run "
                      "without [body]");
    return CT_OK;
}

static int ensemble_values(parse_state *s, ct_scene *sc, const ct_scene_keys *k)
{
    entry *er = find_entry(s, "ensemble", "realisations"), *es = find_entry(s, "ensemble", "split");
    const char *why;
    const int landings = sc->body.landings != 0; /* samples too: split shares them alike */
    if ((er || (es && !landings)) &&
        !ct_surface_kind_supports(ct_surface_kind_index(sc->surface), "ensemble", &why))
        return bad(er ? er : es, why);
    sc->realisations = er ? (uint64_t)k->run.realisations : 0;
    if (es && !er && !landings)
        return bad(es, "needs ensemble.realisations or body.landings");
    if (er && ct_surface_is_set(sc->surface, "surface", "realisation")) {
        entry *e = find_entry(s, "surface", "realisation");
        return bad(e, "names the one realisation of a run without [ensemble]");
    }
    sc->split = (ct_ensemble_split)k->run.split;
    return CT_OK;
}

static int table_values(parse_state *s, ct_scene *sc, const ct_scene_keys *k)
{
    sc->table_tolerance = k->run.table_tolerance;
    sc->table_V_min = sc->table_V_max = 0.0; /* the speeds' range, once they are V* */
    if (find_entry(s, "table", "V_star")) {
        sc->table_V_min = k->run.table_range[0];
        sc->table_V_max = k->run.table_range[1];
    }
    sc->table_interpolation = (ct_interp)k->run.interpolation;
    sc->table_max_nodes = k->run.max_nodes;
    sc->table_check_points = k->run.check_points;
    sc->table_grid = k->run.table_grid;
    sc->table_qtol = k->run.table_quantile_tolerance;
    /* the probabilities, named in the file by 6 significant digits: rounded to them */
    const ct_speeds *q = &k->run.table_quantiles;
    entry *eq = find_entry(s, "table", "quantiles");
    if (q->n > CT_TABLE_MAX_QUANTILES)
        return bad(eq, "more than 64 probabilities");
    sc->table_np = q->n ? q->n : 21;
    for (size_t j = 0; j < sc->table_np; j++) {
        char text[32];
        const double p = !q->n ? (j == 0 ? 0.01 : j == 20 ? 0.99 : (double)j / 20.0) : q->v[j];
        snprintf(text, sizeof text, "%.6g", p);
        sc->table_p[j] = strtod(text, NULL);
        if (!(sc->table_p[j] > 0.0 && sc->table_p[j] <= 1.0) ||
            (j && !(sc->table_p[j] > sc->table_p[j - 1])))
            return bad(eq, "must be probabilities in (0, 1], increasing (6 significant digits)");
    }
    return CT_OK;
}

static void keys_defaults(ct_scene_keys *k)
{
    memset(k, 0, sizeof *k);
    ct_run_keys_defaults(&k->run);
    k->history_points = 200;
}

static void keys_free(ct_scene_keys *k)
{
    ct_run_keys_clear(&k->run);
    for (size_t r = 0; r < NCLI; r++)
        ct_key_clear(&cli_keys[r], k);
}

static int interpret(parse_state *s, ct_scene *sc)
{
    ct_scene_keys k;
    keys_defaults(&k);
    snprintf(sc->name, sizeof sc->name, "%s", s->name);
    int st;
    if (!(st = surface_values(s, sc)) && !(st = cli_values(s, &k, &sc->body)) &&
        !(st = impact_values(s, sc, &k)) && !(st = solver_values(s, sc, &k)) &&
        !(st = ensemble_values(s, sc, &k)) && !(st = output_values(s, sc, &k)))
        st = table_values(s, sc, &k);
    keys_free(&k);
    return st;
}

static void trim_copy(char *dst, size_t cap, const char *begin, const char *end)
{
    while (begin < end && isspace((unsigned char)*begin))
        begin++;
    while (end > begin && isspace((unsigned char)end[-1]))
        end--;
    size_t n = (size_t)(end - begin) < cap - 1 ? (size_t)(end - begin) : cap - 1;
    memcpy(dst, begin, n);
    dst[n] = '\0';
}

/* --set section.key= (an empty value): the key as if the scene had not given it, so that its
 * default or another key applies (a scene given by mass and velocity switched to V*). A key
 * the scene does not give stays unset; an unknown one is refused as by store. */
static int unset(parse_state *s, const char *section, const char *key)
{
    char known[200], hint[200];
    if (!section_known(section)) {
        section_list(known, sizeof known);
        did_you_mean(section, NULL, hint, sizeof hint);
        return scene_error(CT_EINVAL, "--set: [%s]: unknown section%s (known: %s)", section, hint,
                           known);
    }
    if (!key_known(section, key)) {
        did_you_mean(section, key, hint, sizeof hint);
        return scene_error(CT_EINVAL, "--set: %s.%s: unknown key%s", section, key, hint);
    }
    entry *e = find_entry(s, section, key);
    if (e) {
        free(e->value);
        const size_t k = (size_t)(e - s->entries);
        memmove(e, e + 1, (s->n - k - 1) * sizeof *e);
        s->n--;
    }
    return CT_OK;
}

static int apply_overrides(parse_state *s, const char *const *overrides, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        const char *o = overrides[k];
        const char *dot = strchr(o, '.'), *eq = strchr(o, '=');
        if (!dot || !eq || dot > eq || dot == o || eq == dot + 1)
            return scene_error(CT_EINVAL, "--set %s: expected section.key=value", o);
        char section[64], key[64];
        if ((size_t)(dot - o) >= sizeof section || (size_t)(eq - dot - 1) >= sizeof key)
            return scene_error(CT_EINVAL, "--set %.80s: section or key too long", o);
        size_t vlen = strlen(eq + 1) + 1;
        char *value = malloc(vlen);
        if (!value)
            return scene_error(CT_ENOMEM, "--set: out of memory");
        trim_copy(section, sizeof section, o, dot);
        trim_copy(key, sizeof key, dot + 1, eq);
        trim_copy(value, vlen, eq + 1, eq + 1 + strlen(eq + 1));
        int st = value[0] ? store(s, section, key, value, "--set") : unset(s, section, key);
        free(value);
        if (st)
            return st;
    }
    return CT_OK;
}

static int finish(parse_state *s, int ini_status, ct_scene *scene, const char *const *overrides,
                  size_t noverrides)
{
    int st = CT_OK;
    if (ini_status > 0 && (s->status == CT_OK || ini_status < s->error_line))
        st = scene_error(CT_EINVAL, "%s:%d: malformed line (expected [section] or key = value)",
                         s->name, ini_status);
    else if (ini_status != 0 && s->status == CT_OK)
        st = scene_error(CT_EIO, "%s: could not be read", s->name);
    else
        st = s->status;
    if (!st)
        st = apply_overrides(s, overrides, noverrides);
    if (!st)
        st = interpret(s, scene);
    for (size_t k = 0; k < s->n; k++)
        free(s->entries[k].value);
    free(s->entries);
    for (size_t k = 0; k < s->nlong; k++)
        free(s->long_values[k]);
    free(s->long_values);
    if (st)
        ct_scene_free(scene);
    return st;
}

int ct_scene_parse(ct_scene *scene, const char *name, const char *text,
                   const char *const *overrides, size_t noverrides)
{
    parse_state s;
    memset(&s, 0, sizeof s);
    memset(scene, 0, sizeof *scene);
    s.name = name;
    s.text = text;
    int r = ini_parse_stream(read_string_line, &s, handler, &s);
    return finish(&s, r, scene, overrides, noverrides);
}

int ct_scene_load(ct_scene *scene, const char *path, const char *const *overrides,
                  size_t noverrides)
{
    memset(scene, 0, sizeof *scene);
    /* read once, whole: a pipe or FIFO cannot be read twice; "-" is standard input */
    int is_stdin = !strcmp(path, "-");
    const char *name = is_stdin ? "(standard input)" : path;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f)
        return scene_error(CT_EIO, "%s: cannot open: %s", path, strerror(errno));
    size_t cap = 4096, n = 0;
    char *text = malloc(cap);
    int st = CT_OK;
    while (text) {
        if (n + 1 >= cap) {
            if (cap >= CT_MAX_SCENE_BYTES) {
                st = scene_error(CT_EINVAL, "%s: larger than %u MiB: not a scene file", name,
                                 CT_MAX_SCENE_BYTES >> 20);
                break;
            }
            char *t = realloc(text, cap * 2);
            if (!t) {
                free(text);
                text = NULL;
                break;
            }
            text = t;
            cap *= 2;
        }
        size_t got = fread(text + n, 1, cap - 1 - n, f);
        n += got;
        if (got == 0)
            break;
    }
    if (!text)
        st = scene_error(CT_ENOMEM, "%s: out of memory", name);
    else if (!st && ferror(f))
        st = scene_error(CT_EIO, "%s: read error: %s", name, strerror(errno));
    if (!is_stdin)
        fclose(f);
    if (st) {
        free(text);
        return st;
    }
    text[n] = '\0';
    /* binary garbage: a NUL byte cannot be in a text scene */
    const char *nul = memchr(text, '\0', n);
    if (nul) {
        int line = 1;
        for (const char *c = text; c < nul; c++)
            line += *c == '\n' || (*c == '\r' && c[1] != '\n');
        free(text);
        return scene_error(CT_EINVAL, "%s:%d: binary data (NUL byte): not a scene file", name,
                           line);
    }
    st = ct_scene_parse(scene, name, text, overrides, noverrides);
    free(text);
    if (!st && !is_stdin) { /* a measured surface's file is found beside its scene */
        const char *slash = strrchr(path, '/');
        if (slash && !(scene->scene_dir = strndup(path, (size_t)(slash - path + 1)))) {
            ct_scene_free(scene);
            return scene_error(CT_ENOMEM, "scene: out of memory");
        }
    }
    return st;
}

/* Every speed a V* whose impact energy V*^2 l0 E h0 is a number the solver can use. */
static int check_speeds(ct_scene *sc)
{
    const ct_scales *u = &sc->scales;
    for (size_t k = 0; k < sc->nvel; k++) {
        if (sc->speeds_are_velocities) {
            sc->V_star[k] = ct_V_star_of(sc->mass, sc->V_star[k], u->physical.l0, u->physical.E,
                                         u->physical.h0);
            if (!isfinite(sc->V_star[k]) || !(sc->V_star[k] > 0.0)) {
                char drop[96] = ""; /* a dropped body's speed comes from gravity too */
                if (!strcmp(sc->speeds_key, "drop_height"))
                    snprintf(drop, sizeof drop, ", gravity %g: v = sqrt(2 gravity drop_height)",
                             sc->gravity);
                return scene_error(CT_EINVAL,
                                   "%s: impact.%s (speed %zu of the list; with mass %g%s): gives "
                                   "a V* that is not a finite number > 0",
                                   sc->where_speeds, sc->speeds_key, k + 1, sc->mass, drop);
            }
        }
        double W = sc->V_star[k] * sc->V_star[k] * u->energy_scale;
        if (!isfinite(W) || !(W >= DBL_MIN))
            return scene_error(
                CT_EINVAL,
                "%s: impact.%s: V* = %g (speed %zu of the list) gives the impact energy V*^2 "
                "l0 E h0 = %g, not a finite number of at least %g, the smallest "
                "normal double (such an impact is elastic, e = 1, but not "
                "computable)",
                sc->where_speeds, sc->speeds_key, sc->V_star[k], k + 1, W, DBL_MIN);
    }
    sc->speeds_are_velocities = 0;
    return CT_OK;
}

int ct_scene_prepare(ct_scene *sc)
{
    int st = ct_surface_prepare(sc->surface, sc->scene_dir);
    if (st)
        return scene_error(st, "%s", ct_error_message());
    ct_surface_scales(sc->surface, &sc->scales);
    if ((st = check_speeds(sc)))
        return st;
    if (!(sc->table_V_max > 0.0)) {
        sc->table_V_min = sc->table_V_max = sc->V_star[0];
        for (size_t k = 1; k < sc->nvel; k++) {
            sc->table_V_min = fmin(sc->table_V_min, sc->V_star[k]);
            sc->table_V_max = fmax(sc->table_V_max, sc->V_star[k]);
        }
    }
    for (unsigned bit = 0; bit < CT_OUTPUT_NWORDS; bit++) {
        if (!(sc->what & (1u << bit)))
            continue;
        char word[32];
        const char *w = CT_OUTPUT_WORDS;
        for (unsigned j = 0; j < bit; j++)
            w = strchr(w, '|') + 1;
        snprintf(word, sizeof word, "%.*s", (int)strcspn(w, "|"), w);
        if (sc->body.landings && (1u << bit) == CT_OUT_ENSEMBLE)
            snprintf(word, sizeof word, "landings"); /* their statistics */
        if ((st = ct_surface_ready(sc->surface, word)))
            return scene_error(st, "%s", ct_error_message());
    }
    return CT_OK;
}

void ct_scene_request(const ct_scene *sc, int keep_all, ct_build_request *req)
{
    *req = (ct_build_request){.V_star = sc->V_star,
                              .nvel = sc->nvel,
                              .impacts = sc->impacts,
                              .opts = sc->opts,
                              .keep_all_rods = keep_all,
                              .threads = sc->threads,
                              .depth_tolerance = sc->depth_tolerance,
                              .body = &sc->body};
}

void ct_scene_free(ct_scene *scene)
{
    if (!scene)
        return;
    ct_surface_free(scene->surface);
    for (size_t k = 0; k < scene->ninputs; k++)
        free(scene->inputs[k]);
    scene->ninputs = 0;
    free(scene->V_star);
    free(scene->output);
    free(scene->scene_dir);
    scene->surface = NULL;
    scene->V_star = NULL;
    scene->output = NULL;
    scene->scene_dir = NULL;
}
