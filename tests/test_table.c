/* e(V*) tables (src/table.c) and their reader (include/cantact_table.h): a two-rod surface
 * whose e(V*) is derived by hand below, checked at points of the test's own choosing; the
 * build's claimed worst error recomputed from its stated check points; V*_c and the kinks as
 * nodes; the slopes against the Fritsch-Carlson monotonicity conditions; the reader against
 * the library bit for bit through a file; the default Cantor surface against sweeps at points
 * the build never checked; bad input. */
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

#include "assert_rel.h"
#include "cantact.h"
#include "cantact_table.h"

/* Two rods, E = 10, sigma_y = 1 (eps_y = 0.1), H* = 2, l0 = h0 = 1, areas 1:
 *   A: top 0,   L = 2,   k = 5,    yields at 0.2,  plateau 1
 *   B: top 0.5, L = 1.5, k = 20/3, yields at 0.65, plateau 1
 * Loading the virgin surface to u, work W and dissipation D (plastic work):
 *   u <= 0.2:          W = 5 u^2 / 2, D = 0                    (elastic: e = 1)
 *   0.2 <= u <= 0.5:   W = 0.1 + (u - 0.2), D = u - 0.2        W - D = 0.1
 *   0.5 <= u <= 0.65:  s = u - 0.5: W = 0.4 + s + (10/3) s^2, D = u - 0.2, W - D = 0.1 + (10/3) s^2
 *   u >= 0.65:         W = 0.625 + 2 (u - 0.65), W - D = 0.175
 * e = sqrt((W - D) / W), V* = sqrt(W / (l0 E h0)) = sqrt(W / 10). So V*_c = 0.1 (A yields), a
 * kink of e's second derivative at V* = 0.2 (B touches) and a kink at V* = 0.25 (B yields). */
static double two_rod_e(double V)
{
    const double W = 10.0 * V * V;
    if (W <= 0.1)
        return 1.0;
    if (W <= 0.4)
        return sqrt(0.1 / W);
    if (W <= 0.625) {
        const double s = (-1.0 + sqrt(1.0 + (40.0 / 3.0) * (W - 0.4))) / (20.0 / 3.0);
        return sqrt((0.1 + (10.0 / 3.0) * s * s) / W);
    }
    return sqrt(0.175 / W);
}

static ct_bundle *two_rods(void)
{
    ct_layer L = {.E = 10.0, .sigma_y = 1.0, .Hstar = 2.0, .l0 = 1.0, .h0 = 1.0};
    double top[2] = {0.0, 0.5}, area[2] = {1.0, 1.0};
    ct_bundle *b;
    assert_int_equal(ct_bundle_from_rods(&b, &L, 2, top, area), CT_OK);
    return b;
}

static int has_node(const ct_table *t, double V, double rel)
{
    for (size_t i = 0; i < ct_table_size(t); i++)
        if (close_rel(ct_table_V_star(t)[i], V, rel))
            return 1;
    return 0;
}

/* The claims of a built table against the hand-derived e: nodes exact, V*_c and both kinks
 * nodes, the worst error recomputed from the stated check points, and no point of the test's
 * own (a golden-ratio sequence in ln V*) beyond the tolerance. */
static void check_two_rods(ct_interp rule, double tol)
{
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 0.01;
    spec.V_max = 0.5;
    spec.tolerance = tol;
    spec.interpolation = rule;
    ct_table *t;
    assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
    ct_table_info in;
    ct_table_get_info(t, &in);
    const size_t n = ct_table_size(t), K = spec.check_points;
    const double *V = ct_table_V_star(t), *e = ct_table_e(t);
    assert_rel(in.V_star_crit, 0.1, 1e-15);
    assert_true(has_node(t, 0.1, 1e-15));
    assert_true(has_node(t, 0.2, 1e-14));
    assert_true(has_node(t, 0.25, 1e-14));
    assert_int_equal(in.kinks, 2);
    assert_true(V[0] == 0.01 && V[n - 1] == 0.5);
    for (size_t i = 0; i < n; i++) {
        assert_true(fabs(e[i] - two_rod_e(V[i])) <= 1e-14);
        if (i)
            assert_true(V[i] > V[i - 1]);
    }
    /* the claimed worst error is the largest at the stated check points */
    double worst = 0.0;
    size_t checked = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        if (V[i] < in.V_star_crit)
            continue;
        const double x0 = log(V[i]), h = log(V[i + 1]) - x0;
        for (size_t k = 0; k < K; k++) {
            const double Vk = exp(x0 + h * (double)(k + 1) / (double)(K + 1));
            worst = fmax(worst, fabs(ct_table_eval(t, Vk) - two_rod_e(Vk)));
            checked++;
        }
    }
    assert_int_equal(checked, in.checked);
    assert_true(in.worst_error <= tol);
    assert_true(fabs(worst - in.worst_error) <= 1e-14);
    /* points the build never looked at */
    const double lo = log(0.01), span = log(0.5) - lo, phi = (sqrt(5.0) - 1.0) / 2.0;
    double mine = 0.0;
    for (int k = 1; k <= 20000; k++) {
        const double Vk = exp(lo + span * fmod(k * phi, 1.0));
        const double err = fabs(ct_table_eval(t, Vk) - two_rod_e(Vk));
        mine = fmax(mine, err);
        if (Vk <= 0.1)
            assert_true(ct_table_eval(t, Vk) == 1.0); /* the rule, not an interpolation */
        assert_true(ct_table_eval(t, Vk) <= 1.0);
    }
    /* between check points the error may exceed the checked maximum a little; on a smooth
     * interval with 16 checks, by far less than the tolerance */
    assert_true(mine <= 1.05 * tol);
    ct_table_free(t);
    ct_bundle_free(b);
}

static void two_rods_cubic(void **state)
{
    (void)state;
    check_two_rods(CT_INTERP_MONOTONE_CUBIC, 1e-8);
    check_two_rods(CT_INTERP_MONOTONE_CUBIC, 1e-4);
}

static void two_rods_linear(void **state)
{
    (void)state;
    check_two_rods(CT_INTERP_LINEAR, 1e-6);
}

/* Fritsch and Carlson (1980): a cubic Hermite piece with secant delta != 0 is monotone when
 * alpha = d_i/delta and beta = d_i+1/delta lie in [0, 3]; slopes vanish at a local extremum
 * and on flat pieces. Random data of every shape, and linear data (reproduced exactly). */
