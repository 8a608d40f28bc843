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
 *     monotonicity conditions, so e stays between e_i and e_i+1 on every interval), and e is
 *     then kept between e_i and e_i+1 (and in [0, 1]) so that rounding cannot leave them;
 *   - outside [V*_0, V*_(n-1)] and above V*_c: the nearest end's e (the table does not know
 *     it there: ct_tab_covers() says so).
 *
 * A table of samples (`cantact table` of a scene with landings or an ensemble of realisations)
 * has e as the mean over the samples and, per node, e at nq probabilities p_j (its header:
 * `# quantiles = nq`; its columns e_p<p>,de_p<p>_dlnV_star after de_dlnV_star): each column is
 * interpolated in V* as e is, and e at (V*, p) is linear in p between the two nearest p_j (the
 * nearest end's column outside [p_0, p_(nq-1)]), the columns kept non-decreasing in p (a
 * running maximum: each column is within the table's tolerance, so it moves a value by at most
 * twice that): ct_tab_eval_quantile. Drawing p uniform in [0, 1] per contact gives e with the
 * samples' distribution at that speed, to the resolution of the p_j.
 *
 * Numbers are read in the "C" format (a point before the decimals) whatever the locale.
 *
 * e <-> damping (ct_tab_zeta_of_e, ct_tab_e_of_zeta): a DEM code that turns e into the damping
 * of a linear spring-dashpot normal contact, F = k delta + c delta' (delta >= 0 the overlap,
 * delta' its rate, > 0 while approaching; k the normal stiffness, m the contact's mass, m1 m2 /
 * (m1 + m2)), needs the damping ratio zeta = c / (2 sqrt(m k)) that rebounds with e:
 *     c = 2 ct_tab_zeta_of_e(e, law) sqrt(m k).
 * From delta(0) = 0, delta'(0) = v > 0, m delta'' = -F gives (omega = sqrt(k / m); zeta < 1:
 * omega_d = omega sqrt(1 - zeta^2)) delta = (v / omega_d) exp(-zeta omega t) sin(omega_d t), and
 * e = (speed when the contact ends) / v depends on zeta alone, and on the law that ends it:
 *
 * CT_TAB_TENSION: the dashpot may pull (F < 0 near the end; LIGGGHTS's Hooke model,
 *   examples/dem_drop.c); the contact ends when delta returns to 0, at omega_d t = pi:
 *     e = exp(-pi zeta / sqrt(1 - zeta^2))  (zeta < 1),  zeta = -ln e / sqrt(pi^2 + ln^2 e).
 *   zeta >= 1: delta = v t exp(-omega t) (zeta = 1) or (v / (2 omega s)) (exp(-omega (zeta - s) t)
 *   - exp(-omega (zeta + s) t)) (zeta > 1, s = sqrt(zeta^2 - 1)) is > 0 for every t > 0: the
 *   overlap never returns to 0 in finite time, the body creeps out with a speed that tends to
 *   0: no rebound, e = 0 (the limit of e as zeta -> 1 from below, too). Every zeta >= 1 gives
 *   e = 0, so ct_tab_zeta_of_e(0, CT_TAB_TENSION) = 1 (the least: critical damping).
 *
 * CT_TAB_CLIPPED: the force is max(0, k delta + c delta') (Yade's Law2_ScGeom_ViscElPhys_Basic,
 *   LAMMPS's pair granular with limit_damping): the body separates when k delta + c delta'
 *   falls to 0, i.e. delta'' = 0, with delta > 0 and delta' < 0 (from there on F would be
 *   < 0 and stays so: free flight), and e = -delta' there / v. With x = zeta / sqrt(1 - zeta^2),
 *   delta'' = 0 at omega_d t = pi - 2 atan x, where delta' = -v exp(-x (pi - 2 atan x)); at
 *   zeta = 1, delta = v t exp(-omega t) has delta'' = 0 at omega t = 2; for zeta > 1 (real roots
 *   -omega (zeta -+ s)) delta'' = 0 at omega t = 2 acosh(zeta) / s, where delta' = -v (zeta -
 *   s)^2 exp(-2 (zeta - s) acosh(zeta) / s). All three are one formula, analytic in zeta:
 *     ln e = -2 zeta h(zeta),  h = acos(zeta) / sqrt(1 - zeta^2)     (zeta < 1; then
 *                                                                     e = exp(-x (pi - 2 atan x)))
 *                              h = 1                                 (zeta = 1: e = e^-2)
 *                              h = acosh(zeta) / sqrt(zeta^2 - 1)    (zeta > 1)
 *   (h = 1 - (zeta - 1) / 3 + 2 (zeta - 1)^2 / 15 - ... about 1). e falls strictly from 1
 *   (zeta = 0) through e^-2 = 0.1353... (zeta = 1) to 0 (e ~ 1 / (2 zeta)^2 for large zeta):
 *   every e in (0, 1] has one zeta, < 1 above e^-2 and > 1 below it. zeta_of_e solves
 *   2 zeta h(zeta) = -ln e by Newton's method kept inside a bracket (bisection where a step
 *   would leave it), to within 4e-16 max(1, -ln e) relative of the exact root (checked against
 *   50-digit arithmetic from e = 1e-300 to 1; e = 1e-300 gives zeta ~ 1e150).
 *
 * Outside: e_of_zeta is NaN for zeta NaN or < 0, 0 for zeta = +infinity; zeta_of_e is NaN for
 * e NaN, < 0 or > 1, 0 for e = 1, and for e = 0 gives 1 (CT_TAB_TENSION) or +infinity
 * (CT_TAB_CLIPPED); both are NaN for a law that is neither. No errno, no locale.
 *
 * This header alone is under the MIT licence (the rest of cantact is GPL-3.0-or-later), so that
 * DEM engines under any licence can include it: LAMMPS is GPL-2.0-only (dem/lammps/).
 * Copyright (c) 2026 the cantact developers. Permission is hereby granted, free of charge, to
 * any person obtaining a copy of this software and associated documentation files (the
 * "Software"), to deal in the Software without restriction, including without limitation the
 * rights to use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies of the
 * Software, and to permit persons to whom the Software is furnished to do so, subject to the
 * following conditions: The above copyright notice and this permission notice shall be
 * included in all copies or substantial portions of the Software. THE SOFTWARE IS PROVIDED "AS
 * IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR IMPLIED, INCLUDING BUT NOT LIMITED TO THE
 * WARRANTIES OF MERCHANTABILITY, FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO
 * EVENT SHALL THE AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
 * LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN
 * CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
 * SPDX-License-Identifier: MIT
 */
