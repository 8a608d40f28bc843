/* Issue 14's measured surfaces: the steps of an areal topography in one process, and the X3P
 * file the whole-process runs of scripts/bench read.
 *
 *   bench_profile write-x3p FILE N   writes an N x N areal topography (spacing 1 um, heights in
 *                                    metres, doubles; N a power of 2) to FILE: a random
 *                                    self-affine surface by spectral synthesis, Rq 0.3 um,
 *                                    Hurst exponent 0.7 (fixed seed)
 *   bench_profile [--quick] FILE     times reading FILE, levelling, the rod bundle, the plan and
 *                                    a sweep of 2000 speeds (V* 1e-4 .. 1e-2, log), and the
 *                                    Cantor fit, in one process (best of 3); CSV on stdout
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_fft_complex.h>
#include <zip.h>

#include "cantact.h"
#include "common.h"

static uint64_t lcg = 88172645463325252ull;

static double uniform01(void)
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg >> 11) / 9007199254740992.0;
}

static int write_x3p(const char *path, int n)
{
    if (n < 8 || (n & (n - 1))) {
        fprintf(stderr, "bench_profile: N = %d: a power of 2 >= 8\n", n);
        return 2;
    }
    const size_t N = (size_t)n * (size_t)n;
    double *c = malloc(2 * N * sizeof(double)), *z = malloc(N * sizeof(double));
    if (!c || !z) {
        fprintf(stderr, "bench_profile: out of memory\n");
        return 1;
    }
    /* a spectral synthesis: amplitude |k|^-(1 + H) and a random phase at every wavevector,
     * transformed back by GSL (rows, then columns), the real part kept: a random self-affine
     * surface with a continuous spectrum, Hurst exponent H (profiles of dimension 2 - H) */
    const double dx = 1e-6, Hurst = 0.7;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double kx = i < n / 2 ? i : i - n, ky = j < n / 2 ? j : j - n;
            const double k = sqrt(kx * kx + ky * ky), ph = 2.0 * 3.141592653589793 * uniform01();
            const double a = k > 0.0 ? pow(k, -(1.0 + Hurst)) : 0.0;
            c[2 * ((size_t)j * n + i)] = a * cos(ph);
            c[2 * ((size_t)j * n + i) + 1] = a * sin(ph);
        }
    for (int j = 0; j < n; j++)
        gsl_fft_complex_radix2_inverse(c + 2 * (size_t)j * n, 1, (size_t)n);
    for (int i = 0; i < n; i++)
        gsl_fft_complex_radix2_inverse(c + 2 * (size_t)i, (size_t)n, (size_t)n);
    double ss = 0.0;
    for (size_t k = 0; k < N; k++) {
        z[k] = c[2 * k];
        ss += z[k] * z[k];
    }
    free(c);
    const double scale = 3e-7 / sqrt(ss / (double)N); /* Rq 0.3 um */
    for (size_t k = 0; k < N; k++)
        z[k] *= scale;
    char xml[2048];
    snprintf(xml, sizeof xml,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
             "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType>\n"
             "<Axes><CX><AxisType>I</AxisType><DataType>D</DataType><Increment>%g</Increment>"
             "<Offset>0</Offset></CX>\n"
             "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>%g</Increment>"
             "<Offset>0</Offset></CY>\n"
             "<CZ><AxisType>A</AxisType><DataType>D</DataType><Increment>1</Increment>"
             "<Offset>0</Offset></CZ></Axes></Record1>\n"
             "<Record3><MatrixDimension><SizeX>%d</SizeX><SizeY>%d</SizeY><SizeZ>1</SizeZ>"
             "</MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink>"
             "</DataLink></Record3>\n</p:ISO5436_2>\n",
             dx, dx, n, n);
    /* X3P binaries are little-endian */
    const uint16_t probe = 1;
    if (*(const unsigned char *)&probe != 1)
        for (size_t k = 0; k < N; k++) {
            unsigned char *b = (unsigned char *)&z[k];
            for (int i = 0; i < 4; i++) {
                unsigned char t = b[i];
                b[i] = b[7 - i];
                b[7 - i] = t;
            }
        }
    int err;
    zip_t *zp = zip_open(path, ZIP_CREATE | ZIP_TRUNCATE, &err);
    zip_source_t *s1 = zp ? zip_source_buffer(zp, xml, strlen(xml), 0) : NULL;
    zip_source_t *s2 = zp ? zip_source_buffer(zp, z, N * sizeof(double), 0) : NULL;
    if (!zp || !s1 || !s2 || zip_file_add(zp, "main.xml", s1, ZIP_FL_OVERWRITE) < 0 ||
        zip_file_add(zp, "bindata/data.bin", s2, ZIP_FL_OVERWRITE) < 0 || zip_close(zp) != 0) {
        fprintf(stderr, "bench_profile: cannot write %s\n", path);
        free(z);
        return 1;
    }
    free(z);
    return 0;
}

