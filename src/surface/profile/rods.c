/* Measured surfaces (docs/model.md §9): a line profile z(x_j) or a grid z(x_i, y_j) as rods.
 *
 * After levelling, the plane touches the highest point; sample j is a rod with top depth
 * t_j = max z - z_j and length H* - t_j. Its area: on a line, its share of the x-axis (the
 * half-distances to its two neighbours; an end sample the distance to its one neighbour, so
 * that uniform sampling gives every sample dx); on a grid, the pixel dx dy. Invalid grid
 * points (NaN) are left out. The x-order of the rods does not matter to P(u) (a Winkler
 * bundle): only the bearing-area curve does. */
#include "profile.h"

#include <stddef.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    ct_profile *p; /* a copy of the positions (for rod info) */
    size_t *index; /* rod k is sample index[k] (NULL: sample k, every sample valid) */
} profile_meta;

static void profile_meta_free(void *m)
{
    profile_meta *pm = m;
    if (!pm)
        return;
    ct_profile_free(pm->p);
    free(pm->index);
    free(pm);
}

/* The metadata: the profile's positions (no heights) times `position` (the unit they are
 * built in) and each rod's sample; with_index: an index (copied from index when not NULL),
 * else rod k is sample k. */
static profile_meta *meta_new(const ct_profile *p, int with_index, const size_t *index,
                              double position)
{
    profile_meta *pm = calloc(1, sizeof *pm);
    if (!pm || (with_index && !(pm->index = malloc((p->n ? p->n : 1) * sizeof(size_t)))) ||
        !(pm->p = calloc(1, sizeof *pm->p))) {
        profile_meta_free(pm);
        return NULL;
    }
    *pm->p = *p;
    pm->p->z = NULL;
    pm->p->x = NULL;
    if (p->x && !(pm->p->x = malloc(p->nx * sizeof(double)))) {
        profile_meta_free(pm);
        return NULL;
    }
    if (p->x)
        for (size_t j = 0; j < p->nx; j++)
            pm->p->x[j] = p->x[j] * position;
    pm->p->dx = p->dx * position;
    pm->p->dy = p->dy * position;
    if (with_index && index)
        memcpy(pm->index, index, p->n * sizeof(size_t));
    return pm;
}

static void *profile_meta_clone(const void *m)
{
    const profile_meta *src = m;
    return meta_new(src->p, src->index != NULL, src->index, 1.0);
}

static void profile_rod_info(const void *m, size_t k, ct_rod_info *info)
{
    const profile_meta *pm = m;
    const ct_profile *p = pm->p;
    const size_t j = pm->index ? pm->index[k] : k;
    info->stage = -1;
    if (p->ny > 1) { /* a pixel: the rectangle of one increment each way about its sample */
        const double x = (double)(j % p->nx) * p->dx, y = (double)(j / p->nx) * p->dy;
        info->x_left = x - 0.5 * p->dx;
        info->x_right = x + 0.5 * p->dx;
        info->footprint = (ct_footprint){CT_FOOTPRINT_RECTANGLE, info->x_left, info->x_right,
                                         y - 0.5 * p->dy, y + 0.5 * p->dy};
        return;
    }
    double x = p->x ? p->x[j] : (double)j * p->dx;
    double left = j == 0 ? ct_profile_share(p, 0) : (p->x ? 0.5 * (x - p->x[j - 1]) : 0.5 * p->dx);
    double right = j == p->nx - 1 ? 0.0 : (p->x ? 0.5 * (p->x[j + 1] - x) : 0.5 * p->dx);
    if (j == p->nx - 1)
        right = ct_profile_share(p, j) - (p->x ? 0.5 * (x - p->x[j - 1]) : 0.5 * p->dx);
    if (j == 0)
        left = ct_profile_share(p, 0) - right;
    info->x_left = x - left;
    info->x_right = x + right;
}

/* A grid repeats with its whole extent, nx dx by ny dy, whatever points along its edges are
 * invalid (its pixels' footprints then span less); a line's footprints span its period. */
static int profile_period(const void *m, double *x, double *y)
{
    const ct_profile *p = ((const profile_meta *)m)->p;
    if (p->ny < 2)
        return 0;
    *x = (double)p->nx * p->dx;
    *y = (double)p->ny * p->dy;
    return 1;
}

static const ct_rod_meta_kind profile_kind = {
    "profile", profile_rod_info, profile_meta_clone, profile_meta_free, NULL, profile_period};

int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar)
{
    CT_NEED(out);
    CT_NEED(p);
    *out = NULL;
    ct_profile_stats s;
    int st = ct_profile_stats_of(p, &s);
    if (st)
        return st;
    return ct_profile_bundle_of(out, p, &s, E, sigma_y, Hstar, 0, NULL);
}

