/* Measured surfaces (docs/model.md §9): a line profile z(x_j) or a grid z(x_i, y_j) as rods.
 *
 * After levelling, the plane touches the highest point; sample j is a rod with top depth
 * t_j = max z - z_j and length H* - t_j. Its area: on a line, its share of the x-axis (the
 * half-distances to its two neighbours; an end sample the distance to its one neighbour, so
 * that uniform sampling gives every sample dx); on a grid, the pixel dx dy. Invalid grid
 * points (NaN) are left out. The x-order of the rods does not matter to P(u) (a Winkler
 * bundle): only the bearing-area curve does. */
#include "kind.h"
#include "number.h"

#include <gsl/gsl_errno.h>
#include <stddef.h>
#include <stdio.h>
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

/* Sample j's area [length or length^2] (docs/model.md §9). */
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

/* A sample's x and y along a pass over the samples in order, without a division per sample:
 * the sample's column i and row r (of a grid) are carried. */
typedef struct {
    size_t i, r;
} cursor;

static double x_at(const ct_profile *p, size_t j, const cursor *c)
{
    if (p->ny > 1)
        return (double)c->i * p->dx;
    return p->x ? p->x[j] : (double)j * p->dx;
}

static double y_at(const ct_profile *p, const cursor *c)
{
    return p->ny > 1 ? (double)c->r * p->dy : 0.0;
}

static void next(const ct_profile *p, cursor *c)
{
    if (++c->i == p->nx) {
        c->i = 0;
        c->r++;
    }
}

/* Levelling in centred, scaled coordinates s = (x - xm)/xs, r = (y - ym)/ys (about [-1, 1]),
 * so that the normal equations of at most 6 terms stay well conditioned. */
typedef struct {
    int grid, m; /* a grid (s and r); the count of terms */
    double xm, ym, xs, ys;
} level_frame;

/* The power of two 2^k nearest above the largest |height| (k = 0 when there is none): sums of
 * heights and their squares are taken in units of it, which is exact (a power of two changes
 * no digit) and keeps them from overflowing at 1e300 m or underflowing at 1e-170 m, where Rq
 * came out 0 (squares below the smallest double) and trim clipped half the heights. */
int ct_heights_exponent(const double *z, size_t n)
{
    double big = 0.0;
    for (size_t j = 0; j < n; j++)
        if (!isnan(z[j]) && fabs(z[j]) > big)
            big = fabs(z[j]);
    return big > 0.0 && isfinite(big) ? ilogb(big) + 1 : 0;
}

static int height_scale(const ct_profile *p)
{
    return ct_heights_exponent(p->z, p->nx * p->ny);
}

/* The frame of p's valid samples: their centre and the largest distance from it. */
static void level_frame_of(const ct_profile *p, level_frame *L)
{
    const size_t total = p->nx * p->ny;
    double xm = 0.0, ym = 0.0, xs = 0.0, ys = 0.0;
    size_t n = 0;
    cursor c = {0, 0};
    for (size_t j = 0; j < total; j++, next(p, &c))
        if (!isnan(p->z[j])) {
            xm += x_at(p, j, &c);
            ym += y_at(p, &c);
            n++;
        }
    xm /= (double)n;
    ym /= (double)n;
    c = (cursor){0, 0};
    for (size_t j = 0; j < total; j++, next(p, &c))
        if (!isnan(p->z[j])) {
            const double dx = fabs(x_at(p, j, &c) - xm), dy = fabs(y_at(p, &c) - ym);
            xs = dx > xs ? dx : xs;
            ys = dy > ys ? dy : ys;
        }
    L->xm = xm;
    L->ym = ym;
    L->xs = xs > 0.0 ? xs : 1.0;
    L->ys = ys > 0.0 ? ys : 1.0;
}

/* 1 when the m x m normal matrix A (row-major, symmetric, positive semi-definite) is well
 * enough conditioned to solve: its smallest singular value above 1e-10 of its largest. */
static int level_spanned(const double *A, int m)
{
    double copy[36], sv[6], vm[36], work[6];
    memcpy(copy, A, (size_t)(m * m) * sizeof(double));
    for (int k = 0; k < m * m; k++)
        if (!isfinite(copy[k]))
            return 0;
    gsl_matrix_view U = gsl_matrix_view_array(copy, (size_t)m, (size_t)m);
    gsl_matrix_view V = gsl_matrix_view_array(vm, (size_t)m, (size_t)m);
    gsl_vector_view S = gsl_vector_view_array(sv, (size_t)m);
    gsl_vector_view W = gsl_vector_view_array(work, (size_t)m);
    if (gsl_linalg_SV_decomp(&U.matrix, &V.matrix, &S.vector, &W.vector))
        return 0;
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < m; k++) {
        lo = fmin(lo, sv[k]);
        hi = fmax(hi, sv[k]);
    }
    return hi > 0.0 && lo > 1e-10 * hi;
}

/* The m terms at sample j: 1 | s, (r) | s^2, (s r, r^2) (a line: 1, s, s^2). Inlined where m
 * is a constant, so the terms stay in registers (a per-sample array of them, stored one by one
 * and read back in pairs, cost a stalled store forwarding each time). */
#if defined(__GNUC__)
#define CT_INLINE static inline __attribute__((always_inline))
#else
#define CT_INLINE static inline
#endif
CT_INLINE void terms_of(const ct_profile *p, const level_frame *L, size_t j, const cursor *c,
                        const int m, double *f)
{
    const double s = (x_at(p, j, c) - L->xm) / L->xs, r = (y_at(p, c) - L->ym) / L->ys;
    f[0] = 1.0;
    if (m == 6) {
        f[1] = s, f[2] = r, f[3] = s * s, f[4] = s * r, f[5] = r * r;
    } else if (m == 3 && L->grid) {
        f[1] = s, f[2] = r;
    } else if (m >= 2) {
        f[1] = s;
        if (m == 3)
            f[2] = s * s;
    }
}

