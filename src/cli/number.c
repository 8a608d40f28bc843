/* Doubles as text, exactly as printf("%.17g") writes them, without printf's multi-precision
 * path for the common range. A result table of 2000 rows is 12000 such numbers; glibc spends
 * about 2000 instructions on each, this about 100.
 *
 * x = m 2^e exactly (m < 2^53). For 1e-6 <= |x| < 1e17 the 17 significant digits are
 * N = round(x 10^(16 - E)), E the decimal exponent, and m 10^k (k = 16 - E <= 22, so
 * 10^k < 2^74) fits in 128 bits: N is the integer part of m 10^k 2^e and the remainder
 * decides the rounding, to nearest with ties to even, as glibc does. Everything else
 * (zero, subnormals, huge or tiny values, NaN, infinities) goes to snprintf. */
#include "number.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 u128;

/* x 10^k for x = m 2^e: its integer part *trunc and that rounded to nearest, ties to even;
 * 0 if it does not fit the exact path. */
static uint64_t scaled(uint64_t m, int e, int k, uint64_t *trunc)
{
    static const uint64_t pow10[20] = {1u,
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
    /* m 10^k < 2^53 2^74: exact in 128 bits */
    u128 p = (u128)m * (k <= 19 ? pow10[k] : pow10[19]);
    if (k > 19)
        p *= pow10[k - 19];
    int s = -e;
    if (s <= 0 || s >= 127)
        return 0;
    u128 n = p >> s, rem = p & (((u128)1 << s) - 1), half = (u128)1 << (s - 1);
    *trunc = (uint64_t)n;
    if (rem > half || (rem == half && (n & 1u)))
        n++;
    return (uint64_t)n;
}
#endif

size_t ct_format_double(char *buf, double x)
{
#if defined(__SIZEOF_INT128__)
    double ax = fabs(x);
    if (isfinite(x) && ax >= 1e-6 && ax < 1e17) {
        uint64_t bits;
        memcpy(&bits, &ax, sizeof bits);
        int be = (int)(bits >> 52);
        uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
        int e = be - 1075;
        /* the decimal exponent from the binary one (log10 2 = 0.30103); off by at most
         * one, which the loop below corrects on the exact digits */
        int E = (int)floor((double)(be - 1023) * 0.30102999566398120);
        const uint64_t lo = UINT64_C(10000000000000000), hi = UINT64_C(100000000000000000);
        uint64_t N = 0, T = 0;
        for (int tries = 0; tries < 4; tries++) {
            int k = 16 - E;
            if (k < 0 || k > 22 || !(N = scaled(m, e, k, &T)))
                break;
            if (T >= hi) { /* the exponent is decided before rounding */
                E++;
            } else if (T < lo) {
                E--;
            } else {
                if (N == hi) { /* rounding carried into an 18th digit: 1.000...e(E+1) */
                    N = lo;
                    E++;
                }
                break;
            }
            N = 0;
        }
        if (N >= lo && N < hi) {
            char d[17];
            for (int i = 16; i >= 0; i--, N /= 10)
                d[i] = (char)('0' + N % 10);
            int nd = 17; /* significant digits left after dropping trailing zeros */
            while (nd > 1 && d[nd - 1] == '0')
                nd--;
            char *o = buf;
            if (x < 0)
                *o++ = '-';
            if (E < -4 || E >= 17) { /* %g's exponent style (only E < -4 reaches here) */
                *o++ = d[0];
                if (nd > 1) {
                    *o++ = '.';
                    memcpy(o, d + 1, (size_t)nd - 1);
                    o += nd - 1;
                }
                int ae = E < 0 ? -E : E; /* 5..6 here: two digits */
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
                *o++ = '0';
                *o++ = '.';
                for (int i = 0; i < -E - 1; i++)
                    *o++ = '0';
                memcpy(o, d, (size_t)nd);
                o += nd;
            }
            *o = '\0';
            return (size_t)(o - buf);
        }
    }
#endif
    return (size_t)snprintf(buf, CT_NUMBER_MAX, "%.17g", x);
}

void ct_put_double(FILE *f, double x)
{
    char buf[CT_NUMBER_MAX];
    size_t n = ct_format_double(buf, x);
    fwrite(buf, 1, n, f);
}
