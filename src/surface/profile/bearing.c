/* The bearing-area curve of a measured surface (docs/model.md §9): the fraction of the
 * nominal area whose top lies within depth d of the highest point, each sample weighed by its
 * area. */
#include "profile.h"

#include <math.h>
#include <stdlib.h>

static int by_top(const void *a, const void *b)
{
    double x = ((const ct_top_weight *)a)->t, y = ((const ct_top_weight *)b)->t;
    return (x > y) - (x < y);
}

int ct_profile_sorted_tops(const ct_profile *p, ct_top_weight **out, double *wsum)
{
    const size_t total = p->nx * p->ny;
    double zmax = -INFINITY, w = 0.0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j]) && p->z[j] > zmax)
            zmax = p->z[j];
    ct_top_weight *tw = malloc(p->n * sizeof *tw);
    if (!tw)
        return ct_error_set(CT_ENOMEM, "bearing curve of %zu points: out of memory", p->n);
    size_t k = 0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            tw[k].t = zmax - p->z[j];
            tw[k].w = ct_profile_share(p, j);
            w += tw[k++].w;
        }
    qsort(tw, k, sizeof *tw, by_top);
    *out = tw;
    *wsum = w;
    return CT_OK;
}

int ct_profile_bearing(const ct_profile *p, size_t n, const double *d, double *phi)
{
    CT_NEED(p);
    if (n && (!d || !phi))
        return ct_error_set(CT_EINVAL, "bearing curve: NULL arrays for %zu depths", n);
    int st = ct_profile_check_heights(p);
    if (st)
        return st;
    ct_top_weight *tw;
    double W;
    if ((st = ct_profile_sorted_tops(p, &tw, &W)))
        return st;
    double acc = 0.0;
    size_t i = 0;
    for (size_t k = 0; k < n; k++) {
        if (k && d[k] < d[k - 1]) {
            free(tw);
            return ct_error_set(CT_EINVAL, "bearing curve: depths not ascending at %zu", k);
        }
        while (i < p->n && tw[i].t <= d[k])
            acc += tw[i++].w;
        phi[k] = i == p->n ? 1.0 : acc / W; /* every rod: 1, not a rounded sum */
    }
    free(tw);
    return CT_OK;
}
