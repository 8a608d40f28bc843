/* The lean curve's sort of its events (src/curve_lean.c, ct_lean_sort_records) against qsort
 * by the same total order: x's bits as an ordered key, ties in their first order (the tags).
 * The sort splits a range into buckets by x's spread, or by the keys' top bits where x has no
 * finite spread, and sorts the buckets on threads: every kind of range and every thread count
 * must give the reference's order. Linked with the library's objects (the function is
 * internal). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "curve_lean.h"

typedef struct {
    double x;
    uint64_t tag;
} rec;

static uint64_t key(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return (u >> 63) ? ~u : u | (UINT64_C(1) << 63);
}

static int by_key_then_tag(const void *a, const void *b)
{
    const rec *p = a, *q = b;
    const uint64_t kp = key(p->x), kq = key(q->x);
    if (kp != kq)
        return kp < kq ? -1 : 1;
    return p->tag < q->tag ? -1 : p->tag > q->tag;
}

static uint64_t state = 0x9e3779b97f4a7c15u;
static uint64_t next(void) /* xorshift64*: the test's own numbers, the same on every run */
{
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 0x2545f4914f6cdd1dull;
}
static double uniform(void)
{
    return (double)(next() >> 11) * 0x1p-53;
}

/* Sorts v on 1, 2 and 3 threads; each must equal qsort's order, record for record. */
static void sorts_like_qsort(const rec *v, size_t n, const char *what)
{
    rec *ref = malloc((n ? n : 1) * sizeof *ref), *got = malloc((n ? n : 1) * sizeof *got);
    assert_non_null(ref);
    assert_non_null(got);
    memcpy(ref, v, n * sizeof *v);
    qsort(ref, n, sizeof *ref, by_key_then_tag);
    for (int team = 1; team <= 3; team++) {
        memcpy(got, v, n * sizeof *v);
        assert_int_equal(ct_lean_sort_records(got, n, team), 0);
        for (size_t i = 0; i < n; i++)
            if (memcmp(&got[i], &ref[i], sizeof *got))
                fail_msg("%s (n = %zu, %d threads): record %zu is x = %.17g tag %llu, qsort's "
                         "x = %.17g tag %llu",
                         what, n, team, i, got[i].x, (unsigned long long)got[i].tag, ref[i].x,
                         (unsigned long long)ref[i].tag);
    }
    free(ref);
    free(got);
}

/* The sizes: insertion alone, one split, several levels, and past the size from which the
 * buckets go to the threads (131072). */
static const size_t sizes[] = {0, 1, 2, 3, 16, 17, 100, 5000, 70000, 200000};

/* A measured surface's contacts: the largest height minus a normal height (the many binades
 * near 0 hold few events, the top two most of them). */
static void normal_tops(void **s)
{
    (void)s;
    for (size_t z = 0; z < sizeof sizes / sizeof *sizes; z++) {
        const size_t n = sizes[z];
        rec *v = malloc((n ? n : 1) * sizeof *v);
        double top = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            const double u1 = uniform() + 1e-300, u2 = uniform();
            v[i].x = 1e-6 * sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
            top = v[i].x > top ? v[i].x : top;
        }
        for (size_t i = 0; i < n; i++) {
            v[i].x = top - v[i].x;
            v[i].tag = i;
        }
        sorts_like_qsort(v, n, "normal tops");
        free(v);
    }
}

/* Few distinct values (long runs of equal x, -0 beside +0) and values of both signs. */
static void runs_and_signs(void **s)
{
    (void)s;
    for (size_t z = 0; z < sizeof sizes / sizeof *sizes; z++) {
        const size_t n = sizes[z];
        rec *v = malloc((n ? n : 1) * sizeof *v);
        for (size_t i = 0; i < n; i++) {
            const int q = (int)(next() % 9) - 4;
            v[i].x = q == 0 ? (next() & 1 ? -0.0 : 0.0) : 0.25 * q;
            v[i].tag = i;
        }
        sorts_like_qsort(v, n, "runs of equal x");
        for (size_t i = 0; i < n; i++)
            v[i].x = (next() & 1 ? -1.0 : 1.0) * ldexp(uniform(), (int)(next() % 40) - 20);
        sorts_like_qsort(v, n, "both signs over 40 binades");
        for (size_t i = 0; i < n; i++)
            v[i].x = i % 2 ? -0.0 : 0.0; /* no spread: the keys' top bits */
        sorts_like_qsort(v, n, "-0 and +0 alone");
        free(v);
    }
}

/* Where x has no finite spread or its spread is no double: infinities, NaNs of both signs,
 * the extremes (their difference overflows), subnormals (the buckets' scale overflows). */
