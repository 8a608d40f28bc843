/* Reading measured surfaces: text/CSV line profiles, Dektak stylus exports, and ISO 25178-72
 * X3P areal topographies (a zip holding main.xml and a binary height grid; libzip, libxml2).
 * Every file is read once, as a stream: memory holds the points, never the file twice.
 * libzip and libxml2 are loaded (dlopen) the first time an X3P file is read: linked, they and
 * what they pull in (ICU, libstdc++, OpenSSL's libcrypto, liblzma) were loaded and relocated at
 * every start of every program using cantact, about 2 ms, most of a short run's time. */
#define _DEFAULT_SOURCE /* getline, strcasecmp */
#include "internal.h"
#include "number.h"
#include "profile.h"

#include <ctype.h>
#include <errno.h>
#include <locale.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <dlfcn.h>
#include <pthread.h>

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <zip.h>

/* ---- text and Dektak ---- */

typedef struct {
    double *x, *z;
    size_t n, cap;
} points;

static int push(points *p, double x, double z)
{
    if (p->n == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 4096;
        double *a = realloc(p->x, cap * sizeof(double));
        if (a)
            p->x = a;
        double *b = a ? realloc(p->z, cap * sizeof(double)) : NULL;
        if (b)
            p->z = b;
        if (!b)
            return -1;
        p->cap = cap;
    }
    p->x[p->n] = x;
    p->z[p->n] = z;
    p->n++;
    return 0;
}

/* The numbers of a row: separated by commas (when the row has one) or by blanks, tabs and
 * semicolons; empty trailing fields (Dektak's "x,z,,") ignored, as the instruments write them,
 * but an empty field before a number refused (the list rule, src/number.c). Returns the count
 * (at most max stored), or -1 when a field is empty before another or is no usable number
 * (why: which field and why, the rule of every number read). */
static int row_numbers(char *line, double *v, int max, char *why, size_t why_len)
{
    ct_list l;
    const char *f;
    size_t len;
    int n = 0, field = 0, empty = 0; /* empty: the first empty field so far, 0: none */
    why[0] = '\0';
    ct_list_start(&l, line, strchr(line, ',') ? "," : "; ");
    while (ct_list_next(&l, &f, &len)) {
        field++;
        if (!len) {
            if (!empty)
                empty = field;
            continue;
        }
        if (empty) {
            snprintf(why, why_len,
                     "field %d is empty (no field of a row may be empty but its last ones, "
                     "as instruments write them)",
                     empty);
            return -1;
        }
        double x;
        const int st = ct_number_parse(f, len, &x);
        if (st) {
            snprintf(why, why_len, "field %d = %.*s: %s", field, (int)(len < 40 ? len : 40), f,
                     ct_number_why(st));
            return -1;
        }
        if (n < max)
            v[n] = x;
        n++;
    }
    return n;
}

static int is_blank_or_comment(const char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    return !*s || *s == '#' || *s == ';';
}

/* An inline comment: from a '#' on. */
static void strip_comment(char *line)
{
    char *c = strchr(line, '#');
    if (c)
        *c = '\0';
}

/* The length unit a column name carries ("Lateral um", "Raw Micrometer", "z (nm)", "x [mm]"):
 * metres per unit, 0 when it names none. */
static double unit_in_name(const char *s, const char *end)
{
    static const struct {
        const char *word;
        double metres;
    } units[] = {
        {"m", 1.0},           {"meter", 1.0},        {"meters", 1.0},      {"metre", 1.0},
        {"metres", 1.0},      {"mm", 1e-3},          {"millimeter", 1e-3}, {"millimeters", 1e-3},
        {"millimetre", 1e-3}, {"millimetres", 1e-3}, {"um", 1e-6},         {"\xb5m", 1e-6},
        {"\xc2\xb5m", 1e-6},  {"\xce\xbcm", 1e-6},   {"micrometer", 1e-6}, {"micrometers", 1e-6},
        {"micrometre", 1e-6}, {"micrometres", 1e-6}, {"micron", 1e-6},     {"microns", 1e-6},
        {"nm", 1e-9},         {"nanometer", 1e-9},   {"nanometers", 1e-9}, {"nanometre", 1e-9},
        {"nanometres", 1e-9}};
    double found = 0.0;
    while (s < end) {
        /* words: runs of letters and the bytes of a micro sign */
        while (s < end && !(isalpha((unsigned char)*s) || (unsigned char)*s >= 0x80))
            s++;
        const char *w = s;
        while (s < end && (isalpha((unsigned char)*s) || (unsigned char)*s >= 0x80))
            s++;
        const size_t len = (size_t)(s - w);
        for (size_t k = 0; len && k < sizeof units / sizeof units[0]; k++)
            if (strlen(units[k].word) == len && !strncasecmp(w, units[k].word, len)) {
                if (found != 0.0 && found != units[k].metres)
                    return 0.0; /* two different units: none trusted */
                found = units[k].metres;
            }
    }
    return found;
}

