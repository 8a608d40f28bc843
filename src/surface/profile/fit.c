/* The Cantor surface a measured profile looks like (docs/model.md §9).
 *
 * Bearing-area curve: for the Cantor prefractal phi(h0 fz^-i) = fx^-i, a staircase on
 * phi(d) = (d / h0)^alpha, alpha = ln fx / ln fz: ln phi = alpha ln d - alpha ln h0 is fitted
 * by least squares at log-spaced depths of the band (so that every decade weighs the same).
 * Structure function S(tau) = <(z(x + tau) - z(x))^2> ~ tau^(2 (2 - D)) of a self-affine
 * profile, on integer lags of the (uniform) sampling, log-spaced; the power spectrum
 * C(q) ~ q^-(5 - 2D) as a cross-check (GSL's mixed-radix real FFT of each row, a Hann window,
 * the periodogram averaged over rows, then averaged in log-spaced bins of q). Eq. 3 inverted
 * with alpha and D: ln fz = ln 2 (2 - D) / (1 + alpha (D - 1)), ln fx = alpha ln fz. */
#include "profile.h"
#include "number.h"

#include <gsl/gsl_fft_real.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Least squares y = a x + b over the points with x in [lo, hi] (lo, hi in ln units). */
static int fit_line(const double *x, const double *y, size_t n, double lo, double hi,
                    ct_fit_line *f, const char *what)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, xmin = INFINITY, xmax = -INFINITY;
    size_t m = 0;
    for (size_t k = 0; k < n; k++)
        if (x[k] >= lo && x[k] <= hi && isfinite(y[k])) {
            sx += x[k], sy += y[k], sxx += x[k] * x[k], sxy += x[k] * y[k];
            xmin = fmin(xmin, x[k]);
            xmax = fmax(xmax, x[k]);
            m++;
        }
    if (m < 3)
        return ct_error_set(CT_EINVAL, "fit of the %s: %zu points in its band: needs at least 3",
                            what, m);
    double mx = sx / m, my = sy / m, vx = sxx / m - mx * mx;
    if (!(vx > 0.0))
        return ct_error_set(CT_EINVAL, "fit of the %s: its band holds one abscissa", what);
    double a = (sxy / m - mx * my) / vx, b = my - a * mx, ss = 0, st = 0;
    for (size_t k = 0; k < n; k++)
        if (x[k] >= lo && x[k] <= hi && isfinite(y[k])) {
            double r = y[k] - (a * x[k] + b), d = y[k] - my;
            ss += r * r;
            st += d * d;
        }
    f->n = m;
    f->slope = a;
    f->intercept = b;
    f->r2 = st > 0.0 ? 1.0 - ss / st : 1.0;
    f->residual = sqrt(ss / m);
    f->lo = exp(xmin); /* the band its points span */
    f->hi = exp(xmax);
    return CT_OK;
}

/* The heights on a uniform grid along x, row by row: a non-uniform line is interpolated
 * linearly onto its median spacing, at most RESAMPLE_MAX times as many points as it has. */
#define RESAMPLE_MAX 8.0
typedef struct {
    double *z; /* rows of nx, NaN where invalid */
    size_t nx, ny;
    double dx;
} rows;

