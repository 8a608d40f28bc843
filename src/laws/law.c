/* The impact under the paper's laws (docs/model.md §7, Eqs. 39-41): the series or the
 * asymptotic law, chosen by name; e refused where a law's approximations give W_unload > W_load. */
#include "internal.h"

#include <math.h>

const char *ct_law_name(ct_law law)
{
    switch (law) {
    case CT_LAW_SERIES:
        return "series";
    case CT_LAW_ASYMPTOTIC:
        return "asymptotic";
    case CT_LAW_ASYMPTOTIC_CONSISTENT:
        return "asymptotic_consistent";
    }
    return NULL;
}

int ct_law_impact(const ct_params *p, ct_law law, double W, double *u_max, double *e)
{
    CT_NEED(u_max);
    CT_NEED(e);
    int st;
    if ((st = ct_params_validate(p)))
        return st;
    if (!isfinite(W) || !(W > 0.0))
        return ct_error_set(CT_EINVAL, "impact energy %g: must be finite and > 0", W);
    switch (law) {
    case CT_LAW_SERIES:
        st = ct_series_impact(p, W, u_max, e);
        break;
    case CT_LAW_ASYMPTOTIC:
        st = ct_asym_impact(p, 0, W, u_max, e);
        break;
    case CT_LAW_ASYMPTOTIC_CONSISTENT:
        st = ct_asym_impact(p, 1, W, u_max, e);
        break;
    default:
        return ct_error_set(CT_EINVAL, "law %d: unknown", (int)law);
    }
    if (st)
        return st;
    /* The laws' unloading is not the loading's exact elastic part (h_i << H* in the elastic
     * terms, Eq. 38's branches): where that approximation breaks, W_unload can exceed W_load.
     * Such an e is not a coefficient of restitution: refuse it rather than print it. */
    if (!(*e <= 1.0 + 1e-12))
        return ct_error_set(CT_ERANGE,
                            "the %s law gives W_unload > W_load (e = %.6g) at H*/h0 = %g, "
                            "E/sigma_y = %g: its approximations do not hold here",
                            ct_law_name(law), *e, p->Hstar / p->h0, p->E / p->sigma_y);
    if (*e > 1.0)
        *e = 1.0; /* rounding of two equal energies */
    return CT_OK;
}