static void pchip_conditions(void **state)
{
    (void)state;
    enum { N = 40 };
    double x[N], y[N], d[N];
    uint64_t r = 88172645463325252ull;
    for (int trial = 0; trial < 200; trial++) {
        double xx = 0.0;
        for (int i = 0; i < N; i++) {
            r ^= r << 13, r ^= r >> 7, r ^= r << 17;
            xx += 0.01 + (double)(r >> 11) / 9007199254740992.0;
            x[i] = xx;
            r ^= r << 13, r ^= r >> 7, r ^= r << 17;
            const double u = (double)(r >> 11) / 9007199254740992.0;
            /* monotone runs, plateaus and extrema */
            y[i] = trial % 3 == 0 ? (i ? y[i - 1] : 0.0) + (u < 0.2 ? 0.0 : u)
                                  : (trial % 3 == 1 ? sin(3.0 * xx) : (u < 0.3 ? 1.0 : u));
        }
        ct_pchip_slopes(N, x, y, d);
        for (int i = 0; i + 1 < N; i++) {
            const double delta = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
            if (delta == 0.0) {
                assert_true(d[i] == 0.0 && d[i + 1] == 0.0);
                continue;
            }
            const double alpha = d[i] / delta, beta = d[i + 1] / delta;
            if (!(alpha >= 0.0 && alpha <= 3.0 + 1e-12 && beta >= 0.0 && beta <= 3.0 + 1e-12))
                fail_msg("trial %d piece %d: alpha %g, beta %g outside [0, 3]", trial, i, alpha,
                         beta);
        }
        /* and the interpolant is monotone on every piece where the data are */
        double V[N], ones[N];
        for (int i = 0; i < N; i++)
            V[i] = exp(x[i]), ones[i] = fmin(fmax(y[i], 0.0), 1.0);
        if (trial % 3 != 2)
            continue; /* values in [0, 1] only: a table holds e */
        ct_table *t;
        ct_pchip_slopes(N, x, ones, d);
        assert_int_equal(ct_table_from_nodes(&t, N, V, ones, d, CT_INTERP_MONOTONE_CUBIC, 0.0),
                         CT_OK);
        for (int i = 0; i + 1 < N; i++) {
            const double lo = fmin(ones[i], ones[i + 1]), hi = fmax(ones[i], ones[i + 1]);
            double prev = ones[i];
            for (int k = 1; k < 50; k++) {
                const double v = ct_table_eval(t, exp(x[i] + (x[i + 1] - x[i]) * k / 50.0));
                assert_true(v >= lo - 1e-15 && v <= hi + 1e-15);
                assert_true(ones[i + 1] >= ones[i] ? v >= prev - 1e-15 : v <= prev + 1e-15);
                prev = v;
            }
        }
        ct_table_free(t);
    }
    /* linear data: the slope itself, at the ends too */
    for (int i = 0; i < N; i++)
        x[i] = i * i * 0.1, y[i] = 2.0 - 0.5 * x[i];
    ct_pchip_slopes(N, x, y, d);
    for (int i = 0; i < N; i++)
        assert_rel(d[i], -0.5, 1e-13);
}

/* A table written with %.17g and read back by cantact_table.h evaluates to the same bits as
 * the library's; the reader refuses broken files with file:line. */
static void write_table(const char *path, const ct_table *t, const char *rule, double Vc)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "# a test table\n# interpolation = %s\n# V_star_crit = %.17g (comment)\n", rule, Vc);
    fprintf(f, "# v_per_V_star = 2.5\n# nodes = %zu\nV_star,e,de_dlnV_star\n", ct_table_size(t));
    for (size_t i = 0; i < ct_table_size(t); i++)
        fprintf(f, "%.17g,%.17g,%.17g\n", ct_table_V_star(t)[i], ct_table_e(t)[i],
                ct_table_slope(t)[i]);
    fclose(f);
}

static void expect_reader_error(const char *text, const char *message)
{
    char path[] = "/tmp/ct_table_bad_XXXXXX", err[256];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_true(write(fd, text, strlen(text)) == (ssize_t)strlen(text));
    close(fd);
    ct_tab t;
    assert_int_equal(ct_tab_load(&t, path, err, sizeof err), -1);
    if (!strstr(err, message))
        fail_msg("reader said '%s', expected '%s'", err, message);
    assert_true(strncmp(err, path, strlen(path)) == 0);
    unlink(path);
}

/* What a monotone cubic promises is checked on loading (issue: a slope of -500 gave e from
 * -0.656 to 2.648): any slope of a node above V*_c set to -500, 1e300, its opposite or infinity
 * is refused; the genuine table loads, also with a header line longer
 * than the reader's buffer (a long scene path), and evaluates within [0, 1] everywhere. */
static void reader_refuses_foreign_slopes(void **state)
{
    (void)state;
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 0.01;
    spec.V_max = 0.5;
    spec.tolerance = 1e-7;
    ct_table *t;
    assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
    ct_table_info in;
    ct_table_get_info(t, &in);
    const size_t n = ct_table_size(t);
    const double *V = ct_table_V_star(t), *e = ct_table_e(t), *d = ct_table_slope(t);
    char path[] = "/tmp/ct_table_slopes_XXXXXX", err[512];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    char scene[5000]; /* longer than the reader's line (4096) */
    memset(scene, 'x', sizeof scene - 1);
    scene[sizeof scene - 1] = '\0';
    const double bad[] = {-500.0, 1e300, INFINITY, 0.0 /* its opposite */};
    size_t refused = 0, tried = 0;
    for (size_t k = 0; k < n; k++) {
        if (!(V[k] > in.V_star_crit) || e[k] == 1.0)
            continue;
        for (size_t j = 0; j < sizeof bad / sizeof bad[0]; j++) {
            const double slope = bad[j] == 0.0 ? -d[k] : bad[j];
            if (slope == 0.0)
                continue;
            FILE *f = fopen(path, "w");
            fprintf(f, "# scene = %s\n# interpolation = monotone_cubic\n# V_star_crit = %.17g\n",
                    scene, in.V_star_crit);
            fprintf(f, "# nodes = %zu\nV_star,e,de_dlnV_star\n", n);
            for (size_t i = 0; i < n; i++)
                fprintf(f, "%.17g,%.17g,%.17g\n", V[i], e[i], i == k ? slope : d[i]);
            fclose(f);
            ct_tab r;
            tried++;
            if (ct_tab_load(&r, path, err, sizeof err) == 0) {
                ct_tab_free(&r);
                fail_msg("node %zu slope %g accepted", k, slope);
            }
            refused += strstr(err, "not those of a monotone cubic") != NULL ||
                       strstr(err, "not a number") != NULL || strstr(err, "three numbers") != NULL;
        }
    }
    assert_true(tried > 10);
    assert_int_equal(refused, tried);
    /* the genuine table, with the long line, loads and stays in [0, 1] */
    FILE *f = fopen(path, "w");
    fprintf(f, "# scene = %s\n# interpolation = monotone_cubic\n# V_star_crit = %.17g\n", scene,
            in.V_star_crit);
    fprintf(f, "# nodes = %zu\nV_star,e,de_dlnV_star\n", n);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%.17g,%.17g,%.17g\n", V[i], e[i], d[i]);
    fclose(f);
    ct_tab r;
    if (ct_tab_load(&r, path, err, sizeof err))
        fail_msg("%s", err);
    for (int k = 0; k <= 20000; k++) {
        const double x = ct_tab_eval(&r, 0.005 * pow(0.6 / 0.005, k / 20000.0));
        assert_true(x >= 0.0 && x <= 1.0);
    }
    ct_tab_free(&r);
    /* a long line of a key the reader uses is refused, not skipped */
    f = fopen(path, "w");
    fprintf(f, "# interpolation = monotone_cubic %s\n", scene);
    fclose(f);
    assert_int_equal(ct_tab_load(&r, path, err, sizeof err), -1);
    assert_non_null(strstr(err, "line longer than"));
    unlink(path);
    ct_table_free(t);
    ct_bundle_free(b);
}

