/* The registry of kinds of surface and the surface handle every front-end uses: keys set as
 * text through the kind's rows, checked together, prepared, built into rods; the outputs
 * only some kinds give are asked of the kind's descriptor. */
#include "kind.h"
#include "body/body.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static const ct_kind *const registry[] = {&ct_kind_cantor, &ct_kind_random_cantor, &ct_kind_profile,
                                          &ct_kind_rods};
#define NKINDS (sizeof registry / sizeof registry[0])

/* Every kind gives these. */
static const char generic_outputs[] = "e time curve history bounce table";

/* The outputs only some kinds give: the operation that gives each, and what it is, said to a
 * kind without it together with the kinds that have it. A new kind adds no row here; a new
 * kind-specific output adds one. */
static int has_profile(const ct_kind *k)
{
    return k->write_profile != NULL;
}
static int has_compare(const ct_kind *k)
{
    return k->compare != NULL;
}
static int has_bearing(const ct_kind *k)
{
    return k->write_bearing != NULL;
}
static int has_geometry(const ct_kind *k)
{
    return k->write_geometry != NULL;
}
static int has_fit(const ct_kind *k)
{
    return k->write_fit != NULL;
}
static int has_realisations(const ct_kind *k)
{
    return k->realisations;
}

static int one_surface(const ct_kind *k)
{
    return !k->realisations;
}

static const struct {
    const char *output;
    int (*given)(const ct_kind *k);
    const char *what; /* "...: surface.type = <the kinds that give it>" follows */
} kind_outputs[] = {
    {"profile", has_profile, "the surface's rods and their state are written by"},
    {"compare", has_compare,
     "compare sets e beside the paper's laws (a Cantor surface) or beside the Cantor surface a "
     "measured one looks like"},
    {"bearing", has_bearing, "a bearing-area curve is written for measured surfaces"},
    {"ensemble", has_realisations, "ensembles are of random surfaces"},
    {"realisations", has_realisations, "ensembles are of random surfaces"},
    {"geometry", has_geometry, "the stages' geometry is written for the Cantor surface"},
    {"fit", has_fit,
     "cantact fit fits a Cantor surface to a measured profile (or to a profile file given as "
     "it is)"},
    {"merge", has_realisations, "merge combines the parts of an ensemble of a random surface"},
    {"landings", one_surface,
     "landings (body.landings) are apex positions on one surface, not on random realisations: "
     "give one realisation of it (surface.realisation), or its ensemble without landings"},
};
#define NOUTPUTS (sizeof kind_outputs / sizeof kind_outputs[0])

size_t ct_surface_kind_count(void)
{
    return NKINDS;
}

const char *ct_surface_kind_name(size_t k)
{
    return k < NKINDS ? registry[k]->name : NULL;
}

const char *ct_surface_kind_summary(size_t k)
{
    return k < NKINDS ? registry[k]->summary : NULL;
}

const ct_key *ct_surface_kind_keys(size_t k, size_t *n)
{
    if (k >= NKINDS) {
        *n = 0;
        return NULL;
    }
    *n = registry[k]->nkeys;
    return registry[k]->keys;
}

const char *ct_surface_outputs(void)
{
    static _Thread_local char all[200]; /* the generic outputs, then the table's */
    size_t n = (size_t)snprintf(all, sizeof all, "%s", generic_outputs);
    for (size_t o = 0; o < NOUTPUTS; o++)
        n += (size_t)snprintf(all + n, sizeof all - n, " %s", kind_outputs[o].output);
    return all;
}

/* 1 when word is one of the blank-separated words of list. */
static int in_list(const char *list, const char *word)
{
    const size_t n = strlen(word);
    for (const char *p = list; p && *p;) {
        while (*p == ' ')
            p++;
        const char *end = strchr(p, ' ');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == n && n && !strncmp(p, word, n))
            return 1;
        p = end;
    }
    return 0;
}

int ct_surface_kind_supports(size_t k, const char *output, const char **why)
{
    static _Thread_local char reason[300]; /* what the output is, and the kinds that give it */
    static const char unknown[] = "not an output of cantact";
    const char *dummy;
    if (!why)
        why = &dummy;
    *why = NULL;
    if (k >= NKINDS || !output) {
        *why = unknown;
        return 0;
    }
    if (in_list(generic_outputs, output))
        return 1;
    size_t o = 0;
    while (o < NOUTPUTS && strcmp(kind_outputs[o].output, output))
        o++;
    if (o == NOUTPUTS) {
        *why = unknown;
        return 0;
    }
    if (kind_outputs[o].given(registry[k]))
        return 1;
    size_t total = 0, found = 0;
    for (size_t j = 0; j < NKINDS; j++)
        total += kind_outputs[o].given(registry[j]) != 0;
    size_t n = (size_t)snprintf(reason, sizeof reason, "%s: surface.type = ", kind_outputs[o].what);
    for (size_t j = 0; j < NKINDS && n < sizeof reason; j++) {
        if (!kind_outputs[o].given(registry[j]))
            continue;
        const char *sep = found == 0 ? "" : found + 1 == total ? " or " : ", ";
        n += (size_t)snprintf(reason + n, sizeof reason - n, "%s%s", sep, registry[j]->name);
        found++;
    }
    *why = reason;
    return 0;
}