/* The units the column names of a header line carry, into xu, zu (only the ones still 0);
 * one column (heights at a given spacing): its name gives zu. */
static void header_units(const char *line, int one_column, double *xu, double *zu)
{
    const char sep = strchr(line, ',')    ? ','
                     : strchr(line, '\t') ? '\t'
                     : strchr(line, ';')  ? ';'
                                          : ' ';
    double u[2] = {0.0, 0.0};
    int n = 0;
    const char *s = line;
    while (n < 2 && *s) {
        while (sep == ' ' && *s == ' ')
            s++;
        const char *e = strchr(s, sep);
        if (!e)
            e = s + strlen(s);
        u[n++] = unit_in_name(s, e);
        s = *e ? e + 1 : e;
    }
    if (one_column) {
        if (*zu == 0.0)
            *zu = u[0];
    } else if (u[0] > 0.0 && u[1] > 0.0) {
        if (*xu == 0.0)
            *xu = u[0];
        if (*zu == 0.0)
            *zu = u[1];
    }
}

/* A text profile while it is read. */
typedef struct {
    const char *path;
    const char *give;        /* how a missing unit is given: "it (m, mm, um or nm)" */
    ct_profile_read_opts *o; /* units found in the column names are filled in */
    int one_column;          /* heights only, at the spacing o->dx */
    int dektak, in_header, headers;
    char *header; /* the last line before the data: the column names */
    long lineno, data_from;
    points pts;
} text_reader;

/* Before the data, a line that is not a row of numbers: a Dektak header block, or one line of
 * column names (kept for their units). */
static int header_line(text_reader *r, const char *line)
{
    if (r->dektak || r->headers++ == 0) {
        free(r->header);
        if (!(r->header = strdup(line)))
            return ct_error_set(CT_ENOMEM, "%s: out of memory at line %ld", r->path, r->lineno);
        return CT_OK;
    }
    return ct_error_set(CT_EINVAL,
                        "%s:%ld: not a row of numbers (and a column header came "
                        "already at line %ld)",
                        r->path, r->lineno, r->data_from);
}

/* The first row of numbers ends the header: the units, given or from the column names. */
static int data_start(text_reader *r)
{
    ct_profile_read_opts *o = r->o;
    const int one_column = r->one_column;
    r->in_header = 0;
    r->data_from = r->lineno;
    if (r->header && (o->x_unit == 0.0 || o->z_unit == 0.0))
        header_units(r->header, one_column, &o->x_unit, &o->z_unit);
    if ((o->x_unit == 0.0 && !one_column) || o->z_unit == 0.0 || (one_column && o->x_unit == 0.0))
        return ct_error_set(CT_EINVAL,
                            "%s: the length unit of %s is not given and its column "
                            "names state none: give %s",
                            r->path,
                            o->z_unit == 0.0 ? (one_column ? "the heights" : "x and z")
                                             : "x (the spacing)",
                            r->give);
    const double step = o->dx * o->x_unit;
    if (one_column && !(isfinite(step) && step > 0.0 && isnormal(step)))
        return ct_error_set(CT_EINVAL,
                            "%s: the spacing %g in %g m units is %g m: not a number doubles hold "
                            "(it underflows or overflows)",
                            r->path, o->dx, o->x_unit, step);
    return CT_OK;
}

/* A data row of n numbers v (n < 0: not numbers, why says which field when it can): its
 * point, in metres, appended. */
static int data_row(text_reader *r, const double *v, int n, const char *why)
{
    const ct_profile_read_opts *o = r->o;
    const int one_column = r->one_column;
    points *pts = &r->pts;
    if (n < 0 && why[0])
        return ct_error_set(CT_EINVAL, "%s:%ld: not a row of numbers: %s", r->path, r->lineno, why);
    if (n != (one_column ? 1 : 2))
        return ct_error_set(CT_EINVAL, "%s:%ld: %s: expected %s", r->path, r->lineno,
                            n < 0 ? "not a row of numbers" : "wrong number of columns",
                            one_column ? "one column, the height (spacing given)"
                                       : "two columns, x and z");
    double x = one_column ? (double)pts->n * o->dx * o->x_unit : v[0] * o->x_unit;
    double z = (one_column ? v[0] : v[1]) * o->z_unit;
    if (!isfinite(x) || !isfinite(z))
        return ct_error_set(CT_EINVAL, "%s:%ld: a value overflows in the units given", r->path,
                            r->lineno);
    if (pts->n && !(x > pts->x[pts->n - 1]))
        return ct_error_set(CT_EINVAL,
                            "%s:%ld: x = %g is not above the previous %g: x must "
                            "increase",
                            r->path, r->lineno, x, pts->x[pts->n - 1]);
    if (push(pts, x, z))
        return ct_error_set(CT_ENOMEM, "%s: out of memory at line %ld", r->path, r->lineno);
    return CT_OK;
}