static int rows_of(const ct_profile *p, rows *r)
{
    r->ny = p->ny;
    if (p->ny > 1 || !p->x) {
        r->nx = p->nx;
        r->dx = p->dx;
        r->z = malloc(p->nx * p->ny * sizeof(double));
        if (!r->z)
            return ct_error_set(CT_ENOMEM, "fit: out of memory");
        memcpy(r->z, p->z, p->nx * p->ny * sizeof(double));
        return CT_OK;
    }
    double *gaps = malloc((p->nx - 1) * sizeof(double));
    if (!gaps)
        return ct_error_set(CT_ENOMEM, "fit: out of memory");
    for (size_t k = 0; k + 1 < p->nx; k++)
        gaps[k] = p->x[k + 1] - p->x[k];
    /* the median gap (the upper one of an even count): GSL's quickselect, O(n) */
    r->dx = gsl_stats_select(gaps, 1, p->nx - 1, (p->nx - 1) / 2);
    free(gaps);
    /* a grid much finer than the data holds interpolated lines, not the profile's roughness:
     * refuse, with the figures, a spacing so uneven that the median gap would multiply the
     * points by more than RESAMPLE_MAX (a few samples 1 nm apart and one 0.1 m away) */
    const double span = p->x[p->nx - 1] - p->x[0], count = floor(span / r->dx) + 1.0;
    if (!(count <= RESAMPLE_MAX * (double)p->nx))
        return ct_error_set(CT_EINVAL,
                            "fit: the profile's spacing is too uneven to resample: its median "
                            "gap %.3g m over its length %.3g m would make %.3g points of its %zu "
                            "(more than %g times as many); resample it evenly or cut it where the "
                            "gaps change",
                            r->dx, span, count, p->nx, RESAMPLE_MAX);
    r->nx = (size_t)count;
    r->z = malloc(r->nx * sizeof(double));
    if (!r->z)
        return ct_error_set(CT_ENOMEM, "fit: out of memory");
    size_t j = 0;
    for (size_t k = 0; k < r->nx; k++) {
        double x = p->x[0] + (double)k * r->dx;
        while (j + 2 < p->nx && p->x[j + 1] < x)
            j++;
        double t = (x - p->x[j]) / (p->x[j + 1] - p->x[j]);
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        r->z[k] = p->z[j] + t * (p->z[j + 1] - p->z[j]);
    }
    return CT_OK;
}

/* S at integer lag k along x: the mean of (z(x + k dx) - z(x))^2 over valid pairs. */
static double structure(const rows *r, size_t k)
{
    double s = 0.0;
    size_t m = 0;
    for (size_t y = 0; y < r->ny; y++) {
        const double *z = r->z + y * r->nx;
        for (size_t i = 0; i + k < r->nx; i++) {
            double d = z[i + k] - z[i];
            if (!isnan(d)) {
                s += d * d;
                m++;
            }
        }
    }
    return m ? s / (double)m : NAN;
}

/* The variation method (Dubuc et al. 1989): the mean oscillation (max - min) of z over windows
 * of half-width k samples, averaged along every row; the area of the eps-neighbourhood of the
 * graph scales as eps^(2 - D) with D its box-counting dimension, which is Eq. 3's D for the
 * Cantor profile (its 2^i pieces of stage i step by h_i - h_{i+1} over widths (2 fx)^-i), while
 * a step profile's structure function is pinned at D = 1.5 by its jumps. Sliding maxima and
 * minima by monotone deques: O(n) per window. */
static double variation(const rows *r, size_t k, size_t *dq_max, size_t *dq_min)
{
    double total = 0.0;
    size_t m = 0;
    const size_t w = 2 * k + 1, n = r->nx;
    if (w > n)
        return NAN;
    for (size_t y = 0; y < r->ny; y++) {
        const double *z = r->z + y * n;
        size_t hmax = 0, tmax = 0, hmin = 0, tmin = 0;
        int bad = 0;
        for (size_t i = 0; i < n && !bad; i++)
            bad = isnan(z[i]);
        if (bad) /* a row with an invalid point is left out */
            continue;
        for (size_t i = 0; i < n; i++) {
            while (tmax > hmax && z[dq_max[tmax - 1]] <= z[i])
                tmax--;
            dq_max[tmax++] = i;
            while (tmin > hmin && z[dq_min[tmin - 1]] >= z[i])
                tmin--;
            dq_min[tmin++] = i;
            if (i + 1 < w)
                continue;
            const size_t start = i + 1 - w;
            while (dq_max[hmax] < start)
                hmax++;
            while (dq_min[hmin] < start)
                hmin++;
            total += z[dq_max[hmax]] - z[dq_min[hmin]];
            m++;
        }
    }
    return m ? total / (double)m : NAN;
}

