/* Measured surfaces (docs/model.md §9): rods from a profile (areas, tops, the layer), the
 * bearing-area curve by hand, levelling against exact polynomials, trimming, the readers
 * (text, one column, Dektak, X3P written here with libzip) and their errors with line numbers,
 * and the fit: a smooth profile built with a known bearing law, a Weierstrass-Mandelbrot
 * profile of known dimension, and a Cantor prefractal sampled finely. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <gsl/gsl_fft_complex.h>
#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>
#include <zip.h>

#include "assert_rel.h"
#include "cantact.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static char dir[] = "/tmp/ct_profile_XXXXXX";

static const char *path_of(const char *name)
{
    static char buf[256];
    snprintf(buf, sizeof buf, "%s/%s", dir, name);
    return buf;
}

static void write_file(const char *name, const char *text)
{
    FILE *f = fopen(path_of(name), "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void expect_read_error(const char *name, const ct_profile_read_opts *o, const char *needle)
{
    ct_profile *p = (ct_profile *)dir;
    int st = ct_profile_read(path_of(name), o, &p);
    if (st == CT_OK)
        fail_msg("%s: read, expected an error with '%s'", name, needle);
    assert_null(p);
    if (!strstr(ct_error_message(), needle))
        fail_msg("%s: message '%s' lacks '%s'", name, ct_error_message(), needle);
}

/* Three samples by hand: x = 0, 1, 3 with z = 0, -1, -0.5: shares 1 (x1 - x0), 1.5 (half of
 * 3 - 0), 2 (x2 - x1); tops 0, 1, 0.5 below the highest; Rt = 1, l0 = 4.5. With H* = 2,
 * E = 100: P(u) = 100 (1 (u - 0)/2 + 2 (u - 0.5)/1.5 + 1.5 (u - 1)/1) while elastic. */
static void rods_by_hand(void **state)
{
    (void)state;
    const double x[] = {0.0, 1.0, 3.0}, z[] = {0.0, -1.0, -0.5};
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, 3, x, 0.0, z), CT_OK);
    ct_profile_stats s;
    assert_int_equal(ct_profile_stats_of(p, &s), CT_OK);
    assert_rel(s.length, 4.5, 1e-15);
    assert_rel(s.Rt, 1.0, 1e-15);
    assert_rel(s.mean, (0.0 - 1.5 - 1.0) / 4.5, 1e-15);
    ct_bundle *b;
    assert_int_equal(ct_profile_bundle(&b, p, 100.0, 99.0, 2.0), CT_OK); /* eps_y 0.99 */
    assert_int_equal(ct_bundle_size(b), 3);
    const ct_layer *L = ct_bundle_layer(b);
    assert_rel(L->l0, 4.5, 1e-15);
    assert_rel(L->h0, 1.0, 1e-15);
    const double u = 1.2;
    double P = 100.0 * (1.0 * u / 2.0 + 2.0 * (u - 0.5) / 1.5 + 1.5 * (u - 1.0) / 1.0);
    assert_rel(ct_bundle_force(b, u), P, 1e-14);
    ct_rod_info r;
    assert_int_equal(ct_bundle_rod(b, 1, &r), CT_OK); /* sample 1: its share of [0, 3] */
    assert_rel(r.x_right - r.x_left, 1.5, 1e-15);
    assert_rel(r.x_left, 0.5, 1e-15);
    ct_bundle_free(b);
    /* H* must exceed Rt; equal heights are no surface */
    assert_int_equal(ct_profile_bundle(&b, p, 100.0, 99.0, 1.0), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "peak-to-valley"));
    ct_profile_free(p);
    const double flat[] = {1.0, 1.0, 1.0, 1.0};
    assert_int_equal(ct_profile_from_line(&p, 4, NULL, 0.5, flat), CT_OK);
    assert_int_equal(ct_profile_bundle(&b, p, 100.0, 1.0, 2.0), CT_EINVAL);
    ct_profile_fit f = {0};
    assert_int_equal(ct_profile_fit_of(p, 0, 0, 0, 0, &f), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "equal"));
    ct_profile_free(p);
}

/* The bearing curve of the hand profile: tops 0 (area 1), 0.5 (2), 1 (1.5) of 4.5. */
static void bearing_by_hand(void **state)
{
    (void)state;
    const double x[] = {0.0, 1.0, 3.0}, z[] = {0.0, -1.0, -0.5};
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, 3, x, 0.0, z), CT_OK);
    const double d[] = {0.0, 0.25, 0.5, 0.99, 1.0, 2.0};
    const double want[] = {1.0 / 4.5, 1.0 / 4.5, 3.0 / 4.5, 3.0 / 4.5, 1.0, 1.0};
    double phi[6];
    assert_int_equal(ct_profile_bearing(p, 6, d, phi), CT_OK);
    for (int k = 0; k < 6; k++)
        assert_rel(phi[k], want[k], 1e-15);
    ct_profile_free(p);
}

/* Levelling removes exactly what it fits, and is linear: a line (a parabola) alone levels to
 * zero, and line + signal levels to what the signal alone levels to. */
