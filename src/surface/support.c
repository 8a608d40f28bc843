/* What every kind of surface uses to speak of its keys and scales: a key's row, the error
 * naming where a key was given, the front-end's note, relative paths, the scales of a layer.
 * Below the kinds: nothing here knows which kinds exist (the registry, kind.c, is above them). */
#include "kind.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
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

/* 1 for x in [2^-64, 2^64], else 2^-ilogb(x) (even: 2^-(2 floor(ilogb(x) / 2))). */
static double unit_of(double x, int even)
{
    if (x >= 0x1p-64 && x <= 0x1p64)
        return 1.0;
    int k = ilogb(x);
    if (even)
        k -= ((k % 2) + 2) % 2;
    return ldexp(1.0, -k);
}

void ct_build_units_of(const ct_layer *given, int plane, ct_build_units *u)
{
    u->length = unit_of(given->h0, 0);
    u->area = unit_of(given->l0, plane);
    u->stress = unit_of(given->sigma_y, 0);
    u->position = plane ? sqrt(u->area) : u->area;
}

int ct_layer_built(const ct_layer *given, const ct_build_units *u, ct_layer *built)
{
    const double v[] = {given->E, given->sigma_y, given->Hstar, given->l0, given->h0};
    const char *names[] = {"E", "sigma_y", "H*", "l0", "h0"};
    for (int k = 0; k < 5; k++)
        if (!isfinite(v[k]) || !(v[k] >= DBL_MIN))
            return ct_error_set(CT_EINVAL,
                                "%s = %g: must be finite and > 0, a normal double (>= %g)",
                                names[k], v[k], DBL_MIN);
    if (!isfinite(given->E / given->sigma_y))
        return ct_error_set(CT_EINVAL,
                            "E/sigma_y = %g / %g: beyond what doubles hold (a yield strain that "
                            "no double resolves)",
                            given->E, given->sigma_y);
    *built = (ct_layer){.E = given->E * u->stress,
                        .sigma_y = given->sigma_y * u->stress,
                        .Hstar = given->Hstar * u->length,
                        .l0 = given->l0 * u->area,
                        .h0 = given->h0 * u->length};
    return ct_layer_validate(built);
}

/* 10^lg as %g would write it, also beyond the doubles. */
static void sci_text(double lg, char *buf, size_t len)
{
    const double ex = floor(lg), mant = pow(10.0, lg - ex);
    if (fabs(lg) < 300.0)
        snprintf(buf, len, "%.3g", pow(10.0, lg));
    else
        snprintf(buf, len, "%.3ge%+.0f", mant, ex);
}

int ct_rod_representable(const ct_layer *built, double top, double length, double area,
                         const char *what)
{
    const double k = built->E * area / length, ESL = built->E * area * length;
    if (isfinite(k) && k >= DBL_MIN && isfinite(ESL) && ESL >= DBL_MIN && isfinite(top) &&
        (top == 0.0 || top >= DBL_MIN))
        return CT_OK;
    /* in the scales' units (what the doubles cannot carry, whatever the unit), as powers of
     * ten: they may be beyond the doubles themselves */
    const double lg_eps = log10(built->E / built->sigma_y), lg_L = log10(length / built->h0),
                 lg_s = log10(area / built->l0);
    char k_text[32], ESL_text[32];
    sci_text(lg_eps + lg_s - lg_L, k_text, sizeof k_text);
    sci_text(lg_eps + lg_s + lg_L, ESL_text, sizeof ESL_text);
    return ct_error_set(CT_EINVAL,
                        "%s: top %g h0, length %g h0, area %g l0 at E/sigma_y = %g: its stiffness "
                        "E s / L = %s sigma_y l0 / h0 or its energy scale E s L = %s sigma_y l0 h0 "
                        "is beyond what doubles carry",
                        what, top / built->h0, length / built->h0, area / built->l0,
                        built->E / built->sigma_y, k_text, ESL_text);
}

double ct_V_star_of(double m, double v, double l0, double E, double h0)
{
    return sqrt(m / (2.0 * (l0 * E * h0))) * v;
}

double ct_time_scale(const ct_scales *sc, double m)
{
    const ct_layer *p = &sc->physical;
    return sqrt(m * p->h0 / (p->E * p->l0));
}
