/* A user's own rod set (docs/model.md §12): rods given as a file (CSV or blank-separated
 * columns top, area and optionally length; with a header, also the position x and y of each
 * rod, its footprint) or inline (surface.rods = top:area[:length], ...),
 * in one Winkler layer. Everything of §3, §4, §7 and §11 holds rod by rod. Scales: h0 the
 * deepest top (a rod set whose tops are all 0 needs surface.h0 or surface.Hstar), l0 the total
 * area, so V* = sqrt(m v^2 / (2 l0 E h0)) and forces are in P_Y = sigma_y l0. A rod's length,
 * when given, replaces H* - top; the layer's H* is then the shallowest rod bottom,
 * min(top + length), where the first rod would reach strain 1 (the crushed-layer limit). The
 * rods are built in units that are powers of two of the given ones (ct_build_units_of), so
 * that e does not depend on the scale (docs/model.md §13). */
#include "kind.h"
#include "number.h"

#include <ctype.h>
#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A rod file's line is a few numbers: anything longer is not a rod file. */
#define MAX_LINE 4096

typedef struct {
    char *file, *rods; /* [surface]: one of them */
    int unit;          /* index into "m|mm|um|nm" when given */
    double Hstar, H;   /* H* [unit], or H* / h0 */
    double h0, l0;     /* reference depth and length [unit] (defaults: deepest top, total area) */
    double E, sigma_y; /* [material] */
    /* rods from arrays (ct_surface_set_rods), instead of file or rods */
    size_t given_n;
    double *given_top, *given_area, *given_length, *given_x, *given_y;
    /* prepared */
    size_t n;
    double *top, *area, *length; /* length NULL: H* - top */
    double *x, *y;               /* each rod's position (NULL: none given; y NULL: a line) */
    ct_layer layer;              /* as built: in units (a power of two of the given ones) */
    ct_layer physical;           /* as given */
    ct_build_units units;        /* built per given */
    char source[160];
} rods_config;

static const double unit_metres[] = {1.0, 1e-3, 1e-6, 1e-9};

#define AT(field) offsetof(rods_config, field)
static const ct_key rods_keys[] = {
    {"surface", "file", CT_KEY_TEXT, 0, 0, CT_KEY_FILE, NULL, "must be a path", "",
     "a file of rods: rows of top, area and optionally length, separated by commas, semicolons "
     "or blanks, no field empty; lines starting with # or ; are comments (a header naming each "
     "column once may come first; with one, columns x and y place each rod); relative to the "
     "scene's directory",
     AT(file)},
    {"surface", "rods", CT_KEY_TEXT, 0, 0, 0, NULL,
     "must be top:area[:length], ... (no field empty)", "",
     "rods inline: top:area[:length], ... (or give file)", AT(rods)},
    {"surface", "unit", CT_KEY_WORD, 0, 0, 0, "m|mm|um|nm", "must be m, mm, um or nm",
     "the scene's units",
     "the unit of tops, areas, lengths, Hstar, h0 and l0 (areas and l0 of rods placed by x and y: "
     "its square)",
     AT(unit)},
    {"surface", "Hstar", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "layer thickness H* [unit] (or give H; neither when the rods give their lengths)", AT(Hstar)},
    {"surface", "H", CT_KEY_NUMBER, 1.0, INFINITY, 0, NULL, "must satisfy H > 1 (H* = H h0)", "",
     "H* as a multiple of h0", AT(H)},
    {"surface", "h0", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "the deepest top",
     "reference depth [unit]: results are per h0", AT(h0)},
    {"surface", "l0", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "the total area",
     "reference length [unit] (rods placed by x and y: an area [unit^2]): forces are per sigma_y "
     "l0",
     AT(l0)},
    {"material", "E", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",
     "Young's modulus", AT(E)},
    {"material", "sigma_y", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "1",
     "yield stress", AT(sigma_y)},
};
#undef AT

static void rods_defaults(void *config)
{
    rods_config *c = config;
    c->sigma_y = 1.0;
}