/* The periodogram averaged over rows (rows with an invalid point are left out), at
 * q_j = 2 pi j / (nx dx), j = 1 .. nx / 2; *rows_used the rows it holds. */
/* The largest m <= n with no prime factor above 5: GSL's mixed-radix FFT costs O(n p) for a
 * prime factor p, minutes for 10^7 samples with factors in the thousands; the spectrum is
 * taken of the first m samples of each row (m >= 0.9 n for n >= 8, a few percent shorter). */
static size_t fft_length(size_t n)
{
    for (size_t m = n; m > 1; m--) {
        size_t k = m;
        while (k % 2 == 0)
            k /= 2;
        while (k % 3 == 0)
            k /= 3;
        while (k % 5 == 0)
            k /= 5;
        if (k == 1)
            return m;
    }
    return n;
}

/* The periodogram of the first *m samples of each row, averaged over the rows: C[j],
 * 0 < j <= m/2, of wavenumber 2 pi j / (m dx); *m = fft_length(nx). */
static int spectrum(const rows *r, double *C, size_t *rows_used, size_t *m)
{
    const size_t n = fft_length(r->nx);
    *m = n;
    gsl_fft_real_wavetable *wt = gsl_fft_real_wavetable_alloc(n);
    gsl_fft_real_workspace *ws = gsl_fft_real_workspace_alloc(n);
    double *buf = malloc(n * sizeof(double));
    if (!wt || !ws || !buf) {
        gsl_fft_real_wavetable_free(wt);
        gsl_fft_real_workspace_free(ws);
        free(buf);
        return ct_error_set(CT_ENOMEM, "fit: spectrum of %zu points: out of memory", n);
    }
    size_t used = 0;
    for (size_t j = 0; j <= n / 2; j++)
        C[j] = 0.0;
    for (size_t y = 0; y < r->ny; y++) {
        const double *z = r->z + y * r->nx;
        double mean = 0.0;
        int bad = 0;
        for (size_t i = 0; i < n && !bad; i++) {
            bad = isnan(z[i]);
            mean += z[i];
        }
        if (bad)
            continue;
        mean /= (double)n;
        for (size_t i = 0; i < n; i++) /* Hann window */
            buf[i] = (z[i] - mean) * (0.5 - 0.5 * cos(6.283185307179586 * (double)i / (double)n));
        if (gsl_fft_real_transform(buf, 1, n, wt, ws) != 0)
            continue;
        /* halfcomplex: buf[2j - 1] = Re, buf[2j] = Im for 0 < j < n/2 */
        for (size_t j = 1; j <= n / 2; j++) {
            double re = buf[2 * j - 1], im = 2 * j < n ? buf[2 * j] : 0.0;
            C[j] += re * re + im * im;
        }
        used++;
    }
    gsl_fft_real_wavetable_free(wt);
    gsl_fft_real_workspace_free(ws);
    free(buf);
    *rows_used = used;
    return CT_OK;
}