static void no_finite_spread(void **s)
{
    (void)s;
    const double odd[] = {INFINITY, -INFINITY, NAN,        -NAN, DBL_MAX, -DBL_MAX, DBL_MIN,
                          -DBL_MIN, 0x1p-1074, -0x1p-1074, 0.0,  -0.0,    1.0,      -1.0};
    const size_t nodd = sizeof odd / sizeof *odd;
    for (size_t z = 0; z < sizeof sizes / sizeof *sizes; z++) {
        const size_t n = sizes[z];
        rec *v = malloc((n ? n : 1) * sizeof *v);
        for (size_t i = 0; i < n; i++) {
            v[i].x = next() % 3 ? odd[next() % nodd] : uniform() - 0.5;
            v[i].tag = i;
        }
        sorts_like_qsort(v, n, "infinities, NaNs, extremes");
        for (size_t i = 0; i < n; i++)
            v[i].x = (double)(next() % 1000) * 0x1p-1074;
        sorts_like_qsort(v, n, "subnormals");
        for (size_t i = 0; i < n; i++)
            v[i].x = i % 2 ? DBL_MAX : -DBL_MAX * uniform();
        sorts_like_qsort(v, n, "a spread past DBL_MAX");
        for (size_t i = 0; i < n; i++)
            v[i].x = i % 3 ? 1.0 : INFINITY;
        sorts_like_qsort(v, n, "1 and +inf");
        for (size_t i = 0; i < n; i++) /* NaN beside finite values only (x86's NaN is -NaN) */
            v[i].x = i % 7 == 3 ? (i % 2 ? -NAN : NAN) : uniform() - 0.25;
        sorts_like_qsort(v, n, "NaNs of both signs among finite values");
        free(v);
    }
}

typedef struct {
    rec *v;
    size_t n;
    int st;
} sort_job;

static void *sort_on_thread(void *p)
{
    sort_job *j = p;
    j->st = ct_lean_sort_records(j->v, j->n, 1);
    return NULL;
}

/* x spread over every binary order of the doubles (2^-1074 .. 2^1023, repeated):
 * a split by x's spread narrows the largest bucket's spread only by its bucket count, so the
 * levels must go on by the keys' bits (175 levels by spread overflowed the stack). */
static void every_binary_order(void **s)
{
    (void)s;
    enum { N = 3 * 2098 * 8 };
    rec *v = malloc(N * sizeof *v);
    assert_non_null(v);
    size_t n = 0;
    for (int rep = 0; rep < 8; rep++)
        for (int e = -1074; e <= 1023; e++) {
            const double x = ldexp(1.0, e);
            v[n] = (rec){x, n};
            n++;
            v[n] = (rec){x * 1.5, n};
            n++;
            v[n] = (rec){x * (1.0 + 0x1p-52 * rep), n};
            n++;
        }
    for (size_t i = n; i-- > 1;) { /* shuffled */
        const size_t j = next() % (i + 1);
        const rec t = v[i];
        v[i] = v[j];
        v[j] = t;
    }
    for (size_t i = 0; i < n; i++) /* ties in their order here */
        v[i].tag = i;
    sorts_like_qsort(v, n, "every binary order");
    /* and on a thread of a 512 KiB stack (a level's counts are on the stack) */
    sort_job job = {malloc(n * sizeof *v), n, -2};
    assert_non_null(job.v);
    memcpy(job.v, v, n * sizeof *v);
    pthread_attr_t attr;
    pthread_t th;
    assert_int_equal(pthread_attr_init(&attr), 0);
    assert_int_equal(pthread_attr_setstacksize(&attr, 512 * 1024), 0);
    assert_int_equal(pthread_create(&th, &attr, sort_on_thread, &job), 0);
    assert_int_equal(pthread_join(th, NULL), 0);
    pthread_attr_destroy(&attr);
    assert_int_equal(job.st, 0);
    qsort(v, n, sizeof *v, by_key_then_tag);
    assert_memory_equal(job.v, v, n * sizeof *v);
    free(job.v);
    free(v);
}

/* Already in order and in reverse: the buckets' edges (the largest x at the last one). */
static void ordered_and_reversed(void **s)
{
    (void)s;
    for (size_t z = 0; z < sizeof sizes / sizeof *sizes; z++) {
        const size_t n = sizes[z];
        rec *v = malloc((n ? n : 1) * sizeof *v);
        for (size_t i = 0; i < n; i++)
            v[i] = (rec){(double)i * 0.1, i};
        sorts_like_qsort(v, n, "in order");
        for (size_t i = 0; i < n; i++)
            v[i] = (rec){(double)(n - i) * 0.1, i};
        sorts_like_qsort(v, n, "reversed");
        free(v);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(normal_tops),        cmocka_unit_test(runs_and_signs),
        cmocka_unit_test(no_finite_spread),   cmocka_unit_test(ordered_and_reversed),
        cmocka_unit_test(every_binary_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
