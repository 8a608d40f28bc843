/* Measured surfaces (MODEL.md §9): a line profile z(x_j) or a grid z(x_i, y_j) as rods.
 *
 * After levelling, the plane touches the highest point; sample j is a rod with top depth
 * t_j = max z - z_j and length H* - t_j. Its area: on a line, its share of the x-axis (the
 * half-distances to its two neighbours; an end sample the distance to its one neighbour, so
 * that uniform sampling gives every sample dx); on a grid, the pixel dx dy. Invalid grid
 * points (NaN) are left out. The x-order of the rods does not matter to P(u) (a Winkler
 * bundle): only the bearing-area curve does. */
#include "internal.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void ct_profile_free(ct_profile *p)
{
    if (!p)
        return;
    free(p->x);
    free(p->z);
    free(p);
}

static int check_heights(const ct_profile *p)
{
    if (p->n < 3)
        return ct_error_set(CT_EINVAL, "profile: %zu valid points: needs at least 3", p->n);
    return CT_OK;
}

static int check_line(size_t n, const double *x, double dx, const double *z)
{
    if (n < 3)
        return ct_error_set(CT_EINVAL, "profile: %zu points: needs at least 3", n);
    if (!x && !(isfinite(dx) && dx > 0.0))
        return ct_error_set(CT_EINVAL, "profile: spacing dx = %g: must be finite and > 0", dx);
    for (size_t j = 0; j < n; j++) {
        if (!isfinite(z[j]))
            return ct_error_set(CT_EINVAL, "profile: point %zu: height %g is not finite", j, z[j]);
        if (x && (!isfinite(x[j]) || (j && !(x[j] > x[j - 1]))))
            return ct_error_set(
                CT_EINVAL, "profile: point %zu: x = %g is not finite or not increasing", j, x[j]);
    }
    return CT_OK;
}

int ct_profile_adopt_line(ct_profile **out, size_t n, double *x, double dx, double *z)
{
    *out = NULL;
    int st = check_line(n, x, dx, z);
    if (st)
        return st;
    ct_profile *p = calloc(1, sizeof *p);
    if (!p)
        return ct_error_set(CT_ENOMEM, "profile of %zu points: out of memory", n);
    p->z = z;
    p->x = x;
    p->n = p->nx = n;
    p->ny = 1;
    p->dx = x ? 0.0 : dx;
    snprintf(p->source, sizeof p->source, "arrays");
    p->x_unit = p->z_unit = 1.0;
    *out = p;
    return CT_OK;
}

int ct_profile_from_line(ct_profile **out, size_t n, const double *x, double dx, const double *z)
{
    CT_NEED(out);
    CT_NEED(z);
    *out = NULL;
    int st = check_line(n, x, dx, z);
    if (st)
        return st;
    double *zc = malloc(n * sizeof(double)), *xc = x ? malloc(n * sizeof(double)) : NULL;
    if (!zc || (x && !xc)) {
        free(zc);
        free(xc);
        return ct_error_set(CT_ENOMEM, "profile of %zu points: out of memory", n);
    }
    memcpy(zc, z, n * sizeof(double));
    if (x)
        memcpy(xc, x, n * sizeof(double));
    if ((st = ct_profile_adopt_line(out, n, xc, dx, zc))) {
        free(zc);
        free(xc);
    }
    return st;
}

