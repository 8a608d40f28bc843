/* cantact/profile.h: measured surfaces: profiles and maps, levelling, their fit. Part of the
 * library's API: include <cantact.h>, which includes every part; each part includes the parts it
 * needs. SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_PROFILE_H
#define CANTACT_PART_PROFILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/rods.h"
#include "cantact/sweep.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- measured surfaces (docs/model.md §9, src/surface/profile.c, profile_read.c, fit.c) --- */
/* A measured line profile z(x_j) or areal topography z(x_i, y_j) is a rod set directly: after
 * levelling, the plane touches the highest point; sample j is a rod with top depth
 * t_j = max z - z_j, its share of the x-axis (a line) or the pixel area (a grid) as its area,
 * and length H* - t_j. P(u) depends only on the bearing-area curve
 * phi(d) = (area with top depth <= d) / (total area). */

typedef struct {
    size_t n;              /* valid samples */
    size_t nx, ny;         /* a line: nx samples, ny = 1; a grid: nx by ny (row-major, x fastest) */
    double *x;             /* a line: the positions [length], increasing; NULL for a grid */
    double *z;             /* heights [length], up; NaN where a grid point is invalid */
    double dx, dy;         /* a grid's spacings [length]; a uniform line's dx (0: non-uniform) */
    size_t invalid;        /* grid points left out (the X3P mask, or NaN) */
    char source[128];      /* what was read: "text", "dektak", "x3p" */
    double x_unit, z_unit; /* read: metres per file unit of x and z (1 for X3P and made ones) */
} ct_profile;

typedef enum {
    CT_DETREND_NONE = 0,
    CT_DETREND_MEAN = 1,      /* the mean height removed */
    CT_DETREND_LINEAR = 2,    /* the least-squares line (a plane for a grid) removed */
    CT_DETREND_QUADRATIC = 3, /* the least-squares parabola (quadric surface) removed */
} ct_detrend;

/* How a text file is read: two columns x z, or one column z with spacing dx. Values are
 * multiplied by x_unit, z_unit [length / file unit] (1e-6 for micrometres read in metres); a
 * unit 0 takes the one the file's column names state ("Lateral um,Raw Micrometer", "z (nm)",
 * "x [mm]": m, mm, um, micrometre, micron, nm, the micro sign in latin-1 or UTF-8), and it is
 * an error when they state none. X3P files state theirs (metres): units and dx must be 0. */
typedef struct {
    double x_unit, z_unit;
    double dx; /* > 0: one column of heights at this spacing [file units]; 0: two columns */
} ct_profile_read_opts;

/* Reads a profile: an X3P file (ISO 25178-72, a zip with main.xml), a Dektak export (a header
 * block, then "Lateral um,Raw Micrometer" rows), or text/CSV (# or ; comments, commas, tabs
 * or blanks between the columns, latin-1 or UTF-8). One pass over the file. Errors name the
 * file and its line (or the X3P entry): non-numeric rows, x not increasing, fewer than 3
 * points, a zip without main.xml, a grid whose size disagrees with its header. */
int ct_profile_read(const char *path, const ct_profile_read_opts *opts, ct_profile **out);
/* A line profile from arrays (x NULL: uniform spacing dx), copied. */
int ct_profile_from_line(ct_profile **out, size_t n, const double *x, double dx, const double *z);
/* A grid from row-major heights (NaN: invalid), copied. */
int ct_profile_from_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy,
                         const double *z);
void ct_profile_free(ct_profile *p);
/* Removes the least-squares mean, line (plane) or parabola (quadric) from the heights. */
int ct_profile_level(ct_profile *p, ct_detrend how);
/* Spikes, an explicit choice: heights more than k Rq above the mean are cut to mean + k Rq;
 * *clipped gets how many were. */
int ct_profile_trim(ct_profile *p, double k, size_t *clipped);

typedef struct {
    double mean, Ra, Rq; /* [length] about the mean height */
    double Rt;           /* peak to valley [length] */
    double length;       /* the profile's length (a line: x_n - x_1 plus one spacing) or the
                            grid's area [length or length^2]: the surface's l0 */
} ct_profile_stats;
int ct_profile_stats_of(const ct_profile *p, ct_profile_stats *s);

/* The rods of a profile in a layer of thickness Hstar (> Rt) [length] with E, sigma_y: the
 * layer's l0 is the profile's length (a line, forces per unit depth) or area (a grid, forces),
 * its h0 the peak-to-valley depth Rt, so V* = sqrt(m v^2 / (2 l0 E h0)) with that l0 and h0.
 * Rod info gives each rod's x-extent (a line) or x (a grid); no stages. */
int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar);

/* The bearing-area curve at n depths d [length] (ascending): phi[k] = fraction of the area
 * whose top lies within d[k] of the highest point. */
int ct_profile_bearing(const ct_profile *p, size_t n, const double *d, double *phi);