/* The profile of the points read: their arrays become its own (trimmed to their size), no
 * second copy. */
static int text_profile(text_reader *r, ct_profile **out)
{
    const ct_profile_read_opts *o = r->o;
    points *pts = &r->pts;
    double *x = r->one_column ? NULL : realloc(pts->x, pts->n * sizeof(double)),
           *z = realloc(pts->z, pts->n * sizeof(double));
    if (x)
        pts->x = x;
    if (z)
        pts->z = z;
    int st = r->one_column ? ct_profile_adopt_line(out, pts->n, NULL, o->dx * o->x_unit, pts->z)
                           : ct_profile_adopt_line(out, pts->n, pts->x, 0.0, pts->z);
    if (st)
        return st;
    if (!r->one_column)
        pts->x = NULL;
    pts->z = NULL;
    snprintf((*out)->source, sizeof(*out)->source, "%s", r->dektak ? "dektak" : "text");
    (*out)->x_unit = o->x_unit;
    (*out)->z_unit = o->z_unit;
    return CT_OK;
}

/* A line of a text profile is a few numbers or a header: longer is no profile (/dev/zero). */
#define TEXT_LINE_MAX (1u << 20)

/* The next line of f into *buf (grown as needed, at most TEXT_LINE_MAX bytes), its end (\n,
 * \r\n or a lone \r) dropped: its length, -1 at the end of the file, -2 when longer than
 * TEXT_LINE_MAX, -3 on a NUL byte (UTF-16 text or binary data), -4 out of memory. */
static long text_line(FILE *f, char **buf, size_t *cap)
{
    size_t n = 0;
    int c;
    while ((c = getc_unlocked(f)) != EOF) {
        if (c == '\n')
            break;
        if (c == '\r') {
            int d = getc_unlocked(f);
            if (d != '\n' && d != EOF)
                ungetc(d, f);
            break;
        }
        if (c == '\0')
            return -3;
        if (n + 1 >= TEXT_LINE_MAX)
            return -2;
        if (n + 2 > *cap) {
            size_t grown = *cap ? 2 * *cap : 256;
            char *b = realloc(*buf, grown);
            if (!b)
                return -4;
            *buf = b;
            *cap = grown;
        }
        (*buf)[n++] = (char)c;
    }
    if (c == EOF && n == 0)
        return -1;
    if (!*buf && !(*buf = malloc(*cap = 256)))
        return -4;
    (*buf)[n] = '\0';
    return (long)n;
}

/* 1 when the line starts with a number (after blanks): a data row, never a header, even when
 * a later field is no number ("0 nan" is a bad row, not the column names). */
static int starts_with_number(const char *t)
{
    while (*t == ' ' || *t == '\t')
        t++;
    char *end;
    (void)strtod(t, &end);
    return end != t;
}

