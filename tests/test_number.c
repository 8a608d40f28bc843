/* The CLI's number formatting (src/number.c) against glibc's printf("%.17g"): the reference is
 * an independent implementation; they must agree byte for byte. And the one rule by which
 * every reader takes numbers and lists: what is a usable double, what is a list's field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "number.h"

static void check(double x)
{
    char a[CT_NUMBER_MAX], b[64];
    size_t n = ct_format_double(a, x);
    snprintf(b, sizeof b, "%.17g", x);
    if (strcmp(a, b) || n != strlen(b))
        fail_msg("%a: got %s, printf gives %s", x, a, b);
    n = ct_format_g3(a, x);
    snprintf(b, sizeof b, "%.3g", x);
    if (strcmp(a, b) || n != strlen(b))
        fail_msg("%a: got %s, printf(\"%%.3g\") gives %s", x, a, b);
}

static void agrees_with_printf(void **state)
{
    (void)state;
    uint64_t s = 88172645463325252u;
    for (long i = 0; i < 400000; i++) {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        double x;
        if (i % 2) { /* any bit pattern: NaN, infinities, subnormals, everything */
            memcpy(&x, &s, sizeof x);
        } else { /* the range results live in, where the fast path works, and beyond it */
            x = pow(10.0, (double)(int)(s % 45) - 25.0) * (double)(s >> 11) / 9007199254740992.0;
            if (s & 1)
                x = -x;
        }
        check(x);
    }
}

/* Where rounding decides the exponent or sits on a tie. */
static void edges(void **state)
{
    (void)state;
    const double v[] = {0.0,
                        -0.0,
                        1.0,
                        1e-6,
                        1e-5,
                        1e-4,
                        9.9999999999999995e-07,
                        0.1,
                        0.3,
                        2.0 / 3.0,
                        1e16,
                        1e17,
                        9.999999999999999e16,
                        123.456,
                        999.5,
                        999.49999999999989,
                        0.0012345,
                        0.00012345,
                        1.125e-16,
                        1.135e-16,
                        9.995e-5,
                        0.1005,
                        12.25,
                        12.35,
                        1e-22,
                        1e-23,
                        9.9999999999999997e-23,
                        1.1102230246251565e-16,
                        2.2204460492503131e-16,
                        1e-300,
                        DBL_MIN,
                        DBL_MAX,
                        5e-324,
                        0.5,
                        99999999999999999.0,
                        INFINITY,
                        -INFINITY,
                        NAN};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
        check(v[k]);
        check(nextafter(v[k], INFINITY));
        check(nextafter(v[k], -INFINITY));
    }
    for (int e = -24; e <= 17; e++) { /* powers of ten and their neighbours */
        double x = pow(10.0, e);
        check(x);
        check(nextafter(x, 0.0));
        check(nextafter(x, INFINITY));
    }
}

/* ct_put_long against printf("%ld"), through a stream */
static void longs_agree_with_printf(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    char ref[64 * 28] = "", *r = ref;
    const long v[] = {0,   1,         -1,         9,        10,       -10,          99,
                      100, 123456789, -987654321, LONG_MAX, LONG_MIN, LONG_MAX - 1, LONG_MIN + 1};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) {
        ct_put_long(f, v[k]);
        fputc(';', f);
        r += sprintf(r, "%ld;", v[k]);
    }
    char got[sizeof ref] = "";
    rewind(f);
    size_t n = fread(got, 1, sizeof got - 1, f);
    got[n] = '\0';
    fclose(f);
    assert_string_equal(got, ref);
}

/* A ct_line against the same fields through printf into a string: numbers, longs, characters
 * and strings, longer than the line's buffer so that it fills and flushes mid-line (a number
 * landing on every position of the buffer's end), and a string longer than the buffer. */