int ct_profile_adopt_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy, double *z)
{
    *out = NULL;
    if (!(isfinite(dx) && dx > 0.0 && isfinite(dy) && dy > 0.0))
        return ct_error_set(CT_EINVAL, "grid: spacings %g, %g: must be finite and > 0", dx, dy);
    if (nx < 1 || ny < 1 || nx > SIZE_MAX / ny / sizeof(double))
        return ct_error_set(CT_EINVAL, "grid of %zu x %zu points: not a size", nx, ny);
    size_t invalid = 0;
    for (size_t k = 0; k < nx * ny; k++)
        invalid += !isfinite(z[k]);
    if (nx * ny - invalid < 3)
        return ct_error_set(CT_EINVAL, "profile: %zu valid points: needs at least 3",
                            nx * ny - invalid);
    ct_profile *p = calloc(1, sizeof *p);
    if (!p)
        return ct_error_set(CT_ENOMEM, "grid of %zu x %zu points: out of memory", nx, ny);
    for (size_t k = 0; k < nx * ny; k++)
        if (!isfinite(z[k]))
            z[k] = NAN;
    p->z = z;
    p->nx = nx;
    p->ny = ny;
    p->dx = dx;
    p->dy = dy;
    p->invalid = invalid;
    p->n = nx * ny - invalid;
    snprintf(p->source, sizeof p->source, "arrays");
    p->x_unit = p->z_unit = 1.0;
    *out = p;
    return CT_OK;
}

int ct_profile_from_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy,
                         const double *z)
{
    CT_NEED(out);
    CT_NEED(z);
    *out = NULL;
    if (nx < 1 || ny < 1 || nx > SIZE_MAX / ny / sizeof(double))
        return ct_error_set(CT_EINVAL, "grid of %zu x %zu points: not a size", nx, ny);
    double *zc = malloc(nx * ny * sizeof(double));
    if (!zc)
        return ct_error_set(CT_ENOMEM, "grid of %zu x %zu points: out of memory", nx, ny);
    memcpy(zc, z, nx * ny * sizeof(double));
    int st = ct_profile_adopt_grid(out, nx, ny, dx, dy, zc);
    if (st)
        free(zc);
    return st;
}

/* Sample j's area [length or length^2] (MODEL.md §9). */
static double share(const ct_profile *p, size_t j)
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

static double x_of(const ct_profile *p, size_t j)
{
    if (p->ny > 1)
        return (double)(j % p->nx) * p->dx;
    return p->x ? p->x[j] : (double)j * p->dx;
}

static double y_of(const ct_profile *p, size_t j)
{
    return p->ny > 1 ? (double)(j / p->nx) * p->dy : 0.0;
}

