/* Bodies (src/body/, docs/model.md §14): a flat body leaves the rods bit for bit; a cylinder
 * and a sphere shift each rod's top by the gap of their face at the rod's footprint. Checked
 * against closed forms of a smooth Winkler bed (every top 0, one length L): a sphere loads as
 * P = (E/L) pi (R u^2 - u^3/3) while elastic and as pi sigma_y [2R(u - u_y) - (u - u_y)^2 +
 * (R - u) u_y + (2/3) u_y^2] beyond yield; a cylinder per unit depth as (E/L) (R^2 asin(a/R) -
 * a (R - u)), a = sqrt(2Ru - u^2). A grid of point rods is the midpoint rule of those
 * integrals: its error falls about fourfold when the spacing halves. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "cantact.h"
#include "body/body.h"

#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A rods surface of n rods with tops, areas, positions (y NULL: a line), H* = Hstar,
 * E, sigma_y; prepared. */
static ct_surface *rod_set(size_t n, const double *top, const double *area, const double *x,
                           const double *y, double Hstar, double E, double sigma_y)
{
    ct_surface *s;
    char v[64];
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set_rods_at(s, n, top, area, NULL, x, y), CT_OK);
    snprintf(v, sizeof v, "%.17g", Hstar);
    assert_int_equal(ct_surface_set(s, "surface", "Hstar", v, ""), CT_OK);
    snprintf(v, sizeof v, "%.17g", E);
    assert_int_equal(ct_surface_set(s, "material", "E", v, ""), CT_OK);
    snprintf(v, sizeof v, "%.17g", sigma_y);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", v, ""), CT_OK);
    int st = ct_surface_prepare(s, NULL);
    if (st)
        fail_msg("%s", ct_error_message());
    return s;
}

static ct_bundle *build(const ct_surface *s, const ct_body *body)
{
    const double V = 1e-3;
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    int st = ct_surface_build(s, &req, &b, NULL);
    if (st)
        fail_msg("%s", ct_error_message());
    return b;
}

static ct_body body_of(int shape, double R, double x, double y)
{
    ct_body b;
    ct_body_defaults(&b);
    b.shape = shape;
    b.radius = R;
    b.position[0] = x;
    b.position[1] = y;
    return b;
}

/* A smooth bed: an m x m grid of point rods (m x 1 on a line) of spacing h centred on 0, every
 * top 0, area h^2 (a line: h), length L = H*. */
typedef struct {
    size_t n;
    double *top, *area, *x, *y;
} grid;

static grid smooth_grid(size_t m, double h, int areal)
{
    grid g;
    g.n = areal ? m * m : m;
    g.top = calloc(g.n, sizeof(double));
    g.area = malloc(g.n * sizeof(double));
    g.x = malloc(g.n * sizeof(double));
    g.y = areal ? malloc(g.n * sizeof(double)) : NULL;
    assert_true(g.top && g.area && g.x && (!areal || g.y));
    for (size_t i = 0; i < g.n; i++) {
        const size_t c = i % m, r = i / m;
        g.x[i] = ((double)c - 0.5 * (double)(m - 1)) * h;
        if (areal)
            g.y[i] = ((double)r - 0.5 * (double)(m - 1)) * h;
        g.area[i] = areal ? h * h : h;
    }
    return g;
}

static void grid_free(grid *g)
{
    free(g->top);
    free(g->area);
    free(g->x);
    free(g->y);
}

static double sphere_elastic(double E, double L, double R, double u)
{
    return E / L * M_PI * (R * u * u - u * u * u / 3.0);
}

static double sphere_plastic(double sigma_y, double uy, double R, double u)
{
    const double v = u - uy;
    return M_PI * sigma_y * (2.0 * R * v - v * v + (R - u) * uy + 2.0 / 3.0 * uy * uy);
}

static double cylinder_elastic(double E, double L, double R, double u)
{
    const double a = sqrt(2.0 * R * u - u * u);
    return E / L * (R * R * asin(a / R) - a * (R - u));
}