static void lines_agree_with_printf(void **state)
{
    (void)state;
    enum { REF = 1 << 17 };
    static char ref[REF], got[REF];
    size_t r = 0;
    FILE *f = tmpfile();
    assert_non_null(f);
    ct_line line, *l = &line;
    ct_line_start(l, f);
    const long lv[] = {0, -1, 7, -120, LONG_MAX, LONG_MIN, LONG_MIN + 1};
    const double dv[] = {0.1, -2.5e-7, 1.0 / 3.0, -0.0, 6.02214076e23, 4.9e-324, 123456789.0};
    uint64_t s = 42;
    for (int i = 0; i < 1500; i++) { /* about 60 kB: the 2048-byte buffer fills ~30 times */
        s = s * 6364136223846793005u + 1442695040888963407u;
        double x;
        memcpy(&x, &s, sizeof x);
        if (!isfinite(x))
            x = dv[i % 7];
        const long v = lv[i % 7];
        ct_line_double(l, x);
        ct_line_char(l, ',');
        ct_line_long(l, v);
        ct_line_char(l, ';');
        ct_line_g3(l, dv[i % 7]);
        r += (size_t)snprintf(ref + r, REF - r, "%.17g,%ld;%.3g", x, v, dv[i % 7]);
        if (i % 500 == 499) { /* a string longer than the buffer */
            char big[5000];
            for (size_t k = 0; k < sizeof big - 1; k++)
                big[k] = (char)('a' + (k + (size_t)i) % 26);
            big[sizeof big - 1] = '\0';
            ct_line_str(l, big);
            r += (size_t)snprintf(ref + r, REF - r, "%s", big);
        }
        ct_line_str(l, "\n");
        r += (size_t)snprintf(ref + r, REF - r, "\n");
        assert_true(r < REF);
    }
    ct_line_flush(l);
    rewind(f);
    const size_t n = fread(got, 1, REF - 1, f);
    got[n] = '\0';
    fclose(f);
    assert_int_equal(n, r);
    assert_string_equal(got, ref);
}

static void expect_number(const char *text, int status, double want)
{
    double x = -12345.0;
    const int st = ct_number_parse(text, strlen(text), &x);
    if (st != status)
        fail_msg("'%s': status %d, want %d", text, st, status);
    if (st == CT_NUMBER_OK && !(x == want && signbit(x) == signbit(want)))
        fail_msg("'%s': %a, want %a", text, x, want);
    if (st != CT_NUMBER_OK && x != -12345.0)
        fail_msg("'%s': refused but written", text);
}

