/* The CLI's number formatting (src/cli/number.c) against glibc's printf("%.17g"): the
 * reference is an independent implementation; they must agree byte for byte. */
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(agrees_with_printf),
        cmocka_unit_test(edges),
        cmocka_unit_test(longs_agree_with_printf),
        cmocka_unit_test(lines_agree_with_printf),
    };
    return cmocka_run_group_tests_name("number", tests, NULL, NULL);
}
