#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static _Thread_local char error_message[512];

int ct_error_set(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(error_message, sizeof error_message, fmt, ap);
    va_end(ap);
    return status;
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
    default:
        return "unknown error";
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

size_t ct_sort_unique(double *v, size_t n)
{
    qsort(v, n, sizeof(double), cmp_double);
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (m == 0 || v[k] != v[m - 1])
            v[m++] = v[k];
    return m;
}