#ifndef CANTACT_TABLE_H
#define CANTACT_TABLE_H

#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The interpolation rules; libcantact's ct_interp has the same values. */
enum { CT_TAB_MONOTONE_CUBIC = 0, CT_TAB_LINEAR = 1 };

/* A loaded table. A code that fills one by hand (e.g. copies rank 0's to the other MPI ranks)
 * zeroes it first (memset, or `ct_tab t = {0}`): ct_tab_free frees every array, and fields are
 * added at the end as the format grows (nq, p, e_q and slope_q came with tables of samples). */
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
    double worst_V_star; /* where worst_error was found (NaN: not given, or none) */
    size_t nq;           /* quantile columns (0: a table of one surface) */
    double *p;           /* their probabilities, strictly increasing in [0, 1] */
    double *e_q;         /* column j at node i: e_q[j * n + i] (only after loading: rows are
                            read into it with stride cap) */
    double *slope_q;     /* de/d(ln V*) of column j at node i, the same layout */
} ct_tab;

/* At most this many quantile columns (a row of 3 + 2 CT_TAB_MAX_QUANTILES numbers stays within
 * the reader's line). */
enum { CT_TAB_MAX_QUANTILES = 64 };

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

/* v kept between the interval's node values a and b, and in [0, 1]: the interpolant's promise.
 * Exact arithmetic keeps a monotone cubic there (Fritsch-Carlson), rounding does not: slopes at
 * the limit of three secants give 1 + 2^-52 above a node e = 1 and -2e-36 below a node e = 0,
 * where e = 1 or 0 is approached as a cubic in t, and a slope ratio within 1e-12 of 3 (what the
 * reader accepts) overshoots by that much times the rise. A NaN (from nodes no reader accepts)
 * stays NaN. */
static inline double ct_tab_clamp(double v, double a, double b)
{
    const double lo = a < b ? a : b, hi = a < b ? b : a;
    v = v < lo ? lo : (v > hi ? hi : v);
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
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
    double v;
    if (rule == CT_TAB_LINEAR)
        v = e[i] + rise * t;
    else /* cubic Hermite: equal ends with zero slopes give e[i] exactly (a flat interval) */
        v = e[i] + rise * (t * t * (3.0 - 2.0 * t)) +
            h * t * (1.0 - t) * ((1.0 - t) * slope[i] - t * slope[i + 1]);
    return ct_tab_clamp(v, e[i], e[i + 1]);
}

/* e at V_star (dimensionless) from a loaded table. */
static inline double ct_tab_eval(const ct_tab *t, double V_star)
{
    return ct_tab_interp(t->n, t->ln_V_star, t->e, t->slope, t->rule, t->V_star_crit, V_star);
}

/* e at V_star and probability prob in [0, 1] from nq quantile columns (e_q, slope_q: column j
 * at node i at [j * n + i], probabilities p strictly increasing): each column interpolated as e
 * is, kept non-decreasing in p (a running maximum), then linear in prob between the two
 * columns about it (the nearest end's outside [p_0, p_(nq-1)]). NaN for prob outside [0, 1],
 * for nq = 0, and for a V_star that is NaN or not > 0. */
