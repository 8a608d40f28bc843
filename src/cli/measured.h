/* Measured surfaces in the CLI (type = profile, cantact fit): src/cli/measured.c. */
#ifndef CT_CLI_MEASURED_H
#define CT_CLI_MEASURED_H

#include "cantact.h"
#include "scene.h"

#include <stdio.h>

/* Reads, levels (and trims) the scene's profile into sc->profile, sets the surface's l0, h0
 * and H* in sc->params (and sc->physical), turns the speeds into V*, and fits the Cantor
 * surface when the outputs need it. Reports on stderr unless quiet. */
int ct_cli_profile_prepare(ct_scene *sc, int quiet);
/* The rods of the prepared profile. */
int ct_cli_profile_bundle(const ct_scene *sc, ct_bundle **b, ct_plan_info *info);
/* what = compare: for every first-impact row, e of the fitted Cantor surface (exact rods,
 * fractal depth), of the asymptotic law with the fitted parameters, and the fitted surface's
 * V*, at the row's impact energy: out[3 k .. 3 k + 2] (NaN where not given). CT_ERANGE when
 * the fit leaves the model's ranges (the columns stay empty). */
int ct_cli_profile_compare(const ct_scene *sc, const ct_sweep_row *rows, size_t nrows, double *out);
/* After the sweep, with a fit and no [fit] depth band given: the bearing fit redone on the
 * depths the impacts reached (from the shallowest u_max, not above the default band's start,
 * to the deepest, not below Rt), as MODEL.md section 9 asks; the default band is kept (and
 * said, unless quiet) when that band holds no fit. */
int ct_cli_profile_refit(ct_scene *sc, const ct_sweep_row *rows, size_t nrows, int quiet);
/* what = bearing: d, phi and the fitted phi; what = profile: the levelled heights. */
int ct_cli_write_bearing(FILE *f, const ct_scene *sc);
int ct_cli_write_levelled(FILE *f, const ct_scene *sc);
/* The fit as a table: quantity,value,band_lo,band_hi,points,r2,rms_residual_ln. */
void ct_cli_write_fit(FILE *f, const ct_profile_fit *fit, const char *source, size_t n);
/* The message of the last failure of the functions above. */
const char *ct_cli_measured_message(void);
/* cantact fit FILE|SCENE.ini [options] */
int ct_cli_fit_main(int argc, char **argv);

#endif
