/* cantact/laws.h: the paper's series and asymptotic laws. Part of the library's API: include
 * <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_LAWS_H
#define CANTACT_PART_LAWS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/geometry.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- the paper's laws (docs/model.md §5-6) -------------------------------------------- */
/* Loads P [force] at displacement u [length] of the infinite fractal. Each function returns
 * CT_OK, CT_EINVAL (invalid parameters; u or u_max not finite or negative) or CT_ERANGE
 * (outside the law's domain); on error it leaves its output untouched. Thread-safe. */

/* Series, Eqs. 12-21 with Eq. 15 between nodes (h_i << H* in the elastic terms, exact yield
 * test of Eq. 29): P [force] at u [length]; CT_ERANGE for u > H* (crushed layer). */
int ct_series_load(const ct_params *p, double u, double *P);
/* Series unloading from u_max, Eqs. 22-24 (stages release at their own h-bar_i): P [force] at
 * u [length], a branch meant for u <= u_max; CT_ERANGE for u_max or u > H*. */
int ct_series_unload(const ct_params *p, double u_max, double u, double *P);
/* Asymptotic law, Eq. 33 (u <= eps_y H*) and Eq. 34: P [force] at u [length]; CT_ERANGE for
 * u > h0, where its continuous stage index n = -ln(u/h0)/ln fz is negative. */
int ct_asym_load(const ct_params *p, double u, double *P);
/* Asymptotic unloading, Eq. 38 as printed (consistent = 0), or with the second branch times
 * (1 - 1/fz)/(1 - beta) as derived from Eq. 23 (consistent = 1): P [force] at
 * u [length], a branch meant for u <= u_max; CT_ERANGE for u_max or u > h0. */
int ct_asym_unload(const ct_params *p, double u_max, double u, int consistent, double *P);
/* Work W [energy] of Eqs. 33-34 from 0 to u [length], closed form; CT_ERANGE for u > h0. */
int ct_asym_work_load(const ct_params *p, double u, double *W);
/* Work W [energy] of Eq. 38 from h-bar_inf = u_max - eps_y H* to u_max [length], closed form;
 * CT_ERANGE for u_max > h0. */
int ct_asym_work_unload(const ct_params *p, double u_max, int consistent, double *W);

typedef enum { CT_LAW_SERIES = 0, CT_LAW_ASYMPTOTIC = 1, CT_LAW_ASYMPTOTIC_CONSISTENT = 2 } ct_law;

/* e and u_max [length] of one impact of energy W on the virgin surface under a law: u_max
 * from Eq. 39 (to 1e-15 relative, else CT_ENOCONV), unloading energy from Eq. 40,
 * e = sqrt(W_unload / W_load); e = 1 exactly when no stage yields. CT_ERANGE where the law
 * does not apply (u_max beyond h0 or H*, W_unload > W_load). Thread-safe: no global state. */
int ct_law_impact(const ct_params *p, ct_law law, double W, double *u_max, double *e);
const char *ct_law_name(ct_law law);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
