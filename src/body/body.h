/* The seam between bodies and everything else: a body is one descriptor (its name, how it
 * measures the distance from its apex to a rod's footprint, what surface carries it); body.c
 * keeps the registry and shifts each rod's top by the face's gap. Nothing else asks which
 * body struck the rods. */
#ifndef CT_BODY_H
#define CT_BODY_H

#include "internal.h"

#include <stdio.h>

typedef struct {
    const char *name;
    const char *summary; /* one line */
    /* 0: the face is flat (no footprint is read, the rods are left as built); 1: the gap
     * depends on the distance along x (the axis lies across a line surface); 2: on the
     * distance in the plane (an areal surface) */
    int dims;
    /* what the body needs of a surface, said when one cannot carry it */
    const char *needs;
} ct_body_kind;

extern const ct_body_kind ct_body_flat, ct_body_cylinder, ct_body_sphere;

/* The rods of *b as the body meets them: each rod's top shifted by the face's gap at its
 * footprint, the rods the face cannot reach before the layer crushes left out (counted in
 * info->omitted), the layer's H* the new crushed limit. A flat body leaves *b as it is.
 * sc: the surface's scales (the rods' units against the body's). */
int ct_body_apply(const ct_body *body, const ct_scales *sc, ct_bundle **b, ct_plan_info *info);
/* what = profile of rods a curved body met: each rod's footprint [the surface's length unit],
 * its top on the surface, the face's gap there, area, length and residual top on the surface
 * after the impacts, top + plastic strain x length (in h0 and l0). CT_EINVAL when b was not
 * met by a curved body. */
int ct_body_write_rods(const ct_bundle *b, const ct_scales *sc, FILE *f);
/* A surface prepared for many apexes of one curved body (landings): the checks, the extent,
 * the copies of a periodic surface and the rods read once; b must outlive it and not change.
 * Meeting it at an apex reads b only: threads may meet one site at once. */
typedef struct ct_body_site ct_body_site;
int ct_body_site_new(const ct_body *body, const ct_scales *sc, const ct_bundle *b,
                     ct_body_site **out);
void ct_body_site_free(ct_body_site *s);
/* ct_body_landing_region of the site's surface. */
int ct_body_site_region(const ct_body_site *s, double lo[2], double hi[2]);
/* The rods as the body meets them with its apex at pos [the body's length unit; pos[1] unused
 * on a line] into *out, as ct_body_apply with that position would make them. */
int ct_body_site_meet(const ct_body_site *s, const double pos[2], ct_bundle **out);

/* 1 when body is a curved one (it shifts the rods' tops), 0 for the flat strip or NULL. */
int ct_body_curved(const ct_body *body);
/* 1 when b's rods were met by a curved body (their tops shifted). */
int ct_body_met(const ct_bundle *b);

#endif