static void levelling_exact(void **state)
{
    (void)state;
    enum { N = 1001 };
    double z[N], x[N], sig[N], poly[N];
    for (int k = 0; k < N; k++) {
        x[k] = 2.0 + 0.003 * k;
        sig[k] = 1e-3 * cos(40.0 * x[k]) * cos(17.0 * x[k]);
    }
    for (int deg = 1; deg <= 2; deg++) {
        const ct_detrend how = deg == 1 ? CT_DETREND_LINEAR : CT_DETREND_QUADRATIC;
        for (int k = 0; k < N; k++) {
            poly[k] = 5.0 - 3.0 * x[k] + (deg == 2 ? 0.7 * x[k] * x[k] : 0.0);
            z[k] = poly[k] + sig[k];
        }
        ct_profile *pz, *ps, *pp;
        assert_int_equal(ct_profile_from_line(&pz, N, x, 0.0, z), CT_OK);
        assert_int_equal(ct_profile_from_line(&ps, N, x, 0.0, sig), CT_OK);
        assert_int_equal(ct_profile_from_line(&pp, N, x, 0.0, poly), CT_OK);
        assert_int_equal(ct_profile_level(pz, how), CT_OK);
        assert_int_equal(ct_profile_level(ps, how), CT_OK);
        /* the polynomial alone levels to its rounding residue: no roughness, refused */
        assert_int_equal(ct_profile_level(pp, how), CT_EINVAL);
        assert_non_null(strstr(ct_error_message(), "no roughness"));
        for (int k = 0; k < N; k++) {
            assert_true(fabs(pp->z[k]) < 1e-12);
            assert_true(fabs(pz->z[k] - ps->z[k]) < 1e-12);
        }
        ct_profile_stats s;
        assert_int_equal(ct_profile_stats_of(pz, &s), CT_OK);
        assert_true(fabs(s.mean) < 1e-12);
        ct_profile_free(pz);
        ct_profile_free(ps);
        ct_profile_free(pp);
    }
    ct_profile *p;
    /* a plane on a grid with a hole */
    enum { NX = 40, NY = 30 };
    double g[NX * NY];
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++)
            g[j * NX + i] = 1.0 + 0.2 * i - 0.1 * j;
    g[7] = NAN;
    assert_int_equal(ct_profile_from_grid(&p, NX, NY, 0.5, 0.5, g), CT_OK);
    assert_int_equal(p->invalid, 1);
    assert_int_equal(p->n, NX * NY - 1);
    assert_int_equal(ct_profile_level(p, CT_DETREND_LINEAR), CT_EINVAL); /* a plane: flat */
    for (int k = 0; k < NX * NY; k++)
        if (k != 7)
            assert_true(fabs(p->z[k]) < 1e-12);
    assert_true(isnan(p->z[7]));
    ct_profile_stats s;
    assert_int_equal(ct_profile_stats_of(p, &s), CT_OK);
    assert_rel(s.length, 0.25 * (NX * NY - 1), 1e-15); /* the valid pixels' area */
    ct_profile_free(p);
}

/* A grid large enough for its levelled heights to be shared among threads in chunks that
 * start mid-row (530 columns): quadratic + signal levels to what the signal alone levels to,
 * the quadratic alone to its rounding residue, with the same bits on 1 and 2 threads. */
static void levelling_large_grid(void **state)
{
    (void)state;
    enum { NX = 530, NY = 510 };
    const double d = 1e-2;
    double *sig = malloc(NX * NY * sizeof *sig), *all = malloc(NX * NY * sizeof *all),
           *poly = malloc(NX * NY * sizeof *poly);
    assert_true(sig && all && poly);
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            const double x = i * d, y = j * d;
            const size_t k = (size_t)j * NX + i;
            sig[k] = 1e-3 * cos(0.07 * i) * cos(0.05 * j) + 1e-4 * sin(0.3 * i + 0.2 * j);
            poly[k] = 5.0 - 3.0 * x + 2.0 * y + 0.7 * x * x - 0.4 * x * y + 0.3 * y * y;
            all[k] = poly[k] + sig[k];
        }
    all[12345] = sig[12345] = poly[12345] = NAN; /* a hole */
    ct_profile *pz[2], *ps, *pp;
    for (int t = 0; t < 2; t++) {
#ifdef _OPENMP
        omp_set_num_threads(t + 1);
#endif
        assert_int_equal(ct_profile_from_grid(&pz[t], NX, NY, d, d, all), CT_OK);
        assert_int_equal(ct_profile_level(pz[t], CT_DETREND_QUADRATIC), CT_OK);
    }
    assert_int_equal(ct_profile_from_grid(&ps, NX, NY, d, d, sig), CT_OK);
    assert_int_equal(ct_profile_from_grid(&pp, NX, NY, d, d, poly), CT_OK);
    assert_int_equal(ct_profile_level(ps, CT_DETREND_QUADRATIC), CT_OK);
    assert_int_equal(ct_profile_level(pp, CT_DETREND_QUADRATIC), CT_EINVAL);
    for (size_t k = 0; k < (size_t)NX * NY; k++) {
        if (k == 12345) {
            assert_true(isnan(pz[0]->z[k]) && isnan(pz[1]->z[k]));
            continue;
        }
        assert_memory_equal(&pz[0]->z[k], &pz[1]->z[k], sizeof(double));
        if (!(fabs(pz[0]->z[k] - ps->z[k]) < 1e-11 && fabs(pp->z[k]) < 1e-11))
            fail_msg("sample %zu: levelled %.17g, the signal alone %.17g, the quadratic %.3g", k,
                     pz[0]->z[k], ps->z[k], pp->z[k]);
    }
    /* rods of the grid without its hole (rod k is sample k, filled in chunks on threads): each
     * rod's top, length and pixel area by hand */
    all[12345] = 0.5 * (all[12344] + all[12346]);
    ct_profile *pr;
    assert_int_equal(ct_profile_from_grid(&pr, NX, NY, d, d, all), CT_OK);
    double zmax = -INFINITY;
    for (size_t k = 0; k < (size_t)NX * NY; k++)
        zmax = all[k] > zmax ? all[k] : zmax;
    ct_bundle *b;
    assert_int_equal(ct_profile_bundle(&b, pr, 100.0, 1.0, 1000.0), CT_OK);
    assert_int_equal(ct_bundle_size(b), NX * NY);
    for (size_t k = 0; k < (size_t)NX * NY; k++) {
        ct_rod_info r;
        assert_int_equal(ct_bundle_rod(b, k, &r), CT_OK);
        const double top = zmax - all[k];
        if (!(r.top == top && r.length == 1000.0 - top && r.area == d * d &&
              r.plastic_strain == 0.0))
            fail_msg("rod %zu: top %.17g length %.17g area %.17g, by hand %.17g %.17g %.17g", k,
                     r.top, r.length, r.area, top, 1000.0 - top, d * d);
    }
    ct_bundle_free(b);
    ct_profile_free(pr);
    for (int t = 0; t < 2; t++)
        ct_profile_free(pz[t]);
    ct_profile_free(ps);
    ct_profile_free(pp);
    free(sig);
    free(all);
    free(poly);
}

