/* The output columns of a sweep's rows as data: their names (the CSV header and Python's
 * attributes), units, formats and where each value sits in ct_sweep_row. The CLI writes its
 * e table and the time columns from this table; the Python module reads its fields from it. */
#include "internal.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define R(field) offsetof(ct_sweep_row, r.field)
#define D(field) offsetof(ct_sweep_row, dyn.field)

static const ct_column columns[] = {
    {"impact", "e", CT_UNIT_COUNT, 'l', 17, NULL, 1.0, offsetof(ct_sweep_row, impact),
     "the impact's number on the same spot (1: the virgin surface)"},
    {"V_star", "e", CT_UNIT_ONE, 'd', 17, NULL, 1.0, offsetof(ct_sweep_row, V_star),
     "the speed, V* = sqrt(m v^2 / (2 l0 E h0))"},
    {"u_max_over_h0", "e", CT_UNIT_LENGTH, 'd', 17, NULL, 1.0, R(u_max),
     "the deepest displacement (Eq. 39)"},
    {"e", "e", CT_UNIT_ONE, 'd', 17, NULL, 1.0, R(e),
     "the coefficient of restitution sqrt(W_unload / W_load)"},
    {"e_closed_form", "e", CT_UNIT_ONE, 'd', 17, NULL, 1.0, R(e_closed),
     "e from the closed forms rod by rod (empty: unchecked, solver.check = none or outside auto's "
     "sample)"},
    {"quadrature_error", "e", CT_UNIT_ONE, 'd', 3, NULL, 1.0, R(quad_error), "|e - e_closed_form|"},
    {"V_star_crit", "e", CT_UNIT_ONE, 'd', 17, NULL, 1.0, R(V_star_crit),
     "the critical V* of the state struck: below it e = 1"},
    {"u_release_over_h0", "e", CT_UNIT_LENGTH, 'd', 17, NULL, 1.0, R(u_release),
     "where the body leaves the surface"},
    {"elastic", "e", CT_UNIT_COUNT, 'i', 17, NULL, 1.0, R(elastic),
     "1 when no rod yielded (e = 1 exactly)"},
    {"u_contact_over_h0", "row", CT_UNIT_LENGTH, 'd', 17, NULL, 1.0, R(u_contact),
     "first contact of the state struck"},
    {"W_load_over_PY_h0", "row", CT_UNIT_ENERGY, 'd', 17, NULL, 1.0, R(W_load),
     "the loading work (Eq. 39)"},
    {"W_unload_over_PY_h0", "row", CT_UNIT_ENERGY, 'd', 17, NULL, 1.0, R(W_unload),
     "the unloading work (Eq. 40)"},
    {"e_rounding", "row", CT_UNIT_ONE, 'd', 17, NULL, 1.0, R(e_rounding),
     "bound on e's rounding error from stiff rods"},
    {"t_contact_over_tau", "time", CT_UNIT_TIME, 'd', 17, "t_contact_s", 1.0, D(t_contact),
     "contact time, tau = sqrt(m h0 / (E l0))"},
    {"t_load_over_tau", "time", CT_UNIT_TIME, 'd', 17, "t_load_s", 1.0, D(t_load),
     "time to u_max (the peak force)"},
    {"t_unload_over_tau", "time", CT_UNIT_TIME, 'd', 17, "t_unload_s", 1.0, D(t_unload),
     "time from u_max to release"},
    {"P_peak_over_PY", "time", CT_UNIT_FORCE, 'd', 17, "P_peak_N_per_m", 1.0, D(P_peak),
     "the peak force P(u_max), P_Y = sigma_y l0"},
    {"e_kinematic", "time", CT_UNIT_ONE, 'd', 17, NULL, 1.0, D(e_kinematic),
     "v2 / v1 of the motion (checked equal to e)"},
    {"unload_period_over_tau", "time", CT_UNIT_TIME, 'd', 17, "unload_period_s", 1.0, D(period_min),
     "2 pi sqrt(m / k) of the stiffest unloading piece"},
    /* DEM codes resolve a contact with a time step a fraction of its period: LAMMPS and
     * LIGGGHTS users commonly take 1/20 to 1/50 of it */
    {"dem_time_step_over_tau", "time", CT_UNIT_TIME, 'd', 17, "dem_time_step_s", 50.0,
     D(period_min), "unload_period / 50: a DEM time step that resolves the contact"},
    /* with a mass and speeds, the e table carries the speeds themselves (in the scene's units:
     * m/s for SI scenes) */
    {"v_impact_over_h0_per_tau", "speed", CT_UNIT_SPEED, 'd', 17, "v_impact_m_per_s", 1.0,
     offsetof(ct_sweep_row, V_star), "the impact speed v1 = sqrt(2) V* h0 / tau"},
    {"v_rebound_over_h0_per_tau", "speed", CT_UNIT_SPEED, 'w', 17, "v_rebound_m_per_s", 1.0,
     offsetof(ct_sweep_row, V_star), "the rebound speed v2 = e v1"},
};
#undef R
#undef D