/* The normal equations' sums over the valid samples, for m terms (A's upper triangle only: a
 * product f[a] f[c] is f[c] f[a], so the lower one is the same sums, bit for bit). */
CT_INLINE void fit_sums(const ct_profile *p, const level_frame *L, int k, double m2, const int m,
                        double *A, double *bvec)
{
    const size_t total = p->nx * p->ny;
    double a[6][6] = {{0}}, b[6] = {0};
    cursor cu = {0, 0};
    for (size_t j = 0; j < total; j++, next(p, &cu)) {
        if (isnan(p->z[j]))
            continue;
        double f[6];
        terms_of(p, L, j, &cu, m, f);
        const double z = ct_times_pow2(p->z[j], m2, -k);
        for (int u = 0; u < m; u++) {
            b[u] += f[u] * z;
            for (int v = u; v < m; v++)
                a[u][v] += f[u] * f[v];
        }
    }
    for (int u = 0; u < m; u++) {
        bvec[u] = b[u];
        for (int v = u; v < m; v++)
            A[u * m + v] = A[v * m + u] = a[u][v];
    }
}

/* The least-squares coefficients of the terms (coef[0..m)), by LU (GSL) on the normal
 * equations. */
static int level_fit(const ct_profile *p, const level_frame *L, ct_detrend how, double *coef)
{
    const int m = L->m;
    const int k = height_scale(p); /* the right-hand side in units of 2^k: exact, no overflow */
    const double m2 = ldexp(1.0, -k);
    double A[36] = {0}, bvec[6] = {0};
    switch (m) {
    case 1:
        fit_sums(p, L, k, m2, 1, A, bvec);
        break;
    case 2:
        fit_sums(p, L, k, m2, 2, A, bvec);
        break;
    case 3:
        fit_sums(p, L, k, m2, 3, A, bvec);
        break;
    default:
        fit_sums(p, L, k, m2, 6, A, bvec);
        break;
    }
    /* No input may reach GSL's error handler (its default aborts the process, and changing it
     * would change process-wide state): the normal matrix's singular values (SVD never
     * signals rank deficiency) say whether the valid points span the terms before the LU
     * solve, which would report a singular matrix through that handler. */
    if (!level_spanned(A, m))
        return ct_error_set(CT_EINVAL,
                            "levelling: the valid points do not determine a %s fit (they lie on "
                            "a line or too few distinct positions): detrend less (surface.detrend "
                            "= %s)",
                            how == CT_DETREND_LINEAR ? "linear" : "quadratic",
                            how == CT_DETREND_LINEAR ? "mean" : "linear or mean");
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)m, (size_t)m);
    gsl_vector_view bv = gsl_vector_view_array(bvec, (size_t)m);
    gsl_vector_view cv = gsl_vector_view_array(coef, (size_t)m);
    gsl_permutation *perm = gsl_permutation_alloc((size_t)m);
    int sign;
    if (!perm)
        return ct_error_set(CT_ENOMEM, "levelling: out of memory");
    int g = gsl_linalg_LU_decomp(&Av.matrix, perm, &sign);
    if (!g)
        g = gsl_linalg_LU_solve(&Av.matrix, perm, &bv.vector, &cv.vector);
    gsl_permutation_free(perm);
    for (int a = 0; a < m && !g; a++) {
        coef[a] = ldexp(coef[a], k);
        g = !isfinite(coef[a]);
    }
    if (g)
        return ct_error_set(CT_EINVAL, "levelling: the %s fit failed (heights too large?)",
                            how == CT_DETREND_LINEAR ? "linear" : "quadratic");
    return CT_OK;
}

#define LEVEL_TEAM_MIN (1u << 18) /* samples from which the levelled heights take threads */
#define LEVEL_CHUNK (1u << 16)

/* Samples [j0, j1) less the fitted terms (m of them, coef), and the extremes of the heights
 * before (|z|: *big) and after (*lo, *hi). */