/* The statistics and the levelling do not depend on the heights' unit: the same profile
 * scaled by 2^-600 (1e-181) and 2^1000 (1e301), an exact scaling, gives Rq, Ra, Rt and the
 * levelled heights scaled exactly (Rq underflowed to 0 at 1e-170 m, levelling overflowed at
 * 1e300 m). */
static void heights_in_any_unit(void **state)
{
    (void)state;
    enum { N = 300 };
    double z[N];
    for (int k = 0; k < N; k++)
        z[k] = 2.0 + 0.01 * k + 0.3 * sin(0.37 * k) * cos(0.11 * k);
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, N, NULL, 1e-6, z), CT_OK);
    ct_profile_stats s;
    assert_int_equal(ct_profile_level(p, CT_DETREND_LINEAR), CT_OK);
    assert_int_equal(ct_profile_stats_of(p, &s), CT_OK);
    const int scales[2] = {-600, 1000};
    for (int c = 0; c < 2; c++) {
        double zs[N];
        for (int k = 0; k < N; k++)
            zs[k] = ldexp(z[k], scales[c]);
        ct_profile *q;
        assert_int_equal(ct_profile_from_line(&q, N, NULL, 1e-6, zs), CT_OK);
        ct_profile_stats t;
        assert_int_equal(ct_profile_level(q, CT_DETREND_LINEAR), CT_OK);
        assert_int_equal(ct_profile_stats_of(q, &t), CT_OK);
        assert_true(t.Rq == ldexp(s.Rq, scales[c]) && t.Ra == ldexp(s.Ra, scales[c]));
        assert_true(t.Rt == ldexp(s.Rt, scales[c]) && t.Rq > 0.0);
        for (int k = 0; k < N; k++)
            assert_true(q->z[k] == ldexp(p->z[k], scales[c]));
        ct_profile_free(q);
    }
    ct_profile_free(p);
}

static void trimming(void **state)
{
    (void)state;
    double z[100];
    for (int k = 0; k < 100; k++)
        z[k] = (k % 2) ? 1.0 : -1.0;
    z[50] = 50.0; /* a spike */
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, 100, NULL, 1.0, z), CT_OK);
    ct_profile_stats s;
    assert_int_equal(ct_profile_stats_of(p, &s), CT_OK);
    size_t clipped;
    assert_int_equal(ct_profile_trim(p, 3.0, &clipped), CT_OK);
    assert_int_equal(clipped, 1);
    assert_rel(p->z[50], s.mean + 3.0 * s.Rq, 1e-15);
    assert_true(p->z[49] == 1.0);
    assert_int_equal(ct_profile_trim(p, 0.0, &clipped), CT_EINVAL);
    ct_profile_free(p);
}