/* |P_grid - P| / P at u, for spacing h: the sphere (areal) or the cylinder (line) */
static double grid_error(int areal, size_t m, double h, double R, double u, double sigma_y)
{
    const double E = 1.0, L = 1.0;
    grid g = smooth_grid(m, h, areal);
    ct_surface *s = rod_set(g.n, g.top, g.area, g.x, g.y, L, E, sigma_y);
    ct_body body = body_of(areal ? 2 : 1, R, 0.0, areal ? 0.0 : NAN);
    ct_bundle *b = build(s, &body);
    const double P = ct_bundle_force(b, u);
    const double uy = sigma_y / E * L;
    const double exact = !areal    ? cylinder_elastic(E, L, R, u)
                         : u <= uy ? sphere_elastic(E, L, R, u)
                                   : sphere_plastic(sigma_y, uy, R, u);
    ct_bundle_free(b);
    ct_surface_free(s);
    grid_free(&g);
    return fabs(P - exact) / exact;
}

static void smooth_bed_closed_forms(void **state)
{
    (void)state;
    /* a sphere R = 1 pressed u = 0.01 (contact radius 0.141): grids of spacing 0.01 and 0.005
     * over [-0.2, 0.2]^2, elastic (sigma_y = E/2: eps_y = 0.5) */
    const double e1 = grid_error(1, 41, 0.01, 1.0, 0.01, 0.5);
    const double e2 = grid_error(1, 81, 0.005, 1.0, 0.01, 0.5);
    assert_true(e1 < 1e-3);     /* measured 3.6e-4, then 6.2e-5 */
    assert_true(e2 < e1 / 3.0); /* O(h^2) in the mean, a lattice's count of points on a disc
                                   scatters about it */
    /* beyond yield: eps_y = 0.002 (u_y = 0.002 < u = 0.01) */
    const double p1 = grid_error(1, 41, 0.01, 1.0, 0.01, 0.002);
    const double p2 = grid_error(1, 81, 0.005, 1.0, 0.01, 0.002);
    assert_true(p1 < 3e-3); /* 1.6e-3, then 1.5e-4 */
    assert_true(p2 < p1 / 3.0);
    /* a cylinder on a line: the same, per unit depth */
    const double c1 = grid_error(0, 401, 0.001, 1.0, 0.01, 0.5);
    const double c2 = grid_error(0, 801, 0.0005, 1.0, 0.01, 0.5);
    assert_true(c1 < 2e-5); /* 7.9e-6, then 9.5e-7 */
    assert_true(c2 < c1 / 3.0);
}

/* One rod at distance d from the apex: the face reaches it at exactly top + R - sqrt(R^2 - d^2). */
static void one_rod_at_an_offset(void **state)
{
    (void)state;
    const double top[1] = {0.25}, area[1] = {1e-3}, x[1] = {0.3}, y[1] = {-0.4};
    ct_surface *s = rod_set(1, top, area, x, y, 2.0, 100.0, 1.0);
    ct_body body = body_of(2, 2.0, 0.0, 0.0); /* d = 0.5 */
    ct_bundle *b = build(s, &body);
    const long double R = 2.0L, d = 0.5L, f = R - sqrtl(R * R - d * d);
    const double contact = ct_bundle_first_contact(b);
    assert_true(fabsl((long double)contact - (0.25L + f)) <= 1e-16L);
    ct_rod_info r;
    ct_bundle_rod(b, 0, &r);
    assert_int_equal(r.footprint.shape, CT_FOOTPRINT_POINT);
    assert_true(r.footprint.x_lo == 0.3 && r.footprint.y_lo == -0.4);
    ct_bundle_free(b);
    /* beyond R the face never reaches it: the body meets no rod */
    body = body_of(2, 0.4, 0.0, 0.0);
    const double V = 1e-3;
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "reaches no rod"));
    ct_surface_free(s);
}

/* A flat body, given or not, leaves the rods as built, byte for byte. */
static void flat_body_changes_nothing(void **state)
{
    (void)state;
    grid g = smooth_grid(7, 0.1, 1);
    for (size_t i = 0; i < g.n; i++)
        g.top[i] = 0.01 * (double)((i * 5) % 7);
    ct_surface *s = rod_set(g.n, g.top, g.area, g.x, g.y, 1.0, 50.0, 1.0);
    ct_body flat;
    ct_body_defaults(&flat);
    ct_bundle *a = build(s, NULL), *b = build(s, &flat);
    assert_int_equal(ct_bundle_size(a), ct_bundle_size(b));
    for (size_t k = 0; k < ct_bundle_size(a); k++) {
        ct_rod_info ra, rb;
        ct_bundle_rod(a, k, &ra);
        ct_bundle_rod(b, k, &rb);
        assert_memory_equal(&ra, &rb, sizeof ra);
    }
    ct_bundle_free(a);
    ct_bundle_free(b);
    ct_surface_free(s);
    grid_free(&g);
}