/* alpha and h0 from the bearing-area curve on [d_lo, d_hi] (0: the defaults) */
static int fit_bearing(const ct_profile *p, double d_lo, double d_hi, ct_profile_fit *fit)
{
    int st;
    /* the bearing-area curve */
    ct_top_weight *tw;
    double W;
    if ((st = ct_profile_sorted_tops(p, &tw, &W)))
        return st;
    if (d_lo == 0.0)
        d_lo = tw[p->n > 20 ? 19 : p->n - 1].t;
    if (d_hi == 0.0) {
        double acc = 0.0;
        size_t i = 0;
        while (i < p->n && (acc += tw[i].w) < 0.1 * W)
            i++;
        d_hi = tw[i < p->n ? i : p->n - 1].t;
    }
    /* the curve's corners: every distinct depth with the area fraction at and above it (a
     * staircase bearing curve, the prefractal's, touches the power law at its corners), thinned
     * to about NB log-spaced ones so that every decade of the band weighs the same */
    enum { NB = 400 };
    double lx[NB + 1], ly[NB + 1];
    size_t nb = 0;
    if (d_lo > 0.0 && d_hi > d_lo) {
        const double step = log(d_hi / d_lo) / NB;
        double acc = 0.0, last = -INFINITY;
        for (size_t i = 0; i < p->n; i++) {
            acc += tw[i].w;
            if (i + 1 < p->n && tw[i + 1].t == tw[i].t)
                continue; /* the corner is after the last sample of this depth */
            if (tw[i].t < d_lo || tw[i].t > d_hi || nb > NB)
                continue;
            const double lt = log(tw[i].t);
            if (lt < last + step)
                continue;
            lx[nb] = lt;
            ly[nb++] = log(acc / W);
            last = lt;
        }
    }
    free(tw);
    if (nb == 0)
        return ct_error_set(CT_EINVAL,
                            "fit of the bearing curve: depth band [%g, %g] empty (too few "
                            "distinct heights near the top?)",
                            d_lo, d_hi);
    if ((st = fit_line(lx, ly, nb, log(d_lo) - 1e-12, log(d_hi) + 1e-12, &fit->bearing,
                       "bearing-area curve")))
        return st;
    fit->alpha = fit->bearing.slope;
    fit->h0 = exp(-fit->bearing.intercept / fit->alpha);
    return CT_OK;
}

/* Eq. 3 inverted with alpha and the D of the method asked for */
static void fit_eq3(const ct_profile *p, ct_profile_fit *fit)
{
    fit->D = fit->dimension == CT_DIM_STRUCTURE  ? fit->D_structure
             : fit->dimension == CT_DIM_SPECTRUM ? fit->D_spectrum
                                                 : fit->D_variation;
    const double a = fit->alpha, D = fit->D;
    const double ln_fz = log(2.0) * (2.0 - D) / (1.0 + a * (D - 1.0));
    fit->fz = exp(ln_fz);
    fit->fx = exp(a * ln_fz);
    fit->l0 = p->ny > 1 ? (double)p->nx * p->dx : fit->stats.length;
}