static void text_readers(void **state)
{
    (void)state;
    ct_profile_read_opts um = {1e-6, 1e-6, 0.0};
    ct_profile *p;
    write_file("two.csv", "# a comment\nx, z\n0, 1\n0.5, 2\n1.0, -1  # trailing note\n\n2.0,0\n");
    assert_int_equal(ct_profile_read(path_of("two.csv"), &um, &p), CT_OK);
    assert_int_equal(p->n, 4);
    assert_rel(p->x[3], 2e-6, 1e-15);
    assert_rel(p->z[2], -1e-6, 1e-15);
    assert_string_equal(p->source, "text");
    ct_profile_free(p);
    /* units from the column names: latin-1 and UTF-8 micro signs, words, brackets; blanks,
     * tabs or commas between the columns */
    write_file("blank.txt", "x \xb5m\tz \xb5m\n1\t2\n2 3\n3 1\n");
    assert_int_equal(ct_profile_read(path_of("blank.txt"), NULL, &p), CT_OK);
    assert_int_equal(p->n, 3);
    assert_rel(p->x[2], 3e-6, 1e-15);
    assert_rel(p->z[1], 3e-6, 1e-15);
    assert_true(p->x_unit == 1e-6 && p->z_unit == 1e-6);
    ct_profile_free(p);
    write_file("utf8.csv", "x (\xc2\xb5m), height [nm]\n0,5\n1,6\n2,7\n");
    assert_int_equal(ct_profile_read(path_of("utf8.csv"), NULL, &p), CT_OK);
    assert_rel(p->x[1], 1e-6, 1e-15);
    assert_rel(p->z[2], 7e-9, 1e-15);
    ct_profile_free(p);
    write_file("words.csv", "Position/millimetres,Depth/Microns\n0,5\n1,6\n2,7\n");
    ct_profile_read_opts zn = {0.0, 1e-9, 0.0}; /* the caller's unit wins over the file's */
    assert_int_equal(ct_profile_read(path_of("words.csv"), &zn, &p), CT_OK);
    assert_rel(p->x[1], 1e-3, 1e-15);
    assert_rel(p->z[2], 7e-9, 1e-15);
    ct_profile_free(p);
    write_file("nounit.csv", "x,z\n0,5\n1,6\n2,7\n");
    expect_read_error("nounit.csv", NULL, "nounit.csv: the length unit of x and z is not given");
    write_file("mixed.csv", "x (mm um),z (nm)\n0,5\n1,6\n2,7\n"); /* two units: neither */
    expect_read_error("mixed.csv", NULL, "not given and its column names state none");
    write_file("noheader.txt", "0 5\n1 6\n2 7\n");
    expect_read_error("noheader.txt", NULL, "state none");
    ct_profile_read_opts one = {1e-3, 1e-6, 0.25}; /* spacing 0.25 mm, heights in um */
    write_file("one.txt", "5\n6\n7\n8\n");
    assert_int_equal(ct_profile_read(path_of("one.txt"), &one, &p), CT_OK);
    assert_null(p->x);
    assert_rel(p->dx, 0.25e-3, 1e-15);
    assert_rel(p->z[3], 8e-6, 1e-15);
    ct_profile_free(p);
    /* errors with their line */
    write_file("bad1.csv", "x,z\n0,1\n1,2\n2,abc\n3,4\n");
    expect_read_error("bad1.csv", &um, "bad1.csv:4: not a row of numbers");
    write_file("bad2.csv", "0,1\n1,2\n1,3\n");
    expect_read_error("bad2.csv", &um, "bad2.csv:3: x = ");
    write_file("bad3.csv", "0,1\n1,2\n");
    expect_read_error("bad3.csv", &um, "needs at least 3");
    write_file("bad4.csv", "0,1,7\n1,2\n2,3\n");
    expect_read_error("bad4.csv", &um, "bad4.csv:1: wrong number of columns");
    write_file("bad5.csv", "x,z\nx2,z2\n0,1\n");
    expect_read_error("bad5.csv", &um, "bad5.csv:2:");
    /* the rule of every list and number read: no empty field before a number (trailing ones,
     * as instruments write them, are fine), no number beyond doubles */
    write_file("bad6.csv", "0;1\n1;;2\n2;3\n");
    expect_read_error("bad6.csv", &um, "bad6.csv:2: not a row of numbers: field 2 is empty");
    write_file("bad7.csv", "0 1\n1 2\n2 1e-320\n");
    expect_read_error("bad7.csv", &um,
                      "bad7.csv:3: not a row of numbers: field 2 = 1e-320: underflows double");
    write_file("trailing.csv", "0;1;\n1;2;;\n2;3 ;\n");
    assert_int_equal(ct_profile_read(path_of("trailing.csv"), &um, &p), CT_OK);
    assert_int_equal(p->n, 3);
    assert_rel(p->z[2], 3e-6, 1e-15);
    ct_profile_free(p);
    expect_read_error("missing.csv", &um, "cannot open");
}

/* The real Dektak export (tests/data, MIT licence beside it): 9,600 points over 1.5 mm. */
static void dektak(void **state)
{
    (void)state;
    ct_profile_read_opts um = {1e-6, 1e-6, 0.0};
    ct_profile *p;
    assert_int_equal(ct_profile_read(CT_SOURCE_DIR "/tests/data/dektak-1.csv", &um, &p), CT_OK);
    assert_string_equal(p->source, "dektak");
    assert_int_equal(p->n, 9600);
    assert_rel(p->x[0], 0.0, 1e-15);
    assert_rel(p->x[9599], 1499.8e-6, 1e-15);
    assert_rel(p->z[0], -0.00933e-6, 1e-15);
    assert_rel(p->z[9599], 16.58112e-6, 1e-15);
    ct_profile_free(p);
    /* its column names, "Lateral um,Raw Micrometer", give the same units */
    assert_int_equal(ct_profile_read(CT_SOURCE_DIR "/tests/data/dektak-1.csv", NULL, &p), CT_OK);
    assert_rel(p->x[9599], 1499.8e-6, 1e-15);
    assert_rel(p->z[9599], 16.58112e-6, 1e-15);
    ct_profile_free(p);
}