static void rods_release_given(rods_config *c)
{
    free(c->given_top);
    free(c->given_area);
    free(c->given_length);
    free(c->given_x);
    free(c->given_y);
    c->given_top = c->given_area = c->given_length = c->given_x = c->given_y = NULL;
    c->given_n = 0;
}

static void rods_prepared_release(rods_config *c)
{
    free(c->top);
    free(c->area);
    free(c->length);
    free(c->x);
    free(c->y);
    c->top = c->area = c->length = c->x = c->y = NULL;
    c->n = 0;
}

static void rods_release(void *config)
{
    rods_prepared_release(config);
    rods_release_given(config);
}

static int rods_check(ct_surface *s, const char *scene)
{
    rods_config *c = s->config;
    const int file = ct_surface_given(s, "surface", "file"),
              inline_ = ct_surface_given(s, "surface", "rods"), arrays = c->given_top != NULL;
    if (file + inline_ + arrays != 1)
        return ct_error_set(CT_EINVAL,
                            "%s: type = rods needs one of surface.file (a file of rods), "
                            "surface.rods (top:area[:length], ...) and rods as arrays",
                            scene);
    if (ct_surface_given(s, "surface", "H") && ct_surface_given(s, "surface", "Hstar"))
        return ct_surface_key_error(s, "surface", "H", CT_EINVAL, "give H or Hstar, not both");
    if (!(c->E > c->sigma_y))
        return ct_surface_key_error(s, "material", "E", CT_EINVAL,
                                    "must be > sigma_y (yield strain sigma_y/E < 1)");
    return CT_OK;
}

/* Appends one rod; cap grows. */
/* The columns of a rod: v[COL_TOP] .. v[COL_Y]; NaN where not given (read numbers are finite). */
enum { COL_TOP, COL_AREA, COL_LENGTH, COL_X, COL_Y, NCOL };

static int push(rods_config *c, size_t *cap, const double *v)
{
    if (c->n == *cap) {
        size_t grown = *cap ? 2 * *cap : 64;
        double **arrays[NCOL] = {&c->top, &c->area, &c->length, &c->x, &c->y};
        for (int i = 0; i < NCOL; i++) {
            double *t = realloc(*arrays[i], grown * sizeof *t);
            if (!t)
                return ct_error_set(CT_ENOMEM, "rods: out of memory at %zu rods", c->n);
            *arrays[i] = t;
        }
        *cap = grown;
    }
    c->top[c->n] = v[COL_TOP];
    c->area[c->n] = v[COL_AREA];
    c->length[c->n] = v[COL_LENGTH];
    c->x[c->n] = v[COL_X];
    c->y[c->n] = v[COL_Y];
    c->n++;
    return CT_OK;
}

static const char *const column_names[] = {"top", "area", "length", "x", "y"};

/* The separators of a rod file's fields: commas, semicolons, or blanks (runs of blanks are one
 * separator, and blanks around a comma or semicolon belong to it). */
#define FILE_SEPARATORS ",; "

/* A header: the column names top, area and optionally length, x and y, each once, in any
 * order: col[i] is the column (COL_*) of field i. 0, or an error naming the column. */
static int header(const char *line, int col[NCOL], int *ncol, const char *shown, size_t lineno)
{
    int field[NCOL] = {0, 0, 0, 0, 0}; /* the field (from 1) that names each column, 0: none */
    ct_list l;
    const char *tok;
    size_t n;
    *ncol = 0;
    ct_list_start(&l, line, FILE_SEPARATORS);
    for (int i = 1; ct_list_next(&l, &tok, &n); i++) {
        if (!n)
            return ct_error_set(CT_EINVAL, "%s:%zu: header field %d is empty (%s)", shown, lineno,
                                i, ct_list_empty_why());
        int k = 0;
        while (k < NCOL && !(strlen(column_names[k]) == n && !strncmp(tok, column_names[k], n)))
            k++;
        if (k == NCOL)
            return ct_error_set(CT_EINVAL,
                                "%s:%zu: header field %d is '%.*s': neither a number nor a "
                                "column name (top, area, length, x, y)",
                                shown, lineno, i, (int)(n < 40 ? n : 40), tok);
        if (field[k])
            return ct_error_set(CT_EINVAL,
                                "%s:%zu: header: column '%s' named twice (fields %d and %d)", shown,
                                lineno, column_names[k], field[k], i);
        field[k] = i;
        col[(*ncol)++] = k;
    }
    for (int k = 0; k < 2; k++)
        if (!field[k])
            return ct_error_set(CT_EINVAL,
                                "%s:%zu: header: no column '%s' (a header names top, area and "
                                "optionally length, x and y)",
                                shown, lineno, column_names[k]);
    if (field[COL_Y] && !field[COL_X])
        return ct_error_set(CT_EINVAL,
                            "%s:%zu: header: a column 'y' and no 'x' (a rod on a line is placed "
                            "by x, on a plane by x and y)",
                            shown, lineno);
    return CT_OK;
}

