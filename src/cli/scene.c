/* Scene files (INI, parsed with inih) -> validated parameters. Every error names
 * file:line, the key, its value and the valid range. */
#include "scene.h"

#include <ini.h>
#include <stdarg.h>

#include <ctype.h>
#include <locale.h>
#include <errno.h>
#include <math.h>
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

typedef struct {
    const char *section, *key;
    int required;
} key_spec;

static const key_spec known_keys[] = {
    {"surface", "type", 0},
    {"surface", "fx", 0}, /* fx, fz, H: required by type = cantor (interpret) */
    {"surface", "fz", 0},
    {"surface", "H", 0},
    {"surface", "h0", 0},
    {"surface", "l0", 0},
    {"surface", "depth", 0},
    {"surface", "representation", 0},
    {"material", "E", 1},
    {"material", "sigma_y", 0},
    {"impact", "V_star", 0},
    {"impact", "mass", 0},
    {"impact", "velocity", 0},
    {"impact", "impacts", 0},
    {"solver", "quadrature", 0},
    {"solver", "nodes", 0},
    {"solver", "tolerance", 0},
    {"solver", "depth_tolerance", 0},
    {"solver", "threads", 0},
    {"solver", "on_error", 0},
    {"solver", "check", 0},
    {"solver", "path", 0},
    {"output", "file", 0},
    {"output", "what", 0},
    /* type = random_cantor */
    {"surface", "distribution", 0},
    {"surface", "fx_spread", 0},
    {"surface", "fz_spread", 0},
    {"surface", "seed", 0},
    {"surface", "realisation", 0},
    {"ensemble", "realisations", 0},
    {"ensemble", "split", 0},
    /* the impact in time */
    {"impact", "sequence", 0},
    {"impact", "drop_height", 0},
    {"impact", "gravity", 0},
    {"impact", "stop_speed", 0},
    {"output", "history_points", 0},
    /* type = profile */
    {"surface", "file", 0},
    {"surface", "unit", 0},
    {"surface", "x_unit", 0},
    {"surface", "z_unit", 0},
    {"surface", "spacing", 0},
    {"surface", "detrend", 0},
    {"surface", "trim", 0},
    {"surface", "trim_k", 0},
    {"surface", "Hstar", 0},
    {"fit", "depth_lo", 0},
    {"fit", "depth_hi", 0},
    {"fit", "lag_lo", 0},
    {"fit", "lag_hi", 0},
    {"fit", "dimension", 0},
    /* cantact table */
    {"table", "tolerance", 0},
    {"table", "V_star", 0},
    {"table", "interpolation", 0},
    {"table", "max_nodes", 0},
    {"table", "check_points", 0},
};
#define NKEYS (sizeof known_keys / sizeof known_keys[0])

typedef struct {
    char *value;
    char where[300]; /* "file:line" or "--set" */
    int set;
} entry;

typedef struct {
    const char *name;
    entry entries[NKEYS];
    int line;
    int section_line; /* line of the latest [section] header */
    int error_line;   /* line of the handler's first error */
    int status;
    const char *text;   /* what is left to read */
    char **long_values; /* values of lines longer than inih's buffer, by placeholder index */
    size_t nlong;
} parse_state;

static int find_key(const char *section, const char *key)
{
    for (size_t k = 0; k < NKEYS; k++)
        if (!strcmp(known_keys[k].section, section) && !strcmp(known_keys[k].key, key))
            return (int)k;
    return -1;
}

static int section_known(const char *section)
{
    for (size_t k = 0; k < NKEYS; k++)
        if (!strcmp(known_keys[k].section, section))
            return 1;
    return 0;
}

static int store(parse_state *s, const char *section, const char *key, const char *value,
                 const char *where)
{
    if (!section_known(section)) {
        if (strcmp(where, "--set"))
            return scene_error(CT_EINVAL,
                               "%s:%d: [%s]: unknown section (known: surface, material, "
                               "impact, solver, output, ensemble, table, fit)",
                               s->name, s->section_line, section);
        return scene_error(CT_EINVAL,
                           "--set: [%s]: unknown section (known: surface, material, impact, "
                           "solver, output, ensemble, table, fit)",
                           section);
    }
    int k = find_key(section, key);
    if (k < 0)
        return scene_error(CT_EINVAL, "%s: %s.%s: unknown key", where, section, key);
    entry *e = &s->entries[k];
    if (e->set && strcmp(where, "--set") && strncmp(e->where, "--set", 5))
        return scene_error(CT_EINVAL, "%s: %s.%s: duplicate key (first set at %s)", where, section,
                           key, e->where);
    char *copy = strdup(value);
    if (!copy)
        return scene_error(CT_ENOMEM, "scene: out of memory");
    free(e->value);
    e->value = copy;
    e->set = 1;
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
    if (*p == '[') {
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
        if (!section_known(name))
            return reader_error(s,
                                "%s:%d: [%s]: unknown section (known: surface, material, "
                                "impact, solver, output, ensemble, table, fit)",
                                name);
        s->section_line = s->line;
        snprintf(buf, (size_t)size, "[%s]\n", name);
        return buf;
    }
    if (n + 2 <= (size_t)size) {
        memcpy(buf, p, n);
        buf[n] = '\n';
        buf[n + 1] = '\0';
        return buf;
    }
    /* a key line longer than inih's buffer: split it here as inih would (at the first '='
     * or ':', an inline comment starts at ';' after white space) */
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

/* ---- value parsers ---- */

static int bad(const entry *e, const char *section, const char *key, const char *why)
{
    size_t n = strlen(e->value);
    return scene_error(CT_EINVAL, "%s: %s.%s = %.*s%s: %s", e->where, section, key,
                       (int)(n > 80 ? 72 : n), e->value, n > 80 ? "..." : "", why);
}

/* A number the whole text spells (white space around it allowed), finite and representable;
 * else 0 with *why (when not NULL) saying what is wrong. */
static int parse_number_why(const char *text, double *out, const char **why)
{
    char *end;
    const char *reason = "not a finite number";
    while (isspace((unsigned char)*text))
        text++;
    errno = 0;
    double v = *text ? strtod(text, &end) : 0.0;
    if (!*text)
        goto fail;
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == text)
        goto fail;
    if (errno == ERANGE) {
        reason = fabs(v) >= 1.0 ? "overflows double precision (|value| > 1.8e308)"
                                : "underflows double precision (0 < |value| < 2.2e-308)";
        goto fail;
    }
    if (!isfinite(v)) /* inf, nan spelled out */
        goto fail;
    *out = v;
    return 1;
fail:
    if (why)
        *why = reason;
    return 0;
}

