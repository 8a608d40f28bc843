/* cantact/geometry.h: the Cantor surface's parameters and geometry (Eqs. 1-3, 16-18, 28). Part of
 * the library's API: include <cantact.h>, which includes every part; each part includes the parts
 * it needs. SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_GEOMETRY_H
#define CANTACT_PART_GEOMETRY_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/status.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- parameters (docs/model.md §1) ---------------------------------------------------- */

typedef struct {
    double fx;      /* horizontal Cantor ratio, dimensionless, > 1 */
    double fz;      /* vertical Cantor ratio, dimensionless, 1 < fz < 2 */
    double l0;      /* length of stage 0 [length], > 0 */
    double h0;      /* recess depth of stage 0 [length], > 0 */
    double Hstar;   /* Winkler layer thickness H* [length], > h0 */
    double E;       /* Young's modulus [force/length^2], > 0 */
    double sigma_y; /* yield stress [force/length^2], 0 < sigma_y < E */
} ct_params;

/* Returns CT_OK if every parameter is finite and in range, else CT_EINVAL with a
 * message naming the first offending parameter and its valid range. */
int ct_params_validate(const ct_params *p);

/* ---- Cantor geometry (Eqs. 1-3, 16-18, 28) --------------------------------------- */
/* Stage indices are doubles so that deep (millions) and continuous stages work; values
 * that underflow are 0, never NaN. Parameters must have been validated. */

double ct_stage_length(const ct_params *p, double i); /* l_i = l0 fx^-i [length], Eq. 1 */
double ct_stage_depth(const ct_params *p, double i);  /* h_i = h0 fz^-i [length], Eq. 2 */
double ct_stage_area(const ct_params *p, double i);   /* s_i = l_i - l_{i+1} [length] */
double ct_alpha(const ct_params *p);                  /* ln fx / ln fz, Eq. 28 */
double ct_beta(const ct_params *p);                   /* 1/(fx fz), Eq. 18 */
double ct_one_minus_beta(const ct_params *p);         /* 1 - beta without cancellation */
double ct_dimension(const ct_params *p);              /* fractal dimension D, Eq. 3 */
/* Returns sum_{i=n1}^{n2} s_i [length] (Eq. 16); n2 may be INFINITY. */
double ct_sum_area(const ct_params *p, double n1, double n2);
/* Returns sum_{i=n1}^{n2} h_i s_i [length^2] (Eq. 17); n2 may be INFINITY. */
double ct_sum_depth_area(const ct_params *p, double n1, double n2);
/* x-extent [length] of piece j (0 <= j < 2^stage) of a depth-N prefractal: the middle left
 * at that stage, or for stage == depth a whole tip. */
int ct_piece_extent(const ct_params *p, long depth, long stage, size_t j, double *x_left,
                    double *x_right);
/* Returns the critical speed parameter's energy scale l0 E h0 [energy]: V*^2 = W / scale. */
double ct_energy_scale(const ct_params *p);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
