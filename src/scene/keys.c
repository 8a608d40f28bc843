/* Scene keys as data: one parser for every row of every key table (the CLI's sections, each
 * kind of surface's keys), so that a value is accepted or refused with the same words
 * whichever front-end reads it. Numbers are read in the C locale (a decimal comma would make
 * "1.5" fail and "1,5" pass): uselocale is per thread, and restored. */
#include "internal.h"
#include "number.h"

#include <ctype.h>
#include <errno.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ct_word_index(const char *words, const char *word)
{
    if (!words || !word)
        return -1;
    const size_t n = strlen(word);
    int k = 0;
    for (const char *w = words;; k++) {
        const char *bar = strchr(w, '|');
        const size_t len = bar ? (size_t)(bar - w) : strlen(w);
        if (len == n && !strncmp(w, word, n))
            return k;
        if (!bar)
            return -1;
        w = bar + 1;
    }
}

/* Edit distance of a and b (insertions, deletions, substitutions and swaps of neighbours each
 * count 1: the optimal string alignment distance), or cap when it is at least cap. */
static size_t edit_distance(const char *a, const char *b, size_t cap)
{
    const size_t n = strlen(a), m = strlen(b);
    if (n > 62 || m > 62 || (n > m ? n - m : m - n) >= cap)
        return cap;
    size_t d[64][64];
    for (size_t i = 0; i <= n; i++)
        d[i][0] = i;
    for (size_t j = 0; j <= m; j++)
        d[0][j] = j;
    for (size_t i = 1; i <= n; i++)
        for (size_t j = 1; j <= m; j++) {
            size_t best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            best = d[i - 1][j] + 1 < best ? d[i - 1][j] + 1 : best;
            best = d[i][j - 1] + 1 < best ? d[i][j - 1] + 1 : best;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[n][m] < cap ? d[n][m] : cap;
}

size_t ct_nearest_name(const char *given, const char *const *names, size_t n)
{
    if (!given || !names)
        return n;
    /* a slip: one edit in a short name (its last part, after a dot), two in a longer one */
    const char *dot = strrchr(given, '.');
    const size_t tail = strlen(dot ? dot + 1 : given), allowed = tail <= 3 ? 1 : 2;
    size_t best = n, best_d = allowed + 1;
    for (size_t k = 0; k < n; k++) {
        if (!names[k] || !strcmp(names[k], given))
            continue;
        const size_t d = edit_distance(given, names[k], best_d);
        if (d < best_d) {
            best_d = d;
            best = k;
        }
    }
    return best;
}

/* "a, b or c" from "a|b|c" */
static void words_list(const char *words, char *buf, size_t len)
{
    size_t n = 0, count = 1;
    for (const char *c = words; *c; c++)
        count += *c == '|';
    size_t k = 0;
    buf[0] = '\0';
    for (const char *w = words; w && n < len; k++) {
        const char *bar = strchr(w, '|');
        const int wl = (int)(bar ? (size_t)(bar - w) : strlen(w));
        const char *sep = k == 0 ? "" : k + 1 == count ? " or " : ", ";
        n += (size_t)snprintf(buf + n, len - n, "%s%.*s", sep, wl, w);
        w = bar ? bar + 1 : NULL;
    }
}

/* A number the whole text spells (white space around it allowed), finite and representable;
 * else 0 with *why saying what is wrong (one rule: src/number.c). */
static int read_number(const char *text, double *out, const char **why)
{
    const int st = ct_number_parse(text, strlen(text), out);
    if (st)
        *why = ct_number_why(st);
    return !st;
}

/* The fields of a list into parts (at most max, each copied into its own NUL-ended text in
 * buf): their count; an empty field or more than max fields an error. */
static int list_fields(const char *v, const char *seps, char *buf, size_t size, char **parts,
                       int max, int *np, const char *form)
{
    ct_list l;
    const char *f;
    size_t n, used = 0;
    *np = 0;
    ct_list_start(&l, v, seps);
    while (ct_list_next(&l, &f, &n)) {
        if (!n)
            return ct_error_set(CT_EINVAL, "field %d of %s is empty (%s)", *np + 1, form,
                                ct_list_empty_why());
        if (*np == max)
            return ct_error_set(CT_EINVAL, "expected %s (too many fields)", form);
        if (used + n + 1 > size)
            return ct_error_set(CT_EINVAL, "%s longer than %zu characters", form, size - 1);
        memcpy(buf + used, f, n);
        buf[used + n] = '\0';
        parts[(*np)++] = buf + used;
        used += n + 1;
    }
    return CT_OK;
}

static int read_integer(const char *text, long *out)
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

static int read_count(const char *text, uint64_t *out)
{
    char *end;
    while (isspace((unsigned char)*text))
        text++;
    errno = 0;
    unsigned long long x = strtoull(text, &end, 10);
    while (isspace((unsigned char)*end))
        end++;
    if (!isdigit((unsigned char)*text) || *end || errno == ERANGE)
        return 0;
    *out = (uint64_t)x;
    return 1;
}

static int in_range(const ct_key *row, double v)
{
    const int lo = row->flags & CT_KEY_LO_CLOSED ? v >= row->lo : v > row->lo;
    const int hi = row->flags & CT_KEY_HI_CLOSED ? v <= row->hi : v < row->hi;
    return lo && hi;
}

/* from:to:count[:log] */
static int speeds_range(const char *v, ct_speeds *out)
{
    char buf[256];
    char *parts[4];
    int np, st;
    if ((st = list_fields(v, ":", buf, sizeof buf, parts, 4, &np, "from:to:count[:log]")))
        return st;
    double ends[2];
    long cnt;
    const char *why;
    if (np < 3)
        return ct_error_set(CT_EINVAL, "expected from:to:count[:log]");
    for (int k = 0; k < 2; k++)
        if (!read_number(parts[k], &ends[k], &why))
            return ct_error_set(CT_EINVAL, "expected from:to:count[:log]: %s field %s",
                                k ? "the second" : "the first", why);
    if (!read_integer(parts[2], &cnt))
        return ct_error_set(CT_EINVAL, "expected from:to:count[:log]: count is no integer");
    int logscale = 0;
    if (np == 4) {
        if (strcmp(parts[3], "log"))
            return ct_error_set(CT_EINVAL, "the fourth field may only be 'log'");
        logscale = 1;
    }
    if (cnt < 1 || cnt > CT_MAX_SPEEDS)
        return ct_error_set(CT_EINVAL, "count must satisfy 1 <= count <= 1000000");
    const double from = ends[0], to = ends[1];
    if (!(from > 0.0) || !(to > 0.0))
        return ct_error_set(CT_EINVAL, "from and to must be > 0");
    /* one rule for every range (table.V_star's too): it runs upwards */
    if (to == from && cnt > 1)
        return ct_error_set(CT_EINVAL, "expected from:to:count[:log] with 0 < from < to (or one "
                                       "speed: count 1)");
    if (to < from)
        return ct_error_set(CT_EINVAL,
                            "expected from:to:count[:log] with 0 < from < to: a range runs "
                            "upwards (%s:%s:%s%s; speeds in another order as a list a, b, c)",
                            parts[1], parts[0], parts[2], logscale ? ":log" : "");
    double *vals = malloc((size_t)cnt * sizeof(double));
    if (!vals)
        return ct_error_set(CT_ENOMEM, "out of memory");
    for (long k = 0; k < cnt; k++) {
        double t = cnt == 1 ? 0.0 : (double)k / (double)(cnt - 1);
        vals[k] = logscale ? from * exp(t * (log(to) - log(from))) : from + t * (to - from);
    }
    vals[cnt - 1] = to;
    out->v = vals;
    out->n = (size_t)cnt;
    return CT_OK;
}

/* a, b, c: every value finite and > 0, no field empty */
static int speeds_list(const char *v, ct_speeds *out)
{
    size_t cap = 1, n = 0;
    for (const char *c = v; *c; c++)
        cap += *c == ',';
    if (cap > CT_MAX_SPEEDS)
        return ct_error_set(CT_EINVAL, "at most 1000000 values");
    double *vals = malloc(cap * sizeof(double));
    if (!vals)
        return ct_error_set(CT_ENOMEM, "out of memory");
    ct_list l;
    const char *f;
    size_t len;
    ct_list_start(&l, v, ",");
    while (ct_list_next(&l, &f, &len)) {
        int st = len ? ct_number_parse(f, len, &vals[n]) : CT_OK;
        if (!len || st || !(vals[n] > 0.0)) {
            free(vals);
            if (!len)
                return ct_error_set(CT_EINVAL, "field %zu of the list is empty (%s)", n + 1,
                                    ct_list_empty_why());
            return ct_error_set(CT_EINVAL, "value %zu: %s", n + 1,
                                st ? ct_number_why(st) : "must be > 0");
        }
        n++;
    }
    out->v = vals;
    out->n = n;
    return CT_OK;
}

static int parse_range2(const ct_key *row, const char *v, double *out)
{
    char buf[256];
    char *parts[2];
    int np, st;
    const char *why = "not a finite number";
    (void)row;
    if ((st = list_fields(v, ":", buf, sizeof buf, parts, 2, &np, "from:to")))
        return st;
    double a, b;
    if (np != 2)
        return ct_error_set(CT_EINVAL, "expected from:to (two numbers, 0 < from < to)");
    if (!read_number(parts[0], &a, &why) || !read_number(parts[1], &b, &why))
        return ct_error_set(CT_EINVAL, "%s", why);
    if (a > 0.0 && b > 0.0 && b < a)
        return ct_error_set(CT_EINVAL,
                            "expected from:to with 0 < from < to: a range runs upwards (%s:%s)",
                            parts[1], parts[0]);
    if (!(a > 0.0 && b > a))
        return ct_error_set(CT_EINVAL, "expected from:to with 0 < from < to");
    out[0] = a;
    out[1] = b;
    return CT_OK;
}

/* "x" or "x, y": one or two finite numbers (y NaN when one) */
static int parse_point(const ct_key *row, const char *v, double *out)
{
    double p[2] = {NAN, NAN};
    ct_list l;
    const char *f;
    size_t n, k = 0;
    ct_list_start(&l, v, ", ");
    while (ct_list_next(&l, &f, &n)) {
        if (!n)
            return ct_error_set(CT_EINVAL, "field %zu of the list is empty (%s)", k + 1,
                                ct_list_empty_why());
        if (k == 2)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        const int st = ct_number_parse(f, n, &p[k]);
        if (st)
            return ct_error_set(CT_EINVAL, "field %zu = %.*s: %s", k + 1, (int)(n < 40 ? n : 40), f,
                                ct_number_why(st));
        k++;
    }
    if (k == 0)
        return ct_error_set(CT_EINVAL, "%s", row->range);
    out[0] = p[0];
    out[1] = p[1];
    return CT_OK;
}

/* words separated by commas or blanks, no field empty */
static int parse_words(const ct_key *row, const char *v, unsigned *out)
{
    unsigned bits = 0;
    ct_list l;
    const char *f;
    size_t n, k = 0;
    char word[64];
    ct_list_start(&l, v, ", ");
    while (ct_list_next(&l, &f, &n)) {
        k++;
        if (!n)
            return ct_error_set(CT_EINVAL, "field %zu of the list is empty (%s)", k,
                                ct_list_empty_why());
        snprintf(word, sizeof word, "%.*s", (int)(n < sizeof word ? n : sizeof word - 1), f);
        int w = n < sizeof word ? ct_word_index(row->words, word) : -1;
        if (w < 0)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        bits |= 1u << w;
    }
    *out = bits;
    return CT_OK;
}

/* A word with the micro sign (U+00B5) or the Greek small mu (U+03BC), in UTF-8, spelt with u
 * as the words are ("µm" is "um"): 1 when it held one (and fits). */
static int micro_as_u(const char *v, char *buf, size_t len)
{
    size_t n = 0;
    int found = 0;
    for (const unsigned char *p = (const unsigned char *)v; *p; p++) {
        if (n + 2 > len)
            return 0;
        if ((p[0] == 0xC2 && p[1] == 0xB5) || (p[0] == 0xCE && p[1] == 0xBC)) {
            buf[n++] = 'u';
            p++;
            found = 1;
        } else {
            buf[n++] = (char)*p;
        }
    }
    buf[n] = '\0';
    return found;
}

static int parse_value(const ct_key *row, const char *v, void *at)
{
    double x;
    long l;
    const char *why;
    switch (row->type) {
    case CT_KEY_NUMBER:
        if (!read_number(v, &x, &why))
            return ct_error_set(CT_EINVAL, "%s", why);
        if (!in_range(row, x))
            return ct_error_set(CT_EINVAL, "%s", row->range);
        *(double *)at = x;
        return CT_OK;
    case CT_KEY_INTEGER:
        if (!read_integer(v, &l))
            return ct_error_set(CT_EINVAL, "not an integer (%s)", row->range);
        if ((double)l < row->lo || (double)l > row->hi)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        *(long *)at = l;
        return CT_OK;
    case CT_KEY_DEPTH: {
        int w = ct_word_index(row->words, v);
        if (w >= 0) {
            *(long *)at = -1 - (long)w;
            return CT_OK;
        }
        if (!read_integer(v, &l)) {
            char words[128];
            words_list(row->words, words, sizeof words);
            return ct_error_set(CT_EINVAL, "must be an integer, %s", words);
        }
        if ((double)l < row->lo || (double)l > row->hi)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        *(long *)at = l;
        return CT_OK;
    }
    case CT_KEY_COUNT:
        if (!read_count(v, (uint64_t *)at))
            return ct_error_set(CT_EINVAL, "%s", row->range);
        return CT_OK;
    case CT_KEY_WORD: {
        int w = ct_word_index(row->words, v);
        char spelt[64];
        if (w < 0 && micro_as_u(v, spelt, sizeof spelt))
            w = ct_word_index(row->words, spelt);
        if (w < 0)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        *(int *)at = w;
        return CT_OK;
    }
    case CT_KEY_WORDS:
        return parse_words(row, v, (unsigned *)at);
    case CT_KEY_TEXT: {
        if (!*v)
            return ct_error_set(CT_EINVAL, "%s", row->range);
        char *copy = strdup(v);
        if (!copy)
            return ct_error_set(CT_ENOMEM, "out of memory");
        free(*(char **)at);
        *(char **)at = copy;
        return CT_OK;
    }
    case CT_KEY_SPEEDS: {
        ct_speeds s = {0};
        int st = strchr(v, ':') ? speeds_range(v, &s) : speeds_list(v, &s);
        if (st)
            return st;
        free(((ct_speeds *)at)->v);
        *(ct_speeds *)at = s;
        return CT_OK;
    }
    case CT_KEY_RANGE:
        return parse_range2(row, v, (double *)at);
    case CT_KEY_POINT:
        return parse_point(row, v, (double *)at);
    }
    return ct_error_set(CT_EINVAL, "key %s.%s: unknown type %d", row->section, row->name,
                        (int)row->type);
}

int ct_key_parse(const ct_key *row, const char *text, void *settings)
{
    CT_NEED(row);
    CT_NEED(text);
    CT_NEED(settings);
    locale_t c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    locale_t before = c_locale ? uselocale(c_locale) : (locale_t)0;
    int st = parse_value(row, text, (char *)settings + row->offset);
    if (c_locale) {
        uselocale(before);
        freelocale(c_locale);
    }
    return st;
}

void ct_key_clear(const ct_key *row, void *settings)
{
    void *at = (char *)settings + row->offset;
    if (row->type == CT_KEY_TEXT) {
        free(*(char **)at);
        *(char **)at = NULL;
    } else if (row->type == CT_KEY_SPEEDS) {
        free(((ct_speeds *)at)->v);
        ((ct_speeds *)at)->v = NULL;
        ((ct_speeds *)at)->n = 0;
    }
}

void ct_key_describe(const ct_key *row, char *buf, size_t len)
{
    char words[256];
    if (row->words)
        words_list(row->words, words, sizeof words);
    switch (row->type) {
    case CT_KEY_NUMBER:
        snprintf(buf, len, "number: %s", row->range);
        break;
    case CT_KEY_INTEGER:
        snprintf(buf, len, "integer: %s", row->range);
        break;
    case CT_KEY_DEPTH:
        snprintf(buf, len, "integer or %s: %s", words, row->range);
        break;
    case CT_KEY_COUNT:
        snprintf(buf, len, "integer 0 <= n < 2^64");
        break;
    case CT_KEY_WORD:
        snprintf(buf, len, "%s", words);
        break;
    case CT_KEY_WORDS:
        snprintf(buf, len, "a list of %s", words);
        break;
    case CT_KEY_TEXT: /* a path, or text of its own form (its range says which) */
        if (row->flags & CT_KEY_FILE)
            snprintf(buf, len, "text (a path)");
        else
            snprintf(buf, len, "text: %s", row->range);
        break;
    case CT_KEY_SPEEDS:
        snprintf(buf, len,
                 "numbers > 0: a, b, c (in that order) or from:to:count[:log] (from < to)");
        break;
    case CT_KEY_RANGE:
        snprintf(buf, len, "from:to, 0 < from < to");
        break;
    case CT_KEY_POINT:
        snprintf(buf, len, "x, or x and y");
        break;
    }
}