static inline double ct_tab_quantile_interp(size_t n, const double *ln_V, size_t nq,
                                            const double *p, const double *e_q,
                                            const double *slope_q, int rule, double V_star_crit,
                                            double V_star, double prob)
{
    if (!nq || !(prob >= 0.0 && prob <= 1.0))
        return NAN;
    size_t j = 0;
    while (j + 1 < nq && p[j + 1] <= prob)
        j++;
    double a = -INFINITY;
    for (size_t k = 0; k <= j; k++) { /* the running maximum up to column j */
        const double v =
            ct_tab_interp(n, ln_V, e_q + k * n, slope_q + k * n, rule, V_star_crit, V_star);
        a = v > a ? v : a;
    }
    if (isnan(a) || prob <= p[0] || j + 1 >= nq)
        return a;
    double b =
        ct_tab_interp(n, ln_V, e_q + (j + 1) * n, slope_q + (j + 1) * n, rule, V_star_crit, V_star);
    b = b > a ? b : a;
    const double w = (prob - p[j]) / (p[j + 1] - p[j]);
    return ct_tab_clamp(a + w * (b - a), a, b);
}

/* e at V_star (dimensionless) and probability prob from a loaded table of samples (its quantile
 * columns): NaN for a table without them or prob outside [0, 1]. */