static int read_text(const char *path, FILE *f, const ct_profile_read_opts *given, const char *give,
                     ct_profile **out)
{
    ct_profile_read_opts opts = *given;
    text_reader r = {
        .path = path, .give = give, .o = &opts, .one_column = opts.dx > 0.0, .in_header = 1};
    char *line = NULL;
    size_t cap = 0;
    int st = CT_OK;
    long len;
    while ((len = text_line(f, &line, &cap)) != -1) {
        r.lineno++;
        if (len < -1) {
            st = len == -4
                     ? ct_error_set(CT_ENOMEM, "%s: out of memory at line %ld", path, r.lineno)
                 : len == -3
                     ? ct_error_set(CT_EINVAL,
                                    "%s:%ld: a NUL byte: not a text profile (UTF-16 text? save "
                                    "it as UTF-8 or ASCII)",
                                    path, r.lineno)
                     : ct_error_set(CT_EINVAL,
                                    "%s:%ld: a line longer than %u bytes: not a text "
                                    "profile",
                                    path, r.lineno, TEXT_LINE_MAX);
            break;
        }
        if (r.lineno == 1 && !strncmp(line, "\xEF\xBB\xBF", 3)) /* a UTF-8 byte-order mark */
            memmove(line, line + 3, strlen(line + 3) + 1);
        if (is_blank_or_comment(line))
            continue;
        strip_comment(line);
        char *t = line;
        while (isspace((unsigned char)*t))
            t++;
        if (r.in_header && r.lineno == 1 && !strncmp(t, "Scan Parameters", 15))
            r.dektak = 1; /* a Dektak export: its header block runs to "Scan Data" */
        double v[3];
        char why[160];
        int n = row_numbers(line, v, 3, why, sizeof why);
        if (r.in_header && n < 0 && !starts_with_number(t)) {
            if ((st = header_line(&r, line)))
                break;
            continue;
        }
        if ((r.in_header && (st = data_start(&r))) || (st = data_row(&r, v, n, why)))
            break;
    }
    free(line);
    free(r.header);
    if (!st && ferror(f))
        st = ct_error_set(CT_EIO, "%s: read error: %s", path, strerror(errno));
    if (!st && r.pts.n < 3)
        st = ct_error_set(CT_EINVAL, "%s: %zu points: a profile needs at least 3", path, r.pts.n);
    if (!st)
        st = text_profile(&r, out);
    free(r.pts.x);
    free(r.pts.z);
    return st;
}

/* ---- X3P (ISO 25178-72) ---- */

/* The functions of libzip and libxml2 used below, resolved once per process (pthread_once: the
 * library stays reentrant). The sonames are the ones linked against at build time (meson reads
 * them from the libraries), so the headers compiled against and the code loaded agree. */
static struct {
    zip_t *(*zip_open)(const char *, int, int *);
    void (*zip_error_init_with_code)(zip_error_t *, int);
    const char *(*zip_error_strerror)(zip_error_t *);
    void (*zip_error_fini)(zip_error_t *);
    void (*zip_stat_init)(zip_stat_t *);
    int (*zip_stat)(zip_t *, const char *, zip_flags_t, zip_stat_t *);
    zip_file_t *(*zip_fopen)(zip_t *, const char *, zip_flags_t);
    const char *(*zip_strerror)(zip_t *);
    zip_int64_t (*zip_fread)(zip_file_t *, void *, zip_uint64_t);
    int (*zip_fclose)(zip_file_t *);
    int (*zip_close)(zip_t *);
    void (*xmlInitParser)(void);
    xmlDocPtr (*xmlReadMemory)(const char *, int, const char *, const char *, int);
    xmlNodePtr (*xmlDocGetRootElement)(const xmlDoc *);
    xmlChar *(*xmlNodeGetContent)(const xmlNode *);
    xmlFreeFunc *xmlFree; /* a variable of libxml2: the deallocator in use */
    void (*xmlFreeDoc)(xmlDocPtr);
    char why[512]; /* empty when loaded */
} X;
static pthread_once_t x3p_once = PTHREAD_ONCE_INIT;

static void *sym(void *lib, const char *name)
{
    void *p = lib ? dlsym(lib, name) : NULL;
    if (!p && lib && !X.why[0])
        snprintf(X.why, sizeof X.why, "%s has no %s",
                 name[0] == 'z' ? CT_ZIP_SONAME : CT_XML_SONAME, name);
    return p;
}

static void x3p_load(void)
{
    void *z = dlopen(CT_ZIP_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (!z)
        snprintf(X.why, sizeof X.why, "%s", dlerror());
    void *x = z ? dlopen(CT_XML_SONAME, RTLD_NOW | RTLD_LOCAL) : NULL;
    if (z && !x)
        snprintf(X.why, sizeof X.why, "%s", dlerror());
        /* object pointers from dlsym, converted as POSIX requires of the implementation */
#define GET(lib, f) *(void **)&X.f = sym(lib, #f)
    GET(z, zip_open);
    GET(z, zip_error_init_with_code);
    GET(z, zip_error_strerror);
    GET(z, zip_error_fini);
    GET(z, zip_stat_init);
    GET(z, zip_stat);
    GET(z, zip_fopen);
    GET(z, zip_strerror);
    GET(z, zip_fread);
    GET(z, zip_fclose);
    GET(z, zip_close);
    GET(x, xmlInitParser);
    GET(x, xmlReadMemory);
    GET(x, xmlDocGetRootElement);
    GET(x, xmlNodeGetContent);
    GET(x, xmlFree);
    GET(x, xmlFreeDoc);
#undef GET
    if (!X.why[0])
        X.xmlInitParser(); /* once, here: libxml2's own initialisation is not thread-safe */
}

/* CT_OK with X filled, or the reason the X3P libraries cannot be loaded. */
static int x3p_libraries(const char *path)
{
    pthread_once(&x3p_once, x3p_load);
    if (X.why[0])
        return ct_error_set(CT_EIO, "%s: reading X3P needs libzip and libxml2: %s", path, X.why);
    return CT_OK;
}

/* The first element named `name` (local name) below node, depth first. */
static xmlNode *find(xmlNode *node, const char *name)
{
    for (xmlNode *c = node ? node->children : NULL; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE)
            continue;
        if (!strcmp((const char *)c->name, name))
            return c;
        xmlNode *d = find(c, name);
        if (d)
            return d;
    }
    return NULL;
}

