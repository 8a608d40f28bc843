/* cantact_table.h: read and evaluate an e(V*) table written by `cantact table` (or by
 * ct_table_build), for DEM codes. One header, C99 (C++11 too), no dependencies but the C library
 * and libm (link with -lm): no libcantact, no GSL, no OpenMP. Every function is static inline.
 *
 *     #include "cantact_table.h"
 *     ct_tab t;
 *     char err[256];
 *     if (ct_tab_load(&t, "e_table.csv", err, sizeof err)) { fprintf(stderr, "%s\n", err); ... }
 *     double e = ct_tab_eval(&t, V_star);          // or ct_tab_e_of_speed(&t, v_impact)
 *     ct_tab_free(&t);
 *
 * The table holds nodes V*_i (increasing), e_i and slopes d_i = de/d(ln V*) at the nodes. It
 * is evaluated exactly as the table was checked when it was built (libcantact evaluates its
 * tables with ct_tab_interp below, the same code):
 *   - V* <= V*_c (the critical speed, in the file): e = 1 exactly (no rod yields);
 *   - V*_0 <= V* <= V*_(n-1): in x = ln V*, on the interval [x_i, x_i+1] holding x, with
 *     h = x_i+1 - x_i and t = (x - x_i) / h,
 *       linear:          e = e_i + (e_i+1 - e_i) t
 *       monotone_cubic:  e = e_i + (e_i+1 - e_i) t^2 (3 - 2t) + h t (1 - t) ((1 - t) d_i - t d_i+1)
 *     (the cubic Hermite form with the file's slopes; they obey the Fritsch-Carlson
 *     monotonicity conditions, so e stays between e_i and e_i+1 on every interval);
 *   - outside [V*_0, V*_(n-1)] and above V*_c: the nearest end's e (the table does not know
 *     it there: ct_tab_covers() says so).
 *
 * Numbers are read in the "C" format (a point before the decimals) whatever the locale.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef CANTACT_TABLE_H
#define CANTACT_TABLE_H

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The interpolation rules; libcantact's ct_interp has the same values. */
enum { CT_TAB_MONOTONE_CUBIC = 0, CT_TAB_LINEAR = 1 };

typedef struct {
    size_t n;            /* nodes, >= 2 */
    double *V_star;      /* nodes, dimensionless, strictly increasing */
    double *ln_V_star;   /* log(V_star[i]) */
    double *e;           /* e at the nodes, in [0, 1] */
    double *slope;       /* de/d(ln V*) at the nodes */
    int rule;            /* CT_TAB_MONOTONE_CUBIC or CT_TAB_LINEAR */
    double V_star_crit;  /* e = 1 exactly at and below it */
    double tolerance;    /* |e_table - e_model| the table was built for (NaN: not given) */
    double worst_error;  /* the largest |e_table - e_model| found when checked (NaN: none) */
    double v_per_V_star; /* impact speed per unit V* in the scene's units (NaN: no mass given) */
} ct_tab;

/* The interval i with ln_V[i] <= x < ln_V[i + 1] (0 <= i <= n - 2), for ln_V[0] <= x <
 * ln_V[n - 1]: binary search. */