static int parse_integer(const char *text, long *out)
{
    char *end;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return 0;
    errno = 0;
    long v = strtol(text, &end, 10);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == text || errno == ERANGE)
        return 0;
    *out = v;
    return 1;
}

static entry *get(parse_state *s, const char *section, const char *key)
{
    entry *e = &s->entries[find_key(section, key)];
    return e->set ? e : NULL;
}

/* Reads a number key that must satisfy lo < v < hi (open bounds; pass +-INFINITY). */
static int number_key(parse_state *s, const char *section, const char *key, double lo, double hi,
                      const char *range, double *out)
{
    entry *e = get(s, section, key);
    if (!e)
        return CT_OK; /* default stays */
    double v;
    const char *why;
    if (!parse_number_why(e->value, &v, &why))
        return bad(e, section, key, why);
    if (!(v > lo && v < hi))
        return bad(e, section, key, range);
    *out = v;
    return CT_OK;
}

static int integer_key(parse_state *s, const char *section, const char *key, long lo, long hi,
                       const char *range, long *out)
{
    entry *e = get(s, section, key);
    if (!e)
        return CT_OK;
    long v;
    if (!parse_integer(e->value, &v))
        return bad(e, section, key, "not an integer");
    if (v < lo || v > hi)
        return bad(e, section, key, range);
    *out = v;
    return CT_OK;
}

/* one value | a, b, c | from:to:count[:log], every value finite and > 0 */
static int velocity_list(const entry *e, const char *key, double **out, size_t *count)
{
    const char *v = e->value;
    double *vals = NULL;
    size_t n = 0;
    if (strchr(v, ':')) {
        /* exactly three or four fields, none empty: strtok would skip empty ones */
        char buf[256];
        if (strlen(v) >= sizeof buf)
            return bad(e, "impact", key, "from:to:count[:log] longer than 255 characters");
        snprintf(buf, sizeof buf, "%s", v);
        char *parts[4];
        int np = 0;
        for (char *f = buf;;) {
            char *colon = strchr(f, ':');
            if (colon)
                *colon = '\0';
            if (np == 4)
                return bad(e, "impact", key, "expected from:to:count[:log] (too many fields)");
            parts[np++] = f;
            if (!colon)
                break;
            f = colon + 1;
        }
        double from, to;
        long cnt;
        int logscale = 0;
        const char *why;
        if (np < 3)
            return bad(e, "impact", key, "expected from:to:count[:log]");
        for (int k = 0; k < 2; k++)
            if (!parse_number_why(parts[k], k ? &to : &from, &why)) {
                char msg[160];
                snprintf(msg, sizeof msg, "expected from:to:count[:log]: %s field %s",
                         k ? "the second" : "the first", why);
                return bad(e, "impact", key, msg);
            }
        if (!parse_integer(parts[2], &cnt))
            return bad(e, "impact", key, "expected from:to:count[:log]: count is no integer");
        if (np == 4) {
            char *m = parts[3], *end = m + strlen(m);
            while (isspace((unsigned char)*m))
                m++;
            while (end > m && isspace((unsigned char)end[-1]))
                end--;
            if (end - m != 3 || strncmp(m, "log", 3))
                return bad(e, "impact", key, "the fourth field may only be 'log'");
            logscale = 1;
        }
        if (cnt < 1 || cnt > CT_MAX_VELOCITIES)
            return bad(e, "impact", key, "count must satisfy 1 <= count <= 1000000");
        if (!(from > 0.0) || !(to > 0.0))
            return bad(e, "impact", key, "from and to must be > 0");
        vals = malloc((size_t)cnt * sizeof(double));
        if (!vals)
            return scene_error(CT_ENOMEM, "scene: out of memory");
        for (long k = 0; k < cnt; k++) {
            double t = cnt == 1 ? 0.0 : (double)k / (double)(cnt - 1);
            vals[k] = logscale ? from * exp(t * (log(to) - log(from))) : from + t * (to - from);
        }
        vals[cnt - 1] = to;
        n = (size_t)cnt;
    } else {
        size_t cap = 1;
        for (const char *c = v; *c; c++)
            cap += *c == ',';
        if (cap > CT_MAX_VELOCITIES)
            return bad(e, "impact", key, "at most 1000000 values");
        vals = malloc(cap * sizeof(double));
        char *buf = strdup(v);
        if (!vals || !buf) {
            free(vals);
            free(buf);
            return scene_error(CT_ENOMEM, "scene: out of memory");
        }
        char *start = buf;
        for (;;) {
            char *comma = strchr(start, ',');
            if (comma)
                *comma = '\0';
            const char *why = "must be > 0";
            vals[n] = NAN;
            if (!parse_number_why(start, &vals[n], &why) || !(vals[n] > 0.0)) {
                char msg[160];
                snprintf(msg, sizeof msg, "value %zu: %s", n + 1, why);
                free(vals);
                free(buf);
                return bad(e, "impact", key, msg);
            }
            n++;
            if (!comma)
                break;
            start = comma + 1;
        }
        free(buf);
    }
    *out = vals;
    *count = n;
    return CT_OK;
}

