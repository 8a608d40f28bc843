/* cantact: coefficient of restitution of a Cantor-fractal rough surface made of
 * elastic-perfectly-plastic rods on a Winkler foundation (see docs/model.md).
 *
 * Conventions: every fallible function returns an int status (CT_OK = 0); results come
 * back through pointer arguments; ct_error_message() holds the detail of the last error
 * raised in the calling thread. Lengths are in the unit of l_0 and h_0, forces per unit
 * depth, energies per unit depth.
 *
 * NULL: pointer arguments must not be NULL unless a function says otherwise. Functions that
 * create, run, solve or integrate (the *_alloc and builders, ct_curve_build, ct_impact*,
 * ct_sweep, ct_cantor_plan_build, ct_integrate*, the depth searches, the laws) check theirs
 * and return CT_EINVAL naming the argument; the *_free functions accept NULL; accessors and
 * evaluations on a handle (ct_bundle_size, ct_bundle_force, ct_curve_work, ...) do not check,
 * as they sit in hot loops. A NaN displacement gives a NaN force or work, never a number.
 *
 * Thread safety: the library keeps no global state and changes none (not the OpenMP thread
 * count, not GSL's error handler). A function that takes a const handle (const ct_bundle *,
 * const ct_curve *) only reads it: any number of threads may call such functions on one
 * handle at once. A function that takes a non-const handle (ct_bundle_advance, ct_impact,
 * ct_curve_build, ct_bundle_set_threads, ...) needs that handle to itself. Error messages are
 * per thread. Results do not depend on the number of threads.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef CANTACT_H
#define CANTACT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* The parts of the API, in the order of the flow (docs/library.md): */
#include "cantact/status.h"
#include "cantact/geometry.h"
#include "cantact/rods.h"
#include "cantact/curve.h"
#include "cantact/impact.h"
#include "cantact/cantor.h"
#include "cantact/sweep.h"
#include "cantact/laws.h"
#include "cantact/random_cantor.h"
#include "cantact/ensemble.h"
#include "cantact/table.h"
#include "cantact/profile.h"
#include "cantact/columns.h"
#include "cantact/keys.h"
#include "cantact/body.h"
#include "cantact/surface.h"

#endif
