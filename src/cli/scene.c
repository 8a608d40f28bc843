/* Scene files (INI, parsed with inih) -> validated parameters. Every error names
 * file:line, the key, its value and the valid range. */
#include "scene.h"

#include <ini.h>
#include <stdarg.h>

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static _Thread_local char scene_message[512];

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
    const char *text; /* string reader */
    FILE *file;       /* file reader */
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
                               "impact, solver, output, ensemble)",
                               s->name, s->section_line, section);
        return scene_error(CT_EINVAL,
                           "--set: [%s]: unknown section (known: surface, material, impact, "
                           "solver, output, ensemble)",
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
    if (!section[0])
        s->status = scene_error(CT_EINVAL, "%s: %s: key outside any section", where, key);
    else
        s->status = store(s, section, key, value, where);
    return s->status == CT_OK;
}

/* inih reads line by line through these readers; counting here gives every key its line,
 * and every section header its own. */
static void note_line(parse_state *s, const char *buf)
{
    s->line++;
    while (isspace((unsigned char)*buf))
        buf++;
    if (*buf == '[')
        s->section_line = s->line;
}

static char *read_file_line(char *buf, int size, void *stream)
{
    parse_state *s = stream;
    char *r = fgets(buf, size, s->file);
    if (r)
        note_line(s, buf);
    return r;
}

static char *read_string_line(char *buf, int size, void *stream)
{
    parse_state *s = stream;
    if (!*s->text)
        return NULL;
    int n = 0;
    while (n < size - 1 && s->text[n] && s->text[n] != '\n')
        n++;
    if (n < size - 1 && s->text[n] == '\n')
        n++;
    memcpy(buf, s->text, (size_t)n);
    buf[n] = '\0';
    s->text += n;
    note_line(s, buf);
    return buf;
}

/* ---- value parsers ---- */

static int bad(const entry *e, const char *section, const char *key, const char *why)
{
    return scene_error(CT_EINVAL, "%s: %s.%s = %s: %s", e->where, section, key, e->value, why);
}