/* ---- X3P, written here ---- */

static void put_le(unsigned char *out, const void *v, int n)
{
    memcpy(out, v, (size_t)n); /* this machine is little-endian, as X3P */
}

static void write_x3p(const char *name, const char *xml, const void *bin, size_t bin_size,
                      const char *bin_name, const void *mask, size_t mask_size)
{
    int err;
    zip_t *z = zip_open(path_of(name), ZIP_CREATE | ZIP_TRUNCATE, &err);
    assert_non_null(z);
    if (xml) {
        zip_source_t *s = zip_source_buffer(z, xml, strlen(xml), 0);
        assert_true(zip_file_add(z, "main.xml", s, ZIP_FL_OVERWRITE) >= 0);
    }
    if (bin) {
        zip_source_t *s = zip_source_buffer(z, bin, bin_size, 0);
        assert_true(zip_file_add(z, bin_name, s, ZIP_FL_OVERWRITE) >= 0);
    }
    if (mask) {
        zip_source_t *s = zip_source_buffer(z, mask, mask_size, 0);
        assert_true(zip_file_add(z, "bindata/valid.bin", s, ZIP_FL_OVERWRITE) >= 0);
    }
    assert_int_equal(zip_close(z), 0);
}

static char *x3p_xml(int nx, int ny, const char *type, double zinc, int mask)
{
    static char xml[2048];
    snprintf(xml, sizeof xml,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
             "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType>\n"
             "<Axes><CX><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment>"
             "<Offset>0</Offset></CX>\n"
             "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>3e-6</Increment>"
             "<Offset>0</Offset></CY>\n"
             "<CZ><AxisType>A</AxisType><DataType>%s</DataType><Increment>%g</Increment>"
             "<Offset>0</Offset></CZ></Axes></Record1>\n"
             "<Record3><MatrixDimension><SizeX>%d</SizeX><SizeY>%d</SizeY><SizeZ>1</SizeZ>"
             "</MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink>%s"
             "<MD5ChecksumPointData>0</MD5ChecksumPointData></DataLink></Record3>\n"
             "</p:ISO5436_2>\n",
             type, zinc, nx, ny,
             mask ? "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>" : "");
    return xml;
}

static void x3p_reader(void **state)
{
    (void)state;
    enum { NX = 5, NY = 4 };
    unsigned char bin[NX * NY * 8], mask[(NX * NY + 7) / 8];
    for (int k = 0; k < NX * NY; k++) {
        double v = k == 6 ? NAN : 1e-7 * k;
        put_le(bin + 8 * k, &v, 8);
    }
    write_x3p("d.x3p", x3p_xml(NX, NY, "D", 1.0, 0), bin, sizeof bin, "bindata/data.bin", NULL, 0);
    ct_profile *p;
    assert_int_equal(ct_profile_read(path_of("d.x3p"), NULL, &p), CT_OK);
    assert_string_equal(p->source, "x3p");
    assert_int_equal(p->nx, NX);
    assert_int_equal(p->ny, NY);
    assert_int_equal(p->invalid, 1); /* the NaN */
    assert_rel(p->dx, 2e-6, 1e-15);
    assert_rel(p->dy, 3e-6, 1e-15);
    assert_rel(p->z[13], 1.3e-6, 1e-15);
    ct_bundle *b; /* each valid pixel a rod of area dx dy */
    assert_int_equal(ct_profile_bundle(&b, p, 2e11, 4e8, 1e-5), CT_OK);
    assert_int_equal(ct_bundle_size(b), NX * NY - 1);
    ct_rod_info r;
    assert_int_equal(ct_bundle_rod(b, 0, &r), CT_OK);
    assert_rel(r.area, 6e-12, 1e-15);
    assert_int_equal(ct_bundle_omitted(b), 1);
    /* rod 6 is pixel 7 (the NaN at 6 has no rod): its column's x, 2e-6 (7 % NX) */
    assert_int_equal(ct_bundle_rod(b, 6, &r), CT_OK);
    assert_rel(r.x_left, 2e-6 * (7 % NX) - 1e-6, 1e-12);
    ct_bundle_free(b);
    ct_profile_free(p);
    /* int16 heights with the axis' increment, and a mask: bit 0 leaves a point out */
    int16_t ibin[NX * NY];
    for (int k = 0; k < NX * NY; k++)
        ibin[k] = (int16_t)(k - 3);
    memset(mask, 0xff, sizeof mask);
    mask[0] &= (unsigned char)~(1u << 2); /* point 2 */
    mask[1] &= (unsigned char)~(1u << 1); /* point 9 */
    write_x3p("i.x3p", x3p_xml(NX, NY, "I", 5e-9, 1), ibin, sizeof ibin, "bindata/data.bin", mask,
              sizeof mask);
    assert_int_equal(ct_profile_read(path_of("i.x3p"), NULL, &p), CT_OK);
    assert_int_equal(p->invalid, 2);
    assert_true(isnan(p->z[2]) && isnan(p->z[9]));
    assert_rel(p->z[10], 7 * 5e-9, 1e-15);
    ct_profile_free(p);
    /* one row: a line profile, the invalid point dropped and the others at their x */
    double row[NX];
    memcpy(row, bin, sizeof row);
    put_le((unsigned char *)row + 8 * 2, &(double){NAN}, 8);
    write_x3p("row.x3p", x3p_xml(NX, 1, "D", 1.0, 0), row, sizeof row, "bindata/data.bin", NULL, 0);
    assert_int_equal(ct_profile_read(path_of("row.x3p"), NULL, &p), CT_OK);
    assert_int_equal(p->ny, 1);
    assert_int_equal(p->n, NX - 1);
    assert_int_equal(p->invalid, 1);
    assert_non_null(p->x);
    assert_rel(p->x[2], 3 * 2e-6, 1e-15); /* point 3 at 3 dx */
    assert_rel(p->z[2], 3e-7, 1e-15);
    ct_profile_free(p);
    /* errors naming the entry */
    write_x3p("nomain.x3p", NULL, bin, sizeof bin, "bindata/data.bin", NULL, 0);
    expect_read_error("nomain.x3p", NULL, "main.xml missing");
    ct_profile_read_opts um = {1e-6, 1e-6, 0.0};
    expect_read_error("d.x3p", &um, "an X3P file states its lengths");
    write_x3p("size.x3p", x3p_xml(NX + 1, NY, "D", 1.0, 0), bin, sizeof bin, "bindata/data.bin",
              NULL, 0);
    expect_read_error("size.x3p", NULL, "bindata/data.bin holds 160 bytes");
    write_x3p("nobin.x3p", x3p_xml(NX, NY, "D", 1.0, 0), bin, sizeof bin, "bindata/other.bin", NULL,
              0);
    expect_read_error("nobin.x3p", NULL, "bindata/data.bin missing");
    write_x3p("badxml.x3p", "<Record1><oops></Record1>", bin, sizeof bin, "bindata/data.bin", NULL,
              0);
    expect_read_error("badxml.x3p", NULL, "not well-formed");
}