CT_INLINE void subtract_fit(ct_profile *p, const level_frame *L, const double *coef, const int m,
                            size_t j0, size_t j1, double *big, double *lo, double *hi)
{
    cursor cu = {j0 % p->nx, j0 / p->nx};
    double b = *big, l = *lo, h = *hi;
    for (size_t j = j0; j < j1; j++, next(p, &cu)) {
        if (isnan(p->z[j]))
            continue;
        b = fabs(p->z[j]) > b ? fabs(p->z[j]) : b;
        double f[6], t = 0.0;
        terms_of(p, L, j, &cu, m, f);
        for (int a = 0; a < m; a++)
            t += coef[a] * f[a];
        p->z[j] -= t;
        l = p->z[j] < l ? p->z[j] : l;
        h = p->z[j] > h ? p->z[j] : h;
    }
    *big = b, *lo = l, *hi = h;
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
    const int grid = p->ny > 1;
    level_frame L = {.grid = grid,
                     .m = how == CT_DETREND_MEAN     ? 1
                          : how == CT_DETREND_LINEAR ? (grid ? 3 : 2)
                                                     : (grid ? 6 : 3)};
    level_frame_of(p, &L);
    double coef[6];
    if ((st = level_fit(p, &L, how, coef)))
        return st;
    const size_t total = p->nx * p->ny;
    double big = 0.0, lo = INFINITY, hi = -INFINITY;
    /* each sample on its own (the extremes are exact in any order): shared among threads */
    const int team = total >= LEVEL_TEAM_MIN ? ct_default_threads() : 1;
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1) reduction(max            \
                                                                                    : big, hi)     \
    reduction(min                                                                                  \
              : lo)
    for (size_t c = 0; c < (total + LEVEL_CHUNK - 1) / LEVEL_CHUNK; c++) {
        const size_t j0 = c * LEVEL_CHUNK, j1 = j0 + LEVEL_CHUNK < total ? j0 + LEVEL_CHUNK : total;
        switch (L.m) {
        case 1:
            subtract_fit(p, &L, coef, 1, j0, j1, &big, &lo, &hi);
            break;
        case 2:
            subtract_fit(p, &L, coef, 2, j0, j1, &big, &lo, &hi);
            break;
        case 3:
            subtract_fit(p, &L, coef, 3, j0, j1, &big, &lo, &hi);
            break;
        default:
            subtract_fit(p, &L, coef, 6, j0, j1, &big, &lo, &hi);
            break;
        }
    }
    /* A flat or exactly tilted profile levels to its rounding residue (1e-23 m from heights of
     * 1e-7 m), which is no roughness: an e computed from it would be noise. Heights left within
     * 1e-11 of the heights' size carry fewer than five digits: refused. */
    if (hi - lo <= 1e-11 * big)
        return ct_error_set(CT_EINVAL,
                            "all heights are equal after levelling (%s), to rounding: they vary "
                            "by %.3g, heights of %.3g: no roughness (a flat or tilted profile)",
                            how == CT_DETREND_MEAN     ? "mean"
                            : how == CT_DETREND_LINEAR ? "linear"
                                                       : "quadratic",
                            hi - lo, big);
    return CT_OK;
}

/* The valid heights' peak to valley (ct_profile_stats_of's Rt; -inf when none is valid). */
static double heights_span(const ct_profile *p)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < p->nx * p->ny; j++)
        if (!isnan(p->z[j])) {
            lo = p->z[j] < lo ? p->z[j] : lo;
            hi = p->z[j] > hi ? p->z[j] : hi;
        }
    return hi - lo;
}

int ct_profile_stats_of(const ct_profile *p, ct_profile_stats *s)
{
    CT_NEED(p);
    CT_NEED(s);
    int st = check_heights(p);
    if (st)
        return st;
    const size_t total = p->nx * p->ny;
    const int k = height_scale(p);
    const double m2 = ldexp(1.0, -k);
    double w = 0.0, zw = 0.0, lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = share(p, j);
            w += a;
            zw += a * ct_times_pow2(p->z[j], m2, -k);
            lo = p->z[j] < lo ? p->z[j] : lo;
            hi = p->z[j] > hi ? p->z[j] : hi;
        }
    const double mean = zw / w; /* in units of 2^k */
    double ra = 0.0, rq = 0.0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = share(p, j), d = ct_times_pow2(p->z[j], m2, -k) - mean;
            ra += a * fabs(d);
            rq += a * d * d;
        }
    s->mean = ldexp(mean, k);
    s->Ra = ldexp(ra / w, k);
    s->Rq = ldexp(sqrt(rq / w), k);
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

/* The metadata: the profile's positions (no heights) and each rod's sample; with_index: an
 * index (copied from index when not NULL), else rod k is sample k. */
static profile_meta *meta_new(const ct_profile *p, int with_index, const size_t *index)
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
        memcpy(pm->p->x, p->x, p->nx * sizeof(double));
    if (with_index && index)
        memcpy(pm->index, index, p->n * sizeof(size_t));
    return pm;
}

static void *profile_meta_clone(const void *m)
{
    const profile_meta *src = m;
    return meta_new(src->p, src->index != NULL, src->index);
}

static void profile_rod_info(const void *m, size_t k, ct_rod_info *info)
{
    const profile_meta *pm = m;
    const ct_profile *p = pm->p;
    const size_t j = pm->index ? pm->index[k] : k;
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

static const ct_rod_meta_kind profile_kind = {"profile", profile_rod_info, profile_meta_clone,
                                              profile_meta_free};

static int profile_bundle(ct_bundle **out, const ct_profile *p, const ct_profile_stats *sp,
                          double E, double sigma_y, double Hstar, int threads);

int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar)
{
    CT_NEED(out);
    CT_NEED(p);
    *out = NULL;
    ct_profile_stats s;
    int st = ct_profile_stats_of(p, &s);
    if (st)
        return st;
    return profile_bundle(out, p, &s, E, sigma_y, Hstar, 0);
}

/* Rod k of sample j: its top below the highest point, its length, its area, no plastic strain. */
static inline void rod_of(const ct_profile *p, size_t j, double zmax, double Hstar, size_t k,
                          double *top, double *length, double *area, double *eps_p)
{
    top[k] = zmax - p->z[j];
    length[k] = Hstar - top[k];
    area[k] = share(p, j);
    eps_p[k] = 0.0;
}

/* ct_profile_bundle with p's statistics known (sp), filled on threads threads (0: the OpenMP
 * default). */