static int parse_number(const char *text, double *out)
{
    char *end;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return 0;
    errno = 0;
    double v = strtod(text, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (*end || end == text || !isfinite(v) || errno == ERANGE)
        return 0;
    *out = v;
    return 1;
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
    if (!parse_number(e->value, &v))
        return bad(e, section, key, "not a finite number");
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
        char buf[256];
        snprintf(buf, sizeof buf, "%s", v);
        char *parts[5];
        int np = 0;
        for (char *tok = strtok(buf, ":"); tok && np < 5; tok = strtok(NULL, ":"))
            parts[np++] = tok;
        double from, to;
        long cnt;
        int logscale = 0;
        if (np < 3 || np > 4 || !parse_number(parts[0], &from) || !parse_number(parts[1], &to) ||
            !parse_integer(parts[2], &cnt))
            return bad(e, "impact", key, "expected from:to:count[:log]");
        if (np == 4) {
            char *m = parts[3];
            while (isspace((unsigned char)*m))
                m++;
            if (strncmp(m, "log", 3) || (m[3] && !isspace((unsigned char)m[3])))
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
            if (!parse_number(start, &vals[n]) || !(vals[n] > 0.0)) {
                free(vals);
                free(buf);
                return bad(e, "impact", key, "each value must be a finite number > 0");
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
        else
            return bad(e, "surface", "type", "must be cantor or random_cantor");
    }
    if ((st = random_cantor_keys(s, sc)))
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
    if ((st = number_key(s, "surface", "fx", 1.0, INFINITY, "must satisfy fx > 1", &p->fx)) ||
        (st = number_key(s, "surface", "fz", 1.0, 2.0, "must satisfy 1 < fz < 2", &p->fz)) ||
        (st = number_key(s, "surface", "H", 1.0, INFINITY,
                         "H = H*/h0 must satisfy H > 1 (the stage-0 rod needs a length)", &H)) ||
        (st = number_key(s, "surface", "h0", 0.0, INFINITY, "must be > 0", &p->h0)) ||
        (st = number_key(s, "surface", "l0", 0.0, INFINITY, "must be > 0", &p->l0)) ||
        (st = number_key(s, "material", "sigma_y", 0.0, INFINITY, "must be > 0", &p->sigma_y)) ||
        (st = number_key(s, "material", "E", 0.0, INFINITY, "must be > 0", &p->E)))
        return st;
    if (!(p->E > p->sigma_y))
        return bad(get(s, "material", "E"), "material", "E",
                   "must be > sigma_y (yield strain sigma_y/E < 1)");
    p->Hstar = H * p->h0;
    if ((st = ct_params_validate(p)))
        return scene_error(st, "%s: %s", s->name, ct_error_message());

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
    if (ev && (em || evel))
        return bad(ev, "impact", "V_star", "give either V_star or mass + velocity, not both");
    if (!ev && !(em && evel))
        return scene_error(CT_EINVAL, "%s: [impact]: needs V_star, or both mass and velocity",
                           s->name);
    if (ev) {
        if ((st = velocity_list(ev, "V_star", &sc->V_star, &sc->nvel)))
            return st;
    } else {
        double m = 0.0;
        if ((st = number_key(s, "impact", "mass", 0.0, INFINITY, "must be > 0", &m)))
            return st;
        if ((st = velocity_list(evel, "velocity", &sc->V_star, &sc->nvel)))
            return st;
        /* V* = sqrt(m v1^2 / (2 l0 E h0)) */
        double scale = 2.0 * ct_energy_scale(p);
        for (size_t k = 0; k < sc->nvel; k++) {
            sc->V_star[k] = sqrt(m / scale) * sc->V_star[k];
            if (!isfinite(sc->V_star[k]) || !(sc->V_star[k] > 0.0))
                return bad(evel, "impact", "velocity",
                           "gives a V* that is not a finite number > 0");
        }
    }
    sc->impacts = 1;
    if ((st = integer_key(s, "impact", "impacts", 1, 1000000,
                          "must satisfy 1 <= impacts <= 1000000", &sc->impacts)))
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
            else if (!strcmp(tok, "ensemble"))
                sc->what |= CT_OUT_ENSEMBLE;
            else if (!strcmp(tok, "realisations"))
                sc->what |= CT_OUT_REALISATIONS;
            else {
                free(buf);
                return bad(e, "output", "what",
                           "each item must be e, curve, profile, compare, ensemble or "
                           "realisations");
            }
        }
        free(buf);
        if (!sc->what)
            return bad(e, "output", "what", "name at least one of e, curve, profile, compare");
        /* compare adds the paper's laws to e and curve; alone it means e with them */
        if (sc->what == CT_OUT_COMPARE)
            sc->what |= CT_OUT_E;
    }
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
        char section[64], key[64], value[4096];
        if ((size_t)(dot - o) >= sizeof section || (size_t)(eq - dot - 1) >= sizeof key ||
            strlen(eq + 1) >= sizeof value)
            return scene_error(CT_EINVAL, "--set %s: section, key or value too long", o);
        trim_copy(section, sizeof section, o, dot);
        trim_copy(key, sizeof key, dot + 1, eq);
        trim_copy(value, sizeof value, eq + 1, eq + 1 + strlen(eq + 1));
        int st = store(s, section, key, value, "--set");
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
    parse_state s;
    memset(&s, 0, sizeof s);
    memset(scene, 0, sizeof *scene);
    s.name = path;
    s.file = fopen(path, "rb");
    if (!s.file)
        return scene_error(CT_EIO, "%s: cannot open: %s", path, strerror(errno));
    /* Binary garbage: a NUL byte cannot be in a text scene. */
    int c, nul = 0, lines = 1;
    while ((c = fgetc(s.file)) != EOF) {
        if (c == '\n')
            lines++;
        if (c == 0) {
            nul = 1;
            break;
        }
    }
    if (nul || ferror(s.file)) {
        fclose(s.file);
        return scene_error(nul ? CT_EINVAL : CT_EIO, "%s:%d: %s", path, lines,
                           nul ? "binary data (NUL byte): not a scene file" : "read error");
    }
    rewind(s.file);
    int r = ini_parse_stream(read_file_line, &s, handler, &s);
    fclose(s.file);
    return finish(&s, r, scene, overrides, noverrides);
}

void ct_scene_free(ct_scene *scene)
{
    if (!scene)
        return;
    free(scene->V_star);
    free(scene->output);
    scene->V_star = NULL;
    scene->output = NULL;
}