static void reader_round_trip(void **state)
{
    (void)state;
    for (int rule = 0; rule < 2; rule++) {
        ct_bundle *b = two_rods();
        ct_table_spec spec;
        ct_table_spec_default(&spec);
        spec.V_min = 0.01;
        spec.V_max = 0.5;
        spec.tolerance = 1e-7;
        spec.interpolation = (ct_interp)rule;
        ct_table *t;
        assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
        ct_table_info in;
        ct_table_get_info(t, &in);
        char path[] = "/tmp/ct_table_XXXXXX", err[256];
        int fd = mkstemp(path);
        assert_true(fd >= 0);
        close(fd);
        write_table(path, t, ct_interp_name((ct_interp)rule), in.V_star_crit);
        ct_tab r;
        if (ct_tab_load(&r, path, err, sizeof err))
            fail_msg("%s", err);
        assert_int_equal(r.n, ct_table_size(t));
        assert_int_equal(r.rule, rule);
        assert_true(r.v_per_V_star == 2.5);
        for (int k = 0; k <= 5000; k++) {
            const double V = 0.005 * pow(0.6 / 0.005, k / 5000.0);
            const double a = ct_tab_eval(&r, V), c = ct_table_eval(t, V);
            assert_memory_equal(&a, &c, sizeof a);
        }
        assert_true(ct_tab_eval(&r, 0.001) == 1.0);        /* below V*_c */
        assert_true(ct_tab_eval(&r, 0.6) == r.e[r.n - 1]); /* beyond the last node */
        assert_false(ct_tab_covers(&r, 0.6));
        assert_true(ct_tab_covers(&r, 0.3) && ct_tab_covers(&r, 1e-9));
        assert_true(isnan(ct_tab_eval(&r, -1.0)) && isnan(ct_tab_eval(&r, NAN)));
        assert_true(ct_tab_e_of_speed(&r, 2.5 * 0.3) == ct_tab_eval(&r, 0.3));
        ct_tab_free(&r);
        unlink(path);
        ct_table_free(t);
        ct_bundle_free(b);
    }
    const char *head =
        "# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 2\nV_star,e,de_dlnV_star\n";
    char buf[512];
    expect_reader_error("V_star,e,de_dlnV_star\n1,1,0\n2,0.5,0\n", "missing # interpolation");
    expect_reader_error("# interpolation = cubic\n", ":1: interpolation = cubic: must be");
    expect_reader_error("# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 1\n",
                        ":3: nodes = 1: not a count >= 2");
    snprintf(buf, sizeof buf, "%s1,1,0\n0.5,0.5,0\n", head);
    expect_reader_error(buf, ":6: V_star = 0.5: must be > 0 and above the previous node");
    snprintf(buf, sizeof buf, "%s1,1,0\n2,1.5,0\n", head);
    expect_reader_error(buf, ":6: e = 1.5: must be in [0, 1]");
    snprintf(buf, sizeof buf, "%s1,1,0\n2,0.5\n", head);
    expect_reader_error(buf, ":6: expected three numbers");
    snprintf(buf, sizeof buf, "%s1,1,0\n2,nan,0\n", head);
    expect_reader_error(buf, ":6: expected three numbers");
    expect_reader_error("# interpolation = linear\nV,e\n", ":2: expected the header");
}

/* The text of a file, and a file of given bytes (for the cut and corrupted copies below). */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    *len = (size_t)ftell(f);
    rewind(f);
    char *text = malloc(*len + 1);
    assert_non_null(text);
    assert_int_equal(fread(text, 1, *len, f), *len);
    text[*len] = '\0';
    fclose(f);
    return text;
}

static void put_bytes(const char *path, const char *a, size_t na, const char *b, size_t nb)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(a, 1, na, f), na);
    if (nb)
        assert_int_equal(fwrite(b, 1, nb, f), nb);
    fclose(f);
}

/* the loader's verdict on bytes: 0 loaded (freed), else its reason, the message in err */
static int load_bytes(const char *path, const char *a, size_t na, const char *b, size_t nb,
                      char *err, size_t errlen)
{
    put_bytes(path, a, na, b, nb);
    ct_tab r;
    const int why = ct_tab_read(&r, path, err, errlen);
    if (!why)
        ct_tab_free(&r);
    return why;
}

/* A table file that does not know it is cut (issue: 586 of 1477 rows loaded, e(5e-3) = 0.623
 * where the model gives 0.322): the file ct_table_write writes loads whole; every copy of it
 * cut at a line break, and every one cut inside its last rows or one in the middle, is
 * refused; so is a row beyond # nodes, a second table appended, a file without # nodes, a key
 * given twice or after the column header, a value too long to be read whole (it was cut to
 * its first 63 characters: another number), a NUL byte, and a count that is not one. */