static int profile_bundle(ct_bundle **out, const ct_profile *p, const ct_profile_stats *sp,
                          double E, double sigma_y, double Hstar, int threads)
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
    ct_layer L = {.E = E, .sigma_y = sigma_y, .Hstar = Hstar, .l0 = s.length, .h0 = s.Rt};
    if ((st = ct_layer_validate(&L)))
        return st;
    const size_t total = p->nx * p->ny;
    double zmax = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j]) && p->z[j] > zmax)
            zmax = p->z[j];
    profile_meta *pm = meta_new(p, p->n < total, NULL); /* no index when every sample is valid */
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
                rod_of(p, j, zmax, Hstar, j, top, length, area, eps_p);
        }
        ct_bundle_set_surface(b, &profile_kind, pm, p->invalid);
        *out = b;
        return CT_OK;
    }
    size_t k = 0;
    for (size_t j = 0; j < total; j++) {
        if (isnan(p->z[j]))
            continue;
        rod_of(p, j, zmax, Hstar, k, top, length, area, eps_p);
        if (pm->index)
            pm->index[k] = j;
        k++;
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

/* ---- the kind (src/surface/kind.h): a measured profile's keys, reading and levelling, its
 * fitted Cantor surface (what = compare, bearing; cantact fit) ---- */

static const char unit_words[] = "m|mm|um|nm";
static const double unit_metres[] = {1.0, 1e-3, 1e-6, 1e-9};

typedef struct {
    char *file;               /* [surface] */
    int unit, x_unit, z_unit; /* indices into unit_words (read only when given) */
    double spacing;           /* one column of heights at this spacing [x unit]; 0: two */
    int detrend;              /* ct_detrend */
    int trim;                 /* 0 none, 1 rq */
    double trim_k;            /* clip at mean + trim_k Rq */
    double H, Hstar;          /* H* = H Rt, or H* [z unit] */
    double E, sigma_y;        /* [material], Pa */
    double band[4];           /* [fit] depth_lo depth_hi [z unit], lag_lo lag_hi [x unit] */
    int dimension;            /* ct_dimension_method */
    /* prepared */
    ct_profile *profile; /* levelled (and trimmed) */
    ct_profile_stats stats;
    ct_layer layer;
    double band_m[4]; /* the bands in metres (0: the default) */
    ct_profile_fit fit;
    int have_fit, fit_from_impacts;
} profile_config;

#define AT(field) offsetof(profile_config, field)
static const ct_key profile_keys[] = {
    {"surface", "file", CT_KEY_TEXT, 0, 0, CT_KEY_REQUIRED | CT_KEY_FILE, NULL, "must be a path",
     "",
     "the profile: text/CSV (x z, or z with spacing), a Dektak export or an X3P file; relative "
     "to the scene's directory",
     AT(file)},
    {"surface", "unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm",
     "what the file's column names state", "the file's length unit for x and z", AT(unit)},
    {"surface", "x_unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm", "unit",
     "the file's unit of x", AT(x_unit)},
    {"surface", "z_unit", CT_KEY_WORD, 0, 0, 0, unit_words, "must be m, mm, um or nm", "unit",
     "the file's unit of z", AT(z_unit)},
    {"surface", "spacing", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL,
     "must be > 0 (one column of heights at this spacing, in x_unit)", "",
     "a file of one column of heights: their spacing [x unit]", AT(spacing)},
    {"surface", "detrend", CT_KEY_WORD, 0, 0, 0, "none|mean|linear|quadratic",
     "must be none, mean, linear or quadratic", "linear",
     "levelling: the least-squares mean, line (plane) or parabola (quadric) removed", AT(detrend)},
    {"surface", "trim", CT_KEY_WORD, 0, 0, 0, "none|rq",
     "must be none or rq (clip at mean + trim_k Rq)", "none",
     "spikes: rq clips heights above mean + trim_k Rq", AT(trim)},
    {"surface", "trim_k", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "3",
     "the clip level of trim = rq, in Rq", AT(trim_k)},
    {"surface", "H", CT_KEY_NUMBER, 1.0, INFINITY, 0, NULL,
     "must satisfy H > 1 (H* = H Rt must exceed the peak-to-valley depth)", "",
     "H* as a multiple of the peak-to-valley depth Rt (or give Hstar)", AT(H)},
    {"surface", "Hstar", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "H* in the file's z unit (or give H)", AT(Hstar)},
    {"material", "E", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",
     "Young's modulus [Pa]", AT(E)},
    {"material", "sigma_y", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",
     "yield stress [Pa]", AT(sigma_y)},
    {"fit", "depth_lo", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "the 20th highest point", "the bearing fit's shallowest depth [z unit]", AT(band[0])},
    {"fit", "depth_hi", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "phi = 0.1", "the bearing fit's deepest depth [z unit]", AT(band[1])},
    {"fit", "lag_lo", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "2 spacings", "the dimension estimators' shortest lag [x unit]", AT(band[2])},
    {"fit", "lag_hi", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0 (in the file's unit)",
     "a tenth of the length", "the dimension estimators' longest lag [x unit]", AT(band[3])},
    {"fit", "dimension", CT_KEY_WORD, 0, 0, 0, "variation|structure|spectrum",
     "must be variation, structure or spectrum", "variation", "the estimate of D that enters Eq. 3",
     AT(dimension)},
};
#undef AT

static void profile_defaults(void *config)
{
    profile_config *c = config;
    c->detrend = CT_DETREND_LINEAR;
    c->dimension = CT_DIM_VARIATION;
}

static void profile_release(void *config)
{
    profile_config *c = config;
    ct_profile_free(c->profile);
    c->profile = NULL;
}

static int profile_check(ct_surface *s, const char *scene)
{
    profile_config *c = s->config;
    if (ct_surface_given(s, "surface", "trim_k") && c->trim != 1)
        return ct_surface_key_error(s, "surface", "trim_k", CT_EINVAL,
                                    "only with surface.trim = rq");
    if (c->trim == 1 && !ct_surface_given(s, "surface", "trim_k"))
        c->trim_k = 3.0;
    if (c->trim == 0)
        c->trim_k = 0.0;
    if (ct_surface_given(s, "surface", "H") == ct_surface_given(s, "surface", "Hstar"))
        return ct_error_set(CT_EINVAL,
                            "%s: type = profile needs one of surface.H (H* as a multiple of the "
                            "peak-to-valley depth) and surface.Hstar (in z_unit)",
                            scene);
    if (!(c->E > c->sigma_y))
        return ct_surface_key_error(s, "material", "E", CT_EINVAL,
                                    "must be > sigma_y (yield strain sigma_y/E < 1)");
    return CT_OK;
}

static const char *detrend_name(int d)
{
    static const char *const names[] = {"none", "mean", "linear", "quadratic"};
    return d >= 0 && d < 4 ? names[d] : "?";
}

static int profile_prepare(ct_surface *s, const char *dir)
{
    profile_config *c = s->config;
    profile_release(c);
    c->have_fit = c->fit_from_impacts = 0;
    ct_profile_read_opts opts = {0.0, 0.0, 0.0}; /* a unit 0: the one the file states */
    if (ct_surface_given(s, "surface", "unit"))
        opts.x_unit = opts.z_unit = unit_metres[c->unit];
    if (ct_surface_given(s, "surface", "x_unit"))
        opts.x_unit = unit_metres[c->x_unit];
    if (ct_surface_given(s, "surface", "z_unit"))
        opts.z_unit = unit_metres[c->z_unit];
    opts.dx = c->spacing;
    char *path = ct_path_join(dir, c->file);
    if (!path)
        return ct_error_set(CT_ENOMEM, "out of memory");
    int st = ct_profile_read(path, &opts, &c->profile);
    free(path);
    if (st)
        return st;
    ct_profile *p = c->profile;
    /* H* and the fit's bands are given in the file's units, known now */
    const double Hstar = c->Hstar * p->z_unit;
    for (int k = 0; k < 4; k++)
        c->band_m[k] = c->band[k] * (k < 2 ? p->z_unit : p->x_unit);
    ct_profile_stats raw = {.Rt = heights_span(p)}; /* only Rt is asked of the raw heights */
    size_t clipped = 0;
    if ((st = ct_profile_level(p, c->detrend)) ||
        (c->trim_k > 0.0 && (st = ct_profile_trim(p, c->trim_k, &clipped))) ||
        (st = ct_profile_stats_of(p, &c->stats))) {
        return ct_error_set(st, "%s: %s", c->file, ct_error_message()); /* the file named */
    }
    const ct_profile_stats *q = &c->stats;
    if (!isfinite(raw.Rt) || !isfinite(q->Rt))
        return ct_error_set(CT_EINVAL,
                            "%s: the heights span more than doubles hold (peak to valley %g m "
                            "raw, %g m levelled): state them in a unit that fits",
                            c->file, raw.Rt, q->Rt);
    if (!(q->Rt > 0.0))
        return ct_error_set(CT_EINVAL, "%s: all heights are equal after levelling: no roughness",
                            c->file);
    c->layer = (ct_layer){.E = c->E,
                          .sigma_y = c->sigma_y,
                          .Hstar = Hstar > 0.0 ? Hstar : c->H * q->Rt,
                          .l0 = q->length,
                          .h0 = q->Rt};
    if (!(c->layer.Hstar > q->Rt))
        return ct_error_set(CT_EINVAL,
                            "surface.Hstar = %g m: must exceed the profile's peak-to-valley depth "
                            "Rt = %g m after levelling",
                            c->layer.Hstar, q->Rt);
    if ((st = ct_layer_validate(&c->layer))) { /* lengths beyond what doubles hold, named */
        return ct_error_set(st, "%s: %s; from %zu points at a spacing of %g m, Rt %g m", c->file,
                            ct_error_message(), p->n, p->ny > 1 ? p->dx : q->length / (double)p->n,
                            q->Rt);
    }
    ct_scales_of(&s->scales, &c->layer, &c->layer);
    ct_surface_note_set(s,
                        "%s (%s): %zu points%s, levelled (%s): Rq %.4g m, Rt %.4g m (raw Rt %.4g "
                        "m), l0 %.4g m%s, H* %.4g m",
                        c->file, p->source, p->n, p->ny > 1 ? " on a grid" : "",
                        detrend_name(c->detrend), q->Rq, q->Rt, raw.Rt, q->length,
                        p->ny > 1 ? "^2" : "", c->layer.Hstar);
    size_t n = strlen(s->note);
    if (p->invalid)
        n += (size_t)snprintf(s->note + n, sizeof s->note - n, ", %zu invalid points left out",
                              p->invalid);
    if (c->trim_k > 0.0 && n < sizeof s->note)
        snprintf(s->note + n, sizeof s->note - n, ", %zu heights clipped at mean + %g Rq", clipped,
                 c->trim_k);
    return CT_OK;
}

static int profile_build(const ct_surface *s, const ct_build_request *r, ct_bundle **out,
                         ct_plan_info *info)
{
    const profile_config *c = s->config;
    *out = NULL;
    int st = profile_bundle(out, c->profile, &c->stats, c->layer.E, c->layer.sigma_y,
                            c->layer.Hstar, r->threads); /* the profile's statistics as it stands */
    if (st)
        return st;
    info->depth = -1;
    info->bound = 0.0;
    info->rods = ct_bundle_size(*out);
    info->omitted = ct_bundle_omitted(*out);
    info->u_reach = INFINITY;
    return CT_OK;
}

/* The fit the outputs compare with: on the bands given, else the defaults (ct_profile_fit_of). */
static int need_fit(ct_surface *s)
{
    profile_config *c = s->config;
    if (c->have_fit)
        return CT_OK;
    c->fit.dimension = (ct_dimension_method)c->dimension;
    const double *b = c->band_m;
    int st = ct_profile_fit_of(c->profile, b[0], b[1], b[2], b[3], &c->fit);
    if (st)
        return st;
    c->have_fit = 1;
    return CT_OK;
}

int ct_profile_fit_on_reach(const ct_profile *p, const ct_profile_fit *fit, const double *u_max,
                            size_t n, ct_profile_fit *out)
{
    CT_NEED(p);
    CT_NEED(fit);
    CT_NEED(out);
    if (n && !u_max)
        return ct_error_set(CT_EINVAL, "ct_profile_fit_on_reach: u_max is NULL");
    double lo = INFINITY, hi = 0.0;
    for (size_t k = 0; k < n; k++)
        if (isfinite(u_max[k])) {
            lo = fmin(lo, u_max[k]);
            hi = fmax(hi, u_max[k]);
        }
    /* from the shallowest reach (not above the default band's start, the 20th highest
     * point: above it the curve is a few samples) to the deepest (not below Rt) */
    lo = fmax(lo, fit->bearing.lo);
    hi = fmin(hi, fit->stats.Rt);
    if (!(hi > lo))
        return ct_error_set(CT_EINVAL,
                            "the depths the impacts reach, %.4g .. %.4g m, give no bearing fit "
                            "(an empty band)",
                            lo, hi);
    ct_profile_fit f = *fit;
    int st = ct_profile_fit_bearing(p, lo, hi, &f);
    if (st) {
        char why[400];
        snprintf(why, sizeof why, "%s", ct_error_message());
        return ct_error_set(st,
                            "the depths the impacts reach, %.4g .. %.4g m, give no bearing fit "
                            "(%s)",
                            lo, hi, why);
    }
    *out = f;
    return CT_OK;
}

/* After the sweep, with a fit and no [fit] depth band given: the bearing fit redone on the
 * depths the impacts reached (docs/model.md §9); the default band is kept, and said, when
 * that band holds no fit. */
static int profile_after_sweep(ct_surface *s, const ct_sweep_row *rows, size_t n)
{
    profile_config *c = s->config;
    if (!c->have_fit || c->band_m[0] > 0.0 || c->band_m[1] > 0.0)
        return CT_OK;
    double *u = malloc((n ? n : 1) * sizeof *u);
    if (!u)
        return ct_error_set(CT_ENOMEM, "fit: out of memory");
    for (size_t k = 0; k < n; k++)
        u[k] = rows[k].status ? NAN : rows[k].r.u_max;
    ct_profile_fit f;
    int st = ct_profile_fit_on_reach(c->profile, &c->fit, u, n, &f);
    free(u);
    if (st == CT_ENOMEM)
        return st;
    if (st) {
        ct_surface_note_set(s, "fit: %s: the default band kept", ct_error_message());
        return CT_OK;
    }
    static const char *const names[] = {"variation", "structure", "spectrum"};
    c->fit = f;
    c->fit_from_impacts = 1;
    ct_surface_note_set(s,
                        "fit on the depths the impacts reach, %.4g .. %.4g m: alpha %.4g, h0 "
                        "%.4g m, D %.4g (%s), fx %.4g, fz %.4g",
                        f.bearing.lo, f.bearing.hi, f.alpha, f.h0, f.D,
                        names[f.dimension - CT_DIM_VARIATION], f.fx, f.fz);
    return CT_OK;
}

int ct_profile_fitted_e(const ct_profile *p, const ct_profile_fit *fit, const ct_layer *layer,
                        const double *W, size_t n, int threads, double *e_fit, double *e_asym,
                        double *V_fit)
{
    CT_NEED(p);
    CT_NEED(fit);
    CT_NEED(layer);
    if (n && (!W || !e_fit || !e_asym || !V_fit))
        return ct_error_set(CT_EINVAL, "ct_profile_fitted_e: NULL arrays for %zu impacts", n);
    for (size_t k = 0; k < n; k++)
        e_fit[k] = e_asym[k] = V_fit[k] = NAN;
    /* the fitted Cantor surface in dimensionless form with the layer: H* / h0_fit, E/sigma_y */
    ct_params c = {.fx = fit->fx,
                   .fz = fit->fz,
                   .l0 = 1.0,
                   .h0 = 1.0,
                   .Hstar = layer->Hstar / fit->h0,
                   .E = layer->E / layer->sigma_y,
                   .sigma_y = 1.0};
    if (ct_params_validate(&c)) {
        char why[400];
        snprintf(why, sizeof why, "%s", ct_error_message());
        return ct_error_set(CT_ERANGE,
                            "the fitted Cantor surface (fx %g, fz %g, H*/h0 %g) is outside the "
                            "model's ranges: %s",
                            fit->fx, fit->fz, c.Hstar, why);
    }
    /* the impact energy per unit depth (a grid's over its extent in y) in the fitted surface's
     * units: W / (sigma_y l0_fit h0_fit), so V*_fit = sqrt(W / (l0_fit E h0_fit)) */
    const double depth = p->ny > 1 ? (double)p->ny * p->dy : 1.0;
    const double scale = fit->l0 * layer->E * fit->h0;
    double *V = malloc((n ? n : 1) * sizeof(double));
    ct_sweep_row *cr = malloc((n ? n : 1) * sizeof *cr);
    size_t m = 0;
    int st = CT_OK;
    if (!V || !cr) {
        free(V);
        free(cr);
        return ct_error_set(CT_ENOMEM, "compare: out of memory");
    }
    for (size_t k = 0; k < n; k++)
        if (isfinite(W[k]))
            V[m++] = sqrt(W[k] / depth / scale);
    if (m) {
        ct_cantor_plan plan = {.params = c,
                               .depth = CT_DEPTH_FRACTAL,
                               .representation = CT_REP_STAGES,
                               .depth_tolerance = 1e-12,
                               .V_star = V,
                               .nvel = m,
                               .impacts = 1,
                               .threads = threads};
        ct_impact_opts_default(&plan.opts);
        ct_bundle *b;
        ct_plan_info info;
        if (!(st = ct_cantor_plan_build(&plan, &b, &info))) {
            ct_sweep_spec spec = {.V_star = V, .nvel = m, .impacts = 1, .opts = plan.opts};
            st = ct_sweep(b, &spec, cr);
            ct_bundle_free(b);
        }
    }
    for (size_t k = 0, q = 0; k < n && !st; k++) {
        if (!isfinite(W[k]))
            continue;
        V_fit[k] = V[q];
        if (!cr[q].status)
            e_fit[k] = cr[q].r.e;
        double um, e;
        if (ct_law_impact(&c, CT_LAW_ASYMPTOTIC, V[q] * V[q] * c.E, &um, &e) == CT_OK)
            e_asym[k] = e;
        q++;
    }
    free(V);
    free(cr);
    return st;
}

static const char *const fit_e_names[] = {"e_cantor_fit", "e_asymptotic_fit", "V_star_cantor_fit"};

/* For every first impact: e of the fitted Cantor surface (exact rods, fractal depth), of the
 * asymptotic law with the fitted parameters, and the fitted surface's V*, at the row's energy. */
static int profile_compare(ct_surface *s, const ct_sweep_row *rows, size_t n, double *out)
{
    profile_config *c = s->config;
    int st = need_fit(s);
    if (st)
        return st;
    double *W = malloc((n ? n : 1) * 4 * sizeof(double));
    if (!W)
        return ct_error_set(CT_ENOMEM, "compare: out of memory");
    double *ef = W + n, *ea = ef + n, *vf = ea + n;
    for (size_t k = 0; k < n; k++)
        W[k] = !rows[k].status && rows[k].impact == 1 ? rows[k].r.kinetic_energy : NAN;
    st = ct_profile_fitted_e(c->profile, &c->fit, &c->layer, W, n, 0, ef, ea, vf);
    for (size_t k = 0; k < n && !st; k++) {
        out[3 * k] = ef[k];
        out[3 * k + 1] = ea[k];
        out[3 * k + 2] = vf[k];
    }
    free(W);
    return st;
}

static int profile_ready(ct_surface *s, const char *output)
{
    if (!strcmp(output, "compare") || !strcmp(output, "bearing") || !strcmp(output, "fit"))
        return need_fit(s);
    return CT_OK;
}

/* what = bearing: phi(d) on 400 depths log-spaced from 1e-4 Rt to Rt, beside the fit. */
static int profile_write_bearing(const ct_surface *s, FILE *f)
{
    const profile_config *c = s->config;
    if (!c->have_fit)
        return ct_error_set(CT_EINVAL, "bearing: the profile has not been fitted");
    const ct_profile_fit *fit = &c->fit;
    const double Rt = fit->stats.Rt;
    enum { N = 400 };
    double d[N], phi[N];
    for (int k = 0; k < N; k++)
        d[k] = Rt * pow(1e-4, 1.0 - (double)k / (N - 1));
    int st = ct_profile_bearing(c->profile, N, d, phi);
    if (st)
        return st;
    fprintf(f,
            "# bearing fit: phi = (d / h0)^alpha, alpha = %.6g, h0 = %.6g m, on d in [%.4g, "
            "%.4g] m (%s; %zu points, R^2 %.4f, rms residual %.3g in ln phi)\n",
            fit->alpha, fit->h0, fit->bearing.lo, fit->bearing.hi,
            c->band_m[0] > 0.0 || c->band_m[1] > 0.0 ? "the band given"
            : c->fit_from_impacts                    ? "the depths the impacts reach"
                                                     : "the default band",
            fit->bearing.n, fit->bearing.r2, fit->bearing.residual);
    fprintf(f,
            "# Cantor fit (Eq. 3): D = %.17g, fx = %.17g, fz = %.17g, h0 = %.17g m, l0 = %.17g m\n",
            fit->D, fit->fx, fit->fz, fit->h0, fit->l0);
    fputs("d_m,d_over_Rt,phi,phi_fit\n", f);
    for (int k = 0; k < N; k++) {
        const double pf = d[k] < fit->h0 ? pow(d[k] / fit->h0, fit->alpha) : 1.0;
        ct_put_double(f, d[k]);
        fputc(',', f);
        ct_put_double(f, d[k] / Rt);
        fputc(',', f);
        ct_put_double(f, phi[k]);
        fputc(',', f);
        ct_put_double(f, pf);
        fputc('\n', f);
    }
    return CT_OK;
}

/* what = profile: the heights after levelling (a grid: x, y, z of the valid points). */
static int profile_write_levelled(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    (void)b;
    const ct_profile *p = ((const profile_config *)s->config)->profile;
    if (p->ny > 1) {
        fputs("x_m,y_m,z_m\n", f);
        for (size_t j = 0; j < p->nx * p->ny; j++) {
            if (isnan(p->z[j]))
                continue;
            ct_put_double(f, (double)(j % p->nx) * p->dx);
            fputc(',', f);
            ct_put_double(f, (double)(j / p->nx) * p->dy);
            fputc(',', f);
            ct_put_double(f, p->z[j]);
            fputc('\n', f);
        }
        return CT_OK;
    }
    fputs("x_m,z_m\n", f);
    for (size_t j = 0; j < p->nx; j++) {
        ct_put_double(f, p->x ? p->x[j] : (double)j * p->dx);
        fputc(',', f);
        ct_put_double(f, p->z[j]);
        fputc('\n', f);
    }
    return CT_OK;
}

static void fit_row(FILE *f, const char *name, double value, const ct_fit_line *l)
{
    fprintf(f, "%s,", name);
    ct_put_double(f, value);
    if (l)
        fprintf(f, ",%.6g,%.6g,%zu,%.6f,%.4g\n", l->lo, l->hi, l->n, l->r2, l->residual);
    else
        fputs(",,,,,\n", f);
}

int ct_profile_fit_write(FILE *f, const ct_profile_fit *fit, const char *source, size_t n)
{
    CT_NEED(f);
    CT_NEED(fit);
    CT_NEED(source);
    static const char *const names[] = {"variation", "structure", "spectrum"};
    const ct_fit_line *used = fit->dimension == CT_DIM_STRUCTURE  ? &fit->structure
                              : fit->dimension == CT_DIM_SPECTRUM ? &fit->spectrum
                                                                  : &fit->variation;
    fprintf(f,
            "# %s: %zu points; bands: bearing depths [m], variation window widths and "
            "structure-function lags [m], spectrum wavenumbers [1/m]; D (into Eq. 3) from the "
            "%s estimate\n",
            source, n, names[fit->dimension - CT_DIM_VARIATION]);
    fputs("quantity,value,band_lo,band_hi,points,r2,rms_residual_ln\n", f);
    fit_row(f, "Rq_m", fit->stats.Rq, NULL);
    fit_row(f, "Ra_m", fit->stats.Ra, NULL);
    fit_row(f, "Rt_m", fit->stats.Rt, NULL);
    fit_row(f, "alpha", fit->alpha, &fit->bearing);
    fit_row(f, "h0_m", fit->h0, &fit->bearing);
    fit_row(f, "D_variation", fit->D_variation, &fit->variation);
    fit_row(f, "D_structure", fit->D_structure, &fit->structure);
    fit_row(f, "D_spectrum", fit->D_spectrum, &fit->spectrum);
    fit_row(f, "D", fit->D, used);
    fit_row(f, "fx", fit->fx, NULL);
    fit_row(f, "fz", fit->fz, NULL);
    fit_row(f, "l0_m", fit->l0, NULL);
    return CT_OK;
}

static int profile_write_fit(ct_surface *s, FILE *f)
{
    int st = need_fit(s);
    if (st)
        return st;
    const profile_config *c = s->config;
    return ct_profile_fit_write(f, &c->fit, c->profile->source, c->profile->n);
}

int ct_surface_profile(const ct_surface *s, const ct_profile **p, ct_profile_fit *fit)
{
    CT_NEED(s);
    if (s->kind != &ct_kind_profile || !s->prepared)
        return ct_error_set(CT_EINVAL, "surface %s: not a prepared profile", s->kind->name);
    const profile_config *c = s->config;
    if (p)
        *p = c->profile;
    if (fit && !c->have_fit)
        return ct_error_set(CT_EINVAL, "the profile has not been fitted");
    if (fit)
        *fit = c->fit;
    return CT_OK;
}

static void profile_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    (void)s;
    snprintf(buf, len, "measured surface, %zu rods", info->rods);
}

static void profile_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const profile_config *c = s->config;
    const ct_layer *L = &c->layer;
    snprintf(buf, len,
             "profile: %s (%s), %zu rods, l0 = %.17g m, h0 = Rt = %.17g m, H* = %.17g m, E = "
             "%.17g Pa, sigma_y = %.17g Pa, detrend %s",
             c->file, c->profile->source, info->rods, L->l0, L->h0, L->Hstar, L->E, L->sigma_y,
             detrend_name(c->detrend));
}