static inline double ct_tab_eval_quantile(const ct_tab *t, double V_star, double prob)
{
    return ct_tab_quantile_interp(t->n, t->ln_V_star, t->nq, t->p, t->e_q, t->slope_q, t->rule,
                                  t->V_star_crit, V_star, prob);
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
    free(t->p);
    free(t->e_q);
    free(t->slope_q);
    t->V_star = t->ln_V_star = t->e = t->slope = t->p = t->e_q = t->slope_q = NULL;
    t->n = t->nq = 0;
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

/* The keys the loader reads, in the order of the bits of its record of which it has seen. */
static const char *const ct_tab_keys[] = {"interpolation",         "V_star_crit",  "tolerance",
                                          "worst_error",           "v_per_V_star", "nodes",
                                          "worst_error_at_V_star", "quantiles"};
enum { CT_TAB_NKEYS = sizeof ct_tab_keys / sizeof ct_tab_keys[0] };

/* The index in ct_tab_keys of the key of a "# key = value" line (the text between '#' and the
 * first '=', spaces around it dropped), or -1 when it has none the loader reads (prose). */
static inline int ct_tab_key_index(const char *line)
{
    const char *k = line + 1, *eq = strchr(line, '=');
    while (*k == ' ')
        k++;
    if (!eq || eq < k)
        return -1;
    size_t n = (size_t)(eq - k);
    while (n && k[n - 1] == ' ')
        n--;
    for (int i = 0; i < CT_TAB_NKEYS; i++)
        if (strlen(ct_tab_keys[i]) == n && !strncmp(k, ct_tab_keys[i], n))
            return i;
    return -1;
}

/* 1 when a "# key = value" line names a key the loader reads. */
static inline int ct_tab_key_used(const char *line)
{
    return ct_tab_key_index(line) >= 0;
}

/* A count in decimal digits only (no sign, no exponent), without overflow. */
static inline int ct_tab_count(const char *text, size_t *out)
{
    size_t v = 0;
    if (!*text)
        return 0;
    for (; *text; text++) {
        if (*text < '0' || *text > '9' || v > ((size_t)-1 - 9) / 10)
            return 0;
        v = 10 * v + (size_t)(*text - '0');
    }
    *out = v;
    return 1;
}

/* What a monotone cubic table promises, checked on its nodes: every slope finite; on every
 * interval above V*_c (below it e = 1 by the rule) whose nodes have equal e both slopes 0,
 * else both of the secant's sign and at most three secants (Fritsch-Carlson), so that e stays
 * between the interval's nodes. -1 and the interval's index (from 0) when one fails. */
static inline int ct_tab_check_column(const ct_tab *t, const double *e, const double *slope,
                                      size_t *bad)
{
    for (size_t i = 0; i < t->n; i++)
        if (!isfinite(slope[i])) {
            *bad = i;
            return -1;
        }
    if (t->rule != CT_TAB_MONOTONE_CUBIC)
        return 0;
    for (size_t i = 0; i + 1 < t->n; i++) {
        if (t->V_star[i + 1] <= t->V_star_crit)
            continue; /* e = 1 there by the rule: this interval is never interpolated */
        const double secant = (e[i + 1] - e[i]) / (t->ln_V_star[i + 1] - t->ln_V_star[i]);
        const double a = slope[i], b = slope[i + 1];
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

/* ct_tab_check_column on e. */
static inline int ct_tab_check_slopes(const ct_tab *t, size_t *bad)
{
    return ct_tab_check_column(t, t->e, t->slope, bad);
}

/* ct_tab_check_column on e and on every quantile column (*column: 0 for e, j + 1 for column
 * j). */
static inline int ct_tab_check_all_slopes(const ct_tab *t, size_t *bad, size_t *column)
{
    *column = 0;
    if (ct_tab_check_slopes(t, bad))
        return -1;
    for (size_t j = 0; j < t->nq; j++) {
        *column = j + 1;
        if (ct_tab_check_column(t, t->e_q + j * t->n, t->slope_q + j * t->n, bad))
            return -1;
    }
    return 0;
}

/* Why ct_tab_read failed. */
enum { CT_TAB_BAD_FILE = 1, CT_TAB_IO_ERROR = 2, CT_TAB_NO_MEMORY = 3 };

/* The reader's steps say what is wrong with a line in what (CT_TAB_WHAT bytes); ct_tab_read
 * puts file:line before it. */
enum { CT_TAB_WHAT = 200 };

/* The message into what: returns CT_TAB_BAD_FILE. */
static inline int ct_tab_fail(char *what, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static inline int ct_tab_fail(char *what, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, CT_TAB_WHAT, fmt, ap);
    va_end(ap);
    return CT_TAB_BAD_FILE;
}

/* What the reader knows between lines. */
typedef struct {
    size_t cap;      /* rows allocated */
    size_t nodes;    /* # nodes (0: not given yet) */
    unsigned seen;   /* bit k: ct_tab_keys[k] given */
    int have_header; /* the column header was read */
    size_t nq;       /* # quantiles (0: none) */
} ct_tab_reading;

/* How a line that fgets read into line (size bytes, len of them) ends: 0 with its line break
 * (a line to read), -1 a long prose line, skipped whole (the rest of it read from f),
 * CT_TAB_BAD_FILE when no table has such a line (what says why), CT_TAB_IO_ERROR at a read
 * error. */
static inline int ct_tab_line_end(FILE *f, const char *line, size_t len, size_t size, char *what)
{
    if (len + 1 == size && line[len - 1] != '\n') {
        /* a long header line (a long scene path): prose and keys this reader does not use
         * are skipped whole; a key it uses, and a row, are never that long */
        int c;
        if (line[0] != '#' || ct_tab_key_used(line))
            return ct_tab_fail(what, "line longer than %d characters", (int)size - 2);
        while ((c = fgetc(f)) != EOF && c != '\n')
            if (!c)
                return ct_tab_fail(what, "a NUL byte: not a text file");
        if (c == EOF && !ferror(f) && memchr(line, '\r', len))
            return ct_tab_fail(what, "lines end in a carriage return alone: not read");
        if (c == EOF && !ferror(f))
            return ct_tab_fail(what, "the last line has no line break: the file is cut");
        return -1;
    }
    if (!len || line[len - 1] != '\n') {
        /* fgets stops after a line break, at the end of the file, or with its buffer full
         * (above): this line is the last and has no break, or it holds a NUL byte */
        if (ferror(f))
            return CT_TAB_IO_ERROR;
        if (feof(f) && memchr(line, '\r', len))
            return ct_tab_fail(what, "lines end in a carriage return alone: not read");
        if (feof(f))
            return ct_tab_fail(what, "the last line has no line break: the file is cut");
        return ct_tab_fail(what, "a NUL byte: not a text file");
    }
    return 0;
}

/* The value v of a header key (key: its index in ct_tab_keys) into t, the count of rows into
 * *nodes. 0, or CT_TAB_BAD_FILE with what set. */
static inline int ct_tab_key_value(ct_tab *t, int key, const char *v, size_t *nodes, size_t *nq,
                                   char *what)
{
    /* a number is the whole word: strtod's ',' ends a row's field, not a value */
    double x = NAN;
    const int number = key != 0 && key != 5 && key != 7 && !strchr(v, ',') && ct_tab_number(v, &x);
    switch (key) {
    case 0:
        if (!strcmp(v, "monotone_cubic"))
            t->rule = CT_TAB_MONOTONE_CUBIC;
        else if (!strcmp(v, "linear"))
            t->rule = CT_TAB_LINEAR;
        else
            return ct_tab_fail(what, "interpolation = %s: must be monotone_cubic or linear", v);
        break;
    case 1:
        if (!number || !(x >= 0.0))
            return ct_tab_fail(what, "V_star_crit = %s: not a number >= 0", v);
        t->V_star_crit = x;
        break;
    case 2:
        if (!number || !(x > 0.0))
            return ct_tab_fail(what, "tolerance = %s: not a number > 0", v);
        t->tolerance = x;
        break;
    case 3:
        if (!number || !(x >= 0.0))
            return ct_tab_fail(what, "worst_error = %s: not a number >= 0", v);
        t->worst_error = x;
        break;
    case 4:
        if (!number || !(x > 0.0))
            return ct_tab_fail(what, "v_per_V_star = %s: not a number > 0", v);
        t->v_per_V_star = x;
        break;
    case 5:
        if (!ct_tab_count(v, nodes) || *nodes < 2)
            return ct_tab_fail(what, "nodes = %s: not a count >= 2 (the number of rows)", v);
        break;
    case 7:
        if (!ct_tab_count(v, nq) || *nq < 1 || *nq > CT_TAB_MAX_QUANTILES)
            return ct_tab_fail(what, "quantiles = %s: not a count from 1 to %d", v,
                               CT_TAB_MAX_QUANTILES);
        break;
    default: /* where worst_error was found, or none when no point was checked */
        if (strcmp(v, "none") && (!number || !(x > 0.0)))
            return ct_tab_fail(what, "worst_error_at_V_star = %s: not a number > 0 or none", v);
        t->worst_V_star = x;
    }
    return 0;
}

/* A "# key = value" line of a key the reader reads (key: its index in ct_tab_keys): once, before
 * the column header, its value's first word (a comment may follow it) into t. 0, or
 * CT_TAB_BAD_FILE with what set. */
static inline int ct_tab_key_line(ct_tab *t, ct_tab_reading *r, const char *line, int key,
                                  char *what)
{
    if (r->seen & (1u << key))
        return ct_tab_fail(what, "# %s given twice", ct_tab_keys[key]);
    if (r->have_header)
        return ct_tab_fail(what, "# %s after the column header: header keys come first",
                           ct_tab_keys[key]);
    r->seen |= 1u << key;
    char v[64];
    const char *w = strchr(line, '=') + 1;
    size_t vl = 0;
    while (*w == ' ')
        w++;
    while (w[vl] && w[vl] != ' ' && w[vl] != '\t' && w[vl] != '\n' && w[vl] != '\r')
        if (++vl >= sizeof v)
            return ct_tab_fail(what, "%s: value longer than %d characters", ct_tab_keys[key],
                               (int)sizeof v - 1);
    memcpy(v, w, vl);
    v[vl] = '\0';
    return ct_tab_key_value(t, key, v, &r->nodes, &r->nq, what);
}

/* Room for a row more: the arrays doubled (256 rows at first) into *cap. 0, or -1 out of
 * memory (what was allocated stays in t). */
static inline int ct_tab_grow(ct_tab *t, size_t *cap)
{
    size_t ncap = *cap ? 2 * *cap : 256;
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
        return -1;
    if (t->nq) { /* while reading, row i of column j at [i * nq + j] (rows appended) */
        double *q = (double *)realloc(t->e_q, ncap * t->nq * sizeof(double));
        if (q)
            t->e_q = q;
        double *dq = q ? (double *)realloc(t->slope_q, ncap * t->nq * sizeof(double)) : NULL;
        if (dq)
            t->slope_q = dq;
        if (!dq)
            return -1;
    }
    *cap = ncap;
    return 0;
}

/* A row V_star,e,de_dlnV_star appended to t (room made for it). 0, or CT_TAB_BAD_FILE with
 * what set. */
/* The quantile columns of a row (after its first three fields, from *rest), into row i of the
 * reading layout; each e in [0, 1] and not below the previous column's. */
static inline int ct_tab_row_quantiles(ct_tab *t, const char *rest, char *what)
{
    const size_t i = t->n;
    for (size_t j = 0; j < t->nq; j++) {
        double e, d;
        const char *c = rest ? strchr(rest, ',') : NULL;
        if (!rest || !c || !ct_tab_number(rest, &e) || !ct_tab_number(c + 1, &d))
            return ct_tab_fail(what,
                               "expected %lu numbers: V_star,e,de_dlnV_star and two per "
                               "quantile",
                               (unsigned long)(3 + 2 * t->nq));
        rest = strchr(c + 1, ',');
        if (rest)
            rest++;
        if (!(e >= 0.0 && e <= 1.0))
            return ct_tab_fail(what, "e at p = %.6g: %.17g must be in [0, 1]", t->p[j], e);
        if (j && e < t->e_q[i * t->nq + j - 1])
            return ct_tab_fail(what, "e at p = %.6g below e at p = %.6g: quantiles decrease",
                               t->p[j], t->p[j - 1]);
        t->e_q[i * t->nq + j] = e;
        t->slope_q[i * t->nq + j] = d;
    }
    if (rest)
        return ct_tab_fail(what, "more than %lu numbers in a row", (unsigned long)(3 + 2 * t->nq));
    return 0;
}

static inline int ct_tab_row(ct_tab *t, const char *line, char *what)
{
    const char *c1 = strchr(line, ','), *c2 = c1 ? strchr(c1 + 1, ',') : NULL;
    const char *c3 = c2 ? strchr(c2 + 1, ',') : NULL;
    double V, e, d;
    if (t->nq && (!c3 || ct_tab_row_quantiles(t, c3 + 1, what)))
        return c3 ? CT_TAB_BAD_FILE
                  : ct_tab_fail(what,
                                "expected %lu numbers: V_star,e,de_dlnV_star and two per "
                                "quantile",
                                (unsigned long)(3 + 2 * t->nq));
    if (!c2 || (!t->nq && c3) || !ct_tab_number(line, &V) || !ct_tab_number(c1 + 1, &e) ||
        !ct_tab_number(c2 + 1, &d))
        return ct_tab_fail(what, "expected three numbers V_star,e,de_dlnV_star");
    if (!(V > 0.0) || (t->n && !(V > t->V_star[t->n - 1])))
        return ct_tab_fail(what, "V_star = %.17g: must be > 0 and above the previous node", V);
    if (!(e >= 0.0 && e <= 1.0))
        return ct_tab_fail(what, "e = %.17g: must be in [0, 1]", e);
    t->V_star[t->n] = V;
    t->e[t->n] = e;
    t->slope[t->n] = d;
    t->n++;
    return 0;
}

/* The quantile columns' names after V_star,e,de_dlnV_star (text): ",e_p<p>,de_p<p>_dlnV_star"
 * for each of # quantiles, p strictly increasing in [0, 1], into t->p. 0, or CT_TAB_BAD_FILE or
 * CT_TAB_NO_MEMORY with what set. */
static inline int ct_tab_quantile_header(ct_tab *t, const ct_tab_reading *r, const char *text,
                                         char *what)
{
    if (!(t->p = (double *)malloc(r->nq * sizeof(double)))) {
        ct_tab_fail(what, "out of memory");
        return CT_TAB_NO_MEMORY;
    }
    t->nq = r->nq;
    for (size_t j = 0; j < r->nq; j++) {
        char name[40], slope[64];
        const char *end;
        if (strncmp(text, ",e_p", 4) || !(end = strchr(text + 4, ',')) || end - text - 4 >= 32)
            return ct_tab_fail(what,
                               "expected %lu quantile columns e_p<p>,de_p<p>_dlnV_star "
                               "after V_star,e,de_dlnV_star (# quantiles)",
                               (unsigned long)r->nq);
        memcpy(name, text + 4, (size_t)(end - text - 4));
        name[end - text - 4] = '\0';
        double p;
        if (!ct_tab_number(name, &p) || !(p >= 0.0 && p <= 1.0) || (j && !(p > t->p[j - 1])))
            return ct_tab_fail(what, "quantile column e_p%s: p must be in [0, 1] and increasing",
                               name);
        snprintf(slope, sizeof slope, ",de_p%s_dlnV_star", name);
        if (strncmp(end, slope, strlen(slope)))
            return ct_tab_fail(what, "e_p%s: expected %s after it", name, slope + 1);
        t->p[j] = p;
        text = end + strlen(slope);
    }
    if (*text != '\n' && !(text[0] == '\r' && text[1] == '\n'))
        return ct_tab_fail(what, "more columns than # quantiles = %lu says", (unsigned long)r->nq);
    return 0;
}

/* One line with its line break into t: a header key or prose ('#'), the column header, an
 * empty line or a row. 0, or CT_TAB_BAD_FILE or CT_TAB_NO_MEMORY with what set. */
static inline int ct_tab_line(ct_tab *t, ct_tab_reading *r, const char *line, char *what)
{
    if (line[0] == '#') {
        const int key = ct_tab_key_index(line);
        return key < 0 ? 0 : ct_tab_key_line(t, r, line, key, what); /* prose, or a key */
    }
    if (!r->have_header) {
        if (strncmp(line, "V_star,e,de_dlnV_star", 21))
            return ct_tab_fail(what, "expected the header V_star,e,de_dlnV_star");
        r->have_header = 1;
        return r->nq ? ct_tab_quantile_header(t, r, line + 21, what) : 0;
    }
    if (line[0] == '\n' || (line[0] == '\r' && line[1] == '\n'))
        return 0;
    if (r->nodes && t->n == r->nodes)
        return ct_tab_fail(what, "a row beyond the %lu of # nodes", (unsigned long)r->nodes);
    if (t->n == r->cap && ct_tab_grow(t, &r->cap)) {
        ct_tab_fail(what, "out of memory");
        return CT_TAB_NO_MEMORY;
    }
    return ct_tab_row(t, line, what);
}

/* The table once every line is read: the keys that make it a cantact table, as many rows as
 * # nodes says, and ln V* (made here) increasing. 0, or CT_TAB_BAD_FILE or CT_TAB_NO_MEMORY
 * with what set. */
static inline int ct_tab_whole(ct_tab *t, const ct_tab_reading *r, char *what)
{
    if (!(r->seen & 1u) || !(r->seen & 2u))
        return ct_tab_fail(
            what, "missing # interpolation = ... or # V_star_crit = ... (not a cantact table)");
    if (!r->nodes)
        return ct_tab_fail(what, "missing # nodes = ... (the number of rows, without which a cut "
                                 "table cannot be told from a whole one)");
    if (t->n != r->nodes)
        return ct_tab_fail(what, "%lu rows where # nodes = %lu: the file is cut",
                           (unsigned long)t->n, (unsigned long)r->nodes);
    if (!(t->ln_V_star = (double *)malloc(t->n * sizeof(double)))) {
        ct_tab_fail(what, "out of memory");
        return CT_TAB_NO_MEMORY;
    }
    for (size_t i = 0; i < t->n; i++) {
        t->ln_V_star[i] = log(t->V_star[i]);
        if (i && !(t->ln_V_star[i] > t->ln_V_star[i - 1]))
            return ct_tab_fail(what, "nodes %lu and %lu: ln V_star not increasing",
                               (unsigned long)i, (unsigned long)i + 1);
    }
    if (r->nq && !r->have_header)
        return ct_tab_fail(what, "no column header");
    if (t->nq) { /* rows were read as [i * nq + j]: columns [j * n + i] */
        double *q = (double *)malloc(t->n * t->nq * sizeof(double)),
               *dq = (double *)malloc(t->n * t->nq * sizeof(double));
        if (!q || !dq) {
            free(q);
            free(dq);
            ct_tab_fail(what, "out of memory");
            return CT_TAB_NO_MEMORY;
        }
        for (size_t i = 0; i < t->n; i++)
            for (size_t j = 0; j < t->nq; j++) {
                q[j * t->n + i] = t->e_q[i * t->nq + j];
                dq[j * t->n + i] = t->slope_q[i * t->nq + j];
            }
        free(t->e_q);
        free(t->slope_q);
        t->e_q = q;
        t->slope_q = dq;
    }
    return 0;
}

/* Reads a table file: "# key = value" header lines (the keys ct_tab_keys, each at most once,
 * all before the column header; other '#' lines are prose), the column header
 * V_star,e,de_dlnV_star, then exactly `# nodes` rows V_star,e,de_dlnV_star, every line ended by
 * a line break. So a file cut anywhere is refused: at a line break it has fewer rows than
 * `# nodes` says (and a table without `# nodes` cannot tell), inside a row its last line has
 * no line break. Returns 0, or CT_TAB_BAD_FILE (not a table this reader accepts),
 * CT_TAB_IO_ERROR (the file cannot be opened or read) or CT_TAB_NO_MEMORY, with a one-line
 * message naming file:line in err (the table is then empty and needs no ct_tab_free). */
static inline int ct_tab_read(ct_tab *t, const char *path, char *err, size_t errlen)
{
    FILE *f = fopen(path, "r");
    char line[4096], what[CT_TAB_WHAT];
    size_t lineno = 0;
    ct_tab_reading r = {0, 0, 0, 0, 0};
    int why;
    memset(t, 0, sizeof *t);
    t->tolerance = t->worst_error = t->v_per_V_star = t->worst_V_star = NAN;
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return CT_TAB_IO_ERROR;
    }
    while (fgets(line, sizeof line, f)) {
        lineno++;
        why = ct_tab_line_end(f, line, strlen(line), sizeof line, what);
        if (why == 0)
            why = ct_tab_line(t, &r, line, what);
        if (why == CT_TAB_IO_ERROR)
            break;
        if (why > 0)
            goto fail_at_line;
    }
    if (ferror(f)) {
        why = CT_TAB_IO_ERROR;
        snprintf(what, sizeof what, "read error");
        goto fail_at_line;
    }
    if ((why = ct_tab_whole(t, &r, what)))
        goto fail_at_line;
    size_t bad, column;
    if (ct_tab_check_all_slopes(t, &bad, &column)) {
        const double *e = column ? t->e_q + (column - 1) * t->n : t->e,
                     *d = column ? t->slope_q + (column - 1) * t->n : t->slope;
        char of[48] = "";
        if (column)
            snprintf(of, sizeof of, " of e at p = %.6g", t->p[column - 1]);
        snprintf(err, errlen,
                 "%s: nodes %lu and %lu: slopes%s %.6g and %.6g are not those of a monotone "
                 "cubic between e = %.6g and %.6g (a corrupted or foreign table)",
                 path, (unsigned long)bad + 1, (unsigned long)bad + 2, of, d[bad],
                 bad + 1 < t->n ? d[bad + 1] : NAN, e[bad], bad + 1 < t->n ? e[bad + 1] : NAN);
        why = CT_TAB_BAD_FILE;
        goto fail;
    }
    fclose(f);
    return 0;
fail_at_line:
    snprintf(err, errlen, "%s:%lu: %s", path, (unsigned long)lineno, what);
fail:
    fclose(f);
    ct_tab_free(t);
    return why;
}

/* ct_tab_read without the reason: 0, or -1 with the message in err. */
static inline int ct_tab_load(ct_tab *t, const char *path, char *err, size_t errlen)
{
    return ct_tab_read(t, path, err, errlen) ? -1 : 0;
}

/* ---- e <-> damping ratio of a linear spring-dashpot normal contact (see the top) ---- */

/* How the contact ends: CT_TAB_TENSION at zero overlap (the dashpot may pull), CT_TAB_CLIPPED
 * when the force max(0, k delta + c delta') reaches 0. */
enum { CT_TAB_TENSION = 0, CT_TAB_CLIPPED = 1 };

#define CT_TAB_PI 3.14159265358979323846

/* -ln e of the clipped law, 2 zeta h(zeta), at a finite zeta >= 0. */
static inline double ct_tab_clipped_loss(double zeta)
{
    double h;
    if (zeta < 1.0) /* (1 - zeta)(1 + zeta): no cancellation near 1 */
        h = acos(zeta) / sqrt((1.0 - zeta) * (1.0 + zeta));
    else if (zeta > 1.0) /* sqrt of each factor: no overflow for large zeta */
        h = acosh(zeta) / (sqrt(zeta - 1.0) * sqrt(zeta + 1.0));
    else
        h = 1.0;
    return 2.0 * zeta * h;
}

/* d/dzeta of ct_tab_clipped_loss: 2 h + 2 zeta h', h' = (zeta h - 1) / (1 - zeta^2) (both
 * branches), -1/3 - 4 (1 - zeta) / 15 near 1 (the series). Newton's direction only. */
static inline double ct_tab_clipped_loss_slope(double zeta)
{
    const double t = 1.0 - zeta, h = 0.5 * ct_tab_clipped_loss(zeta) / (zeta > 0.0 ? zeta : 1.0);
    double dh;
    if (fabs(t) < 1e-4)
        dh = -1.0 / 3.0 - 4.0 * t / 15.0;
    else
        dh = (zeta * h - 1.0) / (t * (1.0 + zeta));
    return 2.0 * (zeta > 0.0 ? h : CT_TAB_PI / 2.0) + 2.0 * zeta * dh;
}

/* e of a linear spring-dashpot contact with damping ratio zeta under `law` (the top of this
 * file): CT_TAB_TENSION exp(-pi zeta / sqrt(1 - zeta^2)), 0 for zeta >= 1; CT_TAB_CLIPPED
 * exp(-2 zeta h(zeta)). NaN for zeta NaN or < 0 or another law; 0 at zeta = +infinity. */
static inline double ct_tab_e_of_zeta(double zeta, int law)
{
    if (!(zeta >= 0.0) || (law != CT_TAB_TENSION && law != CT_TAB_CLIPPED))
        return NAN;
    if (law == CT_TAB_TENSION)
        return zeta < 1.0 ? exp(-CT_TAB_PI * zeta / sqrt((1.0 - zeta) * (1.0 + zeta))) : 0.0;
    if (isinf(zeta))
        return 0.0;
    return exp(-ct_tab_clipped_loss(zeta));
}

/* The damping ratio zeta that rebounds with e under `law`: CT_TAB_TENSION -ln e /
 * sqrt(pi^2 + ln^2 e) (< 1; 1 for e = 0); CT_TAB_CLIPPED the root of 2 zeta h(zeta) = -ln e
 * (< 1 for e > e^-2, 1 at e^-2, > 1 below; +infinity for e = 0). 0 for e = 1; NaN for e NaN,
 * < 0 or > 1, or another law. The contact's damping is c = 2 zeta sqrt(m k). */
static inline double ct_tab_zeta_of_e(double e, int law)
{
    if (!(e >= 0.0 && e <= 1.0) || (law != CT_TAB_TENSION && law != CT_TAB_CLIPPED))
        return NAN;
    if (e == 1.0)
        return 0.0;
    if (e == 0.0)
        return law == CT_TAB_TENSION ? 1.0 : INFINITY;
    const double L = -log(e); /* > 0, <= 745 */
    if (law == CT_TAB_TENSION)
        return L / sqrt(CT_TAB_PI * CT_TAB_PI + L * L);
    /* 2 zeta h(zeta) rises from 0 (slope pi) to 2 at zeta = 1, then as 2 ln(2 zeta): bracket
     * [0, 1] or [1, exp(L / 2)] (2 zeta h >= 2 ln zeta there), and a first guess */
    double lo, hi, z;
    if (L <= 2.0) {
        /* pi z - (pi - 2) z^2 = L: the quadratic through (0, 0) and (1, 2) with slope pi */
        const double a = CT_TAB_PI - 2.0;
        lo = 0.0;
        hi = 1.0;
        z = 2.0 * L / (CT_TAB_PI + sqrt(fmax(CT_TAB_PI * CT_TAB_PI - 4.0 * a * L, 0.0)));
    } else {
        lo = 1.0;
        hi = exp(0.5 * L);
        z = 0.5 * hi + 0.5;
    }
    double best = z, best_f = INFINITY;
    for (int it = 0; it < 200; it++) {
        const double f = ct_tab_clipped_loss(z) - L;
        if (fabs(f) < best_f) {
            best = z;
            best_f = fabs(f);
        }
        if (f == 0.0)
            break;
        if (f < 0.0)
            lo = z;
        else
            hi = z;
        double next = z - f / ct_tab_clipped_loss_slope(z);
        if (!(next > lo && next < hi)) /* bisection, geometric over a wide bracket */
            next = (lo > 0.0 && hi > 4.0 * lo) ? sqrt(lo * hi) : lo + 0.5 * (hi - lo);
        if (!(next > lo && next < hi))
            break; /* lo and hi are neighbours: the best of them is the root */
        if (fabs(next - z) <= 2e-16 * z) { /* Newton's step is at rounding level */
            best = next;
            break;
        }
        z = next;
    }
    return best;
}

#endif