int ct_profile_fit_of(const ct_profile *p, double d_lo, double d_hi, double tau_lo, double tau_hi,
                      ct_profile_fit *fit)
{
    CT_NEED(p);
    CT_NEED(fit);
    const ct_dimension_method method = fit->dimension;
    if (method < CT_DIM_VARIATION || method > CT_DIM_SPECTRUM)
        return ct_error_set(CT_EINVAL, "fit: dimension method %d unknown", (int)method);
    memset(fit, 0, sizeof *fit);
    fit->dimension = method;
    int st;
    if ((st = ct_profile_stats_of(p, &fit->stats)))
        return st;
    if (!(fit->stats.Rt > 0.0))
        return ct_error_set(CT_EINVAL, "fit: all heights are equal: there is no roughness to fit");
    if (!(d_lo >= 0.0 && d_hi >= 0.0 && tau_lo >= 0.0 && tau_hi >= 0.0))
        return ct_error_set(CT_EINVAL, "fit: bands must be >= 0 (0: the default)");
    if ((st = fit_bearing(p, d_lo, d_hi, fit)))
        return st;
    /* the structure function and the spectrum, along x */
    rows r = {0};
    if ((st = rows_of(p, &r)))
        return st;
    /* Heights far from 1 m (an X3P's CZ increment of 1e300, a profile at 1e-170 m) square to
     * beyond doubles in the structure function and the spectrum; their slopes, all the
     * dimensions take, do not depend on the heights' unit: such rows are taken in units of a
     * power of two (exact), heights of ordinary units as they are */
    const int zk = ct_heights_exponent(r.z, r.nx * r.ny) - 1; /* ilogb of the largest */
    if (zk > 256 || zk < -256)
        for (size_t j = 0; j < r.nx * r.ny; j++)
            r.z[j] = ldexp(r.z[j], -zk);
    if (r.nx < 8) {
        free(r.z);
        return ct_error_set(CT_EINVAL,
                            "fit: rows of %zu points: too short for a structure "
                            "function",
                            r.nx);
    }
    const double L = (double)r.nx * r.dx;
    if (tau_lo == 0.0)
        tau_lo = 2.0 * r.dx;
    if (tau_hi == 0.0)
        tau_hi = 0.1 * L;
    if (!(tau_hi > tau_lo)) {
        free(r.z);
        return ct_error_set(CT_EINVAL, "fit: lag band [%g, %g] is empty", tau_lo, tau_hi);
    }
    size_t k_lo = (size_t)ceil(tau_lo / r.dx), k_hi = (size_t)floor(tau_hi / r.dx);
    k_lo = k_lo < 1 ? 1 : k_lo;
    k_hi = k_hi > r.nx - 1 ? r.nx - 1 : k_hi;
    enum { NL = 40 };
    double sx[NL], sy[NL];
    size_t ns = 0, last = 0;
    for (int q = 0; q < NL && k_hi >= k_lo; q++) {
        size_t k =
            (size_t)llround((double)k_lo * pow((double)k_hi / (double)k_lo, (double)q / (NL - 1)));
        if (k == last)
            continue;
        last = k;
        double S = structure(&r, k);
        sx[ns] = log((double)k * r.dx);
        sy[ns++] = S > 0.0 ? log(S) : NAN;
    }
    st = fit_line(sx, sy, ns, log(k_lo * r.dx) - 1e-12, log(k_hi * r.dx) + 1e-12, &fit->structure,
                  "structure function");
    if (!st) { /* the variation method on the same windows: 2 k + 1 samples wide */
        size_t *dq = malloc(2 * r.nx * sizeof(size_t));
        double vx[NL], vy[NL];
        size_t nv = 0;
        last = 0;
        if (!dq)
            st = ct_error_set(CT_ENOMEM, "fit: out of memory");
        for (int q = 0; q < NL && !st; q++) {
            size_t k = (size_t)llround((double)k_lo *
                                       pow((double)k_hi / (double)k_lo, (double)q / (NL - 1)));
            if (k == last || 2 * k + 1 > r.nx)
                continue;
            last = k;
            double V = variation(&r, k, dq, dq + r.nx);
            vx[nv] = log((double)(2 * k) * r.dx);
            vy[nv++] = V > 0.0 ? log(V) : NAN;
        }
        free(dq);
        if (!st)
            st = fit_line(vx, vy, nv, -INFINITY, INFINITY, &fit->variation,
                          "variation (box-counting) function");
        if (!st)
            fit->D_variation = 2.0 - fit->variation.slope;
    }
    if (!st) {
        fit->D_structure = 2.0 - 0.5 * fit->structure.slope;
        double *C = malloc((r.nx / 2 + 1) * sizeof(double));
        size_t used = 0, m = r.nx;
        st = C ? spectrum(&r, C, &used, &m) : ct_error_set(CT_ENOMEM, "fit: out of memory");
        if (!st && used == 0)
            st = ct_error_set(CT_EINVAL, "fit: every row holds an invalid point: no spectrum");
        if (!st) {
            /* log-spaced bins of q inside [2 pi / tau_hi, 2 pi / tau_lo]: the power in each bin
             * over its width, at the bin's mean ln q. A density: right for the continuous
             * spectra of measured (random) surfaces; a line spectrum with lines further apart
             * than a bin (a Weierstrass function's, a Cantor profile's) leaves bins empty of
             * lines, and the variation or structure estimate is the one to use there */
            const double q0 = 6.283185307179586 / ((double)m * r.dx),
                         q_lo = 6.283185307179586 / tau_hi, q_hi = 6.283185307179586 / tau_lo;
            double bx[NL] = {0}, bs[NL] = {0};
            size_t bn[NL] = {0};
            for (size_t j = 1; j <= m / 2; j++) {
                double q = q0 * (double)j;
                if (q < q_lo || q > q_hi)
                    continue;
                int b = (int)floor(NL * log(q / q_lo) / log(q_hi / q_lo));
                b = b < 0 ? 0 : b >= NL ? NL - 1 : b;
                bs[b] += C[j];
                bx[b] += log(q);
                bn[b]++;
            }
            double fx_[NL], fy_[NL];
            size_t nf = 0;
            for (int b = 0; b < NL; b++)
                if (bn[b] && bs[b] > 0.0) {
                    double width = q0 * (double)bn[b]; /* the bin's wavenumbers, q0 apart */
                    fx_[nf] = bx[b] / (double)bn[b];
                    fy_[nf++] = log(bs[b] / width);
                }
            st = fit_line(fx_, fy_, nf, log(q_lo) - 1e-12, log(q_hi) + 1e-12, &fit->spectrum,
                          "power spectrum");
            if (!st)
                fit->D_spectrum = 0.5 * (5.0 + fit->spectrum.slope); /* C ~ q^-(5 - 2D) */
        }
        free(C);
    }
    free(r.z);
    if (st)
        return st;
    /* Eq. 3 inverted, with the dimension asked for */
    fit_eq3(p, fit);
    return CT_OK;
}