/* What a surface cannot carry is refused, saying what to use. */
static void shapes_a_surface_cannot_carry(void **state)
{
    (void)state;
    grid line = smooth_grid(5, 0.1, 0), plane = smooth_grid(5, 0.1, 1);
    ct_surface *sl = rod_set(line.n, line.top, line.area, line.x, NULL, 1.0, 50.0, 1.0);
    ct_surface *sp = rod_set(plane.n, plane.top, plane.area, plane.x, plane.y, 1.0, 50.0, 1.0);
    const double V = 1e-3;
    ct_body sphere = body_of(2, 1.0, NAN, NAN), cyl = body_of(1, 1.0, NAN, NAN);
    ct_build_request req = {
        .V_star = &V, .nvel = 1, .impacts = 1, .depth_tolerance = 1e-12, .body = &sphere};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    assert_int_equal(ct_surface_build(sl, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "a sphere needs an areal surface"));
    req.body = &cyl;
    assert_int_equal(ct_surface_build(sp, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "a cylinder needs a line surface"));
    /* stage rods of a Cantor surface merge pieces: no single place */
    ct_surface *c;
    assert_int_equal(ct_surface_new(&c, "cantor"), CT_OK);
    assert_int_equal(ct_surface_set(c, "surface", "fx", "1.5", ""), CT_OK);
    assert_int_equal(ct_surface_set(c, "surface", "fz", "1.3", ""), CT_OK);
    assert_int_equal(ct_surface_set(c, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(c, "material", "E", "500", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(c, NULL), CT_OK);
    req.body = &cyl;
    assert_int_equal(ct_surface_build(c, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "representation = segments"));
    /* a cylinder's apex is x alone; a sphere's needs x and y */
    ct_body bad = body_of(1, 1.0, 0.0, 0.0);
    req.body = &bad;
    assert_int_equal(ct_surface_build(sl, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "placed by x alone"));
    bad = body_of(2, 1.0, 0.0, NAN);
    assert_int_equal(ct_surface_build(sp, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "needs x and y"));
    bad = body_of(2, 0.0, NAN, NAN);
    assert_int_equal(ct_surface_build(sp, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "needs a radius"));
    bad = body_of(2, 1.0, NAN, 0.0); /* y without x */
    assert_int_equal(ct_surface_build(sp, &req, &b, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "without x"));
    ct_surface_free(c);
    ct_surface_free(sl);
    ct_surface_free(sp);
    grid_free(&line);
    grid_free(&plane);
}

/* ---- e of a sphere on a smooth bed, against the continuum ---- */

typedef struct {
    double E, L, sigma_y, R, u_max;
} bed;

static double load_at(double u, void *p)
{
    const bed *b = p;
    const double uy = b->sigma_y / b->E * b->L;
    return u <= uy ? sphere_elastic(b->E, b->L, b->R, u) : sphere_plastic(b->sigma_y, uy, b->R, u);
}

/* the energy a rod ring at radius r gives back, per dr: E L min(eps_max, eps_y)^2 / 2 2 pi r */
static double given_back_at(double r, void *p)
{
    const bed *b = p;
    const double f = r * r / (b->R + sqrt((b->R - r) * (b->R + r)));
    const double eps = fmin((b->u_max - f) / b->L, b->sigma_y / b->E);
    return eps > 0.0 ? b->E * b->L * eps * eps / 2.0 * 2.0 * M_PI * r : 0.0;
}

static double integral(double (*fn)(double, void *), bed *b, double lo, double hi)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    gsl_function F = {fn, b};
    double v, err;
    const double pts[3] = {lo, fmin(fmax(b->sigma_y / b->E * b->L, lo), hi), hi};
    gsl_integration_qagp(&F, (double *)pts, 3, 0.0, 1e-13, 1000, w, &v, &err);
    gsl_integration_workspace_free(w);
    return v;
}

static void sphere_e_against_the_continuum(void **state)
{
    (void)state;
    /* R = 1, eps_y = 0.002 (L = 1), an impact of energy W that presses the bed to u = 0.01 in
     * the continuum: u_max by bisection on W_load(u) = int_0^u P; e = sqrt(W_unload / W) */
    bed c = {1.0, 1.0, 0.002, 1.0, 0.0};
    const double u_target = 0.01;
    const double W = integral(load_at, &c, 0.0, u_target);
    double lo = 0.0, hi = 0.02;
    for (int k = 0; k < 200; k++) {
        const double mid = 0.5 * (lo + hi);
        if (integral(load_at, &c, 0.0, mid) < W)
            lo = mid;
        else
            hi = mid;
    }
    c.u_max = 0.5 * (lo + hi);
    const double a = sqrt(2.0 * c.R * c.u_max - c.u_max * c.u_max);
    bed cc = c;
    const double e_cont = sqrt(integral(given_back_at, &cc, 0.0, a) / W);
    /* the grid: its own V* from W (h0 = H* = 1 for a bed of tops 0, l0 = its total area) */
    grid g = smooth_grid(81, 0.005, 1);
    ct_surface *s = rod_set(g.n, g.top, g.area, g.x, g.y, 1.0, 1.0, 0.002);
    ct_scales sc;
    ct_surface_scales(s, &sc);
    const double V = sqrt(W / sc.energy_scale);
    ct_body body = body_of(2, 1.0, 0.0, 0.0);
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    ct_sweep_row row;
    ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .opts = req.opts};
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    assert_int_equal(row.status, CT_OK);
    /* measured: u_max 4e-7 and e 2.6e-5 off (the grid's midpoint rule) */
    assert_true(fabs(row.r.u_max * sc.layer.h0 - c.u_max) / c.u_max < 1e-5);
    assert_true(fabs(row.r.e - e_cont) / e_cont < 1e-4);
    assert_true(row.r.e < 0.9 && row.r.e > 0.1); /* plastic, not trivially 1 */
    ct_bundle_free(b);
    ct_surface_free(s);
    grid_free(&g);
}