static void reader_refuses_cut_tables(void **state)
{
    (void)state;
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 0.01;
    spec.V_max = 0.5;
    spec.tolerance = 1e-6;
    ct_table *t;
    assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
    const size_t n = ct_table_size(t);
    char path[] = "/tmp/ct_table_cut_XXXXXX", err[512];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    ct_table_meta meta = {.version = "test",
                          .scene = "two rods",
                          .tolerance = 1e-6,
                          .check_points = spec.check_points,
                          .v_per_V_star = 2.0};
    assert_int_equal(ct_table_write(f, t, &meta), CT_OK);
    fclose(f);
    size_t len;
    char *text = slurp(path, &len);
    ct_tab r;
    if (ct_tab_read(&r, path, err, sizeof err))
        fail_msg("%s", err);
    assert_int_equal(r.n, n);
    assert_true(r.worst_V_star > 0.0 && r.worst_error <= 1e-6 && r.v_per_V_star == 2.0);
    ct_tab_free(&r);
    /* every cut at a line break (the header's included), and inside rows: the first row, one
     * in the middle and the last two */
    const char *rows = strstr(text, "V_star,e,de_dlnV_star\n");
    assert_non_null(rows);
    const size_t first_row = (size_t)(rows - text) + strlen("V_star,e,de_dlnV_star\n");
    size_t lines = 0, cuts = 0, row_start[4] = {first_row, 0, 0, 0}, k = 0;
    for (size_t i = first_row, row = 0; i < len; i++)
        if (text[i] == '\n' && ++row && (row == n / 2 || row == n - 2 || row == n - 1))
            row_start[++k] = i + 1;
    assert_int_equal(k, 3);
    for (size_t i = 0; i + 1 < len; i++) {
        int inside = 0;
        for (int j = 0; j < 4; j++)
            inside |= i > row_start[j] && i < row_start[j] + 60;
        if (text[i] != '\n' && !inside)
            continue;
        const size_t cut = text[i] == '\n' ? i + 1 : i;
        lines += text[i] == '\n';
        cuts++;
        if (load_bytes(path, text, cut, NULL, 0, err, sizeof err) != CT_TAB_BAD_FILE)
            fail_msg("cut after %zu of %zu bytes: loaded", cut, len);
        if (cut > first_row && !strstr(err, "the file is cut"))
            fail_msg("cut after %zu bytes: '%s'", cut, err);
    }
    assert_true(lines > n && cuts > lines + 100);
    /* the issue's cut: 586 rows of 1477 declared */
    assert_int_equal(load_bytes(path, text, row_start[1], NULL, 0, err, sizeof err),
                     CT_TAB_BAD_FILE);
    char want[64];
    snprintf(want, sizeof want, "%zu rows where # nodes = %zu: the file is cut", n / 2, n);
    assert_non_null(strstr(err, want));
    /* a row beyond # nodes; the table twice */
    const char *beyond = "0.75,0.1,0\n";
    assert_int_equal(load_bytes(path, text, len, beyond, strlen(beyond), err, sizeof err),
                     CT_TAB_BAD_FILE);
    snprintf(want, sizeof want, "a row beyond the %zu of # nodes", n);
    assert_non_null(strstr(err, want));
    assert_int_equal(load_bytes(path, text, len, text, len, err, sizeof err), CT_TAB_BAD_FILE);
    /* header lines changed: each (line to find, replacement, expected message) */
    static const char *const edits[][3] = {
        {"# nodes = ", "# nodez = ", "missing # nodes = "},
        {"# nodes = ", "# nodes = 1e3 ", "nodes = 1e3: not a count"},
        {"# nodes = ", "# nodes = -5 ", "nodes = -5: not a count"},
        {"# nodes = ", "# nodes = +5 ", "nodes = +5: not a count"},
        {"# nodes = ", "# nodes = 99999999999999999999999 ", "not a count"},
        {"# nodes = ", "# nodes = 7\n# nodes = ", "# nodes given twice"},
        {"# tolerance = ", "# tolerance = 1e-6\n# tolerance = ", "# tolerance given twice"},
        {"# worst_error_at_V_star = ", "# worst_error_at_V_star = abc #",
         "worst_error_at_V_star = abc: not a number > 0 or none"},
        {"# V_star_crit = ",
         "# V_star_crit = 0.100000000000000000000000000000000000000000000000000000000000000e-9 #",
         "V_star_crit: value longer than 63 characters"},
        {"V_star,e,de_dlnV_star\n", "V_star,e,de_dlnV_star\n# tolerance = 1\n",
         "# tolerance given twice"},
        {"V_star,e,de_dlnV_star\n", "V_star,e,de_dlnV_star\n# interpolation = linear\n",
         "# interpolation given twice"},
        {"# tolerance = ", "# x = 1\n# tolerance", "given twice"}, /* "# tolerance1e-6": prose */
    };
    for (size_t j = 0; j < sizeof edits / sizeof edits[0]; j++) {
        const char *at = strstr(text, edits[j][0]);
        assert_non_null(at);
        const size_t head = (size_t)(at - text), skip = strlen(edits[j][0]);
        char *copy = malloc(len + 200);
        assert_non_null(copy);
        memcpy(copy, text, head);
        strcpy(copy + head, edits[j][1]);
        strcat(copy, text + head + skip);
        const int why = load_bytes(path, copy, strlen(copy), NULL, 0, err, sizeof err);
        free(copy);
        if (j + 1 == sizeof edits / sizeof edits[0]) {
            assert_int_equal(why, 0); /* prose, and the file still has its tolerance */
            continue;
        }
        if (why != CT_TAB_BAD_FILE || !strstr(err, edits[j][2]))
            fail_msg("edit %zu: '%s', expected '%s'", j, why ? err : "loaded", edits[j][2]);
    }
    /* a key after the column header, once only */
    const char *late = "# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 2\n"
                       "V_star,e,de_dlnV_star\n0.01,1,0\n# tolerance = 1e-6\n0.05,1,0\n";
    assert_int_equal(load_bytes(path, late, strlen(late), NULL, 0, err, sizeof err),
                     CT_TAB_BAD_FILE);
    assert_non_null(strstr(err, "after the column header"));
    /* a NUL byte in a row, and in a header line */
    char *copy = malloc(len + 1);
    assert_non_null(copy);
    memcpy(copy, text, len);
    copy[row_start[1] + 3] = '\0';
    assert_int_equal(load_bytes(path, copy, len, NULL, 0, err, sizeof err), CT_TAB_BAD_FILE);
    assert_non_null(strstr(err, "a NUL byte"));
    memcpy(copy, text, len);
    copy[5] = '\0';
    assert_int_equal(load_bytes(path, copy, len, NULL, 0, err, sizeof err), CT_TAB_BAD_FILE);
    assert_non_null(strstr(err, ":1: a NUL byte"));
    free(copy);
    /* none where no point was checked; a missing file is an I/O error */
    const char *none_text = "# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 2\n"
                            "# worst_error_at_V_star = none (no point)\nV_star,e,de_dlnV_star\n"
                            "0.01,1,0\n0.05,1,0\n";
    put_bytes(path, none_text, strlen(none_text), NULL, 0);
    assert_int_equal(ct_tab_read(&r, path, err, sizeof err), 0);
    assert_true(isnan(r.worst_V_star) && r.n == 2);
    ct_tab_free(&r);
    unlink(path);
    assert_int_equal(ct_tab_read(&r, path, err, sizeof err), CT_TAB_IO_ERROR);
    assert_int_equal(ct_tab_load(&r, path, err, sizeof err), -1);
    assert_non_null(strstr(err, "cannot open"));
    free(text);
    ct_table_free(t);
    ct_bundle_free(b);
}

/* ct_table_read (the library's reader, which Python's read_table calls) is ct_tab_read: the
 * nodes of the file ct_table_write wrote, bit for bit, and the header's numbers; the reader's
 * refusals as CT_EINVAL with its message, a missing file as CT_EIO. */
static void library_reads_with_the_header(void **state)
{
    (void)state;
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 0.01;
    spec.V_max = 0.5;
    spec.tolerance = 1e-6;
    ct_table *t, *r;
    assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
    ct_table_info in;
    ct_table_get_info(t, &in);
    char path[] = "/tmp/ct_table_lib_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    ct_table_meta meta = {
        .version = "", .tolerance = 1e-6, .check_points = 16, .v_per_V_star = 3.0};
    assert_int_equal(ct_table_write(f, t, &meta), CT_OK);
    fclose(f);
    ct_table_file_info file;
    assert_int_equal(ct_table_read(&r, path, &file), CT_OK);
    const size_t n = ct_table_size(t);
    assert_int_equal(ct_table_size(r), n);
    assert_memory_equal(ct_table_V_star(r), ct_table_V_star(t), n * sizeof(double));
    assert_memory_equal(ct_table_e(r), ct_table_e(t), n * sizeof(double));
    assert_memory_equal(ct_table_slope(r), ct_table_slope(t), n * sizeof(double));
    assert_int_equal(ct_table_interpolation(r), ct_table_interpolation(t));
    assert_true(file.tolerance == 1e-6 && file.worst_error == in.worst_error &&
                file.worst_V_star == in.worst_V_star && file.v_per_V_star == 3.0);
    for (int k = 0; k <= 400; k++) {
        const double V = 0.005 * pow(0.6 / 0.005, k / 400.0), a = ct_table_eval(r, V),
                     c = ct_table_eval(t, V);
        assert_memory_equal(&a, &c, sizeof a);
    }
    ct_table_free(r);
    size_t len;
    char *text = slurp(path, &len);
    put_bytes(path, text, len - 40, NULL, 0); /* cut inside its last rows */
    r = (ct_table *)&file;
    assert_int_equal(ct_table_read(&r, path, NULL), CT_EINVAL);
    assert_null(r);
    assert_non_null(strstr(ct_error_message(), path));
    assert_non_null(strstr(ct_error_message(), "the file is cut"));
    unlink(path);
    assert_int_equal(ct_table_read(&r, path, NULL), CT_EIO);
    assert_non_null(strstr(ct_error_message(), "cannot open"));
    assert_int_equal(ct_table_read(&r, NULL, NULL), CT_EINVAL);
    assert_int_equal(ct_table_read(NULL, path, NULL), CT_EINVAL);
    free(text);
    ct_table_free(t);
    ct_bundle_free(b);
}