/* The text of the element at a path of local names below node, or NULL. */
static const char *text_at(xmlNode *node, const char *const *path, int n, char *buf, size_t size)
{
    for (int k = 0; k < n && node; k++)
        node = find(node, path[k]);
    if (!node)
        return NULL;
    xmlChar *t = X.xmlNodeGetContent(node);
    if (!t)
        return NULL;
    const char *s = (const char *)t;
    while (isspace((unsigned char)*s))
        s++;
    snprintf(buf, size, "%s", s);
    for (size_t k = strlen(buf); k > 0 && isspace((unsigned char)buf[k - 1]); k--)
        buf[k - 1] = '\0';
    (*X.xmlFree)(t);
    return buf;
}

static int x3p_number(const char *path, xmlNode *root, const char *a, const char *b, const char *c,
                      double *out, int required)
{
    const char *p3[] = {a, b, c};
    char buf[128];
    const char *t = text_at(root, p3, c ? 3 : 2, buf, sizeof buf);
    if (!t) {
        if (!required)
            return CT_OK;
        return ct_error_set(CT_EINVAL, "%s: main.xml: %s/%s%s%s missing", path, a, b, c ? "/" : "",
                            c ? c : "");
    }
    char *end;
    double v = strtod(t, &end);
    if (end == t || *end || !isfinite(v))
        return ct_error_set(CT_EINVAL, "%s: main.xml: %s/%s%s%s = '%s': not a number", path, a, b,
                            c ? "/" : "", c ? c : "", t);
    *out = v;
    return CT_OK;
}

/* Reads a whole zip entry into memory (*size bytes); CT_EINVAL naming it when absent, when
 * it holds more than max bytes, when it is compressed otherwise than stored or deflated, or
 * when its stated size cannot come from its compressed size (deflate expands at most 1032:1;
 * a stored entry not at all): a forged size is refused before anything is allocated for it,
 * and nothing expands beyond what its compressed bytes allow. */
static int zip_entry(const char *path, zip_t *z, const char *name, zip_uint64_t max, char **data,
                     zip_uint64_t *size)
{
    zip_stat_t zs;
    X.zip_stat_init(&zs);
    if (X.zip_stat(z, name, 0, &zs) != 0 || !(zs.valid & ZIP_STAT_SIZE))
        return ct_error_set(CT_EINVAL, "%s: X3P entry %s missing", path, name);
    if (zs.size > max)
        return ct_error_set(CT_EINVAL,
                            "%s: X3P entry %s holds %llu bytes: more than the %llu it may "
                            "hold",
                            path, name, (unsigned long long)zs.size, (unsigned long long)max);
    /* only what an X3P file is written with, whose expansion is bounded: stored or deflated
     * (bzip2, xz, zstd... expand by factors no stated size can be checked against) */
    if (!(zs.valid & ZIP_STAT_COMP_METHOD) ||
        (zs.comp_method != ZIP_CM_STORE && zs.comp_method != ZIP_CM_DEFLATE))
        return ct_error_set(CT_EINVAL,
                            "%s: X3P entry %s is compressed with zip method %d: X3P files are "
                            "stored or deflated (method 0 or 8)",
                            path, name,
                            (zs.valid & ZIP_STAT_COMP_METHOD) ? (int)zs.comp_method : -1);
    if (!(zs.valid & ZIP_STAT_COMP_SIZE) ||
        (zs.comp_method == ZIP_CM_STORE && zs.size != zs.comp_size) ||
        (zs.comp_method == ZIP_CM_DEFLATE && zs.size / 1032 > zs.comp_size + 1))
        return ct_error_set(CT_EINVAL,
                            "%s: X3P entry %s states %llu bytes from %llu compressed: a corrupt "
                            "zip",
                            path, name, (unsigned long long)zs.size,
                            (unsigned long long)zs.comp_size);
    zip_file_t *f = X.zip_fopen(z, name, 0);
    if (!f)
        return ct_error_set(CT_EINVAL, "%s: X3P entry %s: %s", path, name, X.zip_strerror(z));
    char *buf = malloc(zs.size + 1);
    if (!buf) {
        X.zip_fclose(f);
        return ct_error_set(CT_ENOMEM, "%s: X3P entry %s of %llu bytes: out of memory", path, name,
                            (unsigned long long)zs.size);
    }
    zip_int64_t got = X.zip_fread(f, buf, zs.size);
    X.zip_fclose(f);
    if (got < 0 || (zip_uint64_t)got != zs.size) {
        free(buf);
        return ct_error_set(CT_EIO, "%s: X3P entry %s: short read", path, name);
    }
    buf[zs.size] = '\0';
    *data = buf;
    *size = zs.size;
    return CT_OK;
}