/* ---- the fit ---- */

/* Heights whose bearing curve is (d / h0)^alpha exactly at its corners: the top sample at depth
 * 0 and the sample of rank k >= 1 (of n, from the top) at depth h0 ((k + 1) / n)^(1/alpha), where
 * the area at and above it is (k + 1) / n; in a scrambled order. */
static void bearing_law_recovered(void **state)
{
    (void)state;
    enum { N = 20000 };
    static double z[N];
    const double alpha = 1.7, h0 = 3e-7;
    for (size_t k = 0; k < N; k++) {
        size_t j = (k * 7919) % N; /* a permutation: the x-order does not matter */
        z[j] = k == 0 ? 0.0 : -h0 * pow((k + 1.0) / N, 1.0 / alpha);
    }
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, N, NULL, 1e-7, z), CT_OK);
    ct_profile_fit f = {0};
    assert_int_equal(ct_profile_fit_of(p, 1e-8, 2.5e-7, 0, 0, &f), CT_OK);
    assert_rel(f.alpha, alpha, 1e-9);
    assert_rel(f.h0, h0, 1e-9);
    assert_true(f.bearing.r2 > 0.9999);
    ct_profile_free(p);
}

/* Two profiles self-affine with dimension D = 1.4 over the scales the band covers, on which the
 * estimators must find D within 0.06 (a finite sum, finite sampling):
 * - the Weierstrass-Mandelbrot function z(x) = sum_n g^{-(2 - D) n} cos(g^n x + phase_n): the
 *   variation and the structure function (its spectrum is lines a factor g apart, which bins
 *   narrower than that cannot average: the spectral estimator is for continuous spectra);
 * - a Fourier synthesis with power |a_j|^2 = j^-(5 - 2D) at every harmonic j and random phases
 *   (fractional Brownian motion's spectrum, Hurst exponent 2 - D): all three estimators. */