int ct_profile_fit_bearing(const ct_profile *p, double d_lo, double d_hi, ct_profile_fit *fit)
{
    CT_NEED(p);
    CT_NEED(fit);
    if (!(fit->stats.Rt > 0.0) || !(fit->D > 0.0))
        return ct_error_set(CT_EINVAL, "fit: refit of the bearing curve before a whole fit");
    if (!(d_lo >= 0.0 && d_hi >= 0.0))
        return ct_error_set(CT_EINVAL, "fit: bands must be >= 0 (0: the default)");
    ct_profile_fit f = *fit;
    int st = fit_bearing(p, d_lo, d_hi, &f);
    if (st)
        return st;
    fit_eq3(p, &f);
    *fit = f;
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

static void fit_row(FILE *f, const char *name, double value, const ct_fit_line *l)
{
    fprintf(f, "%s,", name);
    ct_put_double(f, value);
    if (l)
        fprintf(f, ",%.6g,%.6g,%zu,%.6f,%.4g\n", l->lo, l->hi, l->n, l->r2, l->residual);
    else
        fputs(",,,,,\n", f);
}

size_t ct_profile_fit_warning(const ct_profile_fit *fit, char *buf, size_t len)
{
    static const char *const names[] = {"D_variation", "D_structure", "D_spectrum"};
    const double D[] = {fit->D_variation, fit->D_structure, fit->D_spectrum};
    const ct_fit_line *line[] = {&fit->variation, &fit->structure, &fit->spectrum};
    size_t bad = 0, n = 0;
    if (len)
        buf[0] = '\0';
    for (int k = 0; k < 3; k++) {
        if (D[k] > 1.0 && D[k] < 2.0)
            continue;
        n += (size_t)snprintf(buf + n, len > n ? len - n : 0, "%s%s = %.4g (r2 %.3g)",
                              bad ? ", " : "", names[k], D[k], line[k]->r2);
        bad++;
    }
    if (!bad)
        return 0;
    const int used = fit->dimension - CT_DIM_VARIATION;
    const int used_bad = !(D[used] > 1.0 && D[used] < 2.0);
    snprintf(buf + n, len > n ? len - n : 0,
             " outside (1, 2), the range of a fractal profile's dimension: not self-affine in "
             "%s%s%s",
             bad > 1 ? "those bands" : "that band", used_bad ? "; D, fx and fz come from " : "",
             used_bad ? names[used] : "");
    if (used_bad && n < len)
        snprintf(buf + strlen(buf), len - strlen(buf),
                 ", so they describe no Cantor surface (1 < fz < 2, fx > 1)");
    return bad;
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
    char warning[512];
    if (ct_profile_fit_warning(fit, warning, sizeof warning))
        fprintf(f, "# warning: %s\n", warning);
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