/* A profile's samples stand for intervals: the face meets each at the interval's nearest point
 * to the apex (a sample holding the apex: no shift). Five samples 1 mm apart, a cylinder of
 * R = 10 mm landing at x = 1.8 mm (inside sample 2's interval [1.5, 2.5] mm). */
static void profile_intervals_met_at_their_nearest_point(void **state)
{
    (void)state;
    char path[64];
    snprintf(path, sizeof path, "/tmp/ct_body_%d.csv", (int)getpid());
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("x (mm), z (mm)\n0,0.01\n1,0.03\n2,0.02\n3,0.04\n4,0.00\n", f);
    fclose(f);
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "profile"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "detrend", "none", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "2e11", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", "4e8", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    ct_body body = body_of(1, 10e-3, 1.8e-3, NAN);
    ct_bundle *b = build(s, &body);
    /* sample j: top (0.04 - z_j) mm, interval [j - 0.5, j + 0.5] mm (the ends as far out as in) */
    const double z[5] = {0.01, 0.03, 0.02, 0.04, 0.0}, near[5] = {1.3, 0.3, 0.0, 0.7, 1.7};
    assert_int_equal(ct_bundle_size(b), 5);
    for (size_t k = 0; k < 5; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        size_t j = 0;
        while (j < 5 &&
               !(r.footprint.x_lo < (double)j * 1e-3 && (double)j * 1e-3 < r.footprint.x_hi))
            j++;
        assert_true(j < 5);
        const long double R = 10e-3L, d = (long double)near[j] * 1e-3L;
        const long double expect = (0.04L - (long double)z[j]) * 1e-3L + (R - sqrtl(R * R - d * d));
        assert_true(fabsl((long double)r.top - expect) <= 1e-18L);
    }
    ct_bundle_free(b);
    ct_surface_free(s);
    unlink(path);
}

/* ---- periodic surfaces and the border ---- */

/* A line profile file of `copies` periods of 16 samples 0.1 mm apart (heights a fixed
 * pattern in um), levelled not at all: the same surface laid out copies times by hand. */
static ct_surface *tiled_profile(const char *path, int copies, int periodic)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("x (mm), z (um)\n", f);
    for (int c = 0; c < copies; c++)
        for (int j = 0; j < 16; j++)
            fprintf(f, "%.17g,%.17g\n", (c * 16 + j) * 0.1, 0.5 * ((j * 7) % 16) + (j == 5));
    fclose(f);
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "profile"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "detrend", "none", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "2e11", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", "4e8", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    (void)periodic;
    return s;
}