static double le_value(const unsigned char *p, char type)
{
    union {
        unsigned char b[8];
        double d;
        float f;
        int16_t i16;
        int32_t i32;
    } u;
    int n = type == 'D' ? 8 : type == 'F' || type == 'L' ? 4 : 2;
    for (int k = 0; k < n; k++) /* X3P is little-endian */
        u.b[k] = p[k];
    return type == 'D'   ? u.d
           : type == 'F' ? (double)u.f
           : type == 'L' ? (double)u.i32
                         : (double)u.i16;
}

/* What main.xml says of the grid. */
typedef struct {
    size_t nx, ny;
    double dx, dy, zinc, zoff;
    char type[16]; /* D, F, I or L */
    int width;     /* bytes per point */
    int has_mask;
    char link[256], mask[256]; /* the entries of the points and of the valid points' mask */
} x3p_grid;

/* The grid's description from main.xml (root). */
static int x3p_header(const char *path, xmlNode *root, x3p_grid *g)
{
    int st;
    double sx = 0, sy = 0, sz = 0, dx = 0, dy = 0, zinc = 1.0, zoff = 0.0;
    if ((st = x3p_number(path, root, "Record3", "MatrixDimension", "SizeX", &sx, 1)) ||
        (st = x3p_number(path, root, "Record3", "MatrixDimension", "SizeY", &sy, 1)) ||
        (st = x3p_number(path, root, "Record3", "MatrixDimension", "SizeZ", &sz, 1)) ||
        (st = x3p_number(path, root, "CX", "Increment", NULL, &dx, 1)) ||
        (st = x3p_number(path, root, "CY", "Increment", NULL, &dy, 0)) ||
        (st = x3p_number(path, root, "CZ", "Increment", NULL, &zinc, 0)) ||
        (st = x3p_number(path, root, "CZ", "Offset", NULL, &zoff, 0)))
        return st;
    if (!(sx >= 1 && sy >= 1 && sz == 1 && sx == floor(sx) && sy == floor(sy) && sx * sy <= 1e10))
        return ct_error_set(
            CT_EINVAL, "%s: main.xml: MatrixDimension %g x %g x %g: expected a grid, SizeZ = 1",
            path, sx, sy, sz);
    if (!(dx > 0.0) || (sy > 1 && !(dy > 0.0)))
        return ct_error_set(CT_EINVAL, "%s: main.xml: increments CX %g, CY %g: must be > 0", path,
                            dx, dy);
    /* a sample's share (dx, or dx dy on a grid) and the whole must be normal doubles: an
     * increment of 1e-320 m leaves no digits (the surface's l0 would be 0) */
    const double pixel = sy > 1 ? dx * dy : dx, whole = pixel * sx * sy;
    if (!(pixel >= DBL_MIN) || !isfinite(whole))
        return ct_error_set(CT_EINVAL,
                            "%s: main.xml: increments CX %g, CY %g give a sample of %g m%s and %g "
                            "in all: not normal doubles (between %g and %g)",
                            path, dx, dy, pixel, sy > 1 ? "^2" : "", whole, DBL_MIN, DBL_MAX);
    const char *tp[] = {"CZ", "DataType"}, *lp[] = {"DataLink", "PointDataLink"},
               *mp[] = {"DataLink", "ValidPointsLink"};
    const char *type = text_at(root, tp, 2, g->type, sizeof g->type);
    const char *link = text_at(root, lp, 2, g->link, sizeof g->link);
    g->has_mask = text_at(root, mp, 2, g->mask, sizeof g->mask) != NULL;
    if (!type || strlen(type) != 1 || !strchr("DFIL", type[0]))
        return ct_error_set(CT_EINVAL, "%s: main.xml: CZ/DataType = %s: expected D, F, I or L",
                            path, type ? type : "(missing)");
    if (!link)
        return ct_error_set(CT_EINVAL,
                            "%s: main.xml: DataLink/PointDataLink missing (only binary "
                            "point data is read)",
                            path);
    /* its heights (8 bytes a point) and, to be of use, its rods (32): refused up front, with
     * the figure, rather than read for a minute into memory that cannot hold the rods */
    const double need = sx * sy * (8.0 + CT_BYTES_PER_ROD), avail = (double)ct_available_memory();
    if (need > 0.9 * avail)
        return ct_error_set(CT_ENOMEM,
                            "%s: an X3P grid of %g x %g points needs at least %.3g GiB (its "
                            "heights and rods, 40 bytes a point), more than the %.3g GiB of "
                            "memory available",
                            path, sx, sy, need / 1073741824.0, avail / 1073741824.0);
    g->nx = (size_t)sx;
    g->ny = (size_t)sy;
    g->dx = dx;
    g->dy = dy;
    g->zinc = zinc;
    g->zoff = zoff;
    g->width = type[0] == 'D' ? 8 : type[0] == 'F' || type[0] == 'L' ? 4 : 2;
    return CT_OK;
}

