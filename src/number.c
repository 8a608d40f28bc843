/* Doubles as text, exactly as printf("%.17g") (and "%.3g") writes them, without printf's
 * multi-precision path for the range results live in. A result table of 2000 rows is 18000
 * such numbers.
 *
 * x = m 2^e exactly (m < 2^53). For 1e-22 <= |x| < 10^P the P significant digits are
 * N = round(x 10^(P - 1 - E)), E the decimal exponent, and m 10^k (k = P - 1 - E <= 38, so
 * 10^k < 2^127) fits in 192 bits: N is the integer part of m 10^k 2^e and the remainder
 * decides the rounding, to nearest with ties to even, as glibc does. Zero is written
 * directly; everything else (subnormals, huge or tiny values, NaN, infinities) goes to
 * snprintf. */
#define _GNU_SOURCE /* fwrite_unlocked */
#include "number.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 u128;

/* 10^k for k <= 38, exact in 128 bits */
static u128 pow10_128(int k)
{
    static const uint64_t p19[20] = {1u,
                                     10u,
                                     100u,
                                     1000u,
                                     10000u,
                                     100000u,
                                     1000000u,
                                     10000000u,
                                     100000000u,
                                     1000000000u,
                                     10000000000u,
                                     100000000000u,
                                     1000000000000u,
                                     10000000000000u,
                                     100000000000000u,
                                     1000000000000000u,
                                     10000000000000000u,
                                     100000000000000000u,
                                     1000000000000000000u,
                                     10000000000000000000u};
    return k <= 19 ? (u128)p19[k] : (u128)p19[19] * p19[k - 19];
}

/* x 10^k for x = m 2^e (0 <= k <= 38, e < 0): its integer part *trunc and that rounded to
 * nearest, ties to even; 0 if it does not fit the exact path. */
static uint64_t scaled(uint64_t m, int e, int k, uint64_t *trunc)
{
    const u128 t = pow10_128(k);
    /* p = m t < 2^53 2^127, as hi 2^64 + lo (hi < 2^116) */
    const u128 a = (u128)m * (uint64_t)t, b = (u128)m * (uint64_t)(t >> 64);
    const uint64_t lo = (uint64_t)a;
    const u128 hi = b + (a >> 64);
    const int s = -e;
    if (s <= 0 || s >= 127)
        return 0;
    u128 n, rem;
    if (s >= 64) {
        n = hi >> (s - 64);
        rem = ((hi & (((u128)1 << (s - 64)) - 1)) << 64) | lo;
    } else {
        if (hi >> 64) /* p >= 2^128 and the shift leaves more than 64 bits */
            return 0;
        const u128 p = (hi << 64) | lo;
        n = p >> s;
        rem = p & (((u128)1 << s) - 1);
    }
    if (n >> 63)
        return 0;
    const u128 half = (u128)1 << (s - 1);
    *trunc = (uint64_t)n;
    if (rem > half || (rem == half && (n & 1u)))
        n++;
    return (uint64_t)n;
}

static const char pairs[201] = "00010203040506070809101112131415161718192021222324252627282930"
                               "31323334353637383940414243444546474849505152535455565758596061"
                               "62636465666768697071727374757677787980818283848586878889909192"
                               "93949596979899";

/* the 8 decimal digits of y < 10^8: 32-bit quotients by constants, independent halves */
static void digits8(char *d, uint32_t y)
{
    const uint32_t a = y / 10000u, b = y % 10000u;
    memcpy(d, pairs + 2 * (a / 100u), 2);
    memcpy(d + 2, pairs + 2 * (a % 100u), 2);
    memcpy(d + 4, pairs + 2 * (b / 100u), 2);
    memcpy(d + 6, pairs + 2 * (b % 100u), 2);
}

/* the P decimal digits of N < 10^P (P = 3 or 17) */
static void digits(char *d, uint64_t N, int P)
{
    if (P == 17) { /* one 64-bit quotient, then 32-bit work: 1 + 8 + 8 digits */
        const uint64_t hi = N / 100000000u;
        const uint32_t top = (uint32_t)hi;
        d[0] = (char)('0' + top / 100000000u);
        digits8(d + 1, top % 100000000u);
        digits8(d + 9, (uint32_t)(N - hi * 100000000u));
        return;
    }
    const uint32_t v = (uint32_t)N; /* P = 3 */
    d[0] = (char)('0' + v / 100u);
    memcpy(d + 1, pairs + 2 * (v % 100u), 2);
}

/* The decimal exponent E of ax (be: its biased binary exponent): floor((be - 1023) log10 2) by
 * integers (78913 / 2^18 is log10 2 closely enough for |be - 1023| <= 1100), one more when ax
 * reaches the next power of ten. The powers below 1 are rounded, so next to one E may still be
 * off by one: exact_digits corrects it on the exact digits. */