/* A straight-line fit in log-log: y = slope x + intercept through n points whose abscissas
 * span [lo, hi] (in their own units: depth, lag, window width or wavenumber); r2 its
 * coefficient of determination, residual the rms of its residuals (in ln units). */
typedef struct {
    double lo, hi;
    size_t n;
    double slope, intercept, r2, residual;
} ct_fit_line;

/* The profile's fractal dimension D, three ways: the variation method (the area of the
 * graph's eps-neighbourhood ~ eps^(2 - D), its box-counting dimension: Eq. 3's D for a Cantor
 * profile), the structure function S(tau) ~ tau^(2 (2 - D)) and the power spectrum
 * C(q) ~ q^-(5 - 2D) (GSL's FFT, a Hann window). For a self-affine profile all three agree; a
 * step profile (the Cantor prefractal itself) pins the last two at 1.5 by its jumps. */
typedef enum {
    CT_DIM_VARIATION = 0, /* the default */
    CT_DIM_STRUCTURE = 1,
    CT_DIM_SPECTRUM = 2,
} ct_dimension_method;

/* The Cantor surface a profile looks like (docs/model.md §9): alpha and h0 from the bearing curve
 * (ln phi = alpha ln d - alpha ln h0), D by the method asked for (all three reported), then
 * Eq. 3 inverted: ln fz = ln 2 (2 - D) / (1 + alpha (D - 1)), ln fx = alpha ln fz; l0 the
 * profile's length (a grid: its length along x). A grid is read along x, row by row. */
typedef struct {
    ct_dimension_method dimension; /* in: the D that enters Eq. 3 */
    ct_fit_line bearing;           /* ln phi against ln d, d [length] */
    double alpha, h0;              /* dimensionless, [length] */
    ct_fit_line variation;         /* ln V against ln eps, eps [length] (window width) */
    ct_fit_line structure;         /* ln S against ln tau, tau [length] */
    ct_fit_line spectrum;          /* ln C against ln q, q [1/length] */
    double D_variation, D_structure, D_spectrum;
    double D;          /* the one used */
    double fx, fz, l0; /* Eq. 3 with alpha and D; l0 [length] */
    ct_profile_stats stats;
} ct_profile_fit;

/* Bands (0 for the default): depths [d_lo, d_hi] for the bearing fit (default: from the depth
 * of the 20th highest sample to where phi reaches 0.1, the top of the bearing area an impact
 * touches); lags [tau_lo, tau_hi] for the three dimensions (default 2 spacings to a tenth
 * of the length). fit->dimension is read (the method for Eq. 3), everything else written.
 * CT_EINVAL when the heights are all equal or a band holds fewer than 3 points. */
int ct_profile_fit_of(const ct_profile *p, double d_lo, double d_hi, double tau_lo, double tau_hi,
                      ct_profile_fit *fit);
/* The bearing fit of a whole fit (ct_profile_fit_of) redone on depths [d_lo, d_hi] (0: the
 * default), alpha, h0, fx and fz with it; the dimensions are kept. On error fit is unchanged. */
int ct_profile_fit_bearing(const ct_profile *p, double d_lo, double d_hi, ct_profile_fit *fit);
/* The bearing fit redone on the depths n impacts reached (u_max [length], NaN ones left out):
 * from the shallowest (not above the fit's default band's start) to the deepest (not below
 * Rt), as `cantact run` does for compare and bearing. CT_EINVAL when that band holds no fit. */
int ct_profile_fit_on_reach(const ct_profile *p, const ct_profile_fit *fit, const double *u_max,
                            size_t n, ct_profile_fit *out);
/* The fitted Cantor surface beside a profile's rods (layer: its E, sigma_y, H*): for n impact
 * energies W [energy per unit depth; a grid: energy] (NaN ones skipped), e of the fitted
 * surface's exact rods at its fractal depth, e of the asymptotic law with the fitted
 * parameters, and the fitted surface's V*. CT_ERANGE when the fit leaves the model's ranges. */
int ct_profile_fitted_e(const ct_profile *p, const ct_profile_fit *fit, const ct_layer *layer,
                        const double *W, size_t n, int threads, double *e_fit, double *e_asym,
                        double *V_fit);
/* The fit as CSV: quantity,value,band_lo,band_hi,points,r2,rms_residual_ln (lengths in m), after
 * a '#' line on the source and, when a dimension is outside (1, 2), a '# warning: ' line with
 * ct_profile_fit_warning's text. */
int ct_profile_fit_write(FILE *f, const ct_profile_fit *fit, const char *source, size_t n);
/* How many of the fit's three dimensions lie outside (1, 2), the range of a profile's fractal
 * dimension (0: none, buf ""); buf gets one line naming them and, when the one Eq. 3 took is
 * among them, that fx and fz describe no Cantor surface. */
size_t ct_profile_fit_warning(const ct_profile_fit *fit, char *buf, size_t len);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