/* The grid's heights (malloc'ed into *zz): its binary points, integers scaled by the z
 * axis, the points the mask marks invalid NaN. */
static int x3p_heights(const char *path, zip_t *z, const x3p_grid *g, double **zz)
{
    char *bin = NULL, *mask = NULL;
    zip_uint64_t bin_size = 0, mask_size = 0;
    const size_t npts = g->nx * g->ny;
    const int width = g->width;
    int st;
    if ((st = zip_entry(path, z, g->link, (zip_uint64_t)npts * (zip_uint64_t)width, &bin,
                        &bin_size)))
        goto done;
    if (bin_size != (zip_uint64_t)npts * (zip_uint64_t)width) {
        st = ct_error_set(
            CT_EINVAL,
            "%s: X3P entry %s holds %llu bytes; the header's %zu x %zu grid of type %s "
            "needs %llu",
            path, g->link, (unsigned long long)bin_size, g->nx, g->ny, g->type,
            (unsigned long long)npts * (unsigned long long)width);
        goto done;
    }
    if (g->has_mask &&
        (st = zip_entry(path, z, g->mask, (zip_uint64_t)(npts + 7) / 8 + 1024, &mask, &mask_size)))
        goto done;
    if (mask && mask_size < (npts + 7) / 8) {
        st = ct_error_set(CT_EINVAL,
                          "%s: X3P entry %s holds %llu bytes; the mask of %zu points "
                          "needs %zu",
                          path, g->mask, (unsigned long long)mask_size, npts, (npts + 7) / 8);
        goto done;
    }
    if (!(*zz = malloc(npts * sizeof(double)))) {
        st = ct_error_set(CT_ENOMEM, "%s: grid of %zu points: out of memory", path, npts);
        goto done;
    }
    for (size_t k = 0; k < npts; k++) {
        double v = le_value((const unsigned char *)bin + k * (size_t)width, g->type[0]);
        if (g->type[0] == 'I' || g->type[0] == 'L')
            v = g->zinc * v; /* integer heights carry the axis' scale; its offset, a constant
                              * that changes no rod (tops are depths below the highest point)
                              * and no statistic, is left out: added, it could only lose digits
                              * (an Offset of 1.7e308 swallowed them all) */
        if (mask && !((unsigned char)mask[k / 8] >> (k % 8) & 1u))
            v = NAN;         /* the mask's bit 0: an invalid point */
        else if (isinf(v)) { /* NaN marks a missing point; an infinity is no height */
            st = ct_error_set(CT_EINVAL,
                              "%s: point %zu (x %zu, y %zu): height %g%s: not a number doubles "
                              "hold (NaN or the mask marks a missing point)",
                              path, k, k % g->nx, k / g->nx, v,
                              g->type[0] == 'I' || g->type[0] == 'L' ? " (the CZ increment times "
                                                                       "its integer)"
                                                                     : "");
            free(*zz);
            *zz = NULL;
            goto done;
        }
        (*zz)[k] = v;
    }
done:
    free(bin);
    free(mask);
    return st;
}

/* The profile of the heights zz, which it adopts on success: a line (one row) keeps its valid
 * points at their x, a grid all of them. */