size_t ct_sweep_columns(const ct_column **cols)
{
    *cols = columns;
    return sizeof columns / sizeof columns[0];
}

/* The factor that makes a value of this unit dimensionless in a layer's units. */
static double unit_of(ct_unit u, const ct_layer *L)
{
    switch (u) {
    case CT_UNIT_LENGTH:
        return L->h0;
    case CT_UNIT_FORCE:
        return L->sigma_y * L->l0;
    case CT_UNIT_ENERGY:
        return L->sigma_y * L->l0 * L->h0;
    case CT_UNIT_SPEED:
        return 0.70710678118654752440; /* 1/sqrt(2): V* over it is sqrt(2) V*, v in h0/tau */
    default:
        return 1.0;
    }
}

static double raw(const ct_column *c, const ct_sweep_row *row)
{
    const char *at = (const char *)row + c->offset;
    if (c->type == 'l') {
        long x;
        memcpy(&x, at, sizeof x);
        return (double)x;
    }
    if (c->type == 'i') {
        int x;
        memcpy(&x, at, sizeof x);
        return (double)x;
    }
    double v;
    memcpy(&v, at, sizeof v);
    return c->type == 'w' ? v * row->r.e : v;
}

/* The value of column c of a row over u, its unit's factor (unit_of), then over its divisor:
 * the one formula of ct_column_value and ct_column_values. */
static double value_over(const ct_column *c, const ct_sweep_row *row, double u)
{
    const double v = raw(c, row);
    const double x = u == 1.0 ? v : v / u;
    return c->divisor == 1.0 ? x : x / c->divisor;
}

double ct_column_value(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer)
{
    return value_over(c, row, unit_of(c->unit, layer));
}

void ct_column_values(const ct_column *c, const ct_sweep_row *rows, size_t n, const ct_layer *layer,
                      double *out)
{
    const double u = unit_of(c->unit, layer);
    for (size_t k = 0; k < n; k++)
        out[k] = value_over(c, rows + k, u);
}

double ct_column_physical(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer,
                          const ct_layer *physical, double tau)
{
    const double u = unit_of(c->unit, layer), v = raw(c, row);
    const double x = u == 1.0 ? v : v / u;
    double y = x;
    switch (c->unit) {
    case CT_UNIT_LENGTH:
        y = x * physical->h0;
        break;
    case CT_UNIT_FORCE:
        y = x * physical->sigma_y * physical->l0;
        break;
    case CT_UNIT_ENERGY:
        y = x * physical->sigma_y * physical->l0 * physical->h0;
        break;
    case CT_UNIT_TIME:
        y = x * tau;
        break;
    case CT_UNIT_SPEED:
        y = x * physical->h0 / tau;
        break;
    default:
        break;
    }
    return c->divisor == 1.0 ? y : y / c->divisor;
}