/* e and u_max [m] of one impact of energy W [J/m] under body on s */
static int impact_of(const ct_surface *s, const ct_body *body, double W, double *e, double *u,
                     char *msg, size_t len)
{
    ct_scales sc;
    ct_surface_scales(s, &sc);
    const double V = sqrt(W / sc.physical_energy_scale);
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    int st = ct_surface_build(s, &req, &b, NULL);
    if (st)
        return st;
    ct_sweep_row row;
    ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .opts = req.opts};
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    ct_bundle_free(b);
    *e = row.r.e;
    *u = row.r.u_max; /* the layer's unit: metres */
    snprintf(msg, len, "%s", row.message);
    return row.status;
}

static void periodic_as_laid_out_by_hand(void **state)
{
    (void)state;
    char p1[64], p3[64], msg[300];
    snprintf(p1, sizeof p1, "/tmp/ct_per1_%d.csv", (int)getpid());
    snprintf(p3, sizeof p3, "/tmp/ct_per3_%d.csv", (int)getpid());
    ct_surface *one = tiled_profile(p1, 1, 1), *three = tiled_profile(p3, 3, 0);
    /* a cylinder R = 5 mm landing 0.25 mm into the period (the middle copy of the three) */
    ct_body periodic = body_of(1, 5e-3, 0.25e-3, NAN), laid = body_of(1, 5e-3, 1.85e-3, NAN);
    periodic.periodic = 1;
    const double W = 5.0; /* J/m: u_max 20 um, the face 0.45 mm wide either side: into both
                           neighbouring periods */
    double e1, u1, e3, u3;
    assert_int_equal(impact_of(one, &periodic, W, &e1, &u1, msg, sizeof msg), CT_OK);
    assert_int_equal(impact_of(three, &laid, W, &e3, &u3, msg, sizeof msg), CT_OK);
    assert_true(fabs(e1 - e3) <= 1e-12 * e3 && fabs(u1 - u3) <= 1e-12 * u3);
    assert_true(e1 < 0.99); /* a plastic impact, reached into the neighbours */
    /* the same spot periods away, either way: the same surface under the face */
    for (int k = -40; k <= 40; k += 7) {
        ct_body far = periodic;
        far.position[0] = 0.25e-3 + k * 1.6e-3;
        double ek, uk;
        assert_int_equal(impact_of(one, &far, W, &ek, &uk, msg, sizeof msg), CT_OK);
        assert_true(fabs(ek - e1) <= 1e-12 * e1 && fabs(uk - u1) <= 1e-12 * u1);
    }
    /* and near the period's other end, into the copy on the right */
    periodic.position[0] = 1.45e-3;
    laid.position[0] = 3.05e-3;
    assert_int_equal(impact_of(one, &periodic, W, &e1, &u1, msg, sizeof msg), CT_OK);
    assert_int_equal(impact_of(three, &laid, W, &e3, &u3, msg, sizeof msg), CT_OK);
    assert_true(fabs(e1 - e3) <= 1e-12 * e3 && fabs(u1 - u3) <= 1e-12 * u3);
    laid.position[0] = 1.85e-3;
    /* without the repetition the same impact reaches the border of the one period: refused */
    assert_int_equal(impact_of(one, &laid, W, &e1, &u1, msg, sizeof msg), CT_EINVAL);
    ct_body here = body_of(1, 5e-3, 0.25e-3, NAN);
    assert_int_equal(impact_of(one, &here, W, &e1, &u1, msg, sizeof msg), CT_ERANGE);
    assert_non_null(strstr(msg, "reaches the border of the surface"));
    /* a gentle one stays inside */
    assert_int_equal(impact_of(one, &here, 1e-9, &e1, &u1, msg, sizeof msg), CT_OK);
    /* what = profile under the body: every rod kept, with its footprint and the face's gap.
     * The copies of the periodic surface are laid out as far as the face can reach a rod: where
     * its gap passes the deepest rod bottom H*, r = sqrt(H* (2R - H*)), one period more each way
     * (16 samples in each copy, the period 1.6 mm) */
    const double V = 1e-3;
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &periodic};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    ct_plan_info info;
    ct_scales sc;
    ct_surface_scales(one, &sc);
    const double Hs = sc.physical.Hstar, reach = sqrt(Hs * (2.0 * 5e-3 - Hs));
    const int K = (int)ceil(reach / 1.6e-3) + 1;
    assert_true(K < 4); /* ceil(R / P) = 4 each way would lay out copies the face cannot reach */
    assert_int_equal(ct_surface_build(one, &req, &b, &info), CT_OK);
    assert_int_equal(info.rods + info.omitted, 16 * (2 * K + 1));
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_int_equal(ct_surface_write_profile(one, b, f), CT_OK);
    fclose(f);
    size_t lines = 0;
    for (size_t k = 0; k < len; k++)
        lines += text[k] == '\n';
    assert_int_equal(lines, 1 + info.rods);
    assert_non_null(strstr(text, "rod,x_lo,x_hi,top_over_h0,gap_over_h0,"));
    free(text);
    ct_bundle_free(b);
    ct_surface_free(one);
    ct_surface_free(three);
    unlink(p1);
    unlink(p3);
}