static int x3p_profile(const char *path, const x3p_grid *g, double *zz, ct_profile **out)
{
    int st;
    x3p_grid line = *g;
    if (g->nx == 1 && g->ny > 1) { /* one column: a line profile along y, at y's spacing */
        line.nx = g->ny;
        line.ny = 1;
        line.dx = g->dy;
        g = &line;
    }
    const size_t nx = g->nx;
    if (g->ny == 1) {
        size_t m = 0;
        for (size_t k = 0; k < nx; k++)
            m += !isnan(zz[k]);
        double *xs = m < nx ? malloc((m ? m : 1) * sizeof(double)) : NULL;
        if (m < nx && !xs)
            return ct_error_set(CT_ENOMEM, "%s: profile of %zu points: out of memory", path, nx);
        for (size_t k = 0, j = 0; xs && k < nx; k++)
            if (!isnan(zz[k])) {
                xs[j] = (double)k * g->dx;
                zz[j++] = zz[k];
            }
        st = ct_profile_adopt_line(out, m, xs, g->dx, zz);
        if (st)
            free(xs);
        else
            (*out)->invalid = nx - m;
    } else
        st = ct_profile_adopt_grid(out, nx, g->ny, g->dx, g->dy, zz);
    if (!st)
        snprintf((*out)->source, sizeof(*out)->source, "x3p");
    return st;
}

static int read_x3p(const char *path, ct_profile **out)
{
    int err = 0, st = x3p_libraries(path);
    if (st)
        return st;
    zip_t *z = X.zip_open(path, ZIP_RDONLY, &err);
    if (!z) {
        zip_error_t ze;
        X.zip_error_init_with_code(&ze, err);
        st = ct_error_set(CT_EINVAL, "%s: not a readable X3P (zip) file: %s", path,
                          X.zip_error_strerror(&ze));
        X.zip_error_fini(&ze);
        return st;
    }
    char *xml = NULL;
    zip_uint64_t xml_size;
    xmlDoc *doc = NULL;
    double *zz = NULL;
    x3p_grid g;
    if ((st = zip_entry(path, z, "main.xml", 64 << 20, &xml, &xml_size)))
        goto done;
    doc = X.xmlReadMemory(xml, (int)xml_size, "main.xml", NULL,
                          XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    if (!doc) {
        st = ct_error_set(CT_EINVAL, "%s: X3P entry main.xml is not well-formed XML", path);
        goto done;
    }
    if ((st = x3p_header(path, X.xmlDocGetRootElement(doc), &g)) ||
        (st = x3p_heights(path, z, &g, &zz)))
        goto done;
    if (!(st = x3p_profile(path, &g, zz, out)))
        zz = NULL; /* the profile's now */
done:
    free(zz);
    free(xml);
    if (doc)
        X.xmlFreeDoc(doc);
    X.zip_close(z);
    return st;
}

int ct_profile_read(const char *path, const ct_profile_read_opts *opts, ct_profile **out)
{
    return ct_profile_read_giving(path, opts, "it (m, mm, um or nm)", out);
}

int ct_profile_read_giving(const char *path, const ct_profile_read_opts *opts, const char *give,
                           ct_profile **out)
{
    CT_NEED(path);
    CT_NEED(out);
    *out = NULL;
    ct_profile_read_opts o = {0.0, 0.0, 0.0};
    if (opts)
        o = *opts;
    if (!(isfinite(o.x_unit) && o.x_unit >= 0.0 && isfinite(o.z_unit) && o.z_unit >= 0.0) ||
        !(isfinite(o.dx) && o.dx >= 0.0))
        return ct_error_set(CT_EINVAL,
                            "profile: units %g, %g and spacing %g must be finite and >= 0 (a "
                            "unit 0: the file's)",
                            o.x_unit, o.z_unit, o.dx);
    FILE *f = fopen(path, "rb");
    if (!f)
        return ct_error_set(CT_EIO, "%s: cannot open: %s", path, strerror(errno));
    unsigned char magic[4] = {0};
    size_t got = fread(magic, 1, 4, f);
    if (got == 4 && !memcmp(magic, "PK\x03\x04", 4)) {
        fclose(f);
        if (o.x_unit != 0.0 || o.z_unit != 0.0 || o.dx != 0.0)
            return ct_error_set(CT_EINVAL,
                                "%s: an X3P file states its lengths (in metres) and its "
                                "spacing: give no unit or spacing for it",
                                path);
        return read_x3p(path, out); /* X3P: lengths in metres (ISO 25178-72) */
    }
    if (fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        return ct_error_set(CT_EIO,
                            "%s: cannot read it from its start again (a pipe?): give a "
                            "file",
                            path);
    }
    /* numbers in the C locale whatever the caller's (per thread) */
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    locale_t before = c ? uselocale(c) : (locale_t)0;
    int st = read_text(path, f, &o, give, out);
    if (c) {
        uselocale(before);
        freelocale(c);
    }
    fclose(f);
    return st;
}