/* The default Cantor surface: a table at 1e-6 checked against sweeps at points between the
 * build's check points (3 per interval, none of them the build's). */
static void default_cantor(void **state)
{
    (void)state;
    double range[2] = {1e-5, 1e-2};
    ct_cantor_plan plan = {
        .params = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1},
        .depth = CT_DEPTH_AUTO,
        .representation = CT_REP_STAGES,
        .depth_tolerance = 1e-12,
        .V_star = range,
        .nvel = 2,
        .impacts = 1};
    ct_impact_opts_default(&plan.opts);
    ct_bundle *b;
    assert_int_equal(ct_cantor_plan_build(&plan, &b, NULL), CT_OK);
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = range[0];
    spec.V_max = range[1];
    spec.tolerance = 1e-6;
    ct_table *t;
    assert_int_equal(ct_table_build(&t, b, &spec), CT_OK);
    ct_table_info in;
    ct_table_get_info(t, &in);
    assert_true(in.worst_error <= 1e-6);
    /* V*_c a node, bit for bit the one sweeps report, and the first yield's closed form */
    double Wc, uy;
    assert_int_equal(ct_critical_energy(b, &Wc, &uy), CT_OK);
    ct_sweep_row row;
    ct_sweep_spec one = {.V_star = &range[1], .nvel = 1, .impacts = 1};
    ct_impact_opts_default(&one.opts);
    assert_int_equal(ct_sweep(b, &one, &row), CT_OK);
    assert_true(in.V_star_crit == row.r.V_star_crit);
    assert_rel(in.V_star_crit, sqrt(Wc / ct_energy_scale(&plan.params)), 1e-14);
    assert_true(has_node(t, in.V_star_crit, 0.0));
    const size_t n = ct_table_size(t);
    const double *V = ct_table_V_star(t);
    size_t m = 0;
    double *q = malloc(3 * n * sizeof(double));
    ct_sweep_row *rows = malloc(3 * n * sizeof *rows);
    assert_non_null(q);
    assert_non_null(rows);
    for (size_t i = 0; i + 1 < n; i++) {
        const double x0 = log(V[i]), h = log(V[i + 1]) - x0, f[3] = {0.029, 0.5003, 0.971};
        for (int k = 0; k < 3; k++)
            q[m++] = exp(x0 + h * f[k]);
    }
    ct_sweep_spec s = {.V_star = q, .nvel = m, .impacts = 1};
    ct_impact_opts_default(&s.opts);
    assert_int_equal(ct_sweep(b, &s, rows), CT_OK);
    double worst = 0.0;
    for (size_t k = 0; k < m; k++) {
        assert_int_equal(rows[k].status, CT_OK);
        worst = fmax(worst, fabs(ct_table_eval(t, q[k]) - rows[k].r.e));
    }
    if (!(worst <= 1.05e-6))
        fail_msg("worst error %g at unchecked points", worst);
    free(q);
    free(rows);
    ct_table_free(t);
    ct_bundle_free(b);
}

/* The rule of cantact_table.h, written here from the cubic Hermite basis (h00, h10, h01,
 * h11) and the secant, against the library's evaluation of tables made from given nodes. */
static void rule_from_the_basis(void **state)
{
    (void)state;
    /* slopes a monotone cubic allows (the reader refuses others): of each secant's sign, at
     * most three secants, 0 at the extremum at V* = 3 */
    double V[4] = {0.5, 1.0, 3.0, 4.0}, e[4] = {1.0, 0.8, 0.3, 0.35}, d[4] = {0.0, -0.4, 0.0, 0.1};
    for (int rule = 0; rule < 2; rule++) {
        ct_table *t;
        assert_int_equal(ct_table_from_nodes(&t, 4, V, e, d, (ct_interp)rule, 0.25), CT_OK);
        for (int i = 0; i < 3; i++)
            for (int k = 0; k <= 40; k++) {
                const double x0 = log(V[i]), x1 = log(V[i + 1]), h = x1 - x0;
                const double x = x0 + h * k / 40.0, tt = (x - x0) / h;
                const double h00 = 2 * tt * tt * tt - 3 * tt * tt + 1,
                             h10 = tt * tt * tt - 2 * tt * tt + tt,
                             h01 = -2 * tt * tt * tt + 3 * tt * tt, h11 = tt * tt * tt - tt * tt;
                const double want =
                    rule == CT_INTERP_LINEAR
                        ? e[i] + (e[i + 1] - e[i]) * tt
                        : h00 * e[i] + h10 * h * d[i] + h01 * e[i + 1] + h11 * h * d[i + 1];
                assert_true(fabs(ct_table_eval(t, exp(x)) - want) <= 1e-14);
            }
        assert_true(ct_table_eval(t, 0.25) == 1.0 && ct_table_eval(t, 0.3) == e[0]);
        assert_true(ct_table_eval(t, 10.0) == e[3]);
        ct_table_free(t);
    }
}

/* The rule's promise at the edge of what the reader accepts: slopes of three secants (and
 * within 1e-12 of that) are monotone in exact arithmetic, and e = 1 or 0 at a node is then
 * approached as a cubic in t, whose rounding gave e = 1 + 2^-52 and e = -1.9e-36 (and e a few
 * ulps beyond the other node). Every evaluation must lie between the interval's two node values
 * (so in [0, 1]) and give a damping ratio that is not NaN: through the header on nodes, the
 * library on nodes, and the reader on a file holding the same bits. */
static double between_nodes(const double V[2], const double e[2], const double d[2], int rule,
                            size_t m, const double *at)
{
    const double ln[2] = {log(V[0]), log(V[1])};
    ct_table *t;
    assert_int_equal(ct_table_from_nodes(&t, 2, V, e, d, (ct_interp)rule, 0.0), CT_OK);
    char path[] = "/tmp/ct_table_edge_XXXXXX", err[512];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "# interpolation = %s\n# V_star_crit = 0\n# nodes = 2\nV_star,e,de_dlnV_star\n",
            rule == CT_TAB_LINEAR ? "linear" : "monotone_cubic");
    for (int i = 0; i < 2; i++)
        fprintf(f, "%a,%a,%a\n", V[i], e[i], d[i]);
    fclose(f);
    ct_tab r;
    if (ct_tab_load(&r, path, err, sizeof err))
        fail_msg("%s", err);
    unlink(path);
    const double lo = fmin(e[0], e[1]), hi = fmax(e[0], e[1]);
    double last = NAN;
    for (size_t k = 0; k < m; k++) {
        const double a = ct_tab_interp(2, ln, e, d, rule, 0.0, at[k]);
        const double b = ct_table_eval(t, at[k]), c = ct_tab_eval(&r, at[k]);
        if (!(a == b && b == c))
            fail_msg("header %a, library %a, file %a", a, b, c);
        if (!(a >= lo && a <= hi))
            fail_msg("nodes e = %a, %a, slopes %a, %a: e(%a) = %a (%.3g beyond)", e[0], e[1], d[0],
                     d[1], at[k], a, a < lo ? lo - a : a - hi);
        for (int law = CT_TAB_TENSION; law <= CT_TAB_CLIPPED; law++)
            assert_false(isnan(ct_tab_zeta_of_e(a, law)));
        last = a;
    }
    ct_tab_free(&r);
    ct_table_free(t);
    return last;
}

