/* Internal helpers shared by the library's modules. */
#ifndef CT_INTERNAL_H
#define CT_INTERNAL_H

#include "cantact.h"

#if defined(__GNUC__)
#define CT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CT_PRINTF(a, b)
/* e and u_max [length] of one impact of energy W on the virgin surface under the asymptotic
 * law (Eqs. 33-34, 38, 39-40); p validated, W finite and > 0. For ct_law_impact. */
int ct_asym_impact(const ct_params *p, int consistent, double W, double *u_max, double *e);

#endif

/* Records a detailed message for the calling thread and returns status, so that
 * "return ct_error_set(CT_EINVAL, ...)" reads naturally. Every error goes through here:
 * a breakpoint on it catches them all. */
int ct_error_set(int status, const char *fmt, ...) CT_PRINTF(2, 3);

/* Sorts v ascending and drops repeated values; returns the new count. Breakpoint lists of
 * the bundle and of the series go through here. */
size_t ct_sort_unique(double *v, size_t n);

/* e and u_max [length] of one impact of energy W on the virgin surface under the asymptotic
 * law (Eqs. 33-34, 38, 39-40); p validated, W finite and > 0. For ct_law_impact. */
int ct_asym_impact(const ct_params *p, int consistent, double W, double *u_max, double *e);

#endif