int ct_profile_level(ct_profile *p, ct_detrend how)
{
    CT_NEED(p);
    int st = check_heights(p);
    if (st)
        return st;
    if (how == CT_DETREND_NONE)
        return CT_OK;
    if (how < CT_DETREND_NONE || how > CT_DETREND_QUADRATIC)
        return ct_error_set(CT_EINVAL, "detrend %d: must be none, mean, linear or quadratic",
                            (int)how);
    /* least squares in centred, scaled coordinates (s, r in about [-1, 1]): the normal
     * equations of at most 6 terms stay well conditioned; solved by LU (GSL) */
    const int grid = p->ny > 1;
    const size_t total = p->nx * p->ny;
    double xm = 0.0, ym = 0.0, xs = 0.0, ys = 0.0;
    size_t n = 0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            xm += x_of(p, j);
            ym += y_of(p, j);
            n++;
        }
    xm /= (double)n;
    ym /= (double)n;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            xs = fmax(xs, fabs(x_of(p, j) - xm));
            ys = fmax(ys, fabs(y_of(p, j) - ym));
        }
    xs = xs > 0.0 ? xs : 1.0;
    ys = ys > 0.0 ? ys : 1.0;
    /* terms: 1 | s, (r) | s^2, (s r, r^2) */
    int m = how == CT_DETREND_MEAN ? 1 : how == CT_DETREND_LINEAR ? (grid ? 3 : 2) : (grid ? 6 : 3);
    double A[36] = {0}, bvec[6] = {0}, f[6];
    for (size_t j = 0; j < total; j++) {
        if (isnan(p->z[j]))
            continue;
        const double s = (x_of(p, j) - xm) / xs, r = (y_of(p, j) - ym) / ys;
        f[0] = 1.0;
        if (grid) {
            f[1] = s, f[2] = r, f[3] = s * s, f[4] = s * r, f[5] = r * r;
        } else {
            f[1] = s, f[2] = s * s;
        }
        for (int a = 0; a < m; a++) {
            bvec[a] += f[a] * p->z[j];
            for (int c = 0; c < m; c++)
                A[a * m + c] += f[a] * f[c];
        }
    }
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)m, (size_t)m);
    gsl_vector_view bv = gsl_vector_view_array(bvec, (size_t)m);
    double coef[6];
    gsl_vector_view cv = gsl_vector_view_array(coef, (size_t)m);
    gsl_permutation *perm = gsl_permutation_alloc((size_t)m);
    int sign;
    if (!perm)
        return ct_error_set(CT_ENOMEM, "levelling: out of memory");
    /* a singular matrix: LU_decomp succeeds with a zero pivot; the determinant says so
     * before LU_solve would report it through GSL's process-wide error handler */
    int g1 = gsl_linalg_LU_decomp(&Av.matrix, perm, &sign);
    double det = g1 ? 0.0 : gsl_linalg_LU_det(&Av.matrix, sign);
    int g2 = g1 || det == 0.0 ? 1 : gsl_linalg_LU_solve(&Av.matrix, perm, &bv.vector, &cv.vector);
    gsl_permutation_free(perm);
    if (g2)
        return ct_error_set(CT_EINVAL,
                            "levelling: the %s fit is singular (the points do not span it)",
                            how == CT_DETREND_LINEAR ? "linear" : "quadratic");
    for (size_t j = 0; j < total; j++) {
        if (isnan(p->z[j]))
            continue;
        const double s = (x_of(p, j) - xm) / xs, r = (y_of(p, j) - ym) / ys;
        f[0] = 1.0;
        if (grid) {
            f[1] = s, f[2] = r, f[3] = s * s, f[4] = s * r, f[5] = r * r;
        } else {
            f[1] = s, f[2] = s * s;
        }
        double t = 0.0;
        for (int a = 0; a < m; a++)
            t += coef[a] * f[a];
        p->z[j] -= t;
    }
    return CT_OK;
}

int ct_profile_stats_of(const ct_profile *p, ct_profile_stats *s)
{
    CT_NEED(p);
    CT_NEED(s);
    int st = check_heights(p);
    if (st)
        return st;
    const size_t total = p->nx * p->ny;
    double w = 0.0, zw = 0.0, lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = share(p, j);
            w += a;
            zw += a * p->z[j];
            lo = p->z[j] < lo ? p->z[j] : lo;
            hi = p->z[j] > hi ? p->z[j] : hi;
        }
    const double mean = zw / w;
    double ra = 0.0, rq = 0.0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = share(p, j), d = p->z[j] - mean;
            ra += a * fabs(d);
            rq += a * d * d;
        }
    s->mean = mean;
    s->Ra = ra / w;
    s->Rq = sqrt(rq / w);
    s->Rt = hi - lo;
    s->length = w;
    return CT_OK;
}

int ct_profile_trim(ct_profile *p, double k, size_t *clipped)
{
    CT_NEED(p);
    CT_NEED(clipped);
    *clipped = 0;
    if (!isfinite(k) || !(k > 0.0))
        return ct_error_set(CT_EINVAL, "trim: k = %g: must be finite and > 0", k);
    ct_profile_stats s;
    int st = ct_profile_stats_of(p, &s);
    if (st)
        return st;
    const double cut = s.mean + k * s.Rq;
    for (size_t j = 0; j < p->nx * p->ny; j++)
        if (!isnan(p->z[j]) && p->z[j] > cut) {
            p->z[j] = cut;
            (*clipped)++;
        }
    return CT_OK;
}

/* ---- the rods ---- */