static int decimal_exponent(int be, double ax)
{
    static const double p10[] = {1e-22, 1e-21, 1e-20, 1e-19, 1e-18, 1e-17, 1e-16, 1e-15,
                                 1e-14, 1e-13, 1e-12, 1e-11, 1e-10, 1e-9,  1e-8,  1e-7,
                                 1e-6,  1e-5,  1e-4,  1e-3,  1e-2,  1e-1,  1e0,   1e1,
                                 1e2,   1e3,   1e4,   1e5,   1e6,   1e7,   1e8,   1e9,
                                 1e10,  1e11,  1e12,  1e13,  1e14,  1e15,  1e16,  1e17};
    const int t = (be - 1023) * 78913;
    int E = t >= 0 ? t >> 18 : -((-t + (1 << 18) - 1) >> 18);
    if (E + 1 >= -22 && E + 1 <= 17 && ax >= p10[E + 1 + 22])
        E++;
    return E;
}

/* The P significant digits N of m 2^e (10^(P-1) <= N < 10^P), rounded to nearest with ties to
 * even, and its decimal exponent *exponent (an estimate, corrected here); 0 when the exact
 * path does not find them. */
static uint64_t exact_digits(uint64_t m, int e, int P, int *exponent)
{
    const uint64_t lo = P == 3 ? 100u : UINT64_C(10000000000000000), hi = lo * 10u;
    int E = *exponent;
    uint64_t N = 0, T = 0;
    for (int tries = 0; tries < 4; tries++) {
        const int k = P - 1 - E;
        if (k < 0 || k > 38 || !(N = scaled(m, e, k, &T)))
            break;
        if (T >= hi) { /* the exponent is decided before rounding */
            E++;
        } else if (T < lo) {
            E--;
        } else {
            if (N == hi) { /* rounding carried into a digit more: 1.00...e(E+1) */
                N = lo;
                E++;
            }
            break;
        }
        N = 0;
    }
    *exponent = E;
    return N >= lo && N < hi ? N : 0;
}

/* The text %g writes for the P significant digits d and the decimal exponent E, negative or
 * not, into buf; returns its length. The digits are copied 16 or 17 at a time, fixed sizes,
 * where buf's CT_NUMBER_MAX bytes hold them (the text ends at o, what lies past it is never
 * read). */
static size_t write_g(char *buf, int negative, const char d[17], int E, int P)
{
    int nd = P; /* significant digits left after dropping trailing zeros */
    while (nd > 1 && d[nd - 1] == '0')
        nd--;
    char *o = buf;
    if (negative)
        *o++ = '-';
    if (E < -4 || E >= P) { /* %g's exponent style: -22 <= E <= 17, two digits */
        *o++ = d[0];
        if (nd > 1) {
            *o++ = '.';
            memcpy(o, d + 1, 16); /* up to buf + 19 */
            o += nd - 1;
        }
        const int ae = E < 0 ? -E : E;
        *o++ = 'e';
        *o++ = E < 0 ? '-' : '+';
        *o++ = (char)('0' + ae / 10);
        *o++ = (char)('0' + ae % 10);
    } else if (E >= 0) {
        memcpy(o, d, (size_t)E + 1);
        o += E + 1;
        if (nd > E + 1) {
            *o++ = '.';
            memcpy(o, d + E + 1, (size_t)(nd - E - 1));
            o += nd - E - 1;
        }
    } else {
        memcpy(o, "0.000", 5); /* -4 <= E <= -1: "0." and -E - 1 zeros */
        o += 2 + (-E - 1);
        memcpy(o, d, 17); /* up to buf + 23 */
        o += nd;
    }
    *o = '\0';
    return (size_t)(o - buf);
}

/* x as "%.<P>g" writes it (P = 3 or 17) when 1e-22 <= |x| < 10^P; 0 when it is not written
 * here. */
static size_t fast_g(char *buf, double x, int P)
{
    const double ax = fabs(x);
    if (!(ax >= 1e-22 && ax < (P == 3 ? 1e3 : 1e17)))
        return 0;
    uint64_t bits;
    memcpy(&bits, &ax, sizeof bits);
    const int be = (int)(bits >> 52);
    const uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
    int E = decimal_exponent(be, ax);
    const uint64_t N = exact_digits(m, be - 1075, P, &E);
    if (!N)
        return 0;
    char d[17];
    digits(d, N, P);
    return write_g(buf, x < 0, d, E, P);
}
#endif

/* zero and its sign as %g writes them */
static size_t zero(char *buf, double x)
{
    char *o = buf;
    if (signbit(x))
        *o++ = '-';
    *o++ = '0';
    *o = '\0';
    return (size_t)(o - buf);
}

/* x as "%.<P>g" writes it: zero and the exact path here, the rest by snprintf */
static size_t format_g(char *buf, double x, int P)
{
    if (x == 0.0)
        return zero(buf, x);
#if defined(__SIZEOF_INT128__)
    size_t n = fast_g(buf, x, P);
    if (n)
        return n;
#endif
    return (size_t)snprintf(buf, CT_NUMBER_MAX, "%.*g", P, x);
}