int ct_surface_new(ct_surface **out, const char *kind)
{
    CT_NEED(out);
    CT_NEED(kind);
    *out = NULL;
    const ct_kind *d = NULL;
    size_t index = 0;
    for (size_t k = 0; k < NKINDS; k++)
        if (!strcmp(registry[k]->name, kind)) {
            d = registry[k];
            index = k;
        }
    if (!d) {
        char names[200] = "";
        size_t n = 0;
        for (size_t k = 0; k < NKINDS; k++)
            n += (size_t)snprintf(names + n, sizeof names - n, "%s%s",
                                  k == 0            ? ""
                                  : k + 1 == NKINDS ? " or "
                                                    : ", ",
                                  registry[k]->name);
        return ct_error_set(CT_EINVAL, "must be %s", names);
    }
    ct_surface *s = calloc(1, sizeof *s);
    if (!s || !(s->config = calloc(1, d->config_size)) ||
        !(s->given = calloc(d->nkeys ? d->nkeys : 1, sizeof(char *))) ||
        !(s->where = calloc(d->nkeys ? d->nkeys : 1, sizeof(char *)))) {
        if (s) {
            free(s->config);
            free(s->given);
        }
        free(s);
        return ct_error_set(CT_ENOMEM, "surface: out of memory");
    }
    s->kind = d;
    s->index = index;
    d->defaults(s->config);
    *out = s;
    return CT_OK;
}

void ct_surface_free(ct_surface *s)
{
    if (!s)
        return;
    const ct_kind *d = s->kind;
    if (d->release)
        d->release(s->config);
    for (size_t k = 0; k < d->nkeys; k++) {
        ct_key_clear(&d->keys[k], s->config);
        free(s->given[k]);
        free(s->where[k]);
    }
    free(s->given);
    free(s->where);
    free(s->config);
    free(s);
}

size_t ct_surface_kind_index(const ct_surface *s)
{
    return s->index;
}

const char *ct_surface_kind(const ct_surface *s)
{
    return s->kind->name;
}

const ct_key *ct_surface_key(const ct_surface *s, const char *section, const char *name)
{
    return ct_kind_key(s->kind, section, name, NULL);
}

/* "a, b or c" of the kinds that have section.name */
static void kinds_with(const char *section, const char *name, char *buf, size_t len)
{
    size_t n = 0, found = 0, total = 0;
    for (size_t k = 0; k < NKINDS; k++)
        total += ct_kind_key(registry[k], section, name, NULL) != NULL;
    buf[0] = '\0';
    for (size_t k = 0; k < NKINDS && n < len; k++)
        if (ct_kind_key(registry[k], section, name, NULL)) {
            n += (size_t)snprintf(buf + n, len - n, "%s%s",
                                  found == 0           ? ""
                                  : found + 1 == total ? " or "
                                                       : ", ",
                                  registry[k]->name);
            found++;
        }
}

/* " (did you mean section.key?)" for the key of some kind nearest to section.name, the surface's
 * own kind first (a key of another kind names it); "" when none is that close. */
static void nearest_key(const ct_kind *own, const char *section, const char *name, char *buf,
                        size_t len)
{
    enum { CAP = 256 };
    char given[160], names[CAP][80];
    const char *list[CAP];
    const ct_kind *of[CAP];
    size_t n = 0;
    buf[0] = '\0';
    snprintf(given, sizeof given, "%s.%s", section, name);
    for (size_t pass = 0; pass < 2; pass++)
        for (size_t k = 0; k < NKINDS; k++) {
            const ct_kind *d = registry[k];
            if ((d == own) != (pass == 0))
                continue;
            for (size_t r = 0; r < d->nkeys && n < CAP; r++, n++) {
                snprintf(names[n], sizeof names[n], "%s.%s", d->keys[r].section, d->keys[r].name);
                list[n] = names[n];
                of[n] = d;
            }
        }
    const size_t k = ct_nearest_name(given, list, n);
    if (k == n)
        return;
    if (of[k] == own) { /* own keys came first: a name several kinds have is the own kind's */
        snprintf(buf, len, " (did you mean %s?)", list[k]);
        return;
    }
    char kinds[160];
    const char *dot = strchr(list[k], '.');
    char sec[80];
    snprintf(sec, sizeof sec, "%.*s", (int)(dot - list[k]), list[k]);
    kinds_with(sec, dot + 1, kinds, sizeof kinds);
    snprintf(buf, len, " (did you mean %s? only for surface.type = %s)", list[k], kinds);
}

