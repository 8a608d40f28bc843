/* The rod law of docs/model.md §3, for any displacement history (Eqs. 4-11).
 *
 * A rod has its top at depth `top` below the reference plane, length L = H* - top, area s,
 * and plastic strain eps_p (state, starts at 0). With strain eps = (u - top)/L (Eq. 4) the
 * elastic strain is d = eps - eps_p, and
 *   P = E s clamp(d, 0, eps_y)                      (Eqs. 5, 7, 8-9; no tension)
 *   on advancing to u: if d > eps_y then eps_p = eps - eps_y   (Eq. 10)
 * This reproduces yield at u_y = eps_y L + top (Eq. 6), the plateau (Eq. 7), the unloading
 * line (Eq. 11), loss of contact at top + eps_p L and elastic reloading. The hot loops of
 * bundle.c inline these. */
#ifndef CT_ROD_H
#define CT_ROD_H

/* Returns the elastic strain (dimensionless) at displacement u, may be negative. */
static inline double ct_rod_elastic_strain(double u, double top, double length,
                                           double plastic_strain)
{
    return (u - top) * (1.0 / length) - plastic_strain;
}

/* Returns the force [force] P = E s clamp(d, 0, eps_y). */
static inline double ct_rod_force(double u, double top, double length, double area,
                                  double plastic_strain, double E, double eps_y)
{
    double d = ct_rod_elastic_strain(u, top, length, plastic_strain);
    if (d <= 0.0)
        return 0.0;
    if (d > eps_y)
        d = eps_y;
    return E * area * d;
}

/* Returns the plastic strain after the rod is taken to displacement u (Eq. 10). */
static inline double ct_rod_advance(double u, double top, double length, double plastic_strain,
                                    double eps_y)
{
    double strain = (u - top) * (1.0 / length);
    if (strain - plastic_strain > eps_y)
        return strain - eps_y;
    return plastic_strain;
}

/* Antiderivative in u of the force at fixed state, divided by E s L, as a function of the
 * elastic strain d: 0 for d <= 0, d^2/2 up to eps_y, then eps_y d - eps_y^2/2. */
static inline double ct_rod_work_density(double d, double eps_y)
{
    if (d <= 0.0)
        return 0.0;
    if (d <= eps_y)
        return 0.5 * d * d;
    return eps_y * (d - 0.5 * eps_y);
}

/* Returns the work [energy] of the rod's force at its current state from u_a to u_b: the
 * work done when loading from u_a to u_b if u_a is at or below the rod's contact point,
 * W = E s L eps^2/2 (elastic) or E s L (eps_y eps - eps_y^2/2) (yielded) from virgin. */
static inline double ct_rod_work(double u_a, double u_b, double top, double length, double area,
                                 double plastic_strain, double E, double eps_y)
{
    double da = ct_rod_elastic_strain(u_a, top, length, plastic_strain);
    double db = ct_rod_elastic_strain(u_b, top, length, plastic_strain);
    return E * area * length * (ct_rod_work_density(db, eps_y) - ct_rod_work_density(da, eps_y));
}

/* Returns the recoverable elastic energy [energy] E s L min(d, eps_y)^2 / 2 at u. */
static inline double ct_rod_elastic_energy(double u, double top, double length, double area,
                                           double plastic_strain, double E, double eps_y)
{
    double d = ct_rod_elastic_strain(u, top, length, plastic_strain);
    if (d <= 0.0)
        return 0.0;
    if (d > eps_y)
        d = eps_y;
    return 0.5 * E * area * length * d * d;
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
