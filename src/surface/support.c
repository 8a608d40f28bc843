/* What every kind of surface uses to speak of its keys and scales: a key's row, the error
 * naming where a key was given, the front-end's note, relative paths, the scales of a layer.
 * Below the kinds: nothing here knows which kinds exist (the registry, kind.c, is above them). */
#include "kind.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

const ct_key *ct_kind_key(const ct_kind *kind, const char *section, const char *name, size_t *k)
{
    for (size_t i = 0; i < kind->nkeys; i++)
        if (!strcmp(kind->keys[i].section, section) && !strcmp(kind->keys[i].name, name)) {
            if (k)
                *k = i;
            return &kind->keys[i];
        }
    return NULL;
}

void ct_value_shown(const char *value, char *buf, size_t len)
{
    const size_t n = strlen(value);
    snprintf(buf, len, "%.*s%s", (int)(n > 80 ? 72 : n), value, n > 80 ? "..." : "");
}

int ct_surface_given(const ct_surface *s, const char *section, const char *name)
{
    size_t k;
    return ct_kind_key(s->kind, section, name, &k) && s->given[k];
}

int ct_surface_key_error(const ct_surface *s, const char *section, const char *name, int status,
                         const char *fmt, ...)
{
    char why[400], shown[96] = "";
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    size_t k;
    const char *at = "";
    int given = ct_kind_key(s->kind, section, name, &k) && s->given[k];
    if (given) {
        at = s->where[k];
        ct_value_shown(s->given[k], shown, sizeof shown);
    }
    return ct_error_set(status, "%s%s%s.%s%s%s: %s", at, *at ? ": " : "", section, name,
                        given ? " = " : "", shown, why);
}

void ct_surface_note_set(ct_surface *s, const char *fmt, ...)
{
    char text[sizeof s->note];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    size_t n = strlen(s->note);
    snprintf(s->note + n, sizeof s->note - n, "%s%s", n ? "\n" : "", text);
}

char *ct_path_join(const char *dir, const char *path)
{
    if (path[0] == '/' || !dir || !*dir)
        return strdup(path);
    size_t n = strlen(dir), m = strlen(path);
    char *out = malloc(n + m + 2);
    if (!out)
        return NULL;
    memcpy(out, dir, n);
    size_t k = n;
    if (out[k - 1] != '/')
        out[k++] = '/';
    memcpy(out + k, path, m + 1);
    return out;
}

void ct_scales_of(ct_scales *sc, const ct_layer *built, const ct_layer *physical)
{
    sc->layer = *built;
    sc->physical = *physical;
    sc->force_unit = built->sigma_y * built->l0;
    sc->energy_unit = built->sigma_y * built->l0 * built->h0;
    sc->energy_scale = built->l0 * built->E * built->h0;
    sc->physical_energy_scale = physical->l0 * physical->E * physical->h0;
}

double ct_V_star_of(double m, double v, double l0, double E, double h0)
{
    return sqrt(m / (2.0 * (l0 * E * h0))) * v;
}

double ct_speed_to_V_star(const ct_scales *sc, double m, double v)
{
    const ct_layer *p = &sc->physical;
    return ct_V_star_of(m, v, p->l0, p->E, p->h0);
}

double ct_time_scale(const ct_scales *sc, double m)
{
    const ct_layer *p = &sc->physical;
    return sqrt(m * p->h0 / (p->E * p->l0));
}