static void slope_limit_stays_between_nodes(void **state)
{
    (void)state;
    /* e = 1 + 2^-52 near a node e = 1 (slopes 3 secants and 0) */
    const double V1[2] = {0x1.9c8e04684ee68p+13, 0x1.dbb99bf374519p+13},
                 e1[2] = {0x1.5d329019adbap-4, 1.0}, d1[2] = {0x1.34300e2ce7ed1p+4, 0.0};
    assert_true(between_nodes(V1, e1, d1, CT_TAB_MONOTONE_CUBIC, 1,
                              (double[]){0x1.dbb99250668a4p+13}) <= 1.0);
    /* e = -1.9e-36 near a node e = 0 (slopes 0 and 3 secants) */
    const double V2[2] = {0x1.321ef3714ab3ap-11, 0x1.384ba71aa2c6ap-11},
                 e2[2] = {0.0, 0x1.f815c6869f114p-2}, d2[2] = {0.0, 0x1.27cf29891fc47p+6};
    assert_true(between_nodes(V2, e2, d2, CT_TAB_MONOTONE_CUBIC, 1,
                              (double[]){0x1.321ef3714abfep-11}) >= 0.0);
    /* an ulp below the lower node, inside [0, 1] */
    const double V3[2] = {0x1.be8f22efe8da4p+10, 0x1.9f42cf59f30f1p+11},
                 e3[2] = {0x1.e7f7d30ae7102p-1, 0x1.690f1ed1a1668p-3},
                 d3[2] = {-0x1.e0b7f334ac982p+1, 0.0};
    assert_true(between_nodes(V3, e3, d3, CT_TAB_MONOTONE_CUBIC, 1,
                              (double[]){0x1.9f42cf49d8775p+11}) == e3[1]);
    /* random intervals at the limit: slopes of 0, 3 and 3 (1 + 1e-12) secants, nodes at 0, 1
     * and between, evaluated at 2^-k of the interval from either end and at random points */
    uint64_t r = 88172645463325252ull;
#define NEXT_U (r ^= r << 13, r ^= r >> 7, r ^= r << 17, (double)(r >> 11) / 9007199254740992.0)
    const double ratio[3] = {0.0, 3.0, 3.0 * (1.0 + 1e-12)};
    size_t tried = 0;
    for (int trial = 0; trial < 3000; trial++) {
        const double V0 = exp((NEXT_U - 0.5) * 20.0);
        const double V[2] = {V0, V0 * exp(NEXT_U * 3.0 + 1e-6)};
        double e[2] = {NEXT_U, NEXT_U};
        const int m = trial % 5;
        if (m)
            e[(m - 1) % 2] = m <= 2 ? 1.0 : 0.0;
        const double secant = (e[1] - e[0]) / (log(V[1]) - log(V[0]));
        const double d[2] = {ratio[trial / 5 % 3] * secant, ratio[trial / 15 % 3] * secant};
        ct_tab view = {.n = 2, .V_star = (double *)V, .e = e, .slope = (double *)d};
        double ln[2] = {log(V[0]), log(V[1])};
        view.ln_V_star = ln;
        size_t bad;
        if (ct_tab_check_slopes(&view, &bad))
            continue; /* 3 (1 + 1e-12) rounded beyond the reader's limit */
        double at[120];
        for (int k = 0; k < 120; k++) {
            const double s = k < 100 ? ldexp(1.0, -(k / 2) - 1) : NEXT_U;
            at[k] = exp(k % 2 ? ln[1] - (ln[1] - ln[0]) * s : ln[0] + (ln[1] - ln[0]) * s);
        }
        between_nodes(V, e, d, trial % 7 ? CT_TAB_MONOTONE_CUBIC : CT_TAB_LINEAR, 120, at);
        tried += 120;
    }
#undef NEXT_U
    assert_true(tried > 50000);
}

static void bad_input(void **state)
{
    (void)state;
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 0.01;
    spec.V_max = 0.5;
    ct_table *t = (ct_table *)&spec;
    assert_int_equal(ct_table_build(NULL, b, &spec), CT_EINVAL);
    assert_int_equal(ct_table_build(&t, NULL, &spec), CT_EINVAL);
    assert_null(t);
    assert_int_equal(ct_table_build(&t, b, NULL), CT_EINVAL);
    ct_table_spec bad = spec;
    bad.V_max = 0.001;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_EINVAL);
    bad = spec;
    bad.V_min = NAN;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_EINVAL);
    bad = spec;
    bad.tolerance = 1e-20;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_EINVAL);
    bad = spec;
    bad.interpolation = (ct_interp)7;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_EINVAL);
    bad = spec;
    bad.check_points = 0;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_EINVAL);
    /* too few nodes for the tolerance: refused, with the worst error in the message */
    bad = spec;
    bad.max_nodes = 12;
    bad.tolerance = 1e-10;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_ENOCONV);
    assert_non_null(strstr(ct_error_message(), "max_nodes = 12"));
    assert_null(t);
    /* a range that crushes the layer (W = 3.325 at u = H*: V* = 0.577) */
    bad = spec;
    bad.V_max = 0.6;
    assert_int_equal(ct_table_build(&t, b, &bad), CT_ERANGE);
    /* nodes given */
    double V[3] = {1, 2, 3}, e[3] = {1, 0.5, 0.4}, d[3] = {0, 0, 0};
    assert_int_equal(ct_table_from_nodes(&t, 3, V, e, d, CT_INTERP_LINEAR, 0.5), CT_OK);
    assert_rel(ct_table_eval(t, sqrt(2.0)), 0.75, 1e-15); /* half way in ln V* */
    ct_table_free(t);
    V[1] = 1;
    assert_int_equal(ct_table_from_nodes(&t, 3, V, e, d, CT_INTERP_LINEAR, 0.5), CT_EINVAL);
    V[1] = 2, e[1] = 1.5;
    assert_int_equal(ct_table_from_nodes(&t, 3, V, e, d, CT_INTERP_LINEAR, 0.5), CT_EINVAL);
    e[1] = 0.5, d[2] = INFINITY;
    assert_int_equal(ct_table_from_nodes(&t, 3, V, e, d, CT_INTERP_LINEAR, 0.5), CT_EINVAL);
    assert_int_equal(ct_table_from_nodes(&t, 3, NULL, e, d, CT_INTERP_LINEAR, 0.5), CT_EINVAL);
    ct_bundle_free(b);
}

/* A table built with a progress callback is the same bits as without: its calls rise to the
 * exact impacts computed, never past the total planned; a set interrupt flag stops the build
 * (CT_EINTR), and one set by the callback at its first call stops it there. */
typedef struct {
    size_t calls, last, total;
    int rising;
    volatile int *stop;
} table_progress;