/* 1 when a line is a header: its first field is there and is no number (a number that cannot
 * be used, 1e-320 or nan, still makes a row). */
static int is_header(const char *line)
{
    ct_list l;
    const char *f;
    size_t n;
    double x;
    ct_list_start(&l, line, FILE_SEPARATORS);
    return ct_list_next(&l, &f, &n) && n && ct_number_parse(f, n, &x) == CT_NUMBER_NONE &&
           !isdigit((unsigned char)f[0]) && f[0] != '.' && f[0] != '-' && f[0] != '+';
}

/* "top, area, length" of a row's width columns, in the order the file gives them. */
static const char *columns_of(const int col[NCOL], int width)
{
    static _Thread_local char buf[48];
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < width && i < NCOL; i++)
        n += (size_t)snprintf(buf + n, sizeof buf - n, "%s%s", i ? ", " : "", column_names[col[i]]);
    return buf;
}

/* A row of numbers: *width of them (set by the header, else 2 or 3 by the first row: top, area
 * and optionally length), field i the column col[i]. */
static int read_row(rods_config *c, size_t *cap, const char *line, const int col[NCOL], int *width,
                    const char *shown, size_t lineno)
{
    double v[NCOL];
    int nv = 0;
    ct_list l;
    const char *f;
    size_t n;
    ct_list_start(&l, line, FILE_SEPARATORS);
    while (ct_list_next(&l, &f, &n)) {
        if (!n)
            return ct_error_set(CT_EINVAL, "%s:%zu: field %d is empty (%s)", shown, lineno, nv + 1,
                                ct_list_empty_why());
        if (nv == 3 && !*width)
            return ct_error_set(CT_EINVAL,
                                "%s:%zu: more than 3 fields: expected top, area and optionally "
                                "length on every row (a header naming x and y places the rods)",
                                shown, lineno);
        if (*width && nv == *width)
            return ct_error_set(CT_EINVAL,
                                "%s:%zu: more than %d fields: expected %d numbers on "
                                "every row (%s)",
                                shown, lineno, nv, *width, columns_of(col, *width));
        int st = ct_number_parse(f, n, &v[nv]);
        if (st)
            return ct_error_set(CT_EINVAL, "%s:%zu: field %d (%s) = %.*s: %s", shown, lineno,
                                nv + 1, column_names[col[nv]], (int)(n < 40 ? n : 40), f,
                                ct_number_why(st));
        nv++;
    }
    if (!*width && nv >= 2)
        *width = nv;
    if (nv != *width)
        return ct_error_set(CT_EINVAL, "%s:%zu: expected %d numbers on every row (%s)", shown,
                            lineno, *width ? *width : 2, columns_of(col, *width ? *width : 2));
    /* every column once (the header's rule), so every field of row is written: a length or a
     * position only when a column holds it */
    double row[NCOL] = {NAN, NAN, NAN, NAN, NAN};
    for (int i = 0; i < nv; i++)
        row[col[i]] = v[i];
    return push(c, cap, row);
}

/* The next line of f into line (MAX_LINE + 1 bytes), its end (\n, \r\n or a lone \r) dropped:
 * its length, -1 at the end of the file, -2 when longer than MAX_LINE, -3 at a NUL byte. */