static const ct_refusal profile_refusals[] = {
    {"geometry", "a measured profile has no Cantor stages: cantact fit gives the Cantor surface "
                 "it looks like"},
    {"ensemble", "ensembles are of random surfaces: surface.type = random_cantor"},
    {"realisations", "ensembles are of random surfaces: surface.type = random_cantor"},
    {"merge", "merge combines the parts of an ensemble of a random_cantor surface"},
    {NULL, NULL},
};

const ct_kind ct_kind_profile = {
    .name = "profile",
    .summary = "a measured line profile or areal topography (text, Dektak, X3P), one rod per "
               "sample",
    .keys = profile_keys,
    .nkeys = sizeof profile_keys / sizeof profile_keys[0],
    .config_size = sizeof(profile_config),
    .defaults = profile_defaults,
    .gives = "profile compare bearing fit",
    .refusals = profile_refusals,
    .check = profile_check,
    .prepare = profile_prepare,
    .build = profile_build,
    .release = profile_release,
    .ready = profile_ready,
    .describe = profile_describe,
    .table_line = profile_table_line,
    .write_profile = profile_write_levelled,
    .ncompare = 3,
    .compare_names = fit_e_names,
    .compare = profile_compare,
    .after_sweep = profile_after_sweep,
    .write_bearing = profile_write_bearing,
    .write_fit = profile_write_fit,
};
