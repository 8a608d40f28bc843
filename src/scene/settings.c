/* The keys of a run that are not the surface's: the impact (speeds or mass and velocity, how
 * many impacts, a bounce sequence), the solver, a table's build and an ensemble. One table of
 * rows for every front-end: the CLI's scenes and --set, and Python's keyword arguments parse
 * through these rows, and what they mean for the solver is stated once (ct_run_keys_solver). */
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define AT(field) offsetof(ct_run_keys, field)
static const ct_key run_keys[] = {
    {"impact", "V_star", CT_KEY_SPEEDS, 0, 0, 0, NULL, "", "",
     "speeds V* = sqrt(m v^2 / (2 l0 E h0)), dimensionless (or give mass and velocity)",
     AT(V_star)},
    {"impact", "mass", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "mass of the body per unit depth (a grid: its mass), in the scene's units", AT(mass)},
    {"impact", "velocity", CT_KEY_SPEEDS, 0, 0, 0, NULL, "", "",
     "incident speeds, in the scene's units (with mass)", AT(velocity)},
    {"impact", "drop_height", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "a body dropped from rest: velocity = sqrt(2 gravity drop_height) (with mass)",
     AT(drop_height)},
    {"impact", "impacts", CT_KEY_INTEGER, 1, 1000000, 0, NULL,
     "must satisfy 1 <= impacts <= 1000000", "1 (bounce: 20)",
     "impacts per speed on the same spot, the rods' state carried", AT(impacts)},
    {"impact", "sequence", CT_KEY_WORD, 0, 0, 0, "sweep|bounce", "must be sweep or bounce", "sweep",
     "bounce: each impact at the previous rebound speed (needs mass)", AT(sequence)},
    {"impact", "gravity", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "9.81",
     "gravity for drop_height and bounce flights [length/time^2]", AT(gravity)},
    {"impact", "stop_speed", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_LO_CLOSED, NULL, "must be >= 0",
     "0", "a bounce sequence ends once a rebound is slower", AT(stop_speed)},
    {"solver", "quadrature", CT_KEY_WORD, 0, 0, 0, "breakpoints|trapezoid|simpson|gauss|closed",
     "must be breakpoints, trapezoid, simpson, gauss or closed", "breakpoints",
     "how W_load and W_unload are integrated (breakpoints: exact)", AT(quadrature)},
    {"solver", "nodes", CT_KEY_INTEGER, 3, 100000000, 0, NULL, "must satisfy 3 <= nodes <= 1e8",
     "64", "nodes of the composite rules", AT(nodes)},
    {"solver", "tolerance", CT_KEY_NUMBER, 0.0, 1e-3, 0, NULL, "must satisfy 0 < tolerance < 1e-3",
     "1e-14", "relative tolerance of the u_max solve (>= 1e-15)", AT(tolerance)},
    {"solver", "depth_tolerance", CT_KEY_NUMBER, 0.0, 1e-2, 0, NULL,
     "must satisfy 0 < depth_tolerance < 1e-2", "1e-12", "truncation bound of depth auto (Cantor)",
     AT(depth_tolerance)},
    {"solver", "threads", CT_KEY_INTEGER, 0, 1024, 0, NULL, "must satisfy 0 <= threads <= 1024",
     "0", "threads of the sums over rods (0: OMP_NUM_THREADS); results do not depend on it",
     AT(threads)},
    {"solver", "on_error", CT_KEY_WORD, 0, 0, 0, "stop|skip", "must be stop or skip", "stop",
     "skip: a failed impact is a row with its reason, not the end of the run", AT(on_error)},
    {"solver", "check", CT_KEY_WORD, 0, 0, 0, "auto|all|closed|none",
     "must be auto, all, closed or none", "auto",
     "impacts also in closed form rod by rod (e_closed_form, quadrature_error): auto every "
     "speed while rods x impacts x speeds <= 2^19, else a sample (the note says which), and in "
     "an ensemble the realisations whose index is a multiple of 8; all (or closed) every impact",
     AT(check)},
    {"solver", "path", CT_KEY_WORD, 0, 0, 0, "auto|curve|rods|lean",
     "must be auto, curve, rods or lean", "auto",
     "the load curve, Newton on the rods' closed forms (no curve in memory), or the lean curve "
     "(its sorted events: same results, about a sixth of the memory)",
     AT(path)},
    {"table", "tolerance", CT_KEY_NUMBER, 1e-13, 0.5, CT_KEY_LO_CLOSED, NULL,
     "must satisfy 1e-13 <= tolerance < 0.5", "1e-6",
     "largest |e_table - e| at every checked point (cantact table)", AT(table_tolerance)},
    {"table", "V_star", CT_KEY_RANGE, 0, 0, 0, NULL, "", "the range of [impact]'s speeds",
     "the table's range of V*", AT(table_range)},
    {"table", "interpolation", CT_KEY_WORD, 0, 0, 0, "monotone_cubic|linear",
     "must be monotone_cubic or linear", "monotone_cubic", "in x = ln V*", AT(interpolation)},
    {"table", "max_nodes", CT_KEY_INTEGER, 2, 10000000, 0, NULL,
     "must satisfy 2 <= max_nodes <= 10000000", "100000", "the build fails rather than exceed it",
     AT(max_nodes)},
    {"table", "check_points", CT_KEY_INTEGER, 1, 1000, 0, NULL,
     "must satisfy 1 <= check_points <= 1000", "16", "points checked inside every interval",
     AT(check_points)},
    {"table", "quantiles", CT_KEY_SPEEDS, 0, 0, 0, NULL,
     "must be probabilities in (0, 1], increasing (a, b, c or from:to:count)",
     "0.01, 0.05, 0.1, ..., 0.9, 0.95, 0.99 (21)",
     "a table of samples (body.landings or [ensemble]): e at these probabilities beside the mean",
     AT(table_quantiles)},
    {"table", "grid", CT_KEY_INTEGER, 2, 1000000, 0, NULL, "must satisfy 2 <= grid <= 1000000",
     "2000",
     "a table of samples: the speeds, equally spaced in ln V*, every sample is computed and "
     "checked at",
     AT(table_grid)},
    {"table", "quantile_tolerance", CT_KEY_NUMBER, 1e-13, 0.5, CT_KEY_LO_CLOSED, NULL,
     "must satisfy 1e-13 <= quantile_tolerance < 0.5", "table.tolerance",
     "a table of samples: largest error of a quantile column at every checked point (each has "
     "a kink wherever two samples' e cross: far more than the mean)",
     AT(table_quantile_tolerance)},
    {"ensemble", "realisations", CT_KEY_INTEGER, 1, 1000000000, 0, NULL,
     "must satisfy 1 <= realisations <= 1e9", "",
     "realisations of a random surface (their statistics per speed)", AT(realisations)},
    {"ensemble", "split", CT_KEY_WORD, 0, 0, 0, "auto|realisations|rods",
     "must be auto, realisations or rods", "auto",
     "threads over whole realisations, or over one realisation's rods", AT(split)},
};
#undef AT
#define NRUN (sizeof run_keys / sizeof run_keys[0])