static long next_line(FILE *f, char *line)
{
    size_t n = 0;
    int ch;
    while ((ch = getc_unlocked(f)) != EOF) {
        if (ch == '\n')
            break;
        if (ch == '\r') {
            const int d = getc_unlocked(f);
            if (d != '\n' && d != EOF)
                ungetc(d, f);
            break;
        }
        if (ch == '\0')
            return -3;
        if (n == MAX_LINE)
            return -2;
        line[n++] = (char)ch;
    }
    if (ch == EOF && n == 0)
        return -1;
    line[n] = '\0';
    return (long)n;
}

/* A rod file: text as the scenes and profiles are read (line ends \n, \r\n or a lone \r, a
 * UTF-8 byte-order mark dropped, # or ; comments, no NUL byte), a header or rows of numbers. */
static int read_file(rods_config *c, const char *path, const char *shown)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return ct_error_set(CT_EIO, "%s: cannot open: %s", shown, strerror(errno));
    char *line = malloc(MAX_LINE + 1);
    if (!line) {
        fclose(f);
        return ct_error_set(CT_ENOMEM, "rods: out of memory");
    }
    size_t cap = 0, lineno = 0;
    int col[NCOL] = {COL_TOP, COL_AREA, COL_LENGTH, COL_X, COL_Y};
    int width = 0, st = CT_OK; /* width: numbers per row, once known */
    long len;
    while (!st && (len = next_line(f, line)) != -1) {
        lineno++;
        if (len == -2) {
            st = ct_error_set(CT_EINVAL, "%s:%zu: a line longer than %d bytes: not a rod file",
                              shown, lineno, MAX_LINE);
            break;
        }
        if (len == -3) {
            st = ct_error_set(CT_EINVAL,
                              "%s:%zu: a NUL byte: not a text rod file (UTF-16 text? save it as "
                              "UTF-8 or ASCII)",
                              shown, lineno);
            break;
        }
        char *p = line;
        if (lineno == 1 && !strncmp(p, "\xEF\xBB\xBF", 3)) /* a UTF-8 byte-order mark */
            p += 3;
        while (isspace((unsigned char)*p))
            p++;
        if (!*p || *p == '#' || *p == ';')
            continue;
        if (!width && c->n == 0 && is_header(p)) /* a header before the first rod */
            st = header(p, col, &width, shown, lineno);
        else
            st = read_row(c, &cap, p, col, &width, shown, lineno);
    }
    if (!st && ferror(f))
        st = ct_error_set(CT_EIO, "%s: read error", shown);
    fclose(f);
    free(line);
    if (!st && c->n == 0)
        st = ct_error_set(CT_EINVAL, "%s: no rods", shown);
    return st;
}

/* surface.rods = top:area[:length], ...: the same fields and numbers as a file's rows. */
static int read_inline(const ct_surface *s, rods_config *c, const char *text)
{
    size_t cap = 0, k = 0;
    int st = CT_OK;
    ct_list rods;
    const char *item;
    size_t len;
    ct_list_start(&rods, text, ",");
    while (!st && ct_list_next(&rods, &item, &len)) {
        k++;
        if (!len)
            return ct_surface_key_error(s, "surface", "rods", CT_EINVAL,
                                        "rod %zu (field %zu of the list) is empty (%s)", k, k,
                                        ct_list_empty_why());
        char buf[MAX_LINE + 1];
        if (len > MAX_LINE)
            return ct_surface_key_error(s, "surface", "rods", CT_EINVAL,
                                        "rod %zu: longer than %d characters", k, MAX_LINE);
        memcpy(buf, item, len);
        buf[len] = '\0';
        double v[3] = {NAN, NAN, NAN};
        int nv = 0;
        ct_list fields;
        const char *f;
        size_t n;
        ct_list_start(&fields, buf, ":");
        while (ct_list_next(&fields, &f, &n)) {
            if (!n)
                return ct_surface_key_error(s, "surface", "rods", CT_EINVAL,
                                            "rod %zu: field %d of top:area[:length] is empty "
                                            "(%s)",
                                            k, nv + 1, ct_list_empty_why());
            if (nv == 3)
                return ct_surface_key_error(s, "surface", "rods", CT_EINVAL,
                                            "rod %zu: more than 3 fields: expected top:area or "
                                            "top:area:length",
                                            k);
            const int r = ct_number_parse(f, n, &v[nv]);
            if (r)
                return ct_surface_key_error(
                    s, "surface", "rods", CT_EINVAL, "rod %zu: field %d (%s) = %.*s: %s", k, nv + 1,
                    column_names[nv], (int)(n < 40 ? n : 40), f, ct_number_why(r));
            nv++;
        }
        if (nv < 2)
            return ct_surface_key_error(s, "surface", "rods", CT_EINVAL,
                                        "rod %zu: expected top:area or top:area:length", k);
        if (c->n && (nv == 3) != !isnan(c->length[0]))
            return ct_surface_key_error(
                s, "surface", "rods", CT_EINVAL,
                "rod %zu: %s and rod 1 %s (every rod with a length or none)", k,
                nv == 3 ? "has a length" : "has no length", nv == 3 ? "has none" : "has one");
        const double row[NCOL] = {v[0], v[1], v[2], NAN, NAN};
        st = push(c, &cap, row);
    }
    return st;
}