/* Rod k of sample j: its top below the highest point, its length, its area, no plastic strain;
 * in the units u (H* in them already). */
static inline void rod_of(const ct_profile *p, size_t j, double zmax, double Hstar, size_t k,
                          const ct_build_units *u, double *top, double *length, double *area,
                          double *eps_p)
{
    top[k] = (zmax - p->z[j]) * u->length;
    length[k] = Hstar - top[k];
    area[k] = ct_profile_share(p, j) * u->area;
    eps_p[k] = 0.0;
}

/* The areas' extremes (a grid's pixels: one). */
static void share_range(const ct_profile *p, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = 0.0;
    for (size_t j = 0; j < (p->ny > 1 ? 1 : p->nx); j++) {
        const double a = ct_profile_share(p, j);
        *lo = a < *lo ? a : *lo;
        *hi = a > *hi ? a : *hi;
    }
}

int ct_profile_bundle_of(ct_bundle **out, const ct_profile *p, const ct_profile_stats *sp, double E,
                         double sigma_y, double Hstar, int threads, const ct_build_units *units)
{
    const ct_profile_stats s = *sp;
    int st;
    if (!(s.Rt > 0.0))
        return ct_error_set(CT_EINVAL, "profile: all heights are equal (peak to valley 0): a "
                                       "flat surface has no asperities to model");
    if (!isfinite(Hstar) || !(Hstar > s.Rt))
        return ct_error_set(CT_EINVAL,
                            "H* = %g: must exceed the profile's peak-to-valley depth Rt = %g "
                            "(the deepest rod needs a length)",
                            Hstar, s.Rt);
    const ct_build_units given = {1.0, 1.0, 1.0, 1.0}, *u = units ? units : &given;
    const ct_layer G = {.E = E, .sigma_y = sigma_y, .Hstar = Hstar, .l0 = s.length, .h0 = s.Rt};
    ct_layer L;
    if ((st = ct_layer_built(&G, u, &L)))
        return st;
    /* the rods' stiffness and energy scale at their extremes: the shortest (H* - Rt) and
     * longest (H*) with the smallest and largest area */
    double a_lo, a_hi;
    share_range(p, &a_lo, &a_hi);
    const double L_lo = L.Hstar - L.h0, s_lo = a_lo * u->area, s_hi = a_hi * u->area;
    if ((st = ct_rod_representable(&L, L.h0, L_lo, s_hi, "the deepest, widest rod")) ||
        (st = ct_rod_representable(&L, L.h0, L_lo, s_lo, "the deepest, narrowest rod")) ||
        (st = ct_rod_representable(&L, 0.0, L.Hstar, s_hi, "the highest, widest rod")) ||
        (st = ct_rod_representable(&L, 0.0, L.Hstar, s_lo, "the highest, narrowest rod")))
        return st;
    const size_t total = p->nx * p->ny;
    double zmax = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j]) && p->z[j] > zmax)
            zmax = p->z[j];
    profile_meta *pm = meta_new(p, p->n < total, NULL, u->position); /* no index: all valid */
    if (!pm)
        return ct_error_set(CT_ENOMEM, "profile rods: out of memory");
    ct_bundle *b;
    if ((st = ct_bundle_create(&b, &L, p->n, "profile rods"))) {
        profile_meta_free(pm);
        return st;
    }
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(b, &top, &length, &area, &eps_p);
    if (!pm->index) { /* every sample a rod, rod k sample k: the arrays' first touch (the
                         kernel's clearing of their pages) shared among threads */
        const int team = total < LEVEL_TEAM_MIN ? 1 : threads > 0 ? threads : ct_default_threads();
        (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
        for (size_t c = 0; c < (total + LEVEL_CHUNK - 1) / LEVEL_CHUNK; c++) {
            const size_t j1 = (c + 1) * LEVEL_CHUNK < total ? (c + 1) * LEVEL_CHUNK : total;
            for (size_t j = c * LEVEL_CHUNK; j < j1; j++)
                rod_of(p, j, zmax, L.Hstar, j, u, top, length, area, eps_p);
        }
        ct_bundle_set_surface(b, &profile_kind, pm, p->invalid);
        *out = b;
        return CT_OK;
    }
    size_t k = 0;
    for (size_t j = 0; j < total; j++) {
        if (isnan(p->z[j]))
            continue;
        rod_of(p, j, zmax, L.Hstar, k, u, top, length, area, eps_p);
        if (pm->index)
            pm->index[k] = j;
        k++;
    }
    ct_bundle_set_surface(b, &profile_kind, pm, p->invalid);
    *out = b;
    return CT_OK;
}
