/* The rod law of docs/model.md §3, for any displacement history (Eqs. 4-11).
 *
 * A rod has its top at depth `top` below the reference plane, length L = H* - top, area s,
 * and plastic strain eps_p (state, starts at 0). With strain eps = (u - top)/L (Eq. 4) the
 * elastic strain is d = eps - eps_p, and
 *   P = E s clamp(d, 0, eps_y)                      (Eqs. 5, 7, 8-9; no tension)
 *   on advancing to u: if d > eps_y then eps_p = eps - eps_y   (Eq. 10)
 * This reproduces yield at u_y = eps_y L + top (Eq. 6), the plateau (Eq. 7), the unloading
 * line (Eq. 11), loss of contact at top + eps_p L and elastic reloading.
 *
 * This header is the only statement of the law, in two forms built from the same pieces:
 * - the block form (ct_rod_clamp ... ct_rod_energy_of), for a loop over many displacements
 *   of one rod (bundle.c's multi-node kernels): it takes the rod's constants hoisted out of
 *   the loop (1/L, E s, E s L) and chooses between the law's cases by selects, so that such
 *   a loop vectorises;
 * - the scalar form (ct_rod_force ... ct_rod_yield), for one rod at one displacement (sums
 *   over rods): it chooses by branches, which a loop over rods predicts (rods come in runs
 *   of the same case), and returns at once for a rod out of contact, whose area it then
 *   does not read; selects would compute every case.
 * Both give bitwise the same values (a NaN displacement gives NaN; where the block form
 * gives -0 the scalar one gives +0, which no sum can tell apart). */
#ifndef CT_ROD_H
#define CT_ROD_H

/* ---- the pieces ---- */

/* Returns the total strain (u - top)/L, from 1/L (Eq. 4). */
static inline double ct_rod_total_strain(double u, double top, double inv_length)
{
    return (u - top) * inv_length;
}

/* Returns the elastic strain (dimensionless) at u, from 1/L; may be negative. */
static inline double ct_rod_strain(double u, double top, double inv_length, double plastic_strain)
{
    return ct_rod_total_strain(u, top, inv_length) - plastic_strain;
}

/* Returns the plastic strain after the rod is taken to total strain `strain` (Eq. 10). */
static inline double ct_rod_advanced(double strain, double plastic_strain, double eps_y)
{
    return strain - plastic_strain > eps_y ? strain - eps_y : plastic_strain;
}

/* The antiderivative in u of the force at fixed state, divided by E s L, as a function of
 * the elastic strain d > 0: d^2/2 up to eps_y (elastic), then eps_y d - eps_y^2/2 (plateau);
 * 0 for d <= 0. */
static inline double ct_rod_work_elastic(double d)
{
    return 0.5 * d * d;
}

static inline double ct_rod_work_plateau(double d, double eps_y)
{
    return eps_y * (d - 0.5 * eps_y);
}

/* ---- the block form ---- */

/* Returns the strain that carries force, clamp(d, 0, eps_y): 0 off contact (no tension; -0
 * for d = -0), eps_y on the plateau. */
static inline double ct_rod_clamp(double d, double eps_y)
{
    d = d < 0.0 ? 0.0 : d;
    return d > eps_y ? eps_y : d;
}

/* Returns the force [force] at elastic strain d of a rod of E s = Es. */
static inline double ct_rod_force_of(double d, double Es, double eps_y)
{
    return Es * ct_rod_clamp(d, eps_y);
}

/* Returns the work density (the antiderivative above) at elastic strain d. */
static inline double ct_rod_work_density(double d, double eps_y)
{
    const double w = d > eps_y ? ct_rod_work_plateau(d, eps_y) : ct_rod_work_elastic(d);
    return d <= 0.0 ? 0.0 : w;
}

/* Returns the recoverable elastic energy [energy] at elastic strain d of a rod of
 * E s L / 2 = half_EsL: E s L min(d, eps_y)^2 / 2. */
static inline double ct_rod_energy_of(double d, double half_EsL, double eps_y)
{
    const double c = ct_rod_clamp(d, eps_y);
    return half_EsL * c * c;
}

/* ---- the scalar form ---- */

/* Returns the elastic strain (dimensionless) at displacement u, may be negative. */
static inline double ct_rod_elastic_strain(double u, double top, double length,
                                           double plastic_strain)
{
    return ct_rod_strain(u, top, 1.0 / length, plastic_strain);
}

/* Returns the force [force] P = E s clamp(d, 0, eps_y). */
static inline double ct_rod_force(double u, double top, double length, double area,
                                  double plastic_strain, double E, double eps_y)
{
    const double d = ct_rod_elastic_strain(u, top, length, plastic_strain);
    if (d <= 0.0)
        return 0.0;
    return ct_rod_force_of(d, E * area, eps_y);
}

/* Returns the plastic strain after the rod is taken to displacement u (Eq. 10). */
static inline double ct_rod_advance(double u, double top, double length, double plastic_strain,
                                    double eps_y)
{
    return ct_rod_advanced(ct_rod_total_strain(u, top, 1.0 / length), plastic_strain, eps_y);
}

/* Returns ct_rod_work_density(d, eps_y), by branches. */
static inline double ct_rod_work_density_scalar(double d, double eps_y)
{
    if (d <= 0.0)
        return 0.0;
    if (d <= eps_y)
        return ct_rod_work_elastic(d);
    return ct_rod_work_plateau(d, eps_y);
}

/* Returns the work [energy] of the rod's force at its current state from u_a to u_b: the
 * work done when loading from u_a to u_b if u_a is at or below the rod's contact point,
 * W = E s L eps^2/2 (elastic) or E s L (eps_y eps - eps_y^2/2) (yielded) from virgin. */
static inline double ct_rod_work(double u_a, double u_b, double top, double length, double area,
                                 double plastic_strain, double E, double eps_y)
{
    const double da = ct_rod_elastic_strain(u_a, top, length, plastic_strain);
    const double db = ct_rod_elastic_strain(u_b, top, length, plastic_strain);
    return E * area * length *
           (ct_rod_work_density_scalar(db, eps_y) - ct_rod_work_density_scalar(da, eps_y));
}

/* Returns the recoverable elastic energy [energy] E s L min(d, eps_y)^2 / 2 at u. */
static inline double ct_rod_elastic_energy(double u, double top, double length, double area,
                                           double plastic_strain, double E, double eps_y)
{
    const double d = ct_rod_elastic_strain(u, top, length, plastic_strain);
    if (d <= 0.0)
        return 0.0;
    return ct_rod_energy_of(d, 0.5 * E * area * length, eps_y);
}

/* Returns the displacement [length] where the rod touches the plane: top + eps_p L. */
static inline double ct_rod_contact(double top, double length, double plastic_strain)
{
    return top + plastic_strain * length;
}

/* Returns the displacement [length] where the rod (re)yields: top + (eps_p + eps_y) L. */
static inline double ct_rod_yield(double top, double length, double plastic_strain, double eps_y)
{
    return top + (plastic_strain + eps_y) * length;
}

#endif