static void dimension_of_a_known_profile(void **state)
{
    (void)state;
    enum { N = 1 << 17 };
    static double z[N];
    const double D = 1.4, g = 1.5;
    for (size_t k = 0; k < N; k++) {
        double x = 2.0 * 3.141592653589793 * (double)k / N, s = 0.0;
        for (int n = 0; n < 40; n++)
            s += pow(g, -(2.0 - D) * n) * cos(pow(g, n) * x + 1.7 * n * n);
        z[k] = 1e-6 * s;
    }
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, N, NULL, 1e-6, z), CT_OK);
    for (int m = CT_DIM_VARIATION; m <= CT_DIM_STRUCTURE; m++) {
        ct_profile_fit f = {.dimension = (ct_dimension_method)m};
        assert_int_equal(ct_profile_fit_of(p, 0, 0, 4e-6, 1e-3, &f), CT_OK);
        if (!(fabs(f.D - D) < 0.06))
            fail_msg("Weierstrass-Mandelbrot, method %d: D = %g, expected %g", m, f.D, D);
    }
    ct_profile_free(p);
    /* the synthesis: halfcomplex coefficients (z[2j - 1], z[2j]) = a_j (cos, sin) of a phase
     * from a fixed linear congruential sequence, transformed back by GSL */
    uint64_t lcg = 12345;
    z[0] = 0.0;
    for (size_t j = 1; j < N / 2; j++) {
        lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
        const double phase = 6.283185307179586 * (double)(lcg >> 11) / 9007199254740992.0,
                     a = pow((double)j, -0.5 * (5.0 - 2.0 * D));
        z[2 * j - 1] = a * cos(phase);
        z[2 * j] = a * sin(phase);
    }
    z[N - 1] = 0.0;
    gsl_fft_halfcomplex_wavetable *wt = gsl_fft_halfcomplex_wavetable_alloc(N);
    gsl_fft_real_workspace *ws = gsl_fft_real_workspace_alloc(N);
    assert_non_null(wt);
    assert_non_null(ws);
    assert_int_equal(gsl_fft_halfcomplex_inverse(z, 1, N, wt, ws), 0);
    gsl_fft_halfcomplex_wavetable_free(wt);
    gsl_fft_real_workspace_free(ws);
    for (size_t k = 0; k < N; k++)
        z[k] *= 1e-3;
    assert_int_equal(ct_profile_from_line(&p, N, NULL, 1e-6, z), CT_OK);
    for (int m = CT_DIM_VARIATION; m <= CT_DIM_SPECTRUM; m++) {
        ct_profile_fit f = {.dimension = (ct_dimension_method)m};
        assert_int_equal(ct_profile_fit_of(p, 0, 0, 4e-6, 1e-3, &f), CT_OK);
        if (!(fabs(f.D - D) < 0.06))
            fail_msg("spectral synthesis, method %d: D = %g, expected %g", m, f.D, D);
        print_message("spectral synthesis, method %d: D = %.4f\n", m, f.D);
    }
    ct_profile_free(p);
}

/* Areal surfaces by spectral synthesis (amplitude |k|^-(1 + H), random phases, H = 0.7, GSL's
 * FFT along rows and columns): their rows are profiles of dimension 2 - H = 1.3. One 256 x 256
 * realisation scatters by about 0.03 about its estimator's mean, so the three estimators, reading
 * each grid row by row, must find 1.3 within 0.06 on the mean of 8 realisations. */
static void dimension_of_a_grid(void **state)
{
    (void)state;
    enum { N = 256, R = 8 };
    static double c[2 * N * N], z[N * N];
    const double H = 0.7;
    double mean[3] = {0.0, 0.0, 0.0};
    for (int rz = 0; rz < R; rz++) {
        uint64_t lcg = 7919u * (uint64_t)(rz + 1);
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                const double kx = i < N / 2 ? i : i - N, ky = j < N / 2 ? j : j - N;
                const double k = sqrt(kx * kx + ky * ky), a = k > 0.0 ? pow(k, -(1.0 + H)) : 0.0;
                lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
                const double phase = 6.283185307179586 * (double)(lcg >> 11) / 9007199254740992.0;
                c[2 * (j * N + i)] = a * cos(phase);
                c[2 * (j * N + i) + 1] = a * sin(phase);
            }
        for (int j = 0; j < N; j++)
            assert_int_equal(gsl_fft_complex_radix2_inverse(c + 2 * j * N, 1, N), 0);
        for (int i = 0; i < N; i++)
            assert_int_equal(gsl_fft_complex_radix2_inverse(c + 2 * i, N, N), 0);
        for (int k = 0; k < N * N; k++)
            z[k] = 1e-3 * c[2 * k];
        ct_profile *p;
        assert_int_equal(ct_profile_from_grid(&p, N, N, 1e-6, 1e-6, z), CT_OK);
        for (int m = CT_DIM_VARIATION; m <= CT_DIM_SPECTRUM; m++) {
            ct_profile_fit f = {.dimension = (ct_dimension_method)m};
            assert_int_equal(ct_profile_fit_of(p, 0, 0, 0, 0, &f), CT_OK);
            mean[m - CT_DIM_VARIATION] += f.D / R;
            assert_rel(f.l0, N * 1e-6, 1e-12); /* l0: the length along x */
        }
        ct_profile_free(p);
    }
    for (int m = 0; m < 3; m++) {
        print_message("grids, method %d: mean D = %.4f\n", m, mean[m]);
        if (!(fabs(mean[m] - (2.0 - H)) < 0.06))
            fail_msg("grids, method %d: mean D = %g, expected %g", m, mean[m], 2.0 - H);
    }
}

/* A Cantor prefractal (fx 1.5, fz 1.9, depth 12) sampled at 2^22 points: the fit gives back
 * alpha to 2 % and h0 to 4 % (the bearing curve is a staircase that touches (d / h0)^alpha at its
 * corners, fitted there; d counts from the tips at h_12 = 4.5e-4 h0, not from the plane) and fx,
 * fz to 8 %: the box-counting dimension of a Cantor step profile converges to Eq. 3's only as
 * (2 / fz)^i over the stages i the lag band resolves (1.107 measured at the finest lags against
 * 1.047). */