/* The rods from arrays, a file or the inline list; *lengths: whether they give lengths. */
static int read_rods(const ct_surface *s, rods_config *c, const char *dir, int *lengths)
{
    int st = CT_OK;
    if (c->given_top) {
        size_t cap = 0;
        for (size_t k = 0; k < c->given_n && !st; k++) {
            const double v[NCOL] = {
                c->given_top[k], c->given_area[k], c->given_length ? c->given_length[k] : NAN,
                c->given_x ? c->given_x[k] : NAN, c->given_y ? c->given_y[k] : NAN};
            st = push(c, &cap, v);
        }
        snprintf(c->source, sizeof c->source, "arrays");
        *lengths = c->given_length != NULL;
        return st;
    }
    /* numbers in the C locale whatever the caller's (per thread), as scenes and profiles */
    locale_t c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    locale_t before = c_locale ? uselocale(c_locale) : (locale_t)0;
    if (c->file) {
        char *path = ct_path_join(dir, c->file);
        st = path ? read_file(c, path, c->file) : ct_error_set(CT_ENOMEM, "out of memory");
        free(path);
        snprintf(c->source, sizeof c->source, "%s", c->file);
    } else {
        st = read_inline(s, c, c->rods);
        snprintf(c->source, sizeof c->source, "surface.rods");
    }
    if (c_locale) {
        uselocale(before);
        freelocale(c_locale);
    }
    *lengths = !st && c->n && !isnan(c->length[0]); /* read numbers are finite: NaN means none */
    return st;
}

/* An error of rod k (from 0): named by the key and where it was set for inline rods, else by
 * the file (or "arrays"). */
static int rod_error(const ct_surface *s, const rods_config *c, size_t k, const char *fmt, ...)
    CT_PRINTF(4, 5);
static int rod_error(const ct_surface *s, const rods_config *c, size_t k, const char *fmt, ...)
{
    char why[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, sizeof why, fmt, ap);
    va_end(ap);
    if (!c->given_top && !c->file)
        return ct_surface_key_error(s, "surface", "rods", CT_EINVAL, "rod %zu: %s", k + 1, why);
    return ct_error_set(CT_EINVAL, "%s: rod %zu: %s", c->source, k + 1, why);
}

/* The factor of an area in the unit u [m per unit]: rods placed on a plane (x and y) have
 * areas, u^2; any other set, lengths per unit depth of the body (a line model), u. */
static double area_unit(const rods_config *c, double u)
{
    return c->y ? u * u : u;
}

/* Every rod in the unit u [m per unit; 1: as given] and checked; the deepest top, the total
 * area and the shallowest bottom (top + length; infinite without lengths). */