static int fail(const char *what)
{
    fprintf(stderr, "bench_profile: %s: %s\n", what, ct_error_message());
    return 1;
}

int main(int argc, char **argv)
{
    if (argc == 4 && !strcmp(argv[1], "write-x3p"))
        return write_x3p(argv[2], atoi(argv[3]));
    int quick = argc == 3 && !strcmp(argv[1], "--quick");
    if (argc != 2 + quick) {
        fprintf(stderr, "usage: bench_profile write-x3p FILE N | bench_profile [--quick] FILE\n");
        return 2;
    }
    const char *file = argv[1 + quick];
    const int reps = 3;
    double best[6] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
    size_t rods = 0;
    enum { NV = 2000 };
    static double V[NV];
    for (int k = 0; k < NV; k++)
        V[k] = 1e-4 * pow(100.0, (double)k / (NV - 1));
    for (int r = 0; r < reps; r++) {
        ct_profile *p;
        double t0 = bench_now();
        if (ct_profile_read(file, NULL, &p))
            return fail("read");
        double t1 = bench_now();
        ct_profile_stats s;
        if (ct_profile_level(p, CT_DETREND_LINEAR) || ct_profile_stats_of(p, &s))
            return fail("level");
        double t2 = bench_now();
        /* E / sigma_y = 500, H* = 10 Rt; V* with l0 = the area, h0 = Rt, as the CLI */
        ct_bundle *b;
        if (ct_profile_bundle(&b, p, 500.0, 1.0, 10.0 * s.Rt))
            return fail("bundle");
        rods = ct_bundle_size(b);
        double t3 = bench_now();
        ct_sweep_spec spec = {.V_star = V, .nvel = NV, .impacts = 1};
        ct_impact_opts_default(&spec.opts);
        spec.opts.check = 0;
        ct_sweep_row *rows = malloc(NV * sizeof *rows);
        if (!rows || ct_sweep(b, &spec, rows))
            return fail("sweep");
        for (int k = 0; k < NV; k++)
            if (rows[k].status)
                return fail(rows[k].message);
        free(rows);
        double t4 = bench_now();
        ct_bundle_free(b);
        ct_profile_fit f = {0};
        if (!quick && ct_profile_fit_of(p, 0, 0, 0, 0, &f))
            return fail("fit");
        double t5 = bench_now();
        ct_profile_free(p);
        const double t[6] = {t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4, t5 - t0};
        for (int k = 0; k < 6; k++)
            best[k] = t[k] < best[k] ? t[k] : best[k];
    }
    static const char *const names[] = {"read", "level", "bundle", "sweep_2000_speeds",
                                        "fit",  "total"};
    printf("step,rods,best_seconds_of_3\n");
    for (int k = 0; k < 6; k++)
        if (!(quick && k == 4))
            printf("%s,%zu,%.6g\n", names[k], rods, best[k]);
    return 0;
}