typedef struct {
    ct_profile *p; /* a copy of the positions (for rod info) */
    size_t *index; /* rod k is sample index[k] */
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

/* The metadata: the profile's positions (no heights) and each rod's sample. */
static profile_meta *meta_new(const ct_profile *p, const size_t *index)
{
    profile_meta *pm = calloc(1, sizeof *pm);
    if (!pm || !(pm->index = malloc((p->n ? p->n : 1) * sizeof(size_t))) ||
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
        memcpy(pm->p->x, p->x, p->nx * sizeof(double));
    if (index)
        memcpy(pm->index, index, p->n * sizeof(size_t));
    return pm;
}

static void *profile_meta_clone(const void *m)
{
    const profile_meta *src = m;
    return meta_new(src->p, src->index);
}

static void profile_rod_info(const void *m, size_t k, ct_rod_info *info)
{
    const profile_meta *pm = m;
    const ct_profile *p = pm->p;
    const size_t j = pm->index[k];
    info->stage = -1;
    if (p->ny > 1) { /* a pixel: its x; the extent in x of its column */
        double x = (double)(j % p->nx) * p->dx;
        info->x_left = x - 0.5 * p->dx;
        info->x_right = x + 0.5 * p->dx;
        return;
    }
    double x = p->x ? p->x[j] : (double)j * p->dx;
    double left = j == 0 ? share(p, 0) : (p->x ? 0.5 * (x - p->x[j - 1]) : 0.5 * p->dx);
    double right = j == p->nx - 1 ? 0.0 : (p->x ? 0.5 * (p->x[j + 1] - x) : 0.5 * p->dx);
    if (j == p->nx - 1)
        right = share(p, j) - (p->x ? 0.5 * (x - p->x[j - 1]) : 0.5 * p->dx);
    if (j == 0)
        left = share(p, 0) - right;
    info->x_left = x - left;
    info->x_right = x + right;
}

static const ct_surface_kind profile_kind = {"profile", profile_rod_info, profile_meta_clone,
                                             profile_meta_free};

int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar)
{
    CT_NEED(out);
    CT_NEED(p);
    *out = NULL;
    ct_profile_stats s;
    int st = ct_profile_stats_of(p, &s);
    if (st)
        return st;
    if (!(s.Rt > 0.0))
        return ct_error_set(CT_EINVAL, "profile: all heights are equal (peak to valley 0): a "
                                       "flat surface has no asperities to model");
    if (!isfinite(Hstar) || !(Hstar > s.Rt))
        return ct_error_set(CT_EINVAL,
                            "H* = %g: must exceed the profile's peak-to-valley depth Rt = %g "
                            "(the deepest rod needs a length)",
                            Hstar, s.Rt);
    ct_layer L = {.E = E, .sigma_y = sigma_y, .Hstar = Hstar, .l0 = s.length, .h0 = s.Rt};
    if ((st = ct_layer_validate(&L)))
        return st;
    const size_t total = p->nx * p->ny;
    double zmax = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j]) && p->z[j] > zmax)
            zmax = p->z[j];
    profile_meta *pm = meta_new(p, NULL);
    if (!pm)
        return ct_error_set(CT_ENOMEM, "profile rods: out of memory");
    ct_bundle *b;
    if ((st = ct_bundle_create(&b, &L, p->n, "profile rods"))) {
        profile_meta_free(pm);
        return st;
    }
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(b, &top, &length, &area, &eps_p);
    size_t k = 0;
    for (size_t j = 0; j < total; j++) {
        if (isnan(p->z[j]))
            continue;
        top[k] = zmax - p->z[j];
        length[k] = Hstar - top[k];
        area[k] = share(p, j);
        eps_p[k] = 0.0;
        pm->index[k++] = j;
    }
    ct_bundle_set_surface(b, &profile_kind, pm, p->invalid);
    *out = b;
    return CT_OK;
}

/* ---- the bearing-area curve ---- */

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
            tw[k].w = share(p, j);
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
    int st = check_heights(p);
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