static int check_rods(const ct_surface *s, rods_config *c, int lengths, double u, double *deepest,
                      double *total, double *bottom)
{
    *deepest = *total = 0.0;
    *bottom = INFINITY;
    for (size_t k = 0; k < c->n; k++) {
        c->top[k] *= u;
        c->area[k] *= area_unit(c, u);
        if (!(c->top[k] >= 0.0) || !isfinite(c->top[k]))
            return rod_error(s, c, k, "top = %g: must be finite and >= 0", c->top[k]);
        if (!(c->area[k] > 0.0) || !isfinite(c->area[k]))
            return rod_error(s, c, k, "area = %g: must be finite and > 0", c->area[k]);
        if (lengths) {
            c->length[k] *= u;
            if (!(c->length[k] > 0.0) || !isfinite(c->length[k]))
                return rod_error(s, c, k, "length = %g: must be finite and > 0", c->length[k]);
            *bottom = fmin(*bottom, c->top[k] + c->length[k]);
        }
        for (int i = 0; i < 2; i++) {
            double *pos = i ? c->y : c->x;
            if (!pos)
                continue;
            pos[k] *= u;
            if (!isfinite(pos[k]))
                return rod_error(s, c, k, "%s = %g: must be finite", i ? "y" : "x", pos[k]);
        }
        *deepest = fmax(*deepest, c->top[k]);
        *total += c->area[k];
    }
    return CT_OK;
}

static int rods_prepare(ct_surface *s, const char *dir)
{
    rods_config *c = s->config;
    rods_prepared_release(c);
    int lengths = 0, st = read_rods(s, c, dir, &lengths);
    if (!st && c->n == 0)
        st = ct_error_set(CT_EINVAL, "%s: no rods", c->source);
    if (st)
        return st;
    if (!lengths) {
        free(c->length);
        c->length = NULL;
    }
    if (isnan(c->x[0])) { /* a file's columns and the arrays give a position to all or none */
        free(c->x);
        c->x = NULL;
    }
    if (!c->x || isnan(c->y[0])) {
        free(c->y);
        c->y = NULL;
    }
    const double u = ct_surface_given(s, "surface", "unit") ? unit_metres[c->unit] : 1.0;
    double deepest, total, bottom;
    if ((st = check_rods(s, c, lengths, u, &deepest, &total, &bottom)))
        return st;
    const int given_H = ct_surface_given(s, "surface", "H"),
              given_Hstar = ct_surface_given(s, "surface", "Hstar");
    if (lengths && (given_H || given_Hstar))
        return ct_surface_key_error(s, "surface", given_H ? "H" : "Hstar", CT_EINVAL,
                                    "not with rods that give their lengths (H* is where the "
                                    "first of them reaches strain 1)");
    if (!lengths && !given_H && !given_Hstar)
        return ct_error_set(CT_EINVAL,
                            "%s: type = rods needs surface.Hstar or surface.H (or a length "
                            "for every rod)",
                            c->source);
    double h0 = ct_surface_given(s, "surface", "h0") ? c->h0 * u : deepest;
    const double l0 = ct_surface_given(s, "surface", "l0") ? c->l0 * area_unit(c, u) : total;
    double Hstar = lengths ? bottom : given_Hstar ? c->Hstar * u : NAN;
    if (!(h0 > 0.0)) {
        if (given_H)
            return ct_surface_key_error(s, "surface", "H", CT_EINVAL,
                                        "every top is 0: give surface.h0 (or Hstar)");
        h0 = Hstar; /* every top is 0: depths are per H* */
    }
    if (given_H)
        Hstar = c->H * h0;
    /* Without lengths every rod reaches down to the layer's bottom H*, so it must start above
     * it. With lengths a rod's top may lie at or below another's bottom (the crushed limit
     * H*): it is reached only after the layer has crushed, so no impact within the model
     * touches it, and it only counts in the scales (h0, l0), as docs/model.md §12 says. */
    for (size_t k = 0; k < c->n && !lengths; k++)
        if (!(c->top[k] < Hstar)) {
            char from[96];
            if (given_H)
                snprintf(from, sizeof from, "surface.H = %g times h0 = %g", c->H, h0);
            else
                snprintf(from, sizeof from, "surface.Hstar");
            return rod_error(s, c, k,
                             "top = %g: must be < H* = %g (%s): a rod without a length reaches "
                             "down to the layer's bottom H*",
                             c->top[k], Hstar, from);
        }
    /* built in units of the given ones times powers of two (ct_build_units_of: the given ones
     * for scales within [2^-64, 2^64]), so that e does not depend on the scale */
    c->physical = (ct_layer){.E = c->E, .sigma_y = c->sigma_y, .Hstar = Hstar, .l0 = l0, .h0 = h0};
    ct_build_units_of(&c->physical, c->y != NULL, &c->units);
    if ((st = ct_layer_built(&c->physical, &c->units, &c->layer)))
        return st;
    const ct_build_units *un = &c->units;
    for (size_t k = 0; k < c->n; k++) {
        c->top[k] *= un->length;
        c->area[k] *= un->area;
        if (c->length)
            c->length[k] *= un->length;
        if (c->x)
            c->x[k] *= un->position;
        if (c->y)
            c->y[k] *= un->position;
        char what[32];
        snprintf(what, sizeof what, "rod %zu", k + 1);
        const double len = c->length ? c->length[k] : c->layer.Hstar - c->top[k];
        if ((st = ct_rod_representable(&c->layer, c->top[k], len, c->area[k], what)))
            return rod_error(s, c, k, "%s", strchr(ct_error_message(), ':') + 2);
    }
    ct_scales_of(&s->scales, &c->layer, &c->physical);
    return CT_OK;
}