int ct_surface_set(ct_surface *s, const char *section, const char *name, const char *value,
                   const char *where)
{
    CT_NEED(s);
    CT_NEED(section);
    CT_NEED(name);
    CT_NEED(value);
    const char *at = where && *where ? where : "";
    const char *colon = *at ? ": " : "";
    char shown[96];
    ct_value_shown(value, shown, sizeof shown);
    size_t k;
    const ct_key *row = ct_kind_key(s->kind, section, name, &k);
    if (!row) {
        char kinds[200];
        kinds_with(section, name, kinds, sizeof kinds);
        if (!kinds[0]) {
            char hint[400];
            nearest_key(s->kind, section, name, hint, sizeof hint);
            return ct_error_set(CT_EINVAL, "%s%s%s.%s: unknown key%s", at, colon, section, name,
                                hint);
        }
        return ct_error_set(CT_EINVAL, "%s%s%s.%s = %s: only for surface.type = %s (not %s)", at,
                            colon, section, name, shown, kinds, s->kind->name);
    }
    char *given = strdup(value), *w = strdup(at);
    if (!given || !w) {
        free(given);
        free(w);
        return ct_error_set(CT_ENOMEM, "surface: out of memory");
    }
    int st = ct_key_parse(row, value, s->config);
    if (st) {
        free(given);
        free(w);
        if (st == CT_ENOMEM)
            return st;
        char why[400];
        snprintf(why, sizeof why, "%s", ct_error_message());
        return ct_error_set(st, "%s%s%s.%s = %s: %s", at, colon, section, name, shown, why);
    }
    free(s->given[k]);
    free(s->where[k]);
    s->given[k] = given;
    s->where[k] = w;
    s->checked = s->prepared = 0;
    return CT_OK;
}

int ct_surface_value(const ct_surface *s, const char *section, const char *name, double *out)
{
    CT_NEED(s);
    CT_NEED(out);
    const ct_key *row = ct_kind_key(s->kind, section, name, NULL);
    if (!row)
        return ct_error_set(CT_EINVAL, "%s.%s: not a key of type = %s", section, name,
                            s->kind->name);
    const char *at = (const char *)s->config + row->offset;
    switch (row->type) {
    case CT_KEY_NUMBER:
        *out = *(const double *)at;
        return CT_OK;
    case CT_KEY_INTEGER:
    case CT_KEY_DEPTH:
        *out = (double)*(const long *)at;
        return CT_OK;
    case CT_KEY_COUNT:
        *out = (double)*(const uint64_t *)at;
        return CT_OK;
    case CT_KEY_WORD:
        *out = (double)*(const int *)at;
        return CT_OK;
    default:
        return ct_error_set(CT_EINVAL, "%s.%s: not a number", section, name);
    }
}

int ct_surface_is_set(const ct_surface *s, const char *section, const char *name)
{
    return ct_surface_given(s, section, name);
}

const char *ct_surface_note(ct_surface *s)
{
    return s->note;
}

void ct_surface_note_clear(ct_surface *s)
{
    s->note[0] = '\0';
}

int ct_surface_check(ct_surface *s, const char *scene)
{
    CT_NEED(s);
    const ct_kind *d = s->kind;
    for (size_t k = 0; k < d->nkeys; k++)
        if ((d->keys[k].flags & CT_KEY_REQUIRED) && !s->given[k])
            return ct_error_set(CT_EINVAL, "%s%s%s.%s: required key missing%s%s%s",
                                scene ? scene : "", scene ? ": " : "", d->keys[k].section,
                                d->keys[k].name, " (type = ", d->name, ")");
    int st = d->check(s, scene ? scene : "");
    s->checked = st == CT_OK;
    return st;
}

int ct_surface_input(const ct_surface *s, size_t k, const char *dir, char *buf, size_t len)
{
    const ct_kind *d = s->kind;
    for (size_t r = 0; r < d->nkeys; r++) {
        if (!(d->keys[r].flags & CT_KEY_FILE) || d->keys[r].type != CT_KEY_TEXT || !s->given[r])
            continue;
        if (k--)
            continue;
        const char *value = *(char *const *)((const char *)s->config + d->keys[r].offset);
        char *path = value ? ct_path_join(dir, value) : NULL;
        if (!path)
            return 0;
        snprintf(buf, len, "%s", path);
        free(path);
        return 1;
    }
    return 0;
}

int ct_surface_prepare(ct_surface *s, const char *dir)
{
    CT_NEED(s);
    int st;
    if (!s->checked && (st = ct_surface_check(s, NULL)))
        return st;
    if (s->prepared)
        return CT_OK;
    if ((st = s->kind->prepare(s, dir)))
        return st;
    s->prepared = 1;
    return CT_OK;
}