static void log_table_progress(size_t done, size_t total, void *ctx)
{
    table_progress *g = ctx;
    g->rising &= done > g->last && done <= total && total >= g->total;
    g->last = done;
    g->total = total;
    g->calls++;
    if (g->stop)
        *g->stop = 1;
}

static void progress_and_interrupt(void **state)
{
    (void)state;
    ct_bundle *b = two_rods();
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = 1e-3;
    spec.V_max = 0.3;
    spec.tolerance = 1e-9;
    ct_table *plain, *seen;
    assert_int_equal(ct_table_build(&plain, b, &spec), CT_OK);
    table_progress g = {.rising = 1};
    spec.progress = log_table_progress;
    spec.progress_ctx = &g;
    assert_int_equal(ct_table_build(&seen, b, &spec), CT_OK);
    ct_table_info a, c;
    ct_table_get_info(plain, &a);
    ct_table_get_info(seen, &c);
    assert_true(g.rising && g.calls > 1);
    assert_int_equal(g.last, c.evaluations);
    assert_int_equal(g.total, c.evaluations);
    const size_t n = ct_table_size(plain);
    assert_int_equal(ct_table_size(seen), n);
    assert_true(!memcmp(&a, &c, sizeof a));
    assert_true(!memcmp(ct_table_V_star(plain), ct_table_V_star(seen), n * sizeof(double)));
    assert_true(!memcmp(ct_table_e(plain), ct_table_e(seen), n * sizeof(double)));
    assert_true(!memcmp(ct_table_slope(plain), ct_table_slope(seen), n * sizeof(double)));
    ct_table_free(seen);
    volatile int stop = 1;
    spec.interrupt = &stop;
    spec.progress = NULL;
    assert_int_equal(ct_table_build(&seen, b, &spec), CT_EINTR);
    assert_null(seen);
    stop = 0;
    table_progress h = {.rising = 1, .stop = &stop};
    spec.progress = log_table_progress;
    spec.progress_ctx = &h;
    assert_int_equal(ct_table_build(&seen, b, &spec), CT_EINTR);
    assert_string_equal(ct_error_message(), "interrupted");
    assert_int_equal(h.calls, 1);
    ct_table_free(plain);
    ct_bundle_free(b);
}

/* ---- tables of samples: the landings of a cylinder on rods placed along a line ---- */

enum { LANDINGS = 40 };
static const double PQ[3] = {0.1, 0.5, 0.9};

static ct_surface *placed_rods(void)
{
    enum { N = 80 };
    double top[N], area[N], x[N];
    for (int k = 0; k < N; k++) {
        top[k] = 0.5 * (1.0 + sin(1.7 * k));
        area[k] = 1.0;
        x[k] = k;
    }
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set_rods_at(s, N, top, area, NULL, x, NULL), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "Hstar", "2", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "500", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    return s;
}

static ct_body cylinder(void)
{
    ct_body b;
    ct_body_defaults(&b);
    for (size_t k = 0; k < ct_body_count(); k++)
        if (!strcmp(ct_body_name(k), "cylinder"))
            b.shape = (int)k;
    b.radius = 30.0;
    b.landings = LANDINGS;
    b.seed = 3;
    return b;
}

static double type7(const double *sorted, size_t n, double p)
{
    const double h = (double)(n - 1) * p;
    const size_t f = (size_t)floor(h);
    return f + 1 < n ? sorted[f] + (h - (double)f) * (sorted[f + 1] - sorted[f]) : sorted[n - 1];
}