int ct_surface_set_rods(ct_surface *s, size_t n, const double *top, const double *area,
                        const double *length)
{
    return ct_surface_set_rods_at(s, n, top, area, length, NULL, NULL);
}

int ct_surface_set_rods_at(ct_surface *s, size_t n, const double *top, const double *area,
                           const double *length, const double *x, const double *y)
{
    CT_NEED(s);
    if (s->kind != &ct_kind_rods)
        return ct_error_set(CT_EINVAL, "ct_surface_set_rods: a surface of type %s, not rods",
                            s->kind->name);
    if (!n || !top || !area)
        return ct_error_set(CT_EINVAL, "ct_surface_set_rods: %zu rods (tops, areas NULL?)", n);
    rods_config *c = s->config;
    rods_release_given(c);
    c->given_top = malloc(n * sizeof(double));
    c->given_area = malloc(n * sizeof(double));
    if (y && !x)
        return ct_error_set(CT_EINVAL, "ct_surface_set_rods_at: y without x (a rod on a line is "
                                       "placed by x, on a plane by x and y)");
    c->given_length = length ? malloc(n * sizeof(double)) : NULL;
    c->given_x = x ? malloc(n * sizeof(double)) : NULL;
    c->given_y = y ? malloc(n * sizeof(double)) : NULL;
    if (!c->given_top || !c->given_area || (length && !c->given_length) || (x && !c->given_x) ||
        (y && !c->given_y)) {
        rods_release_given(c);
        return ct_error_set(CT_ENOMEM, "rods: out of memory for %zu rods", n);
    }
    memcpy(c->given_top, top, n * sizeof(double));
    memcpy(c->given_area, area, n * sizeof(double));
    if (length)
        memcpy(c->given_length, length, n * sizeof(double));
    if (x)
        memcpy(c->given_x, x, n * sizeof(double));
    if (y)
        memcpy(c->given_y, y, n * sizeof(double));
    c->given_n = n;
    s->checked = s->prepared = 0;
    return CT_OK;
}

/* The bundle's metadata: each rod's position, its footprint (a point). */
typedef struct {
    size_t n;
    double *x, *y; /* y NULL: rods on a line */
} rods_meta;

static void rods_meta_free(void *meta)
{
    rods_meta *m = meta;
    if (m) {
        free(m->x);
        free(m->y);
        free(m);
    }
}

static rods_meta *rods_meta_new(size_t n, const double *x, const double *y)
{
    rods_meta *m = calloc(1, sizeof *m);
    if (!m || !(m->x = malloc(n * sizeof(double))) || (y && !(m->y = malloc(n * sizeof(double))))) {
        rods_meta_free(m);
        return NULL;
    }
    m->n = n;
    memcpy(m->x, x, n * sizeof(double));
    if (y)
        memcpy(m->y, y, n * sizeof(double));
    return m;
}