/* The border rule holds on every path an impact takes: one that reaches the border fails the
 * same way in a sweep (with and without an observer: the observer never sees it), ct_impact,
 * ct_impact_history and a bounce, and leaves the state as it was. */
static int observed;
static int count_observed(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                          void *ctx)
{
    (void)row, (void)phase, (void)b, (void)c, (void)ctx;
    observed++;
    return 0;
}

static int keep_row(const ct_sweep_row *rows, size_t n, void *ctx)
{
    assert_int_equal(n, 1);
    *(ct_sweep_row *)ctx = rows[0];
    return 0;
}

static void the_border_holds_on_every_path(void **state)
{
    (void)state;
    char path[64];
    snprintf(path, sizeof path, "/tmp/ct_border_%d.csv", (int)getpid());
    ct_surface *s = tiled_profile(path, 1, 0);
    ct_scales sc;
    ct_surface_scales(s, &sc);
    /* the periodic test's impact at 0.25 mm: u_max 20 um, the face past the left edge */
    const ct_body here = body_of(1, 5e-3, 0.25e-3, NAN);
    const double W = 5.0, V = sqrt(W / sc.physical_energy_scale);
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &here};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    ct_sweep_row row;
    ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .opts = req.opts};
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    assert_int_equal(row.status, CT_ERANGE);
    assert_non_null(strstr(row.message, "reaches the border of the surface"));
    observed = 0;
    spec.observe = count_observed;
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    assert_int_equal(row.status, CT_ERANGE);
    assert_int_equal(observed, 0);
    spec.observe = NULL;
    for (int p = CT_PATH_CURVE; p <= CT_PATH_LEAN; p++) { /* whole, and in blocks */
        spec.path = (ct_sweep_path)p;
        row.status = CT_OK;
        assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
        assert_int_equal(row.status, CT_ERANGE);
        row.status = CT_OK;
        assert_int_equal(ct_sweep_blocks(b, &spec, 1, keep_row, &row), CT_OK);
        assert_int_equal(row.status, CT_ERANGE);
    }
    spec.path = CT_PATH_AUTO;
    /* one impact, its history and a bounce, in the layer's units (tau = 1 for m = E l0 / h0) */
    const ct_layer *L = ct_bundle_layer(b);
    const double Wl = V * V * L->l0 * L->E * L->h0, m = L->E * L->l0 / L->h0,
                 v1 = sqrt(2.0 * Wl / m);
    ct_bundle *copy;
    assert_int_equal(ct_bundle_clone(&copy, b), CT_OK);
    ct_impact_result res[3];
    ct_dynamics dyn[3];
    size_t n = 9;
    assert_int_equal(ct_impact(copy, Wl, NULL, &res[0]), CT_ERANGE);
    assert_non_null(strstr(ct_error_message(), "reaches the border of the surface"));
    for (size_t k = 0; k < ct_bundle_size(copy); k++) { /* the state as it was */
        ct_rod_info r;
        ct_bundle_rod(copy, k, &r);
        assert_true(r.plastic_strain == 0.0);
    }
    assert_int_equal(ct_impact_history(b, m, v1, 10, &res[0], &dyn[0], NULL), CT_ERANGE);
    assert_int_equal(ct_bounce(b, m, v1, 3, 0.0, res, dyn, &n), CT_ERANGE);
    assert_int_equal(n, 0);
    /* a gentle impact stays inside, on every path */
    const double Vg = sqrt(1e-9 / sc.physical_energy_scale), Wg = Vg * Vg * L->l0 * L->E * L->h0;
    spec.V_star = &Vg;
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    assert_int_equal(row.status, CT_OK);
    assert_int_equal(ct_impact(copy, Wg, NULL, &res[0]), CT_OK);
    assert_int_equal(ct_bounce(b, m, sqrt(2.0 * Wg / m), 3, 0.0, res, dyn, &n), CT_OK);
    assert_int_equal(n, 3);
    ct_bundle_free(copy);
    ct_bundle_free(b);
    ct_surface_free(s);
    unlink(path);
}

