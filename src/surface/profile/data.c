/* Measured surfaces (docs/model.md §9): a line profile z(x_j) or a grid z(x_i, y_j) held,
 * levelled (least squares in centred, scaled coordinates), described by its statistics and
 * trimmed. The rods are rods.c's, the bearing-area curve bearing.c's, the kind kind.c's. */
#include "profile.h"

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

int ct_profile_check_heights(const ct_profile *p)
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
    int st = ct_profile_check_heights(p);
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
double ct_profile_heights_span(const ct_profile *p)
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
    int st = ct_profile_check_heights(p);
    if (st)
        return st;
    const size_t total = p->nx * p->ny;
    const int k = height_scale(p);
    const double m2 = ldexp(1.0, -k);
    double w = 0.0, zw = 0.0, lo = INFINITY, hi = -INFINITY;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = ct_profile_share(p, j);
            w += a;
            zw += a * ct_times_pow2(p->z[j], m2, -k);
            lo = p->z[j] < lo ? p->z[j] : lo;
            hi = p->z[j] > hi ? p->z[j] : hi;
        }
    const double mean = zw / w; /* in units of 2^k */
    double ra = 0.0, rq = 0.0;
    for (size_t j = 0; j < total; j++)
        if (!isnan(p->z[j])) {
            double a = ct_profile_share(p, j), d = ct_times_pow2(p->z[j], m2, -k) - mean;
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