static void numbers_read(void **state)
{
    (void)state;
    expect_number("1.5", CT_NUMBER_OK, 1.5);
    expect_number(" \t-2e3 ", CT_NUMBER_OK, -2000.0);
    expect_number("-0.0", CT_NUMBER_OK, -0.0);
    expect_number("0e-400", CT_NUMBER_OK, 0.0); /* zero spelled small is zero, exactly */
    expect_number("2.2250738585072014e-308", CT_NUMBER_OK, DBL_MIN);
    expect_number("1.7976931348623157e308", CT_NUMBER_OK, DBL_MAX);
    expect_number("", CT_NUMBER_NONE, 0);
    expect_number("  ", CT_NUMBER_NONE, 0);
    expect_number("1x", CT_NUMBER_NONE, 0);
    expect_number("1 2", CT_NUMBER_NONE, 0);
    expect_number("x1", CT_NUMBER_NONE, 0);
    expect_number("inf", CT_NUMBER_NOT_FINITE, 0);
    expect_number("-Infinity", CT_NUMBER_NOT_FINITE, 0);
    expect_number("nan", CT_NUMBER_NOT_FINITE, 0);
    expect_number("1e309", CT_NUMBER_OVERFLOW, 0);
    expect_number("-1e400", CT_NUMBER_OVERFLOW, 0);
    /* below the smallest normal double, DBL_MIN = 2^-1022: a subnormal or a lost value */
    expect_number("1e-320", CT_NUMBER_UNDERFLOW, 0);
    expect_number("-2e-310", CT_NUMBER_UNDERFLOW, 0);
    expect_number("2.2250738585072009e-308", CT_NUMBER_UNDERFLOW, 0); /* DBL_MIN - 2^-1074 */
    expect_number("1e-400", CT_NUMBER_UNDERFLOW, 0);
    expect_number("0x1p-1030", CT_NUMBER_UNDERFLOW, 0); /* exact, yet subnormal */
    /* only the n bytes given: a field inside a longer text */
    double x = 0;
    assert_int_equal(ct_number_parse("12,34", 2, &x), CT_NUMBER_OK);
    assert_true(x == 12.0);
    assert_int_equal(ct_number_parse("0.5e", 3, &x), CT_NUMBER_OK);
    assert_true(x == 0.5);
    /* a long spelling (past any fixed buffer) is still read whole: 1.000...0001 with 300
     * digits rounds to 1 */
    char longer[320] = "1.";
    memset(longer + 2, '0', 300);
    longer[302] = '1';
    longer[303] = '\0';
    expect_number(longer, CT_NUMBER_OK, 1.0);
    longer[303] = 'x';
    longer[304] = '\0';
    expect_number(longer, CT_NUMBER_NONE, 0);
    assert_non_null(strstr(ct_number_why(CT_NUMBER_UNDERFLOW), "underflows"));
    assert_non_null(strstr(ct_number_why(CT_NUMBER_OVERFLOW), "overflows"));
    assert_non_null(strstr(ct_number_why(CT_NUMBER_NOT_FINITE), "not a finite number"));
}

/* The fields of text as "[a][][b]" */
static void expect_fields(const char *text, const char *seps, const char *want)
{
    char got[256] = "";
    size_t used = 0, n;
    const char *f;
    ct_list l;
    ct_list_start(&l, text, seps);
    while (ct_list_next(&l, &f, &n))
        used += (size_t)snprintf(got + used, sizeof got - used, "[%.*s]", (int)n, f);
    if (strcmp(got, want))
        fail_msg("'%s' split at '%s': %s, want %s", text, seps, got, want);
}

static void list_fields(void **state)
{
    (void)state;
    expect_fields("a,b,c", ",", "[a][b][c]");
    expect_fields(" a , b ", ",", "[a][b]");
    expect_fields("a,,b", ",", "[a][][b]"); /* two separators in a row */
    expect_fields("a,", ",", "[a][]");      /* a trailing separator */
    expect_fields("a , ", ",", "[a][]");    /* also with blanks after it */
    expect_fields(",a", ",", "[][a]");      /* a leading one */
    expect_fields("", ",", "[]");           /* nothing at all */
    expect_fields("   ", ",", "[]");
    expect_fields("a b", ",", "[a b]"); /* blanks separate only where seps say so */
    expect_fields("1:2::3", ":", "[1][2][][3]");
    /* a blank in seps: runs of blanks separate, blanks around a comma belong to it */
    expect_fields("a  b\tc", ", ", "[a][b][c]");
    expect_fields("a , b;c", ",; ", "[a][b][c]");
    expect_fields("a ,, b", ", ", "[a][][b]");
    expect_fields("a , ; b", ",; ", "[a][][b]");
    expect_fields("a b ,", ", ", "[a][b][]");
    expect_fields(" a b ", ", ", "[a][b]");
    expect_fields(", a", ", ", "[][a]");
    assert_non_null(strstr(ct_list_empty_why(), "empty"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(agrees_with_printf),
        cmocka_unit_test(edges),
        cmocka_unit_test(longs_agree_with_printf),
        cmocka_unit_test(lines_agree_with_printf),
        cmocka_unit_test(numbers_read),
        cmocka_unit_test(list_fields),
    };
    return cmocka_run_group_tests_name("number", tests, NULL, NULL);
}