static int cmp_d(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The table of the landings' statistics: at its nodes (grid speeds) the mean and the type-7
 * quantiles of e over the landings, each landing run on its own here (the body at its apex,
 * ct_surface_build and ct_sweep: not the ensemble the table was built by); the file read back
 * by the library and by cantact_table.h evaluates to the same bits; e at (V*, p) is
 * non-decreasing in p, the nearest column outside [0.1, 0.9], linear between columns, NaN for
 * p outside [0, 1]; a file whose quantiles decrease, or whose columns disagree with
 * # quantiles, is refused. */
static void samples_table(void **state)
{
    (void)state;
    ct_surface *s = placed_rods();
    ct_body body = cylinder();
    ct_scales sc;
    ct_surface_scales(s, &sc);
    const double V[2] = {1e-3, 1e-2};
    ct_build_request req = {.V_star = V, .nvel = 2, .impacts = 1, .body = &body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *rods;
    assert_int_equal(ct_surface_build_unmet(s, &req, &rods, NULL), CT_OK);
    ct_ensemble_spec es = {.first = 0,
                           .count = LANDINGS,
                           .impacts = 1,
                           .body = &body,
                           .scales = sc,
                           .rods = rods,
                           .threads = 2};
    ct_impact_opts_default(&es.opts);
    ct_table_spec spec;
    ct_table_spec_default(&spec);
    spec.V_min = V[0];
    spec.V_max = V[1];
    spec.tolerance = 1e-2; /* 80 rods: e of each landing has kinks a grid cannot smooth */
    ct_table_quantiles q = {.p = PQ, .np = 3, .grid = 600};
    ct_table *t;
    assert_int_equal(ct_table_build_samples(&t, &es, &spec, &q), CT_OK);
    assert_int_equal(ct_table_quantile_count(t), 3);
    assert_int_equal(ct_table_samples(t), LANDINGS);
    ct_table_info in;
    ct_table_get_info(t, &in);
    assert_true(in.worst_error <= 1e-2);
    /* the nodes against each landing run alone */
    double lo[2], hi[2];
    assert_int_equal(ct_body_landing_region(&body, &sc, rods, lo, hi), CT_OK);
    const size_t n = ct_table_size(t);
    int checked = 0;
    for (size_t i = 1; i < n; i += n / 7) {
        const double Vi = ct_table_V_star(t)[i];
        if (!(Vi > in.V_star_crit))
            continue;
        double e[LANDINGS], sum = 0.0;
        for (uint64_t k = 0; k < LANDINGS; k++) {
            double pos[2];
            ct_body_landing(lo, hi, body.seed, k, pos);
            ct_body at = body;
            at.landings = 0;
            at.position[0] = pos[0];
            ct_build_request one = {.V_star = &Vi, .nvel = 1, .impacts = 1, .body = &at};
            ct_impact_opts_default(&one.opts);
            ct_bundle *b;
            assert_int_equal(ct_surface_build(s, &one, &b, NULL), CT_OK);
            ct_sweep_spec sw = {.V_star = &Vi, .nvel = 1, .impacts = 1};
            ct_impact_opts_default(&sw.opts);
            ct_sweep_row row;
            assert_int_equal(ct_sweep(b, &sw, &row), CT_OK);
            e[k] = row.r.e;
            sum += e[k];
            ct_bundle_free(b);
        }
        qsort(e, LANDINGS, sizeof(double), cmp_d);
        assert_true(fabs(ct_table_e(t)[i] - sum / LANDINGS) <= 1e-13);
        for (size_t j = 0; j < 3; j++)
            assert_true(fabs(ct_table_e_quantile(t, j)[i] - type7(e, LANDINGS, PQ[j])) <= 1e-15);
        checked++;
    }
    assert_true(checked >= 5);
    /* the quantile columns against a tolerance of their own (each has a kink wherever two
     * samples' e cross): the mean within the table's, the quantiles within theirs, and looser */
    ct_table *t2;
    ct_table_spec spec2 = spec;
    spec2.tolerance = 2e-3;
    ct_table_quantiles q2 = q;
    q2.tolerance = 2e-2;
    assert_int_equal(ct_table_build_samples(&t2, &es, &spec2, &q2), CT_OK);
    ct_table_info in2;
    ct_table_get_info(t2, &in2);
    assert_true(in2.worst_error <= 2e-3);
    assert_true(ct_table_quantile_tolerance(t2) == 2e-2);
    assert_true(ct_table_quantile_worst_error(t2) <= 2e-2);
    assert_true(ct_table_quantile_worst_error(t2) > 2e-3); /* the looser one was used */
    ct_table_free(t2);
    q2.tolerance = 1.5;
    assert_int_equal(ct_table_build_samples(&t2, &es, &spec2, &q2), CT_EINVAL);
    /* the file read back, by the library and by the header alone */
    char path[] = "/tmp/ct_samples_XXXXXX", err[512];
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    ct_table_meta meta = {.version = "test",
                          .tolerance = 1e-3,
                          .v_per_V_star = NAN,
                          .samples = "landings",
                          .grid = 300};
    assert_int_equal(ct_table_write(f, t, &meta), CT_OK);
    fclose(f);
    ct_table *back;
    assert_int_equal(ct_table_read(&back, path, NULL), CT_OK);
    ct_tab tab;
    assert_int_equal(ct_tab_load(&tab, path, err, sizeof err), 0);
    assert_int_equal(tab.nq, 3);
    for (int a = 0; a <= 200; a++) {
        const double Va = V[0] * pow(V[1] / V[0], a / 200.0);
        double prev = -1.0;
        for (int b = -2; b <= 102; b++) {
            const double p = b / 100.0, v = ct_table_eval_quantile(t, Va, p);
            const double u = ct_table_eval_quantile(back, Va, p);
            assert_true(v == u || (isnan(v) && isnan(u)));
            const double w = ct_tab_eval_quantile(&tab, Va, p);
            assert_true(v == w || (isnan(v) && isnan(w)));
            if (p < 0.0 || p > 1.0) {
                assert_true(isnan(v));
                continue;
            }
            assert_true(v >= prev); /* non-decreasing in p */
            prev = v;
        }
        /* the columns: the nearest outside, linear between (the running maximum) */
        double c[3];
        for (size_t j = 0; j < 3; j++)
            c[j] = ct_tab_interp(tab.n, tab.ln_V_star, tab.e_q + j * tab.n, tab.slope_q + j * tab.n,
                                 tab.rule, tab.V_star_crit, Va);
        const double c1 = fmax(c[0], c[1]), c2 = fmax(c1, c[2]);
        assert_true(ct_tab_eval_quantile(&tab, Va, 0.0) == c[0]);
        assert_true(ct_tab_eval_quantile(&tab, Va, 0.05) == c[0]);
        assert_true(ct_tab_eval_quantile(&tab, Va, 1.0) == c2);
        assert_true(fabs(ct_tab_eval_quantile(&tab, Va, 0.3) - 0.5 * (c[0] + c1)) <= 1e-15);
        assert_true(fabs(ct_tab_eval_quantile(&tab, Va, 0.8) - (0.25 * c1 + 0.75 * c2)) <= 1e-15);
    }
    ct_tab_free(&tab);
    /* columns that cross between nodes (each within its tolerance): e stays non-decreasing in
     * p, the running maximum of the columns below it (linear, two nodes, p = 0.1 and 0.5) */
    const double lnV[2] = {0.0, 1.0}, pp[2] = {0.1, 0.5}, eq[4] = {0.2, 0.6, 0.5, 0.3},
                 dq[4] = {0.0, 0.0, 0.0, 0.0};
    const double at = exp(0.75); /* column 0.1 at 0.5, column 0.5 at 0.35 */
    assert_true(fabs(ct_tab_quantile_interp(2, lnV, 2, pp, eq, dq, CT_TAB_LINEAR, 0.0, at, 0.3) -
                     0.5) <= 1e-15);
    assert_true(fabs(ct_tab_quantile_interp(2, lnV, 2, pp, eq, dq, CT_TAB_LINEAR, 0.0, at, 0.5) -
                     0.5) <= 1e-15);
    assert_true(
        fabs(ct_tab_quantile_interp(2, lnV, 2, pp, eq, dq, CT_TAB_LINEAR, 0.0, exp(0.25), 0.3) -
             0.5 * (0.3 + 0.45)) <= 1e-15);
    /* refused: a row whose quantiles decrease, a header that disagrees with # quantiles */
    size_t len;
    char *text = slurp(path, &len);
    char *row = strstr(text, "\n1e-3") ? NULL : strstr(strstr(text, "\nV_star,") + 1, "\n") + 1;
    assert_non_null(row);
    char *bad = strdup(text);
    char *brow = bad + (row - text);
    char *f4 = brow; /* the row's fourth field (e at p = 0.1): set above every other */
    for (int k = 0; k < 3; k++)
        f4 = strchr(f4, ',') + 1;
    f4[0] = '1';
    for (char *q2 = f4 + 1; *q2 != ','; q2++)
        *q2 = *q2 == '.' ? '.' : '0';
    expect_reader_error(bad, "quantiles decrease");
    free(bad);
    bad = strdup(text);
    char *nq = strstr(bad, "# quantiles = 3");
    assert_non_null(nq);
    nq[14] = '2';
    expect_reader_error(bad, "more columns than # quantiles");
    free(bad);
    /* a quantile column's slope of the wrong sign in the middle row (field 7: de_p0.5) */
    bad = malloc(len + 16);
    const char *mid = strstr(text, "\nV_star,") + 1;
    for (size_t k = 0; k <= n / 2; k++)
        mid = strchr(mid, '\n') + 1;
    const char *f7 = mid;
    for (int k = 0; k < 6; k++)
        f7 = strchr(f7, ',') + 1;
    const char *f7end = strchr(f7, ',');
    const size_t head = (size_t)(f7 - text);
    memcpy(bad, text, head);
    strcpy(bad + head, "-500");
    strcat(bad, f7end);
    expect_reader_error(bad, "slopes of e at p = 0.5");
    free(bad);
    free(text);
    unlink(path);
    ct_table_free(back);
    ct_table_free(t);
    ct_bundle_free(rods);
    ct_surface_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_rods_cubic),
        cmocka_unit_test(two_rods_linear),
        cmocka_unit_test(pchip_conditions),
        cmocka_unit_test(reader_round_trip),
        cmocka_unit_test(reader_refuses_foreign_slopes),
        cmocka_unit_test(library_reads_with_the_header),
        cmocka_unit_test(default_cantor),
        cmocka_unit_test(rule_from_the_basis),
        cmocka_unit_test(slope_limit_stays_between_nodes),
        cmocka_unit_test(bad_input),
        cmocka_unit_test(progress_and_interrupt),
        cmocka_unit_test(samples_table),
        /* last: it writes and reads some hundred cut files (the slowest here), so that a
         * mistake another test catches is caught without it (the mutation check) */
        cmocka_unit_test(reader_refuses_cut_tables),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