/* what = profile under a body is in the surface's frame: a rod's residual top is its top on
 * the surface plus its plastic set (strain x length), the face's gap in a column of its own;
 * a rod the impact did not yield keeps its top. */
static void profile_residual_top_on_the_surface(void **state)
{
    (void)state;
    char path[64];
    snprintf(path, sizeof path, "/tmp/ct_resid_%d.csv", (int)getpid());
    ct_surface *s = tiled_profile(path, 1, 0);
    ct_scales sc;
    ct_surface_scales(s, &sc);
    const ct_body body = body_of(1, 5e-3, 0.8e-3, NAN);
    const double V = sqrt(1e-2 / sc.physical_energy_scale);
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    const ct_layer *L = ct_bundle_layer(b);
    ct_impact_result res;
    assert_int_equal(ct_impact(b, V * V * L->l0 * L->E * L->h0, NULL, &res), CT_OK);
    assert_true(res.e < 0.99); /* some rods yielded, others not */
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    assert_int_equal(ct_surface_write_profile(s, b, f), CT_OK);
    fclose(f);
    const char *line = strchr(text, '\n') + 1;
    size_t yielded = 0, kept = 0;
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        long rod;
        double x_lo, x_hi, top, gap, area, length, residual;
        assert_int_equal(sscanf(line, "%ld,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &rod, &x_lo, &x_hi, &top,
                                &gap, &area, &length, &residual),
                         8);
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        const double set = r.plastic_strain * r.length / L->h0;
        assert_true(fabs(residual - (top + set)) <= 1e-12 * (top + set + gap));
        assert_true(fabs(top + gap - r.top / L->h0) <= 1e-12 * (r.top / L->h0));
        yielded += r.plastic_strain > 0.0;
        kept += r.plastic_strain == 0.0 && residual == top;
        line = strchr(line, '\n') + 1;
    }
    assert_true(yielded > 0 && kept > 0 && yielded + kept == ct_bundle_size(b));
    free(text);
    ct_bundle_free(b);
    ct_surface_free(s);
    unlink(path);
}

/* Landings meet a site prepared once (its rods read and sorted into cells, a cell the face
 * cannot reach below H passed over whole): for every apex the rods kept, their order, tops,
 * lengths, areas, footprints and the crushed limit are those of ct_body_apply with the apex
 * there, which reads every rod. Rods at random places on a plane (a sphere) and on a line (a
 * cylinder), points and, periodic, a map's pixels; apexes anywhere, near the borders too. */
static void compare_bundles(const ct_bundle *a, const ct_bundle *b)
{
    assert_int_equal(ct_bundle_size(a), ct_bundle_size(b));
    assert_true(ct_bundle_layer(a)->Hstar == ct_bundle_layer(b)->Hstar);
    assert_int_equal(ct_bundle_omitted(a), ct_bundle_omitted(b));
    for (size_t k = 0; k < ct_bundle_size(a); k++) {
        ct_rod_info ra, rb;
        ct_bundle_rod(a, k, &ra);
        ct_bundle_rod(b, k, &rb);
        assert_true(ra.top == rb.top && ra.length == rb.length && ra.area == rb.area);
        assert_true(ra.footprint.x_lo == rb.footprint.x_lo &&
                    ra.footprint.x_hi == rb.footprint.x_hi);
        assert_true(ra.footprint.y_lo == rb.footprint.y_lo ||
                    (isnan(ra.footprint.y_lo) && isnan(rb.footprint.y_lo)));
    }
}