static void cantor_prefractal_recovered(void **state)
{
    (void)state;
    const ct_params c = {
        .fx = 1.5, .fz = 1.9, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    const long N = 12;
    const size_t n = (size_t)1 << 22;
    double *z = malloc(n * sizeof(double));
    assert_non_null(z);
    const double dx = 1.0 / (double)n;
    for (size_t k = 0; k < n; k++)
        z[k] = -ct_stage_depth(&c, (double)N);
    for (long i = 0; i < N; i++)
        for (size_t j = 0; j < ((size_t)1 << i); j++) {
            double xl, xr;
            assert_int_equal(ct_piece_extent(&c, N, i, j, &xl, &xr), CT_OK);
            for (size_t k = (size_t)ceil(xl / dx - 0.5); k < (size_t)ceil(xr / dx - 0.5) && k < n;
                 k++)
                z[k] = -ct_stage_depth(&c, (double)i);
        }
    ct_profile *p;
    assert_int_equal(ct_profile_from_line(&p, n, NULL, dx, z), CT_OK);
    free(z);
    ct_profile_fit f = {0};
    const double hN = ct_stage_depth(&c, (double)N);
    assert_int_equal(ct_profile_fit_of(p, ct_stage_depth(&c, 8) - hN,
                                       ct_stage_depth(&c, 1) - hN - 1e-12, 2e-6, 1e-4, &f),
                     CT_OK);
    assert_rel(f.alpha, ct_alpha(&c), 0.02);
    assert_rel(f.h0, c.h0, 0.04);
    assert_rel(f.fx, c.fx, 0.08);
    assert_rel(f.fz, c.fz, 0.08);
    ct_profile_free(p);
}

static int setup(void **state)
{
    (void)state;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* e and u_max [m] of one impact of energy W [J] under a sphere of R = 20 um at (x, y) on the
 * map of file name (levelled not at all, H = 10), repeated or not. */
static double sphere_on_map(const char *name, int periodic, double x, double y, double W, double *u)
{
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "profile"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path_of(name), ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "detrend", "none", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "2e11", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", "4e8", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    ct_scales sc;
    ct_surface_scales(s, &sc);
    ct_body body;
    ct_body_defaults(&body);
    body.shape = 2;
    body.radius = 2e-5;
    body.position[0] = x;
    body.position[1] = y;
    body.periodic = periodic;
    const double V = sqrt(W / sc.physical_energy_scale);
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    ct_sweep_row row;
    ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1, .opts = req.opts};
    assert_int_equal(ct_sweep(b, &spec, &row), CT_OK);
    assert_int_equal(row.status, CT_OK);
    ct_bundle_free(b);
    ct_surface_free(s);
    *u = row.r.u_max;
    return row.r.e;
}

/* A map repeats with its grid, nx dx by ny dy, also when the points along an edge are invalid
 * (those pixels have no rods, so the rods span a column less): a sphere on a 9 x 9 map whose
 * last column is invalid, repeated, meets what it meets on the map laid out 3 x 3 by hand. */
static void map_repeats_with_its_grid(void **state)
{
    (void)state;
    enum { N = 9, M = 3 * N };
    static unsigned char one[N * N * 8], three[M * M * 8];
    for (int j = 0; j < M; j++)
        for (int i = 0; i < M; i++) {
            const int a = i % N, c = j % N;
            const double z = a == N - 1 ? NAN : 1e-7 * sin(1.3 * a + 2.1 * c) * cos(0.7 * a * c);
            put_le(three + 8 * (j * M + i), &z, 8);
            if (i < N && j < N)
                put_le(one + 8 * (j * N + i), &z, 8);
        }
    write_x3p("one.x3p", x3p_xml(N, N, "D", 1.0, 0), one, sizeof one, "bindata/data.bin", NULL, 0);
    write_x3p("three.x3p", x3p_xml(M, M, "D", 1.0, 0), three, sizeof three, "bindata/data.bin",
              NULL, 0);
    /* pixels 2 um x 3 um: the apex at (14, 12) um of the period, near its invalid column, the
     * face reaching into the next period across it */
    double u1, u3;
    const double W = 2e-11;
    const double e1 = sphere_on_map("one.x3p", 1, 14e-6, 12e-6, W, &u1);
    const double e3 = sphere_on_map("three.x3p", 0, 14e-6 + N * 2e-6, 12e-6 + N * 3e-6, W, &u3);
    assert_true(e1 < 0.9); /* plastic */
    assert_true(fabs(e1 - e3) <= 1e-12 * e3 && fabs(u1 - u3) <= 1e-12 * u3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rods_by_hand),
        cmocka_unit_test(bearing_by_hand),
        cmocka_unit_test(levelling_exact),
        cmocka_unit_test(levelling_large_grid),
        cmocka_unit_test(heights_in_any_unit),
        cmocka_unit_test(trimming),
        cmocka_unit_test(text_readers),
        cmocka_unit_test(dektak),
        cmocka_unit_test(x3p_reader),
        cmocka_unit_test(map_repeats_with_its_grid),
        cmocka_unit_test(bearing_law_recovered),
        cmocka_unit_test(dimension_of_a_known_profile),
        cmocka_unit_test(dimension_of_a_grid),
        cmocka_unit_test(cantor_prefractal_recovered),
    };
    return cmocka_run_group_tests_name("profile", tests, setup, teardown);
}