const ct_key *ct_run_keys_table(size_t *n)
{
    *n = NRUN;
    return run_keys;
}

void ct_run_keys_defaults(ct_run_keys *k)
{
    memset(k, 0, sizeof *k);
    k->impacts = 1;
    k->gravity = 9.81;
    k->nodes = 64;
    k->tolerance = 1e-14;
    k->depth_tolerance = 1e-12;
    k->table_tolerance = 1e-6;
    k->max_nodes = 100000;
    k->check_points = 16;
    k->table_grid = 2000;
}

void ct_run_keys_clear(ct_run_keys *k)
{
    for (size_t r = 0; r < NRUN; r++)
        ct_key_clear(&run_keys[r], k);
}

int ct_run_keys_solver(const ct_run_keys *k, ct_run_solver *out)
{
    CT_NEED(k);
    CT_NEED(out);
    /* the row's range says < 1e-3; below 1e-15 no double precision solve can meet it */
    if (!(k->tolerance >= 1e-15))
        return ct_error_set(CT_EINVAL, "must be >= 1e-15 (double precision)");
    ct_impact_opts_default(&out->opts);
    out->opts.rule = (ct_quad_rule)k->quadrature;
    out->opts.nodes = (size_t)k->nodes;
    out->opts.tolerance = k->tolerance;
    out->opts.check = k->check == 0 ? CT_CHECK_AUTO : k->check == 3 ? CT_CHECK_NONE : CT_CHECK_ALL;
    out->path = (ct_sweep_path)k->path;
    out->threads = (int)k->threads;
    out->skip_failed = k->on_error == 1;
    out->depth_tolerance = k->depth_tolerance;
    return CT_OK;
}