static inline size_t ct_tab_interval(size_t n, const double *ln_V, double x)
{
    size_t lo = 0, hi = n - 1; /* ln_V[lo] <= x < ln_V[hi] */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (ln_V[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* e at V_star from nodes (ln_V, e, slope) under `rule`: the rule stated at the top of this
 * file. NaN for a V_star that is NaN or not > 0. */
static inline double ct_tab_interp(size_t n, const double *ln_V, const double *e,
                                   const double *slope, int rule, double V_star_crit, double V_star)
{
    if (!(V_star > 0.0))
        return NAN;
    if (V_star <= V_star_crit)
        return 1.0;
    const double x = log(V_star);
    if (!(x > ln_V[0]))
        return e[0];
    if (!(x < ln_V[n - 1]))
        return e[n - 1];
    const size_t i = ct_tab_interval(n, ln_V, x);
    const double h = ln_V[i + 1] - ln_V[i], t = (x - ln_V[i]) / h;
    const double rise = e[i + 1] - e[i];
    if (rule == CT_TAB_LINEAR)
        return e[i] + rise * t;
    /* cubic Hermite: equal ends with zero slopes give e[i] exactly (a flat interval) */
    return e[i] + rise * (t * t * (3.0 - 2.0 * t)) +
           h * t * (1.0 - t) * ((1.0 - t) * slope[i] - t * slope[i + 1]);
}

/* e at V_star (dimensionless) from a loaded table. */
static inline double ct_tab_eval(const ct_tab *t, double V_star)
{
    return ct_tab_interp(t->n, t->ln_V_star, t->e, t->slope, t->rule, t->V_star_crit, V_star);
}

/* e at an impact speed v in the scene's units (the table's v_per_V_star: from the scene's
 * [impact] mass); NaN when the table has no v_per_V_star. */
static inline double ct_tab_e_of_speed(const ct_tab *t, double v)
{
    return ct_tab_eval(t, v / t->v_per_V_star);
}

/* 1 when the table knows e at V_star: at or below V*_c, or within its nodes. */
static inline int ct_tab_covers(const ct_tab *t, double V_star)
{
    return V_star > 0.0 &&
           (V_star <= t->V_star_crit || (V_star >= t->V_star[0] && V_star <= t->V_star[t->n - 1]));
}

static inline void ct_tab_free(ct_tab *t)
{
    if (!t)
        return;
    free(t->V_star);
    free(t->ln_V_star);
    free(t->e);
    free(t->slope);
    t->V_star = t->ln_V_star = t->e = t->slope = NULL;
    t->n = 0;
}

/* strtod in the "C" format whatever the locale: the text's '.' becomes the locale's decimal
 * point first. The whole field (white space around allowed) must be the number. */
static inline int ct_tab_number(const char *text, double *out)
{
    char buf[64];
    const char *point = localeconv()->decimal_point;
    size_t n = 0;
    while (*text == ' ' || *text == '\t')
        text++;
    for (; *text && *text != ',' && *text != '\n' && *text != '\r'; text++) {
        if (n + 4 >= sizeof buf)
            return 0;
        if (*text == '.' && point && point[0] && strcmp(point, ".")) {
            size_t k = strlen(point);
            if (n + k + 4 >= sizeof buf)
                return 0;
            memcpy(buf + n, point, k);
            n += k;
        } else {
            buf[n++] = *text;
        }
    }
    while (n && (buf[n - 1] == ' ' || buf[n - 1] == '\t'))
        n--;
    buf[n] = '\0';
    if (!n)
        return 0;
    char *end;
    errno = 0;
    double v = strtod(buf, &end);
    if (*end || errno == ERANGE || isnan(v) || isinf(v))
        return 0;
    *out = v;
    return 1;
}

/* 1 when a "# key = value" line names a key the loader reads. */
static inline int ct_tab_key_used(const char *line)
{
    static const char *const used[] = {"interpolation", "V_star_crit", "tolerance", "worst_error",
                                       "v_per_V_star"};
    const char *k = line + 1;
    while (*k == ' ')
        k++;
    for (size_t i = 0; i < sizeof used / sizeof used[0]; i++) {
        size_t n = strlen(used[i]);
        if (!strncmp(k, used[i], n) && (k[n] == ' ' || k[n] == '='))
            return 1;
    }
    return 0;
}

/* What a monotone cubic table promises, checked on its nodes: every slope finite; on every
 * interval above V*_c (below it e = 1 by the rule) whose nodes have equal e both slopes 0,
 * else both of the secant's sign and at most three secants (Fritsch-Carlson), so that e stays
 * between the interval's nodes. -1 and the interval's index (from 0) when one fails. */
static inline int ct_tab_check_slopes(const ct_tab *t, size_t *bad)
{
    for (size_t i = 0; i < t->n; i++)
        if (!isfinite(t->slope[i])) {
            *bad = i;
            return -1;
        }
    if (t->rule != CT_TAB_MONOTONE_CUBIC)
        return 0;
    for (size_t i = 0; i + 1 < t->n; i++) {
        if (t->V_star[i + 1] <= t->V_star_crit)
            continue; /* e = 1 there by the rule: this interval is never interpolated */
        const double secant = (t->e[i + 1] - t->e[i]) / (t->ln_V_star[i + 1] - t->ln_V_star[i]);
        const double a = t->slope[i], b = t->slope[i + 1];
        int ok;
        if (secant == 0.0)
            ok = a == 0.0 && b == 0.0;
        else {
            const double ra = a / secant, rb = b / secant, lim = 3.0 * (1.0 + 1e-12);
            ok = ra >= 0.0 && rb >= 0.0 && ra <= lim && rb <= lim;
        }
        if (!ok) {
            *bad = i;
            return -1;
        }
    }
    return 0;
}

/* Reads "# key = value" header lines and the rows "V_star,e,de_dlnV_star" of a table file.
 * Returns 0, or -1 with a one-line message naming file:line in err (the table is then empty
 * and needs no ct_tab_free). */
static inline int ct_tab_load(ct_tab *t, const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    size_t cap = 0, lineno = 0;
    int have_rule = 0, have_crit = 0, have_header = 0;
    memset(t, 0, sizeof *t);
    t->tolerance = t->worst_error = t->v_per_V_star = NAN;
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
#define CT_TAB_FAIL(...)                                                                           \
    do {                                                                                           \
        char what_[200];                                                                           \
        snprintf(what_, sizeof what_, __VA_ARGS__);                                                \
        snprintf(err, errlen, "%s:%lu: %s", path, (unsigned long)lineno, what_);                   \
        goto fail;                                                                                 \
    } while (0)
    while (fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len + 1 == sizeof line && line[len - 1] != '\n') {
            /* a long header line (a long scene path): prose and keys this reader does not use
             * are skipped whole; a key it uses, and a row, are never that long */
            int c;
            if (line[0] != '#' || ct_tab_key_used(line))
                CT_TAB_FAIL("line longer than %d characters", (int)sizeof line - 2);
            while ((c = fgetc(f)) != EOF && c != '\n')
                ;
            continue;
        }
        if (line[0] == '#') {
            char key[64];
            const char *eq = strchr(line, '=');
            const char *k = line + 1;
            while (*k == ' ')
                k++;
            if (!eq || (size_t)(eq - k) >= sizeof key)
                continue; /* prose */
            size_t kl = (size_t)(eq - k);
            memcpy(key, k, kl);
            while (kl && key[kl - 1] == ' ')
                kl--;
            key[kl] = '\0';
            char v[64]; /* the value's first word: a comment may follow it */
            const char *w = eq + 1;
            size_t vl = 0;
            while (*w == ' ')
                w++;
            while (w[vl] && w[vl] != ' ' && w[vl] != '\t' && w[vl] != '\n' && w[vl] != '\r' &&
                   vl + 1 < sizeof v)
                vl++;
            memcpy(v, w, vl);
            v[vl] = '\0';
            if (!strcmp(key, "interpolation")) {
                if (!strcmp(v, "monotone_cubic"))
                    t->rule = CT_TAB_MONOTONE_CUBIC;
                else if (!strcmp(v, "linear"))
                    t->rule = CT_TAB_LINEAR;
                else
                    CT_TAB_FAIL("interpolation: must be monotone_cubic or linear");
                have_rule = 1;
            } else if (!strcmp(key, "V_star_crit")) {
                if (!ct_tab_number(v, &t->V_star_crit) || !(t->V_star_crit >= 0.0))
                    CT_TAB_FAIL("V_star_crit: not a number >= 0");
                have_crit = 1;
            } else if (!strcmp(key, "tolerance")) {
                if (!ct_tab_number(v, &t->tolerance))
                    CT_TAB_FAIL("tolerance: not a number");
            } else if (!strcmp(key, "worst_error")) {
                if (!ct_tab_number(v, &t->worst_error))
                    CT_TAB_FAIL("worst_error: not a number");
            } else if (!strcmp(key, "v_per_V_star")) {
                if (!ct_tab_number(v, &t->v_per_V_star) || !(t->v_per_V_star > 0.0))
                    CT_TAB_FAIL("v_per_V_star: not a number > 0");
            }
            continue;
        }
        if (!have_header) {
            if (strncmp(line, "V_star,e,de_dlnV_star", 21))
                CT_TAB_FAIL("expected the header V_star,e,de_dlnV_star");
            have_header = 1;
            continue;
        }
        if (line[0] == '\n' || (line[0] == '\r' && line[1] == '\n'))
            continue;
        if (t->n == cap) {
            size_t ncap = cap ? 2 * cap : 256;
            double *a = (double *)realloc(t->V_star, ncap * sizeof(double));
            if (a)
                t->V_star = a;
            double *b = a ? (double *)realloc(t->e, ncap * sizeof(double)) : NULL;
            if (b)
                t->e = b;
            double *c = b ? (double *)realloc(t->slope, ncap * sizeof(double)) : NULL;
            if (c)
                t->slope = c;
            if (!c)
                CT_TAB_FAIL("out of memory");
            cap = ncap;
        }
        const char *c1 = strchr(line, ','), *c2 = c1 ? strchr(c1 + 1, ',') : NULL;
        double V, e, d;
        if (!c2 || strchr(c2 + 1, ',') || !ct_tab_number(line, &V) || !ct_tab_number(c1 + 1, &e) ||
            !ct_tab_number(c2 + 1, &d))
            CT_TAB_FAIL("expected three numbers V_star,e,de_dlnV_star");
        if (!(V > 0.0) || (t->n && !(V > t->V_star[t->n - 1])))
            CT_TAB_FAIL("V_star = %.17g: must be > 0 and above the previous node", V);
        if (!(e >= 0.0 && e <= 1.0))
            CT_TAB_FAIL("e = %.17g: must be in [0, 1]", e);
        t->V_star[t->n] = V;
        t->e[t->n] = e;
        t->slope[t->n] = d;
        t->n++;
    }
    if (ferror(f))
        CT_TAB_FAIL("read error");
    if (!have_rule || !have_crit)
        CT_TAB_FAIL("missing # interpolation = ... or # V_star_crit = ... (not a cantact table)");
    if (t->n < 2)
        CT_TAB_FAIL("%lu nodes: a table needs at least 2", (unsigned long)t->n);
    if (!(t->ln_V_star = (double *)malloc(t->n * sizeof(double))))
        CT_TAB_FAIL("out of memory");
    for (size_t i = 0; i < t->n; i++) {
        t->ln_V_star[i] = log(t->V_star[i]);
        if (i && !(t->ln_V_star[i] > t->ln_V_star[i - 1]))
            CT_TAB_FAIL("nodes %lu and %lu: ln V_star not increasing", (unsigned long)i,
                        (unsigned long)i + 1);
    }
    size_t bad;
    if (ct_tab_check_slopes(t, &bad)) {
        snprintf(err, errlen,
                 "%s: nodes %lu and %lu: slopes %.6g and %.6g are not those of a monotone cubic "
                 "between e = %.6g and %.6g (a corrupted or foreign table)",
                 path, (unsigned long)bad + 1, (unsigned long)bad + 2, t->slope[bad],
                 bad + 1 < t->n ? t->slope[bad + 1] : NAN, t->e[bad],
                 bad + 1 < t->n ? t->e[bad + 1] : NAN);
        goto fail;
    }
#undef CT_TAB_FAIL
    fclose(f);
    return 0;
fail:
    fclose(f);
    ct_tab_free(t);
    return -1;
}

#endif
