/* What the files of the measured-surface kind share (src/surface/profile/): not public. */
#ifndef CT_SURFACE_PROFILE_H
#define CT_SURFACE_PROFILE_H

#include "internal.h"
#include "surface/kind.h"

/* Samples from which the levelled heights and the rods are filled by threads, in chunks of
 * LEVEL_CHUNK samples (the same values for any thread count). */
#define LEVEL_TEAM_MIN (1u << 18)
#define LEVEL_CHUNK (1u << 16)

/* ct_profile_read, a missing length unit's message ending "give <give>": the kind names its
 * keys ("surface.unit (m, mm, um or nm; ...)"), ct_profile_read "it (m, mm, um or nm)". */
int ct_profile_read_giving(const char *path, const ct_profile_read_opts *opts, const char *give,
                           ct_profile **out);
/* The heights' peak to valley (the raw heights' Rt: one pass, no statistics). */
double ct_profile_heights_span(const ct_profile *p);
/* ct_profile_bundle with p's statistics known (sp), filled on threads threads (0: the OpenMP
 * default), E, sigma_y and H* as given, built in units u (ct_build_units_of; NULL: as given):
 * tops and lengths, areas, stresses and the footprints' positions each times its unit. */
int ct_profile_bundle_of(ct_bundle **out, const ct_profile *p, const ct_profile_stats *sp, double E,
                         double sigma_y, double Hstar, int threads, const ct_build_units *u);
/* CT_OK when p has the 3 valid points every statistic and fit needs, else CT_EINVAL. */
int ct_profile_check_heights(const ct_profile *p);

/* Sample j's area [length or length^2] (docs/model.md §9). */
static inline double ct_profile_share(const ct_profile *p, size_t j)
{
    if (p->ny > 1)
        return p->dx * p->dy;
    if (!p->x)
        return p->dx;
    const size_t n = p->nx;
    if (j == 0)
        return p->x[1] - p->x[0];
    if (j == n - 1)
        return p->x[n - 1] - p->x[n - 2];
    return 0.5 * (p->x[j + 1] - p->x[j - 1]);
}

#endif
