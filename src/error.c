#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static _Thread_local char error_message[512];

/* Formatted into a buffer of its own first: a message that quotes the previous one
 * (ct_error_set(st, "%s: %s", where, ct_error_message())) must not read what it overwrites. */
int ct_error_set(int status, const char *fmt, ...)
{
    char next[sizeof error_message];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(next, sizeof next, fmt, ap);
    va_end(ap);
    memcpy(error_message, next, sizeof next);
    return status;
}

int ct_error_interrupted(void)
{
    return ct_error_set(CT_EINTR, "interrupted");
}

const char *ct_error_message(void)
{
    return error_message;
}

const char *ct_strerror(int status)
{
    switch (status) {
    case CT_OK:
        return "success";
    case CT_EINVAL:
        return "invalid input";
    case CT_ENOMEM:
        return "out of memory";
    case CT_ERANGE:
        return "outside the model's range";
    case CT_ENOCONV:
        return "tolerance not met";
    case CT_EIO:
        return "input/output error";
    case CT_ESKIPPED:
        return "not run: an earlier impact of the same speed failed";
    case CT_EINTR:
        return "interrupted";
    default:
        return "unknown error";
    }
}

int ct_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Merges the sorted runs v[0..m) and v[m..n) through tmp. */
static void merge_runs(double *v, size_t m, size_t n, double *tmp)
{
    size_t i = 0, j = m, k = 0;
    while (i < m && j < n)
        tmp[k++] = v[j] < v[i] ? v[j++] : v[i++];
    while (i < m)
        tmp[k++] = v[i++];
    while (j < n)
        tmp[k++] = v[j++];
    memcpy(v, tmp, n * sizeof(double));
}

/* Breakpoint lists come as a few monotone runs (a stage bundle's contacts and yields both
 * fall with the stage index); sorting them by merging those runs is O(n) instead of the
 * O(n log n) of qsort, which dominated a sweep of many velocities. Lists of many runs,
 * or where the buffer cannot be had, go to qsort. */
#define CT_MAX_RUNS 8

size_t ct_sort_unique(double *v, size_t n)
{
    size_t ends[CT_MAX_RUNS], runs = 0, start = 0;
    double *tmp = NULL;
    while (start < n && runs < CT_MAX_RUNS) {
        size_t end = start + 1;
        if (end < n && v[end] < v[start]) {
            while (end < n && v[end] < v[end - 1])
                end++;
            for (size_t a = start, b = end - 1; a < b; a++, b--) { /* strictly falling: reverse */
                double t = v[a];
                v[a] = v[b];
                v[b] = t;
            }
        } else {
            while (end < n && v[end] >= v[end - 1])
                end++;
        }
        ends[runs++] = end;
        start = end;
    }
    if (start < n || (runs > 1 && !(tmp = malloc(n * sizeof(double))))) {
        qsort(v, n, sizeof(double), ct_cmp_double);
    } else {
        for (size_t r = 1; r < runs; r++)
            merge_runs(v, ends[r - 1], ends[r], tmp);
        free(tmp);
    }
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (m == 0 || v[k] != v[m - 1])
            v[m++] = v[k];
    return m;
}