/* A length unit's size in metres. */
static double unit_of(const char *name)
{
    static const struct {
        const char *name;
        double metres;
    } units[] = {{"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}};
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++)
        if (!strcmp(name, units[k].name))
            return units[k].metres;
    return 0.0;
}

int ct_scene_dimension_of(const char *name)
{
    static const char *const names[] = {"variation", "structure", "spectrum"};
    for (int k = 0; k < 3; k++)
        if (!strcmp(name, names[k]))
            return CT_DIM_VARIATION + k;
    return -1;
}

/* Keys of type = profile and [fit]: given with another type they are errors that name them,
 * and the Cantor keys are errors with this type. */
static int profile_keys(parse_state *s, ct_scene *sc)
{
    static const char *const only[] = {"file",    "unit", "x_unit", "z_unit", "spacing",
                                       "detrend", "trim", "trim_k", "Hstar"};
    static const char *const fit_keys[] = {"depth_lo", "depth_hi", "lag_lo", "lag_hi", "dimension"};
    static const char *const not_here[] = {"fx", "fz", "h0", "l0", "depth", "representation"};
    const int profile = sc->surface_type == CT_SURFACE_PROFILE;
    entry *e;
    int st;
    for (size_t k = 0; k < sizeof only / sizeof only[0]; k++)
        if (!profile && (e = get(s, "surface", only[k])))
            return bad(e, "surface", only[k], "only for surface.type = profile");
    for (size_t k = 0; k < 5; k++)
        if (!profile && (e = get(s, "fit", fit_keys[k])))
            return bad(e, "fit", fit_keys[k], "only for surface.type = profile");
    if (!profile)
        return CT_OK;
    for (size_t k = 0; k < sizeof not_here / sizeof not_here[0]; k++)
        if ((e = get(s, "surface", not_here[k])))
            return bad(e, "surface", not_here[k],
                       "not for surface.type = profile (the measured surface gives it)");
    if (!(e = get(s, "surface", "file")) || !e->value[0])
        return scene_error(CT_EINVAL, "%s: surface.file: required key missing (type = profile)",
                           s->name);
    if (!(sc->profile_file = strdup(e->value)))
        return scene_error(CT_ENOMEM, "scene: out of memory");
    if (!get(s, "material", "sigma_y"))
        return scene_error(CT_EINVAL,
                           "%s: material.sigma_y: required key missing (type = profile: E and "
                           "sigma_y in Pa)",
                           s->name);
    double xu = 0.0, zu = 0.0; /* 0: the unit the file's column names state */
    static const char *const unit_keys[] = {"unit", "x_unit", "z_unit"};
    for (int k = 0; k < 3; k++)
        if ((e = get(s, "surface", unit_keys[k]))) {
            double u = unit_of(e->value);
            if (!(u > 0.0))
                return bad(e, "surface", unit_keys[k], "must be m, mm, um or nm");
            if (k != 2)
                xu = u;
            if (k != 1)
                zu = u;
        }
    sc->read_opts.x_unit = xu;
    sc->read_opts.z_unit = zu;
    sc->read_opts.dx = 0.0;
    if ((st = number_key(s, "surface", "spacing", 0.0, INFINITY,
                         "must be > 0 (one column of heights at this spacing, in x_unit)",
                         &sc->read_opts.dx)))
        return st;
    sc->detrend = CT_DETREND_LINEAR;
    if ((e = get(s, "surface", "detrend"))) {
        static const char *const names[] = {"none", "mean", "linear", "quadratic"};
        int found = -1;
        for (int k = 0; k < 4; k++)
            if (!strcmp(e->value, names[k]))
                found = k;
        if (found < 0)
            return bad(e, "surface", "detrend", "must be none, mean, linear or quadratic");
        sc->detrend = (ct_detrend)found;
    }
    sc->trim_k = 0.0;
    if ((e = get(s, "surface", "trim"))) {
        if (!strcmp(e->value, "rq"))
            sc->trim_k = 3.0;
        else if (strcmp(e->value, "none"))
            return bad(e, "surface", "trim", "must be none or rq (clip at mean + trim_k Rq)");
    }
    if ((e = get(s, "surface", "trim_k"))) {
        if (!(sc->trim_k > 0.0))
            return bad(e, "surface", "trim_k", "only with surface.trim = rq");
        if ((st = number_key(s, "surface", "trim_k", 0.0, INFINITY, "must be > 0", &sc->trim_k)))
            return st;
    }
    entry *eh = get(s, "surface", "H"), *es = get(s, "surface", "Hstar");
    if (!eh == !es)
        return scene_error(CT_EINVAL,
                           "%s: type = profile needs one of surface.H (H* as a multiple of the "
                           "peak-to-valley depth) and surface.Hstar (in z_unit)",
                           s->name);
    sc->Hstar_given = sc->H_over_Rt = 0.0;
    if ((st = number_key(s, "surface", "Hstar", 0.0, INFINITY, "must be > 0", &sc->Hstar_given)) ||
        (st = number_key(s, "surface", "H", 1.0, INFINITY,
                         "must satisfy H > 1 (H* = H Rt must exceed the peak-to-valley depth)",
                         &sc->H_over_Rt)))
        return st;
    for (int k = 0; k < 4; k++) {
        sc->fit_band[k] = 0.0;
        if ((st = number_key(s, "fit", fit_keys[k], 0.0, INFINITY,
                             "must be > 0 (in the file's unit)", &sc->fit_band[k])))
            return st;
    }
    sc->fit_dimension = CT_DIM_VARIATION;
    if ((e = get(s, "fit", "dimension"))) {
        const int m = ct_scene_dimension_of(e->value);
        if (m < 0)
            return bad(e, "fit", "dimension", "must be variation, structure or spectrum");
        sc->fit_dimension = (ct_dimension_method)m;
    }
    return CT_OK;
}

/* Keys of type = random_cantor and [ensemble]: given with another type they are errors that
 * name them; representation (a cantor key) is one with this type. */
static int random_cantor_keys(parse_state *s, ct_scene *sc)
{
    static const char *const random_only[] = {"distribution", "fx_spread", "fz_spread", "seed",
                                              "realisation"};
    entry *e;
    int st;
    const int random = sc->surface_type == CT_SURFACE_RANDOM_CANTOR;
    for (size_t k = 0; k < sizeof random_only / sizeof random_only[0]; k++)
        if (!random && (e = get(s, "surface", random_only[k])))
            return bad(e, "surface", random_only[k], "only for surface.type = random_cantor");
    static const char *const ensemble_keys[] = {"realisations", "split"};
    for (size_t k = 0; k < 2; k++)
        if (!random && (e = get(s, "ensemble", ensemble_keys[k])))
            return bad(e, "ensemble", ensemble_keys[k], "only for surface.type = random_cantor");
    if (!random)
        return CT_OK;
    if ((e = get(s, "surface", "representation")))
        return bad(e, "surface", "representation",
                   "not for surface.type = random_cantor (every piece is its own rod)");
    if (!get(s, "surface", "depth"))
        return scene_error(CT_EINVAL,
                           "%s: surface.depth: required key missing (type = "
                           "random_cantor needs an integer depth 0..%d)",
                           s->name, CT_MAX_RANDOM_DEPTH);
    sc->ratio_dist = CT_RATIO_LOGNORMAL;
    if ((e = get(s, "surface", "distribution"))) {
        if (!strcmp(e->value, "uniform"))
            sc->ratio_dist = CT_RATIO_UNIFORM;
        else if (!strcmp(e->value, "lognormal"))
            sc->ratio_dist = CT_RATIO_LOGNORMAL;
        else
            return bad(e, "surface", "distribution", "must be uniform or lognormal");
    }
    const int uniform = sc->ratio_dist == CT_RATIO_UNIFORM;
    const char *range = uniform ? "must satisfy 0 <= spread < 1 (distribution = uniform)"
                                : "must satisfy 0 <= spread <= 10 (distribution = lognormal)";
    sc->fx_spread = sc->fz_spread = 0.0;
    if ((st = number_key(s, "surface", "fx_spread", -INFINITY, INFINITY, range, &sc->fx_spread)) ||
        (st = number_key(s, "surface", "fz_spread", -INFINITY, INFINITY, range, &sc->fz_spread)))
        return st;
    const char *keys[2] = {"fx_spread", "fz_spread"};
    const double v[2] = {sc->fx_spread, sc->fz_spread};
    for (int k = 0; k < 2; k++)
        if (!(v[k] >= 0.0) || (uniform ? !(v[k] < 1.0) : !(v[k] <= 10.0)))
            return bad(get(s, "surface", keys[k]), "surface", keys[k], range);
    static const char *const counts[] = {"seed", "realisation"};
    uint64_t *dst[] = {&sc->seed, &sc->realisation};
    for (int k = 0; k < 2; k++) {
        *dst[k] = 0;
        if (!(e = get(s, "surface", counts[k])))
            continue;
        const char *t = e->value;
        char *end;
        while (isspace((unsigned char)*t))
            t++;
        errno = 0;
        unsigned long long x = strtoull(t, &end, 10);
        while (isspace((unsigned char)*end))
            end++;
        if (!isdigit((unsigned char)*t) || *end || errno == ERANGE)
            return bad(e, "surface", counts[k], "must be an integer 0 <= n < 2^64");
        *dst[k] = (uint64_t)x;
    }
    sc->realisations = 0;
    if ((e = get(s, "ensemble", "realisations"))) {
        long r;
        if (!parse_integer(e->value, &r))
            return bad(e, "ensemble", "realisations", "not an integer");
        if (r < 1 || r > 1000000000L)
            return bad(e, "ensemble", "realisations", "must satisfy 1 <= realisations <= 1e9");
        sc->realisations = (uint64_t)r;
        if ((e = get(s, "surface", "realisation")))
            return bad(e, "surface", "realisation",
                       "names the one realisation of a run without [ensemble]");
    }
    sc->split = CT_SPLIT_AUTO;
    if ((e = get(s, "ensemble", "split"))) {
        if (!sc->realisations)
            return bad(e, "ensemble", "split", "needs ensemble.realisations");
        if (!strcmp(e->value, "auto"))
            sc->split = CT_SPLIT_AUTO;
        else if (!strcmp(e->value, "realisations"))
            sc->split = CT_SPLIT_REALISATIONS;
        else if (!strcmp(e->value, "rods"))
            sc->split = CT_SPLIT_RODS;
        else
            return bad(e, "ensemble", "split", "must be auto, realisations or rods");
    }
    return CT_OK;
}

/* [table]: the keys of cantact table. Its V* range defaults to the range of [impact]'s speeds. */
static int table_keys(parse_state *s, ct_scene *sc)
{
    entry *e;
    int st;
    sc->table_tolerance = 1e-6;
    if ((st = number_key(s, "table", "tolerance", -INFINITY, INFINITY,
                         "must satisfy 1e-13 <= tolerance < 0.5", &sc->table_tolerance)))
        return st;
    if (!(sc->table_tolerance >= 1e-13 && sc->table_tolerance < 0.5))
        return bad(get(s, "table", "tolerance"), "table", "tolerance",
                   "must satisfy 1e-13 <= tolerance < 0.5");
    sc->table_V_min = sc->table_V_max = sc->V_star[0];
    for (size_t k = 1; k < sc->nvel; k++) {
        sc->table_V_min = fmin(sc->table_V_min, sc->V_star[k]);
        sc->table_V_max = fmax(sc->table_V_max, sc->V_star[k]);
    }
    if ((e = get(s, "table", "V_star"))) {
        const char *colon = strchr(e->value, ':');
        char first[128];
        const char *why = "not a finite number";
        if (!colon || strchr(colon + 1, ':') || (size_t)(colon - e->value) >= sizeof first)
            return bad(e, "table", "V_star", "expected from:to (two numbers, 0 < from < to)");
        memcpy(first, e->value, (size_t)(colon - e->value));
        first[colon - e->value] = '\0';
        if (!parse_number_why(first, &sc->table_V_min, &why) ||
            !parse_number_why(colon + 1, &sc->table_V_max, &why))
            return bad(e, "table", "V_star", why);
        if (!(sc->table_V_min > 0.0 && sc->table_V_max > sc->table_V_min))
            return bad(e, "table", "V_star", "expected from:to with 0 < from < to");
    }
    sc->table_interpolation = CT_INTERP_MONOTONE_CUBIC;
    if ((e = get(s, "table", "interpolation"))) {
        if (!strcmp(e->value, "monotone_cubic"))
            sc->table_interpolation = CT_INTERP_MONOTONE_CUBIC;
        else if (!strcmp(e->value, "linear"))
            sc->table_interpolation = CT_INTERP_LINEAR;
        else
            return bad(e, "table", "interpolation", "must be monotone_cubic or linear");
    }
    sc->table_max_nodes = 100000;
    sc->table_check_points = 16;
    if ((st = integer_key(s, "table", "max_nodes", 2, 10000000,
                          "must satisfy 2 <= max_nodes <= 10000000", &sc->table_max_nodes)) ||
        (st = integer_key(s, "table", "check_points", 1, 1000,
                          "must satisfy 1 <= check_points <= 1000", &sc->table_check_points)))
        return st;
    return CT_OK;
}

void ct_scene_random_cantor(const ct_scene *sc, ct_random_cantor *rc)
{
    rc->params = sc->params;
    rc->dist = sc->ratio_dist;
    rc->fx_spread = sc->fx_spread;
    rc->fz_spread = sc->fz_spread;
    rc->depth = sc->depth;
    rc->seed = sc->seed;
}

static int interpret(parse_state *s, ct_scene *sc)
{
    int st;
    entry *e;
    sc->surface_type = CT_SURFACE_CANTOR;
    if ((e = get(s, "surface", "type"))) {
        if (!strcmp(e->value, "cantor"))
            sc->surface_type = CT_SURFACE_CANTOR;
        else if (!strcmp(e->value, "random_cantor"))
            sc->surface_type = CT_SURFACE_RANDOM_CANTOR;
        else if (!strcmp(e->value, "profile"))
            sc->surface_type = CT_SURFACE_PROFILE;
        else
            return bad(e, "surface", "type", "must be cantor, random_cantor or profile");
    }
    if ((st = random_cantor_keys(s, sc)) || (st = profile_keys(s, sc)))
        return st;
    for (size_t k = 0; k < NKEYS; k++)
        if (known_keys[k].required && !s->entries[k].set)
            return scene_error(CT_EINVAL, "%s: %s.%s: required key missing", s->name,
                               known_keys[k].section, known_keys[k].key);

    if (sc->surface_type == CT_SURFACE_CANTOR || sc->surface_type == CT_SURFACE_RANDOM_CANTOR) {
        static const char *const cantor_required[] = {"fx", "fz", "H"};
        for (size_t k = 0; k < 3; k++)
            if (!get(s, "surface", cantor_required[k]))
                return scene_error(CT_EINVAL, "%s: surface.%s: required key missing", s->name,
                                   cantor_required[k]);
    }

    ct_params *p = &sc->params;
    double H = 0.0;
    p->h0 = 1.0;
    p->l0 = 1.0;
    p->sigma_y = 1.0;
    if (sc->surface_type == CT_SURFACE_PROFILE) { /* the material; the rest is the file's */
        if ((st =
                 number_key(s, "material", "sigma_y", 0.0, INFINITY, "must be > 0", &p->sigma_y)) ||
            (st = number_key(s, "material", "E", 0.0, INFINITY, "must be > 0", &p->E)))
            return st;
        if (!(p->E > p->sigma_y))
            return bad(get(s, "material", "E"), "material", "E",
                       "must be > sigma_y (yield strain sigma_y/E < 1)");
    } else if ((st =
                    number_key(s, "surface", "fx", 1.0, INFINITY, "must satisfy fx > 1", &p->fx)) ||
               (st = number_key(s, "surface", "fz", 1.0, 2.0, "must satisfy 1 < fz < 2", &p->fz)) ||
               (st = number_key(s, "surface", "H", 1.0, INFINITY,
                                "H = H*/h0 must satisfy H > 1 (the stage-0 rod needs a length)",
                                &H)) ||
               (st = number_key(s, "surface", "h0", 0.0, INFINITY, "must be > 0", &p->h0)) ||
               (st = number_key(s, "surface", "l0", 0.0, INFINITY, "must be > 0", &p->l0)) ||
               (st = number_key(s, "material", "sigma_y", 0.0, INFINITY, "must be > 0",
                                &p->sigma_y)) ||
               (st = number_key(s, "material", "E", 0.0, INFINITY, "must be > 0", &p->E)))
        return st;
    if (sc->surface_type != CT_SURFACE_PROFILE) {
        if (!(p->E > p->sigma_y))
            return bad(get(s, "material", "E"), "material", "E",
                       "must be > sigma_y (yield strain sigma_y/E < 1)");
        p->Hstar = H * p->h0;
        if ((st = ct_params_validate(p)))
            return scene_error(st, "%s: %s", s->name, ct_error_message());
    }

    sc->depth = CT_DEPTH_AUTO;
    if ((e = get(s, "surface", "depth"))) {
        long d;
        if (!strcmp(e->value, "auto"))
            sc->depth = CT_DEPTH_AUTO;
        else if (!strcmp(e->value, "fractal"))
            sc->depth = CT_DEPTH_FRACTAL;
        else if (!parse_integer(e->value, &d))
            return bad(e, "surface", "depth", "must be an integer >= 0, auto or fractal");
        else if (d < 0 || d > CT_MAX_STAGES_DEPTH)
            return bad(e, "surface", "depth", "must satisfy 0 <= depth <= 100000000");
        else
            sc->depth = d;
    }
    if (sc->surface_type == CT_SURFACE_RANDOM_CANTOR &&
        (sc->depth < 0 || sc->depth > CT_MAX_RANDOM_DEPTH))
        return bad(get(s, "surface", "depth"), "surface", "depth",
                   "type = random_cantor needs an integer 0 <= depth <= 30");
    sc->representation = CT_REP_STAGES;
    if ((e = get(s, "surface", "representation"))) {
        if (!strcmp(e->value, "stages"))
            sc->representation = CT_REP_STAGES;
        else if (!strcmp(e->value, "segments"))
            sc->representation = CT_REP_SEGMENTS;
        else
            return bad(e, "surface", "representation", "must be stages or segments");
    }
    if (sc->representation == CT_REP_SEGMENTS) {
        e = get(s, "surface", "depth");
        if (sc->depth < 0)
            return scene_error(CT_EINVAL,
                               "%s: surface.representation = segments: needs an integer "
                               "surface.depth (0..%d)",
                               e ? e->where : s->name, CT_MAX_SEGMENTS_DEPTH);
        if (sc->depth > CT_MAX_SEGMENTS_DEPTH)
            return bad(e, "surface", "depth", "segments allow 0 <= depth <= 40");
    }

    entry *ev = get(s, "impact", "V_star"), *em = get(s, "impact", "mass"),
          *evel = get(s, "impact", "velocity");
    entry *edrop = get(s, "impact", "drop_height");
    sc->gravity = 9.81;
    if ((st = number_key(s, "impact", "gravity", 0.0, INFINITY, "must be > 0", &sc->gravity)))
        return st;
    if (edrop) { /* a body dropped from rest: v1 = sqrt(2 g h), as the velocity list */
        double hd = 0.0;
        if (evel || ev)
            return bad(edrop, "impact", "drop_height",
                       "give either drop_height or velocity / V_star, not both");
        if (!em)
            return bad(edrop, "impact", "drop_height", "needs impact.mass");
        if ((st = number_key(s, "impact", "drop_height", 0.0, INFINITY, "must be > 0", &hd)))
            return st;
        char speed[64];
        snprintf(speed, sizeof speed, "%.17g", sqrt(2.0 * sc->gravity * hd));
        if ((st = store(s, "impact", "velocity", speed, edrop->where)))
            return st;
        evel = get(s, "impact", "velocity");
    }
    if (ev && (em || evel))
        return bad(ev, "impact", "V_star", "give either V_star or mass + velocity, not both");
    if (!ev && !(em && evel))
        return scene_error(CT_EINVAL, "%s: [impact]: needs V_star, or both mass and velocity",
                           s->name);
    sc->mass = 0.0;
    if (ev) {
        if ((st = velocity_list(ev, "V_star", &sc->V_star, &sc->nvel)))
            return st;
    } else {
        double m = 0.0;
        if ((st = number_key(s, "impact", "mass", 0.0, INFINITY, "must be > 0", &m)))
            return st;
        if ((st = velocity_list(evel, "velocity", &sc->V_star, &sc->nvel)))
            return st;
        sc->mass = m;
        /* V* = sqrt(m v1^2 / (2 l0 E h0)); a measured surface's l0 and h0 come with its file */
        double scale = 2.0 * ct_energy_scale(p);
        sc->speeds_are_velocities = sc->surface_type == CT_SURFACE_PROFILE;
        for (size_t k = 0; k < sc->nvel && !sc->speeds_are_velocities; k++) {
            sc->V_star[k] = sqrt(m / scale) * sc->V_star[k];
            if (!isfinite(sc->V_star[k]) || !(sc->V_star[k] > 0.0))
                return bad(evel, "impact", "velocity",
                           "gives a V* that is not a finite number > 0");
        }
    }
    /* every impact energy V*^2 l0 E h0 must be a number the solver can use */
    for (size_t k = 0; k < sc->nvel && !sc->speeds_are_velocities; k++) {
        double W = sc->V_star[k] * sc->V_star[k] * ct_energy_scale(p);
        if (!isfinite(W) || !(W > 0.0)) {
            char msg[200];
            snprintf(msg, sizeof msg,
                     "V* = %g (value %zu) gives the impact energy V*^2 l0 E h0 = %g, not a finite "
                     "number > 0",
                     sc->V_star[k], k + 1, W);
            return bad(ev ? ev : evel, "impact", ev ? "V_star" : "velocity", msg);
        }
    }
    sc->bounce = 0;
    if ((e = get(s, "impact", "sequence"))) {
        if (!strcmp(e->value, "bounce"))
            sc->bounce = 1;
        else if (strcmp(e->value, "sweep"))
            return bad(e, "impact", "sequence", "must be sweep or bounce");
    }
    sc->stop_speed = 0.0;
    if ((e = get(s, "impact", "stop_speed"))) {
        if (!sc->bounce)
            return bad(e, "impact", "stop_speed", "only with sequence = bounce");
        if ((st = number_key(s, "impact", "stop_speed", -1.0, INFINITY, "must be >= 0",
                             &sc->stop_speed)) ||
            !(sc->stop_speed >= 0.0))
            return st ? st : bad(e, "impact", "stop_speed", "must be >= 0");
    }
    if (sc->bounce && !(sc->mass > 0.0 && sc->nvel == 1))
        return scene_error(CT_EINVAL,
                           "%s: impact.sequence = bounce: needs impact.mass and one first speed "
                           "(impact.velocity or impact.drop_height)",
                           s->name);
    sc->impacts = sc->bounce ? 20 : 1;
    if ((st = integer_key(s, "impact", "impacts", 1, 1000000,
                          "must satisfy 1 <= impacts <= 1000000", &sc->impacts)))
        return st;
    if ((st = table_keys(s, sc)))
        return st;

    ct_impact_opts_default(&sc->opts);
    if ((e = get(s, "solver", "quadrature"))) {
        int found = 0;
        for (int r = CT_QUAD_BREAKPOINTS; r <= CT_QUAD_CLOSED; r++)
            if (!strcmp(e->value, ct_quad_rule_name((ct_quad_rule)r))) {
                sc->opts.rule = (ct_quad_rule)r;
                found = 1;
            }
        if (!found)
            return bad(e, "solver", "quadrature",
                       "must be breakpoints, trapezoid, simpson, gauss or closed");
    }
    long nodes = (long)sc->opts.nodes;
    if ((st = integer_key(s, "solver", "nodes", 3, 100000000, "must satisfy 3 <= nodes <= 1e8",
                          &nodes)))
        return st;
    sc->opts.nodes = (size_t)nodes;
    sc->skip_failed = 0;
    if ((e = get(s, "solver", "on_error"))) {
        if (!strcmp(e->value, "skip"))
            sc->skip_failed = 1;
        else if (strcmp(e->value, "stop"))
            return bad(e, "solver", "on_error", "must be stop or skip");
    }
    sc->path = CT_PATH_AUTO;
    if ((e = get(s, "solver", "path"))) {
        if (!strcmp(e->value, "auto"))
            sc->path = CT_PATH_AUTO;
        else if (!strcmp(e->value, "curve"))
            sc->path = CT_PATH_CURVE;
        else if (!strcmp(e->value, "rods"))
            sc->path = CT_PATH_RODS;
        else
            return bad(e, "solver", "path", "must be auto, curve or rods");
    }
    if ((e = get(s, "solver", "check"))) {
        if (!strcmp(e->value, "closed"))
            sc->opts.check = 1;
        else if (!strcmp(e->value, "none"))
            sc->opts.check = 0;
        else
            return bad(e, "solver", "check", "must be closed or none");
    }
    if ((st = number_key(s, "solver", "tolerance", 0.0, 1e-3, "must satisfy 0 < tolerance < 1e-3",
                         &sc->opts.tolerance)))
        return st;
    if (sc->opts.tolerance < 1e-15)
        return bad(get(s, "solver", "tolerance"), "solver", "tolerance",
                   "must be >= 1e-15 (double precision)");
    sc->depth_tolerance = 1e-12;
    if ((st = number_key(s, "solver", "depth_tolerance", 0.0, 1e-2,
                         "must satisfy 0 < depth_tolerance < 1e-2", &sc->depth_tolerance)))
        return st;
    long threads = 0;
    if ((st = integer_key(s, "solver", "threads", 0, 1024, "must satisfy 0 <= threads <= 1024",
                          &threads)))
        return st;
    sc->threads = (int)threads;

    e = get(s, "output", "file");
    if (e && !e->value[0])
        return bad(e, "output", "file", "must be a path or -");
    sc->output = strdup(e ? e->value : "-");
    if (!sc->output)
        return scene_error(CT_ENOMEM, "scene: out of memory");
    sc->what = CT_OUT_E;
    if ((e = get(s, "output", "what"))) {
        sc->what = 0;
        char *buf = strdup(e->value);
        if (!buf)
            return scene_error(CT_ENOMEM, "scene: out of memory");
        for (char *tok = strtok(buf, ", \t"); tok; tok = strtok(NULL, ", \t")) {
            if (!strcmp(tok, "e"))
                sc->what |= CT_OUT_E;
            else if (!strcmp(tok, "curve"))
                sc->what |= CT_OUT_CURVE;
            else if (!strcmp(tok, "profile"))
                sc->what |= CT_OUT_PROFILE;
            else if (!strcmp(tok, "compare"))
                sc->what |= CT_OUT_COMPARE;
            else if (!strcmp(tok, "bearing"))
                sc->what |= CT_OUT_BEARING;
            else if (!strcmp(tok, "ensemble"))
                sc->what |= CT_OUT_ENSEMBLE;
            else if (!strcmp(tok, "realisations"))
                sc->what |= CT_OUT_REALISATIONS;
            else if (!strcmp(tok, "time"))
                sc->what |= CT_OUT_TIME;
            else if (!strcmp(tok, "history"))
                sc->what |= CT_OUT_HISTORY;
            else if (!strcmp(tok, "bounce"))
                sc->what |= CT_OUT_BOUNCE;
            else {
                free(buf);
                return bad(e, "output", "what",
                           "each item must be e, time, curve, history, profile, compare, "
                           "bearing, bounce, ensemble or realisations");
            }
        }
        free(buf);
        if (!sc->what)
            return bad(e, "output", "what", "name at least one of e, curve, profile, compare");
        /* compare adds the paper's laws to e and curve, time adds the impact in time to e:
         * alone they mean e with them */
        if (!(sc->what & ~(unsigned)(CT_OUT_COMPARE | CT_OUT_TIME)))
            sc->what |= CT_OUT_E;
    }
    if (sc->bounce) { /* a bounce sequence writes its own table */
        if (e && (sc->what & ~(unsigned)CT_OUT_BOUNCE))
            return bad(e, "output", "what", "with impact.sequence = bounce it must be bounce");
        sc->what = CT_OUT_BOUNCE;
    } else if (sc->what & CT_OUT_BOUNCE) {
        return bad(e, "output", "what", "bounce needs impact.sequence = bounce");
    }
    long hp = 200;
    if ((st = integer_key(s, "output", "history_points", 0, 100000000,
                          "must satisfy 0 <= history_points <= 1e8", &hp)))
        return st;
    sc->history_points = (size_t)hp;
    /* an ensemble writes its statistics and samples, a single surface the rest */
    const unsigned ens = CT_OUT_ENSEMBLE | CT_OUT_REALISATIONS;
    if (sc->realisations && !e)
        sc->what = CT_OUT_ENSEMBLE;
    else if (sc->realisations && (sc->what & ~ens))
        return bad(e, "output", "what",
                   "with [ensemble] each item must be ensemble or realisations");
    else if (!sc->realisations && (sc->what & ens))
        return bad(e, "output", "what", "ensemble and realisations need [ensemble] realisations");
    if (sc->surface_type == CT_SURFACE_RANDOM_CANTOR && (sc->what & CT_OUT_COMPARE))
        return bad(e, "output", "what",
                   "compare: the paper's laws model the deterministic surface (type = cantor)");
    if (sc->surface_type != CT_SURFACE_PROFILE && (sc->what & CT_OUT_BEARING))
        return bad(e, "output", "what", "bearing: only for surface.type = profile");
    return CT_OK;
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
        int st = store(s, section, key, value, "--set");
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
    for (size_t k = 0; k < NKEYS; k++)
        free(s->entries[k].value);
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
    /* numbers are read in the C locale whatever the caller's (a decimal comma would make
     * "1.5" fail and "1,5" pass): uselocale is per thread, and restored */
    locale_t c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    locale_t before = c_locale ? uselocale(c_locale) : (locale_t)0;
    int r = ini_parse_stream(read_string_line, &s, handler, &s);
    int st = finish(&s, r, scene, overrides, noverrides);
    if (c_locale) {
        uselocale(before);
        freelocale(c_locale);
    }
    return st;
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
void ct_scene_make_dimensionless(ct_scene *sc)
{
    ct_params *p = &sc->params;
    sc->physical = *p;
    if (sc->surface_type != CT_SURFACE_CANTOR && sc->surface_type != CT_SURFACE_RANDOM_CANTOR)
        return;
    p->Hstar = p->Hstar / p->h0;
    p->E = p->E / p->sigma_y;
    p->l0 = p->h0 = p->sigma_y = 1.0;
}

void ct_scene_free(ct_scene *scene)
{
    if (!scene)
        return;
    free(scene->V_star);
    free(scene->output);
    free(scene->profile_file);
    free(scene->scene_dir);
    ct_profile_free(scene->profile);
    scene->V_star = NULL;
    scene->output = NULL;
    scene->profile_file = NULL;
    scene->scene_dir = NULL;
    scene->profile = NULL;
}