static int need_prepared(const ct_surface *s)
{
    if (!s->prepared)
        return ct_error_set(CT_EINVAL, "surface %s: not prepared (ct_surface_prepare)",
                            s->kind->name);
    return CT_OK;
}

void ct_surface_scales(const ct_surface *s, ct_scales *out)
{
    *out = s->scales;
}

int ct_surface_build_unmet(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                           ct_plan_info *info)
{
    CT_NEED(s);
    CT_NEED(req);
    CT_NEED(out);
    *out = NULL;
    int st;
    if ((st = need_prepared(s)))
        return st;
    ct_plan_info dummy;
    if ((st = s->kind->build(s, req, out, info ? info : &dummy)))
        return st;
    ct_bundle_set_threads(*out, req->threads);
    return CT_OK;
}

int ct_surface_build(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                     ct_plan_info *info)
{
    ct_plan_info dummy;
    if (!info)
        info = &dummy;
    int st = ct_surface_build_unmet(s, req, out, info);
    if (st)
        return st;
    if ((st = ct_body_apply(req->body, &s->scales, out, info))) {
        ct_bundle_free(*out);
        *out = NULL;
        return st;
    }
    ct_bundle_set_threads(*out, req->threads);
    return CT_OK;
}

int ct_surface_ready(ct_surface *s, const char *output)
{
    CT_NEED(s);
    CT_NEED(output);
    const char *why;
    if (!ct_surface_kind_supports(s->index, output, &why))
        return ct_error_set(CT_EINVAL, "%s: %s", output, why);
    int st = need_prepared(s);
    if (st)
        return st;
    return s->kind->ready ? s->kind->ready(s, output) : CT_OK;
}

int ct_surface_profile_shows_state(const ct_surface *s)
{
    return s->kind->profile_shows_state;
}

void ct_surface_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    s->kind->describe(s, info, buf, len);
}

void ct_surface_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    s->kind->table_line(s, info, buf, len);
}

/* An optional output the kind does not give: CT_EINVAL with its refusal. */
static int refused(const ct_surface *s, const char *output)
{
    const char *why;
    ct_surface_kind_supports(s->index, output, &why);
    return ct_error_set(CT_EINVAL, "%s: %s", output, why ? why : "not given");
}

int ct_surface_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    CT_NEED(s);
    CT_NEED(b);
    CT_NEED(f);
    if (ct_body_met(b)) /* under a curved body: the rods as it met them, whatever the kind */
        return ct_body_write_rods(b, &s->scales, f);
    return s->kind->write_profile ? s->kind->write_profile(s, b, f) : refused(s, "profile");
}

size_t ct_surface_compare_columns(const ct_surface *s, const char *const **names)
{
    *names = s->kind->compare_names;
    return s->kind->compare ? s->kind->ncompare : 0;
}

int ct_surface_compare(ct_surface *s, const ct_sweep_row *rows, size_t nrows, double *out)
{
    CT_NEED(s);
    if (!s->kind->compare)
        return refused(s, "compare");
    for (size_t k = 0; k < nrows * s->kind->ncompare; k++)
        out[k] = NAN;
    return s->kind->compare(s, rows, nrows, out);
}

size_t ct_surface_curve_compare_columns(const ct_surface *s, const char *const **names)
{
    *names = s->kind->curve_compare_names;
    return s->kind->curve_compare ? s->kind->ncurve_compare : 0;
}

void ct_surface_curve_compare(const ct_surface *s, int unload, double u_max, double u, double *out)
{
    if (s->kind->curve_compare)
        s->kind->curve_compare(s, unload, u_max, u, out);
}

int ct_surface_after_sweep(ct_surface *s, const ct_sweep_row *rows, size_t nrows)
{
    CT_NEED(s);
    return s->kind->after_sweep ? s->kind->after_sweep(s, rows, nrows) : CT_OK;
}

int ct_surface_write_bearing(const ct_surface *s, FILE *f)
{
    CT_NEED(s);
    CT_NEED(f);
    return s->kind->write_bearing ? s->kind->write_bearing(s, f) : refused(s, "bearing");
}

int ct_surface_write_geometry(const ct_surface *s, const ct_build_request *req, FILE *f)
{
    CT_NEED(s);
    CT_NEED(f);
    return s->kind->write_geometry ? s->kind->write_geometry(s, req, f) : refused(s, "geometry");
}

int ct_surface_write_fit(ct_surface *s, FILE *f)
{
    CT_NEED(s);
    CT_NEED(f);
    int st = need_prepared(s);
    if (st)
        return st;
    return s->kind->write_fit ? s->kind->write_fit(s, f) : refused(s, "fit");
}