size_t ct_format_double(char *buf, double x)
{
    return format_g(buf, x, 17);
}

size_t ct_format_g3(char *buf, double x)
{
    return format_g(buf, x, 3);
}

/* the CLI writes from one thread: no stream lock per number */
static void put(FILE *f, const char *s, size_t n)
{
#if defined(__GLIBC__)
    fwrite_unlocked(s, 1, n, f);
#else
    fwrite(s, 1, n, f);
#endif
}

void ct_put_double(FILE *f, double x)
{
    char buf[CT_NUMBER_MAX];
    put(f, buf, ct_format_double(buf, x));
}

void ct_put_g3(FILE *f, double x)
{
    char buf[CT_NUMBER_MAX];
    put(f, buf, ct_format_g3(buf, x));
}

/* v as "%ld" writes it, at the end of d[24]: returns where it starts. */
static const char *format_long(char d[24], long v)
{
    char *o = d + 24;
    unsigned long a = v < 0 ? 0ul - (unsigned long)v : (unsigned long)v;
    do
        *--o = (char)('0' + a % 10);
    while (a /= 10);
    if (v < 0)
        *--o = '-';
    return o;
}

void ct_put_long(FILE *f, long v)
{
    char d[24];
    const char *o = format_long(d, v);
    put(f, o, (size_t)(d + sizeof d - o));
}

void ct_line_flush(ct_line *l)
{
    put(l->f, l->b, l->n);
    l->n = 0;
}

void ct_line_long(ct_line *l, long v)
{
    char d[24];
    const char *o = format_long(d, v);
    const size_t n = (size_t)(d + sizeof d - o);
    memcpy(ct_line_room(l, n), o, n);
    l->n += n;
}

void ct_line_str(ct_line *l, const char *s)
{
    for (size_t n = strlen(s); n > 0;) {
        const size_t k = n < sizeof l->b ? n : sizeof l->b;
        memcpy(ct_line_room(l, k), s, k);
        l->n += k;
        s += k;
        n -= k;
    }
}

int ct_number_parse(const char *text, size_t n, double *out)
{
    const char *end_text = text + n;
    while (text < end_text && isspace((unsigned char)*text))
        text++;
    while (end_text > text && isspace((unsigned char)end_text[-1]))
        end_text--;
    if (text == end_text)
        return CT_NUMBER_NONE;
    char small[128], *end;
    const size_t len = (size_t)(end_text - text);
    /* a copy ends where the field ends: strtod cannot read into what follows it */
    char *buf = len < sizeof small ? small : malloc(len + 1);
    if (!buf)
        return CT_NUMBER_NONE;
    memcpy(buf, text, len);
    buf[len] = '\0';
    errno = 0;
    const double v = strtod(buf, &end);
    const int whole = end == buf + len, range = errno == ERANGE;
    if (buf != small)
        free(buf);
    if (!whole)
        return CT_NUMBER_NONE;
    if (isinf(v) && range)
        return CT_NUMBER_OVERFLOW;
    if (!isfinite(v))
        return CT_NUMBER_NOT_FINITE;
    /* a subnormal, or 0 from a text that is not zero: digits lost (glibc flags both ERANGE;
     * an exact subnormal, e.g. in hex, is no more usable) */
    if ((v != 0.0 && fabs(v) < DBL_MIN) || (v == 0.0 && range))
        return CT_NUMBER_UNDERFLOW;
    *out = v;
    return CT_NUMBER_OK;
}

const char *ct_number_why(int status)
{
    switch (status) {
    case CT_NUMBER_OK:
        return "a number";
    case CT_NUMBER_OVERFLOW:
        return "overflows double precision (|value| > 1.8e308)";
    case CT_NUMBER_UNDERFLOW:
        return "underflows double precision (0 < |value| < 2.2e-308)";
    default:
        return "not a finite number";
    }
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t';
}

void ct_list_start(ct_list *l, const char *text, const char *seps)
{
    l->next = text;
    l->seps = seps;
    l->blanks = strchr(seps, ' ') != NULL;
    l->done = 0;
}

int ct_list_next(ct_list *l, const char **field, size_t *len)
{
    if (l->done)
        return 0;
    const char *p = l->next;
    while (isspace((unsigned char)*p))
        p++;
    const char *start = p;
    /* a hard separator: one of seps that is not a blank */
    while (*p && !(strchr(l->seps, *p) && !is_blank(*p)) &&
           !(l->blanks && isspace((unsigned char)*p)))
        p++;
    const char *end = p;
    while (end > start && isspace((unsigned char)end[-1]))
        end--;
    while (isspace((unsigned char)*p))
        p++;
    *field = start;
    *len = (size_t)(end - start);
    if (!*p)
        l->done = 1;
    else if (strchr(l->seps, *p) && !is_blank(*p))
        l->next = p + 1; /* another field follows, maybe an empty one */
    else
        l->next = p; /* blanks alone separated it */
    return 1;
}

const char *ct_list_empty_why(void)
{
    return "lists take no empty field, a separator at either end included";
}