static void *rods_meta_clone(const void *meta)
{
    const rods_meta *m = meta;
    return rods_meta_new(m->n, m->x, m->y);
}

static void rods_rod_info(const void *meta, size_t k, ct_rod_info *info)
{
    const rods_meta *m = meta;
    const double x = m->x[k], y = m->y ? m->y[k] : NAN;
    info->x_left = info->x_right = x;
    info->footprint = (ct_footprint){CT_FOOTPRINT_POINT, x, x, y, y};
}

static const ct_rod_meta_kind rods_meta_kind = {"rods",         rods_rod_info, rods_meta_clone,
                                                rods_meta_free, NULL,          NULL};

static int rods_build(const ct_surface *s, const ct_build_request *r, ct_bundle **out,
                      ct_plan_info *info)
{
    (void)r;
    const rods_config *c = s->config;
    ct_bundle *b;
    int st = ct_bundle_create(&b, &c->layer, c->n, "rods");
    if (st)
        return st;
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(b, &top, &length, &area, &eps_p);
    for (size_t k = 0; k < c->n; k++) {
        top[k] = c->top[k];
        length[k] = c->length ? c->length[k] : c->layer.Hstar - c->top[k];
        area[k] = c->area[k];
        eps_p[k] = 0.0;
    }
    if (c->x) {
        rods_meta *m = rods_meta_new(c->n, c->x, c->y);
        if (!m) {
            ct_bundle_free(b);
            return ct_error_set(CT_ENOMEM, "rods: out of memory for %zu positions", c->n);
        }
        ct_bundle_set_surface(b, &rods_meta_kind, m, 0);
    }
    *out = b;
    info->depth = -1;
    info->bound = 0.0;
    info->rods = c->n;
    info->omitted = 0;
    info->u_reach = INFINITY;
    return CT_OK;
}

static void rods_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const rods_config *c = s->config;
    snprintf(buf, len, "rods of %s, %zu rods", c->source, info->rods);
}

static void rods_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const rods_config *c = s->config;
    const ct_layer *L = &c->physical;
    snprintf(buf, len,
             "rods: %s, %zu rods, l0 = %.17g, h0 = %.17g, H* = %.17g, E = %.17g, sigma_y = %.17g",
             c->source, info->rods, L->l0, L->h0, L->Hstar, L->E, L->sigma_y);
}

/* what = profile: every rod in input order, its top after the impacts beside its top. */
static int rods_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    const rods_config *c = s->config;
    const ct_layer *L = ct_bundle_layer(b);
    fputs("rod,top_over_h0,area_over_l0,length_over_h0,residual_top_over_h0", f);
    fputs(!c->x ? "\n" : c->y ? ",x,y\n" : ",x\n", f);
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info info;
        ct_bundle_rod(b, k, &info);
        ct_put_long(f, (long)k + 1);
        const double v[4] = {info.top / L->h0, info.area / L->l0, info.length / L->h0,
                             (info.top + info.plastic_strain * info.length) / L->h0};
        for (int i = 0; i < 4; i++) {
            fputc(',', f);
            ct_put_double(f, v[i]);
        }
        for (int i = 0; c->x && i < (c->y ? 2 : 1); i++) { /* the position, in the rods' unit */
            fputc(',', f);
            ct_put_double(f, (i ? info.footprint.y_lo : info.footprint.x_lo) / c->units.position);
        }
        fputc('\n', f);
    }
    return CT_OK;
}

const ct_kind ct_kind_rods = {
    .name = "rods",
    .summary = "your own rods: a file or a list of tops, areas and optionally lengths and "
               "positions",
    .keys = rods_keys,
    .nkeys = sizeof rods_keys / sizeof rods_keys[0],
    .config_size = sizeof(rods_config),
    .defaults = rods_defaults,
    .check = rods_check,
    .prepare = rods_prepare,
    .build = rods_build,
    .release = rods_release,
    .describe = rods_describe,
    .table_line = rods_table_line,
    .write_profile = rods_write_profile,
    .profile_shows_state = 1,
};