static void site_as_every_rod_read(ct_surface *s, ct_body body, int dims, uint64_t seed)
{
    const double V = 1e-3;
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *rods;
    ct_scales sc;
    ct_surface_scales(s, &sc);
    assert_int_equal(ct_surface_build_unmet(s, &req, &rods, NULL), CT_OK);
    ct_body_site *site;
    assert_int_equal(ct_body_site_new(&body, &sc, rods, &site), CT_OK);
    double lo[2], hi[2];
    assert_int_equal(ct_body_site_region(site, lo, hi), CT_OK);
    /* over the region and beyond it (an apex at the border: the cells near the edges) */
    for (uint64_t k = 0; k < 24; k++) {
        double pos[2], wide_lo[2], wide_hi[2];
        for (int i = 0; i < 2; i++) {
            const double w = hi[i] - lo[i];
            wide_lo[i] = k % 2 ? lo[i] - 0.3 * w : lo[i];
            wide_hi[i] = k % 2 ? hi[i] + 0.3 * w : hi[i];
        }
        ct_body_landing(wide_lo, wide_hi, seed, k, pos);
        ct_body at = body;
        at.position[0] = pos[0];
        at.position[1] = dims == 2 ? pos[1] : NAN;
        ct_bundle *by_site = NULL, *by_rods = NULL;
        const int st = ct_body_site_meet(site, pos, &by_site);
        ct_bundle *copy;
        assert_int_equal(ct_bundle_clone(&copy, rods), CT_OK);
        by_rods = copy;
        const int st2 = ct_body_apply(&at, &sc, &by_rods, NULL);
        assert_int_equal(st, st2);
        if (st == CT_OK)
            compare_bundles(by_site, by_rods);
        else
            ct_bundle_free(copy);
        ct_bundle_free(by_site);
        if (st2 == CT_OK)
            ct_bundle_free(by_rods);
    }
    ct_body_site_free(site);
    ct_bundle_free(rods);
}

static void landings_meet_as_every_rod_read(void **state)
{
    (void)state;
    enum { N = 3000 };
    double *top = malloc(N * sizeof *top), *area = malloc(N * sizeof *area),
           *x = malloc(N * sizeof *x), *y = malloc(N * sizeof *y);
    uint64_t r = 88172645463325252ULL; /* xorshift64: places and tops */
    for (size_t k = 0; k < N; k++) {
        double u[3];
        for (int i = 0; i < 3; i++) {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            u[i] = (double)(r >> 11) * 0x1p-53;
        }
        x[k] = 100.0 * u[0];
        y[k] = 100.0 * u[1];
        top[k] = u[2];
        area[k] = 1.0;
    }
    ct_surface *plane = rod_set(N, top, area, x, y, 2.0, 500.0, 1.0),
               *line = rod_set(N, top, area, x, NULL, 2.0, 500.0, 1.0);
    site_as_every_rod_read(plane, body_of(2, 20.0, NAN, NAN), 2, 1);
    site_as_every_rod_read(plane, body_of(2, 400.0, NAN, NAN), 2, 2);
    site_as_every_rod_read(line, body_of(1, 30.0, NAN, NAN), 1, 3);
    ct_surface_free(plane);
    ct_surface_free(line);
    /* a periodic map of pixels: copies of the surface met too */
    char path[64];
    snprintf(path, sizeof path, "/tmp/ct_site_%d.csv", (int)getpid());
    ct_surface *tiled = tiled_profile(path, 1, 1);
    ct_body cyl = body_of(1, 5e-3, NAN, NAN);
    cyl.periodic = 1;
    site_as_every_rod_read(tiled, cyl, 1, 4);
    ct_surface_free(tiled);
    unlink(path);
    /* the shipped map's pixels (rectangles on a plane) under a ball, the map repeating */
    ct_surface *map;
    assert_int_equal(ct_surface_new(&map, "profile"), CT_OK);
    assert_int_equal(
        ct_surface_set(map, "surface", "file", CT_SOURCE_DIR "/examples/data/map128.x3p", ""),
        CT_OK);
    assert_int_equal(ct_surface_set(map, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(map, "material", "E", "2e11", ""), CT_OK);
    assert_int_equal(ct_surface_set(map, "material", "sigma_y", "4e8", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(map, NULL), CT_OK);
    ct_body ball = body_of(2, 2.5e-3, NAN, NAN);
    ball.periodic = 1;
    site_as_every_rod_read(map, ball, 2, 5);
    ct_body small = body_of(2, 2e-5, NAN, NAN); /* a face narrower than the period */
    small.periodic = 1;
    site_as_every_rod_read(map, small, 2, 6);
    ct_surface_free(map);
    free(top);
    free(area);
    free(x);
    free(y);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(smooth_bed_closed_forms),
        cmocka_unit_test(sphere_e_against_the_continuum),
        cmocka_unit_test(one_rod_at_an_offset),
        cmocka_unit_test(profile_intervals_met_at_their_nearest_point),
        cmocka_unit_test(periodic_as_laid_out_by_hand),
        cmocka_unit_test(the_border_holds_on_every_path),
        cmocka_unit_test(profile_residual_top_on_the_surface),
        cmocka_unit_test(flat_body_changes_nothing),
        cmocka_unit_test(landings_meet_as_every_rod_read),
        cmocka_unit_test(shapes_a_surface_cannot_carry),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
