/* The registry of kinds of surface (src/surface/kind.c) and the rods kind (src/surface/rods.c):
 * every kind's rows and outputs are complete, and a user's rods give the closed forms of
 * docs/model.md §3 rod by rod (one rod: W_load, W_unload and e; lengths given: the crushed
 * limit at the shallowest bottom; the scales h0 = deepest top, l0 = total area). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "cantact.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static void registry_complete(void **state)
{
    (void)state;
    const size_t n = ct_surface_kind_count();
    assert_true(n >= 4);
    for (size_t k = 0; k < n; k++) {
        const char *name = ct_surface_kind_name(k);
        assert_non_null(name);
        assert_true(strlen(ct_surface_kind_summary(k)) > 10);
        for (size_t j = 0; j < k; j++)
            assert_string_not_equal(name, ct_surface_kind_name(j));
        size_t m;
        const ct_key *rows = ct_surface_kind_keys(k, &m);
        assert_true(m > 0);
        for (size_t r = 0; r < m; r++) {
            assert_true(rows[r].section[0] && rows[r].name[0] && rows[r].doc[0]);
            if (rows[r].type == CT_KEY_WORD || rows[r].type == CT_KEY_WORDS ||
                rows[r].type == CT_KEY_DEPTH)
                assert_non_null(rows[r].words);
            if (rows[r].type == CT_KEY_NUMBER || rows[r].type == CT_KEY_INTEGER)
                assert_true(rows[r].range && rows[r].range[0]);
            for (size_t q = 0; q < r; q++) /* one row per key */
                assert_false(!strcmp(rows[r].section, rows[q].section) &&
                             !strcmp(rows[r].name, rows[q].name));
        }
        /* every output is given, or refused with a reason and what to use instead */
        char outputs[256];
        snprintf(outputs, sizeof outputs, "%s", ct_surface_outputs());
        for (char *o = strtok(outputs, " "); o; o = strtok(NULL, " ")) {
            const char *why = NULL;
            if (ct_surface_kind_supports(k, o, &why))
                continue;
            assert_true(why && strlen(why) > 20);
            /* the reason names exactly the kinds that give the output, after "surface.type =" */
            char reason[400];
            snprintf(reason, sizeof reason, "%s", why);
            const char *kinds = strstr(reason, "surface.type = ");
            assert_non_null(kinds);
            for (size_t j = 0; j < n; j++) {
                char word[64];
                int named = 0;
                for (const char *p = kinds + 15; *p;) {
                    size_t len = strcspn(p, ", ");
                    snprintf(word, sizeof word, "%.*s", (int)len, p);
                    named |= !strcmp(word, ct_surface_kind_name(j));
                    p += len;
                    p += strspn(p, ", ");
                }
                assert_int_equal(named, ct_surface_kind_supports(j, o, NULL));
            }
        }
        const char *why;
        assert_false(ct_surface_kind_supports(k, "nonsense", &why));
    }
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "voxels"), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "cantor"));
}

static ct_surface *rods(const char *list, const char *Hstar, const char *E, const char *sigma_y)
{
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "rods", list, "test"), CT_OK);
    if (Hstar)
        assert_int_equal(ct_surface_set(s, "surface", "Hstar", Hstar, "test"), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", E, "test"), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", sigma_y, "test"), CT_OK);
    assert_int_equal(ct_surface_check(s, "test"), CT_OK);
    int st = ct_surface_prepare(s, NULL);
    if (st)
        fail_msg("%s", ct_error_message());
    return s;
}

/* first impacts at the speeds V: rows */
static void sweep(const ct_surface *s, const double *V, size_t n, ct_sweep_row *rows)
{
    ct_build_request req = {.V_star = V, .nvel = n, .impacts = 1, .depth_tolerance = 1e-12};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    ct_plan_info info;
    assert_int_equal(ct_surface_build(s, &req, &b, &info), CT_OK);
    ct_sweep_spec spec = {.V_star = V, .nvel = n, .impacts = 1, .opts = req.opts};
    assert_int_equal(ct_sweep(b, &spec, rows), CT_OK);
    ct_bundle_free(b);
}

static void one_rod_closed_forms(void **state)
{
    (void)state;
    /* a rod of area s = 2, length L = H* = 4, E = 1000, sigma_y = 1: eps_y = 1e-3, its top at
     * 0, so h0 = H* (every top is 0) and l0 = s */
    ct_surface *s = rods("0:2", "4", "1000", "1");
    ct_scales sc;
    ct_surface_scales(s, &sc);
    assert_true(sc.layer.h0 == 4.0 && sc.layer.l0 == 2.0 && sc.layer.Hstar == 4.0);
    assert_true(sc.force_unit == 2.0 && sc.energy_scale == 2.0 * 1000.0 * 4.0);
    const double E = 1000, A = 2, L = 4, ey = 1e-3, Wy = E * A * L * ey * ey / 2;
    double V[3];
    const double W[3] = {0.5 * Wy, 4 * Wy, 100 * Wy};
    for (int k = 0; k < 3; k++)
        V[k] = sqrt(W[k] / sc.energy_scale);
    ct_sweep_row r[3];
    sweep(s, V, 3, r);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(r[k].status, CT_OK);
        /* W <= Wy: elastic, u = L sqrt(2 W / (E A L)); else eps = (W / (E A L) + ey^2/2) / ey,
         * e = sqrt(Wy / W) */
        const double u = W[k] <= Wy ? L * sqrt(2 * W[k] / (E * A * L))
                                    : L * (W[k] / (E * A * L) + ey * ey / 2) / ey;
        const double e = W[k] <= Wy ? 1.0 : sqrt(Wy / W[k]);
        assert_true(fabs(r[k].r.u_max - u) <= 1e-14 * u);
        assert_true(fabs(r[k].r.e - e) <= 1e-14);
        assert_int_equal(r[k].r.elastic, W[k] <= Wy);
    }
    ct_surface_free(s);
}

static void lengths_set_the_crushed_limit(void **state)
{
    (void)state;
    /* rods 0:1:1 and 0.5:1:2: H* is the shallowest bottom, min(0 + 1, 0.5 + 2) = 1 */
    ct_surface *s = rods("0:1:1, 0.5:1:2", NULL, "100", "1");
    ct_scales sc;
    ct_surface_scales(s, &sc);
    assert_true(sc.layer.Hstar == 1.0 && sc.layer.h0 == 0.5 && sc.layer.l0 == 2.0);
    ct_bundle *b;
    ct_build_request req = {.V_star = (double[]){1e-3}, .nvel = 1, .impacts = 1};
    ct_impact_opts_default(&req.opts);
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    ct_rod_info info;
    assert_int_equal(ct_bundle_rod(b, 1, &info), CT_OK);
    assert_true(info.top == 0.5 && info.length == 2.0);
    /* loading to u = 1 does W(1) = rod 1 plastic from 0 to 1 plus rod 2 from 0.5 to 1: an
     * energy beyond it crushes rod 1 (strain 1): refused as outside the model */
    double W1 = ct_bundle_work(b, 0.0, 1.0);
    ct_impact_opts o;
    ct_impact_opts_default(&o);
    ct_impact_result res;
    assert_int_equal(ct_impact(b, 1.01 * W1, &o, &res), CT_ERANGE);
    ct_bundle_reset(b);
    assert_int_equal(ct_impact(b, 0.5 * W1, &o, &res), CT_OK);
    ct_bundle_free(b);
    ct_surface_free(s);
    /* lengths with a layer given: refused, H* is the rods' */
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "rods", "0:1:1", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "Hstar", "3", "--set"), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "t"), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "--set: surface.Hstar = 3: not with rods"));
    ct_surface_free(s);
}

/* With lengths, a rod whose top lies below another's bottom (0:1:1, 2:1:10: rod 2 starts at
 * 2, rod 1 crushes at H* = 1) is never reached within the model: the set is computed, and its
 * impacts are those of rod 1 alone (docs/model.md §3 in closed form); only the scales count
 * rod 2 (h0 = its top 2, l0 = both areas 2). */
static void deep_rod_never_reached(void **state)
{
    (void)state;
    ct_surface *s = rods("0:1:1, 2:1:10", NULL, "100", "1");
    ct_scales sc;
    ct_surface_scales(s, &sc);
    assert_true(sc.layer.Hstar == 1.0 && sc.layer.h0 == 2.0 && sc.layer.l0 == 2.0);
    /* rod 1: E = 100, A = 1, L = 1, eps_y = 0.01: Wy = E A L eps_y^2 / 2 = 5e-3 */
    const double E = 100, A = 1, L = 1, ey = 0.01, Wy = E * A * L * ey * ey / 2;
    const double W[3] = {0.5 * Wy, 4 * Wy, 100 * Wy};
    double V[3];
    for (int k = 0; k < 3; k++)
        V[k] = sqrt(W[k] / sc.energy_scale); /* l0 E h0 = 400 */
    ct_sweep_row r[3];
    sweep(s, V, 3, r);
    for (int k = 0; k < 3; k++) {
        assert_int_equal(r[k].status, CT_OK);
        const double u = W[k] <= Wy ? L * sqrt(2 * W[k] / (E * A * L))
                                    : L * (W[k] / (E * A * L) + ey * ey / 2) / ey;
        const double e = W[k] <= Wy ? 1.0 : sqrt(Wy / W[k]);
        if (!(fabs(r[k].r.u_max - u) <= 1e-14 * u && fabs(r[k].r.e - e) <= 1e-14))
            fail_msg("W = %g: u_max %.17g (want %.17g), e %.17g (want %.17g)", W[k], r[k].r.u_max,
                     u, r[k].r.e, e);
    }
    /* rod 1 crushes at u = 1 after W(1) = E A eps_y L (1 - eps_y / 2) = 0.995: beyond it the
     * impact is refused as outside the model, never computed on rod 2 */
    ct_bundle *b;
    ct_build_request req = {.V_star = V, .nvel = 1, .impacts = 1};
    ct_impact_opts_default(&req.opts);
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    ct_impact_opts o;
    ct_impact_opts_default(&o);
    ct_impact_result res;
    assert_int_equal(ct_impact(b, 0.995 * 1.001, &o, &res), CT_ERANGE);
    ct_bundle_reset(b);
    assert_int_equal(ct_impact(b, 0.995 * 0.999, &o, &res), CT_OK);
    assert_true(res.u_max < 1.0);
    ct_bundle_free(b);
    ct_surface_free(s);
    /* without lengths every rod reaches down to H*: a top at or below it is refused, naming
     * where H* came from */
    const char *bad[][3] = {{"0:1, 5:1", "Hstar", "4"}, {"0:1, 4:1", "Hstar", "4"}};
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
        assert_int_equal(ct_surface_set(s, "surface", "rods", bad[k][0], "s.ini:3"), CT_OK);
        assert_int_equal(ct_surface_set(s, "surface", bad[k][1], bad[k][2], ""), CT_OK);
        assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
        assert_int_equal(ct_surface_check(s, "s.ini"), CT_OK);
        assert_int_equal(ct_surface_prepare(s, NULL), CT_EINVAL);
        assert_non_null(strstr(ct_error_message(), "s.ini:3: surface.rods = "));
        assert_non_null(strstr(ct_error_message(), ": rod 2: top = "));
        assert_non_null(strstr(ct_error_message(), "must be < H* = 4 (surface.Hstar): a rod "
                                                   "without a length reaches down"));
        ct_surface_free(s);
    }
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "rods", "1:1, 5:1", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "2", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "h0", "2", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "s.ini"), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "top = 5: must be < H* = 4 (surface.H = 2 times "
                                               "h0 = 2)"));
    ct_surface_free(s);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* The rods of a file (unit mm, E = 100; H = 10 unless H is NULL: lengths in the file). */
static int file_rods_H(const char *path, const char *H, ct_scales *sc)
{
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    if (H)
        assert_int_equal(ct_surface_set(s, "surface", "H", H, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "unit", "mm", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "t"), CT_OK);
    int st = ct_surface_prepare(s, NULL);
    if (!st)
        ct_surface_scales(s, sc);
    ct_surface_free(s);
    return st;
}

static int file_rods(const char *path, ct_scales *sc)
{
    return file_rods_H(path, "10", sc);
}

static void rod_files(void **state)
{
    (void)state;
    char path[] = "/tmp/cantact_rods_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    ct_scales sc;
    /* a header naming the columns in its own order, comments, blank-separated numbers; mm */
    write_file(path, "# two rods\narea;top\n\n3 0.5\n1,0\n");
    assert_int_equal(file_rods(path, &sc), CT_OK);
    assert_true(sc.layer.h0 == 0.5e-3 && sc.layer.l0 == 4e-3 && sc.layer.Hstar == 10 * 0.5e-3);
    const char *bad[][2] = {
        {"0 1\n2\n", ":2: expected 2 numbers"},
        {"depth,area\n0,1\n", ":1: header field 1 is 'depth': neither a number nor a column"},
        /* a header names every column once: a repeated one would leave a field unread */
        {"top,area,area\n0,1,0.5\n0.5,1,0.7\n",
         ":1: header: column 'area' named twice (fields 2 and 3)"},
        {"top,top,area\n0,0,1\n", ":1: header: column 'top' named twice (fields 1 and 2)"},
        {"top,area,length,top\n0,1,2,0\n", "column 'top' named twice (fields 1 and 4)"},
        {"top,length\n0,1\n", ":1: header: no column 'area'"},
        {"length;area\n1,1\n", ":1: header: no column 'top'"},
        {"top area depth\n0 1 2\n", ":1: header field 3 is 'depth'"},
        {"0 1 2 3\n", ":1: more than 3 fields"},
        {"0 1\n0.5 1 2\n", ":2: more than 2 fields: expected 2 numbers"},
        {"0 -1\n", "area = -0.001: must be finite and > 0"},
        {"0 x\n", ":1:"},
        {"", "no rods"},
        {"-1 1\n", "top = -0.001: must be finite and >= 0"},
        /* no field is empty: none between two separators, none at either end of a row */
        {"0.5,,2\n", ":1: field 2 is empty"},
        {"0,1\n0.5,1,\n", ":2: field 3 is empty"},
        {",0,1\n", ":1: field 1 is empty"},
        {"0 ; ; 1\n", ":1: field 2 is empty"},
        {"0;1;\n", ":1: field 3 is empty"},
        {"top,,area\n0,1\n", ":1: header field 2 is empty"},
        {"top,area,\n0,1\n", ":1: header field 3 is empty"},
        /* a number that is no usable double is named, with its field and column */
        {"0,1\n1e-320,1\n", ":2: field 1 (top) = 1e-320: underflows double precision"},
        {"area top\n1 1e-320\n", ":2: field 2 (top) = 1e-320: underflows"},
        {"0 1e999\n", ":1: field 2 (area) = 1e999: overflows double precision"},
        {"0 nan\n", ":1: field 2 (area) = nan: not a finite number"},
        {"nan 1\n", ":1: field 1 (top) = nan: not a finite number"}, /* a row, not a header */
        {"-inf,1\n", ":1: field 1 (top) = -inf: not a finite number"},
        {"0 1\n0.5 1x\n", ":2: field 2 (area) = 1x: not a finite number"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        write_file(path, bad[k][0]);
        assert_int_equal(file_rods(path, &sc), CT_EINVAL);
        if (!strstr(ct_error_message(), bad[k][1]))
            fail_msg("'%s': message '%s' lacks '%s'", bad[k][0], ct_error_message(), bad[k][1]);
    }
    /* text as scenes and profiles: a UTF-8 byte-order mark dropped (before a header or a
     * row), line ends \n, \r\n or a lone \r, blanks around separators; all the same two rods
     * (tops 0.5 and 0 mm, areas 3 and 1 mm) */
    const char *same[] = {"\xEF\xBB\xBFtop,area\n0.5,3\n0,1\n",
                          "\xEF\xBB\xBF"
                          "0.5 3\n0 1\n",
                          "0.5 3\r0 1\r",
                          "0.5 3\r\n0 1\r\n",
                          "0.5 , 3\n\t0 ;1 \n",
                          "area\ttop\n3  0.5\n1 0\n"};
    for (size_t k = 0; k < sizeof same / sizeof same[0]; k++) {
        write_file(path, same[k]);
        if (file_rods(path, &sc))
            fail_msg("'%s': %s", same[k], ct_error_message());
        assert_true(sc.layer.h0 == 0.5e-3 && sc.layer.l0 == 4e-3);
    }
    /* a NUL byte (UTF-16 text, binary data) makes no rod file */
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fwrite("0 1\n0.5\0 3\n", 1, 11, f);
    fclose(f);
    assert_int_equal(file_rods(path, &sc), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), ":2: a NUL byte"));
    /* columns in the header's order, lengths among them: rod (top 0.5, area 1, length 2) and
     * (top 0, area 3, length 4) in mm; H* = min(top + length) = 2.5 mm, h0 = 0.5, l0 = 4 */
    write_file(path, "length,area,top\n2,1,0.5\n4,3,0\n");
    assert_int_equal(file_rods_H(path, NULL, &sc), CT_OK);
    assert_true(sc.layer.Hstar == 2.5e-3 && sc.layer.h0 == 0.5e-3 && sc.layer.l0 == 4e-3);
    unlink(path);
    assert_int_equal(file_rods("/nonexistent/rods.csv", &sc), CT_EIO);
}

/* surface.rods: the rule of every list (no empty field, a trailing separator included) and
 * of every number (one that underflows is named), the key and where it was set in the
 * message. */
static void inline_rods(void **state)
{
    (void)state;
    const char *bad[][2] = {
        {"0:1,,1:1,", "s.ini:3: surface.rods = 0:1,,1:1,: rod 2 (field 2 of the list) is empty"},
        {"0:1, 1:1,", "rod 3 (field 3 of the list) is empty"},
        {",0:1", "rod 1 (field 1 of the list) is empty"},
        {"0::1", "rod 1: field 2 of top:area[:length] is empty"},
        {"0:1:", "rod 1: field 3 of top:area[:length] is empty"},
        {":1", "rod 1: field 1 of top:area[:length] is empty"},
        {"0:1, 1e-320:1", "rod 2: field 1 (top) = 1e-320: underflows double precision"},
        {"0:1e999", "rod 1: field 2 (area) = 1e999: overflows"},
        {"0:1:1:1", "rod 1: more than 3 fields"},
        {"0:1, 1:1:1", "rod 2: has a length and rod 1 has none"},
        {"0", "rod 1: expected top:area or top:area:length"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        ct_surface *s;
        assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
        assert_int_equal(ct_surface_set(s, "surface", "rods", bad[k][0], "s.ini:3"), CT_OK);
        assert_int_equal(ct_surface_set(s, "surface", "Hstar", "2", ""), CT_OK);
        assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
        assert_int_equal(ct_surface_check(s, "s.ini"), CT_OK);
        assert_int_equal(ct_surface_prepare(s, NULL), CT_EINVAL);
        if (!strstr(ct_error_message(), bad[k][1]))
            fail_msg("'%s': message '%s' lacks '%s'", bad[k][0], ct_error_message(), bad[k][1]);
        ct_surface_free(s);
    }
    /* blanks around separators are not fields: tops 0.5 and 0, areas 3 and 1 */
    ct_surface *s = rods(" 0.5 : 3 ,0:1 ", "2", "100", "1");
    ct_scales sc;
    ct_surface_scales(s, &sc);
    assert_true(sc.layer.h0 == 0.5 && sc.layer.l0 == 4.0);
    ct_surface_free(s);
}

static void keys_of_other_kinds(void **state)
{
    (void)state;
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "fx", "1.5", "s.ini:3"), CT_EINVAL);
    assert_string_equal(ct_error_message(), "s.ini:3: surface.fx = 1.5: only for surface.type = "
                                            "cantor or random_cantor (not rods)");
    assert_int_equal(ct_surface_set(s, "surface", "colour", "red", "s.ini:4"), CT_EINVAL);
    assert_string_equal(ct_error_message(), "s.ini:4: surface.colour: unknown key");
    assert_int_equal(ct_surface_set(s, "surface", "Hstar", "-1", "--set"), CT_EINVAL);
    assert_string_equal(ct_error_message(), "--set: surface.Hstar = -1: must be > 0");
    /* neither file nor rods, or both */
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "t.ini"), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "t.ini: type = rods needs one of surface.file"));
    /* outputs only other kinds give: refused, before anything is read */
    assert_int_equal(ct_surface_set(s, "surface", "rods", "0:1", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "Hstar", "2", ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "t.ini"), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    assert_int_equal(ct_surface_ready(s, "compare"), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "compare: compare sets e beside the paper's laws"));
    assert_non_null(strstr(ct_error_message(), "surface.type = cantor or profile"));
    assert_int_equal(ct_surface_write_geometry(s, NULL, stdout), CT_EINVAL);
    ct_surface_free(s);
}

/* ---- footprints: every rod knows where it stands (docs/model.md §12) ---- */

static int by_lo(const void *a, const void *b)
{
    const double x = ((const double *)a)[0], y = ((const double *)b)[0];
    return (x > y) - (x < y);
}

/* The rods' intervals of a line surface tile [lo, hi] exactly: each interval as wide as the
 * rod's area (a line rod's area is its share of the x-axis), no gap, no overlap. Checks the
 * footprints against the areas, an independent statement of the same geometry. */
static void intervals_tile(const ct_bundle *b, double lo, double hi, double rel)
{
    const size_t n = ct_bundle_size(b);
    double *iv = malloc(2 * n * sizeof *iv);
    assert_non_null(iv);
    double total = 0.0;
    for (size_t k = 0; k < n; k++) {
        ct_rod_info r;
        assert_int_equal(ct_bundle_rod(b, k, &r), CT_OK);
        assert_int_equal(r.footprint.shape, CT_FOOTPRINT_INTERVAL);
        assert_true(isnan(r.footprint.y_lo) && isnan(r.footprint.y_hi));
        const double w = r.footprint.x_hi - r.footprint.x_lo;
        assert_true(fabs(w - r.area) <= rel * (hi - lo));
        assert_true(r.footprint.x_lo == r.x_left && r.footprint.x_hi == r.x_right);
        iv[2 * k] = r.footprint.x_lo;
        iv[2 * k + 1] = r.footprint.x_hi;
        total += r.area;
    }
    qsort(iv, n, 2 * sizeof *iv, by_lo);
    assert_true(fabs(iv[0] - lo) <= rel * (hi - lo));
    assert_true(fabs(iv[2 * n - 1] - hi) <= rel * (hi - lo));
    for (size_t k = 1; k < n; k++) /* each starts where the one before ends */
        assert_true(fabs(iv[2 * k] - iv[2 * k - 1]) <= rel * (hi - lo));
    assert_true(fabs(total - (hi - lo)) <= rel * (hi - lo));
    free(iv);
}

static void every_rod_knows_its_footprint(void **state)
{
    (void)state;
    /* the Cantor prefractal, one rod per piece: the middles of stages 0 .. N-1 and the tips of
     * stage N tile [0, l0]; a piece of stage i, index j lies where its binary digits put it
     * (children of width w / (2 fx) at both ends of their parent, so that the middle left is
     * w (1 - 1/fx) wide, docs/model.md §2) */
    const ct_params p = {
        .fx = 1.5, .fz = 1.3, .l0 = 2.0, .h0 = 1.0, .Hstar = 10.0, .E = 500.0, .sigma_y = 1.0};
    ct_bundle *b;
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, 6, INFINITY), CT_OK);
    intervals_tile(b, 0.0, p.l0, 1e-14);
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        const long i = r.stage;
        const size_t j = k - (((size_t)1 << i) - 1);
        double L = 0.0, w = p.l0;
        for (long s = i - 1; s >= 0; s--) {
            if ((j >> s) & 1u)
                L += w - w / (2.0 * p.fx);
            w /= 2.0 * p.fx;
        }
        const double c = w / (2.0 * p.fx);
        const double lo = i < 6 ? L + c : L, hi = i < 6 ? L + w - c : L + w;
        assert_true(fabs(r.footprint.x_lo - lo) <= 1e-14 && fabs(r.footprint.x_hi - hi) <= 1e-14);
    }
    ct_bundle_free(b);
    /* stage rods merge the pieces of a stage: no single place */
    assert_int_equal(ct_cantor_bundle(&b, &p, CT_REP_STAGES, 6, INFINITY), CT_OK);
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        assert_int_equal(r.footprint.shape, CT_FOOTPRINT_NONE);
        assert_true(isnan(r.footprint.x_lo) && isnan(r.footprint.x_hi));
    }
    ct_bundle_free(b);
    /* a random Cantor realisation: the same tiling, piece by piece */
    ct_random_cantor rc = {.params = p,
                           .dist = CT_RATIO_LOGNORMAL,
                           .fx_spread = 0.2,
                           .fz_spread = 0.1,
                           .depth = 8,
                           .seed = 7};
    assert_int_equal(ct_random_cantor_bundle(&b, &rc, 3, 1), CT_OK);
    intervals_tile(b, 0.0, p.l0, 1e-13);
    ct_bundle_free(b);
    /* a measured line with uneven spacing: sample j stands from halfway to its left neighbour
     * to halfway to its right one (an end sample as far out as in), the areas of §9 */
    const double x[6] = {0.0, 0.1, 0.35, 0.4, 0.8, 1.0}, z[6] = {1, 3, 2, 5, 4, 0.5};
    ct_profile *prof;
    assert_int_equal(ct_profile_from_line(&prof, 6, x, 0.0, z), CT_OK);
    assert_int_equal(ct_profile_bundle(&b, prof, 100.0, 1.0, 20.0), CT_OK);
    intervals_tile(b, -0.05, 1.1, 1e-15);
    for (size_t k = 0; k < ct_bundle_size(b); k++) { /* each holds its sample, by its top */
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        size_t j = 0;
        while (j < 6 && fabs((5.0 - z[j]) - r.top) > 1e-15)
            j++;
        assert_true(j < 6 && r.footprint.x_lo < x[j] && x[j] < r.footprint.x_hi);
    }
    ct_bundle_free(b);
    ct_profile_free(prof);
    /* an areal map: the pixel, one increment each way about its sample (sample (i, r) at
     * x = i dx, y = r dy), its area dx dy */
    double zg[12];
    for (int q = 0; q < 12; q++)
        zg[q] = (double)((q * 7) % 12);
    assert_int_equal(ct_profile_from_grid(&prof, 4, 3, 0.5, 0.25, zg), CT_OK);
    assert_int_equal(ct_profile_bundle(&b, prof, 100.0, 1.0, 20.0), CT_OK);
    assert_int_equal(ct_bundle_size(b), 12);
    for (size_t k = 0; k < 12; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        assert_int_equal(r.footprint.shape, CT_FOOTPRINT_RECTANGLE);
        size_t q = 0;
        while (q < 12 && fabs((11.0 - zg[q]) - r.top) > 1e-15)
            q++;
        assert_true(q < 12);
        const double xs = (double)(q % 4) * 0.5, ys = (double)(q / 4) * 0.25;
        assert_true(r.footprint.x_lo == xs - 0.25 && r.footprint.x_hi == xs + 0.25);
        assert_true(r.footprint.y_lo == ys - 0.125 && r.footprint.y_hi == ys + 0.125);
        assert_true(
            fabs((r.footprint.x_hi - r.footprint.x_lo) * (r.footprint.y_hi - r.footprint.y_lo) -
                 r.area) <= 1e-15);
    }
    ct_bundle_free(b);
    ct_profile_free(prof);
    /* rods given by their positions: points (a line: y NaN); without positions: none */
    const double top[3] = {0.0, 0.5, 0.25}, area[3] = {1.0, 2.0, 1.5}, px[3] = {-1.0, 0.0, 2.5},
                 py[3] = {3.0, 1.0, -2.0};
    for (int with = 0; with < 3; with++) {
        ct_surface *s;
        assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
        assert_int_equal(
            ct_surface_set_rods_at(s, 3, top, area, NULL, with ? px : NULL, with == 2 ? py : NULL),
            CT_OK);
        assert_int_equal(ct_surface_set(s, "surface", "Hstar", "10", ""), CT_OK);
        assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
        assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
        const double V = 1e-3;
        ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1};
        ct_impact_opts_default(&req.opts);
        assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
        for (size_t k = 0; k < 3; k++) {
            ct_rod_info r;
            ct_bundle_rod(b, k, &r);
            if (!with) {
                assert_int_equal(r.footprint.shape, CT_FOOTPRINT_NONE);
                continue;
            }
            assert_int_equal(r.footprint.shape, CT_FOOTPRINT_POINT);
            assert_true(r.footprint.x_lo == px[k] && r.footprint.x_hi == px[k]);
            if (with == 2)
                assert_true(r.footprint.y_lo == py[k] && r.footprint.y_hi == py[k]);
            else
                assert_true(isnan(r.footprint.y_lo) && isnan(r.footprint.y_hi));
        }
        ct_bundle_free(b);
        ct_surface_free(s);
    }
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set_rods_at(s, 3, top, area, NULL, NULL, py), CT_EINVAL);
    ct_surface_free(s);
    /* a rod file places its rods by columns x and y, in the unit of its tops (mm here) */
    char path[64];
    snprintf(path, sizeof path, "/tmp/ct_foot_%d.csv", (int)getpid());
    write_file(path, "y; x; top; area\n3; -1; 0; 1\n1; 0; 0.5; 2\n-2; 2.5; 0.25; 1.5\n");
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "unit", "mm", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    const double V = 1e-3;
    ct_build_request req = {.V_star = &V, .nvel = 1, .impacts = 1};
    ct_impact_opts_default(&req.opts);
    assert_int_equal(ct_surface_build(s, &req, &b, NULL), CT_OK);
    for (size_t k = 0; k < 3; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        assert_int_equal(r.footprint.shape, CT_FOOTPRINT_POINT);
        assert_true(fabs(r.footprint.x_lo - px[k] * 1e-3) <= 1e-18);
        assert_true(fabs(r.footprint.y_lo - py[k] * 1e-3) <= 1e-18);
        assert_true(fabs(r.top - top[k] * 1e-3) <= 1e-18);
        assert_true(fabs(r.area - area[k] * 1e-6) <= 1e-21); /* an area on a plane: mm^2 */
    }
    ct_scales scp;
    ct_surface_scales(s, &scp);
    assert_true(fabs(scp.layer.l0 - 4.5e-6) <= 1e-21);
    ct_bundle_free(b);
    /* l0 given for rods on a plane: an area too */
    assert_int_equal(ct_surface_set(s, "surface", "l0", "2", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    ct_surface_scales(s, &scp);
    assert_true(fabs(scp.layer.l0 - 2e-6) <= 1e-21);
    ct_surface_free(s);
    /* rods on a line keep the areas of a line model, lengths per unit depth: mm */
    write_file(path, "x; top; area\n-1; 0; 1\n0; 0.5; 2\n2.5; 0.25; 1.5\n");
    assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "unit", "mm", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "10", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "material", "E", "100", ""), CT_OK);
    assert_int_equal(ct_surface_prepare(s, NULL), CT_OK);
    ct_surface_scales(s, &scp);
    assert_true(fabs(scp.layer.l0 - 4.5e-3) <= 1e-18);
    ct_surface_free(s);
    /* y without x, and positions without a header, are refused naming why */
    write_file(path, "y,top,area\n1,0,1\n2,0.5,1\n");
    ct_scales sc;
    assert_int_equal(file_rods(path, &sc), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "a column 'y' and no 'x'"));
    write_file(path, "0,1,1,2\n0.5,1,1,3\n");
    assert_int_equal(file_rods(path, &sc), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "a header naming x and y places the rods"));
    unlink(path);
}

/* ---- the rods and profile kinds are scale-free ---- */

/* Sweep s (prepared) at the speeds V, the impacts in time too, body (NULL: flat); rows, or the
 * status of the build. */
static int sweep_timed(const ct_surface *s, const ct_body *body, const double *V, size_t n,
                       ct_sweep_row *rows)
{
    ct_build_request req = {.V_star = V, .nvel = n, .impacts = 1, .body = body};
    ct_impact_opts_default(&req.opts);
    ct_bundle *b;
    int st = ct_surface_build(s, &req, &b, NULL);
    if (st)
        return st;
    ct_sweep_spec spec = {.V_star = V, .nvel = n, .impacts = 1, .opts = req.opts, .dynamics = 1};
    st = ct_sweep(b, &spec, rows);
    ct_bundle_free(b);
    return st;
}

/* A rods surface from rods "top:area:length, ..." with each top and length times lam, each
 * area times mu, and E, sigma_y (times kap); CT_OK or the status of its preparation. */
static int scaled_rods(ct_surface **out, const double (*r)[3], size_t n, double lam, double mu,
                       double E, double kap)
{
    char list[1024] = "", v[64];
    for (size_t k = 0; k < n; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.17g:%.17g:%.17g",
                 k ? ", " : "", r[k][0] * lam, r[k][1] * mu, r[k][2] * lam);
    assert_int_equal(ct_surface_new(out, "rods"), CT_OK);
    assert_int_equal(ct_surface_set(*out, "surface", "rods", list, "t"), CT_OK);
    snprintf(v, sizeof v, "%.17g", E * kap);
    assert_int_equal(ct_surface_set(*out, "material", "E", v, "t"), CT_OK);
    snprintf(v, sizeof v, "%.17g", kap);
    assert_int_equal(ct_surface_set(*out, "material", "sigma_y", v, "t"), CT_OK);
    assert_int_equal(ct_surface_check(*out, "t"), CT_OK);
    return ct_surface_prepare(*out, NULL);
}

static const double scale_grid[] = {1e-300, 1e-160, 0x1p-70, 1.0, 1e20, 1e160, 1e290};
#define NSCALE (sizeof scale_grid / sizeof *scale_grid)

/* Rows (u_max in units of h0) against the reference rows (in units of h0_ref): e, u_max/h0,
 * V*_c, the contact time in tau and e_kinematic to 1e-12. */
static void rows_agree(const ct_sweep_row *r, double h0, const ct_sweep_row *ref, double h0_ref,
                       size_t n, const char *what)
{
    for (size_t k = 0; k < n; k++) {
        if (r[k].status)
            fail_msg("%s, V* %g: %s", what, r[k].V_star, r[k].message);
        const double got[] = {r[k].r.e, r[k].r.u_max / h0, r[k].r.V_star_crit, r[k].dyn.t_contact,
                              r[k].dyn.e_kinematic},
                     want[] = {ref[k].r.e, ref[k].r.u_max / h0_ref, ref[k].r.V_star_crit,
                               ref[k].dyn.t_contact, ref[k].dyn.e_kinematic};
        for (int q = 0; q < 5; q++)
            if (!(fabs(got[q] - want[q]) <= 1e-12 * fabs(want[q])))
                fail_msg("%s, V* %g: figure %d is %.17g, at unit scale %.17g", what, r[k].V_star, q,
                         got[q], want[q]);
    }
}

/* The h0 of a prepared surface as built (the unit of its rows' u_max). */
static double built_h0(const ct_surface *s)
{
    ct_scales sc;
    ct_surface_scales(s, &sc);
    return sc.layer.h0;
}

/* One rod of area s and length L, top 0 (h0 = H* = L, l0 = s), at E/sigma_y = 1000: V*^2 =
 * W / (s E L), its first yield at V*_y^2 = eps_y^2 / 2; above it e = V*_y / V* and u_max / h0
 * = (V*^2 + eps_y^2 / 2) / eps_y (docs/model.md §3). At any length, area and stress scale
 * (lengths 1e-300 .. 1e290, areas alike, E 1e-297 .. 1e293): rods 1e-160 long at E = 1e200
 * were refused as crushed, 1e20 long of area 1e-300 failed the u_max solve. */
static void one_rod_at_every_scale(void **state)
{
    (void)state;
    const double rod[1][3] = {{0.0, 1.0, 1.0}}, ey = 1e-3, Vy = ey / sqrt(2.0);
    const double V[2] = {2.0 * Vy, 10.0 * Vy};
    for (size_t a = 0; a < NSCALE; a++)
        for (size_t b = 0; b < NSCALE; b++)
            for (size_t c = 0; c < NSCALE; c += 2) {
                ct_surface *s;
                ct_sweep_row r[2];
                const double lam = scale_grid[a], mu = scale_grid[b], kap = scale_grid[c] * 1e3;
                int st = scaled_rods(&s, rod, 1, lam, mu, 1000.0, kap);
                if (!st)
                    st = sweep_timed(s, NULL, V, 2, r);
                if (st)
                    fail_msg("length %g, area %g, sigma_y %g: %s", lam, mu, kap,
                             ct_error_message());
                for (int k = 0; k < 2; k++) {
                    const double e = Vy / V[k], u = (V[k] * V[k] + ey * ey / 2.0) / ey;
                    const double u_h0 = r[k].r.u_max / built_h0(s);
                    if (r[k].status || !(fabs(r[k].r.e - e) <= 1e-12 * e) ||
                        !(fabs(u_h0 - u) <= 1e-12 * u))
                        fail_msg("length %g, area %g, sigma_y %g, V* %g: e %.17g (want %.17g), "
                                 "u_max/h0 %.17g (want %.17g): %s",
                                 lam, mu, kap, V[k], r[k].r.e, e, u_h0, u, r[k].message);
                }
                ct_surface_free(s);
            }
}

/* Three rods of their own lengths on the same grid of scales: every row as at unit scale (e,
 * u_max/h0, V*_c, the contact time in tau, e_kinematic: 1e-12); and rods whose own figures
 * leave the doubles (a stiffness E s / L of 1e310 sigma_y l0 / h0) refused naming it. */
static void rods_at_every_scale(void **state)
{
    (void)state;
    const double rods3[3][3] = {{0.0, 1.0, 1.0}, {0.25, 2.0, 1.5}, {0.5, 1.0, 2.0}};
    const double V[3] = {2e-3, 6e-3, 2e-2};
    ct_sweep_row ref[3], r[3];
    ct_surface *s;
    assert_int_equal(scaled_rods(&s, rods3, 3, 1.0, 1.0, 500.0, 1.0), CT_OK);
    assert_int_equal(sweep_timed(s, NULL, V, 3, ref), CT_OK);
    const double h0_ref = built_h0(s);
    ct_surface_free(s);
    for (size_t a = 0; a < NSCALE; a++)
        for (size_t b = 0; b < NSCALE; b++)
            for (size_t c = 0; c < NSCALE; c += 3) {
                const double lam = scale_grid[a], mu = scale_grid[b], kap = scale_grid[c];
                char what[96];
                snprintf(what, sizeof what, "length %g, area %g, sigma_y %g", lam, mu, kap);
                int st = scaled_rods(&s, rods3, 3, lam, mu, 500.0, kap);
                if (!st)
                    st = sweep_timed(s, NULL, V, 3, r);
                if (st)
                    fail_msg("%s: %s", what, ct_error_message());
                rows_agree(r, built_h0(s), ref, h0_ref, 3, what);
                ct_surface_free(s);
            }
    const double stiff[2][3] = {{0.0, 1.0, 1e-300}, {1.0, 1.0, 1.0}};
    assert_int_equal(scaled_rods(&s, stiff, 2, 1.0, 1.0, 1e10, 1.0), CT_EINVAL);
    assert_non_null(strstr(ct_error_message(), "rod 1: top 0 h0, length 1e-300 h0, area 0.5 l0 at "
                                               "E/sigma_y = 1e+10: its stiffness E s / L = "
                                               "5e+309 sigma_y l0 / h0"));
    ct_surface_free(s);
}

/* Rods on a plane (x and y) under a sphere: lengths and positions times lam, areas times lam^2
 * (the rods' own unit), each row as at unit scale. Their positions are built in the unit of
 * the square root of l0's, which a curved body reads (its gaps at the rods were those of
 * another surface when it took l0's). */
static void rods_on_a_plane_at_every_scale(void **state)
{
    (void)state;
    enum { M = 5 };
    double top[M * M], area[M * M], x[M * M], y[M * M], len[M * M];
    const double V[2] = {1e-3, 4e-3};
    ct_sweep_row ref[2], r[2];
    double h0_ref = NAN;
    const double lams[] = {1.0, 1e-100, 1e150};
    for (size_t q = 0; q < sizeof lams / sizeof *lams; q++) {
        const double lam = lams[q];
        for (int i = 0; i < M * M; i++) {
            x[i] = (i % M - 2) * 0.1 * lam;
            y[i] = (i / M - 2) * 0.1 * lam;
            top[i] = (i % 3) * 0.01 * lam;
            area[i] = 0.01 * lam * lam;
            len[i] = lam;
        }
        ct_surface *s;
        assert_int_equal(ct_surface_new(&s, "rods"), CT_OK);
        assert_int_equal(ct_surface_set_rods_at(s, M * M, top, area, len, x, y), CT_OK);
        assert_int_equal(ct_surface_set(s, "material", "E", "500", ""), CT_OK);
        assert_int_equal(ct_surface_check(s, "t"), CT_OK);
        if (ct_surface_prepare(s, NULL))
            fail_msg("lam %g: %s", lam, ct_error_message());
        ct_body sphere;
        ct_body_defaults(&sphere);
        sphere.shape = 2;
        sphere.radius = 2.0 * lam;
        assert_string_equal(ct_body_name(2), "sphere");
        if (sweep_timed(s, &sphere, V, 2, q ? r : ref))
            fail_msg("lam %g: %s", lam, ct_error_message());
        if (q) {
            char what[64];
            snprintf(what, sizeof what, "rods on a plane, lengths %g", lam);
            rows_agree(r, built_h0(s), ref, h0_ref, 2, what);
        } else {
            h0_ref = built_h0(s);
        }
        ct_surface_free(s);
    }
}

/* A profile surface from the heights z (201, unit spacing) with heights times lz, positions
 * times lx (in metres) and E = 500 kap, sigma_y = kap, H = 3, prepared. */
static ct_surface *scaled_profile(const char *path, const double *z, double lz, double lx,
                                  double kap)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    for (int j = 0; j < 201; j++)
        fprintf(f, "%.17g %.17g\n", j * lx, z[j] * lz);
    fclose(f);
    ct_surface *s;
    char v[64];
    assert_int_equal(ct_surface_new(&s, "profile"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "file", path, ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "unit", "m", ""), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "H", "3", ""), CT_OK);
    snprintf(v, sizeof v, "%.17g", 500.0 * kap);
    assert_int_equal(ct_surface_set(s, "material", "E", v, ""), CT_OK);
    snprintf(v, sizeof v, "%.17g", kap);
    assert_int_equal(ct_surface_set(s, "material", "sigma_y", v, ""), CT_OK);
    assert_int_equal(ct_surface_check(s, "t"), CT_OK);
    if (ct_surface_prepare(s, NULL))
        fail_msg("profile: heights %g, x %g, sigma_y %g: %s", lz, lx, kap, ct_error_message());
    return s;
}

/* A line profile (201 heights of a random walk) with its heights, its positions and E,
 * sigma_y each scaled (the file's numbers, in metres): every row as at unit scale. */
static void profile_at_every_scale(void **state)
{
    (void)state;
    char path[] = "/tmp/cantact_prof_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    double z[201];
    uint64_t g = 12345;
    z[0] = 0.0;
    for (int j = 1; j < 201; j++) {
        g = g * 6364136223846793005u + 1442695040888963407u;
        z[j] = z[j - 1] + ((double)(g >> 11) / 9007199254740992.0 - 0.5);
    }
    const double V[3] = {1e-3, 5e-3, 2e-2};
    ct_sweep_row ref[3], r[3];
    ct_surface *s = scaled_profile(path, z, 1.0, 1.0, 1.0);
    if (sweep_timed(s, NULL, V, 3, ref))
        fail_msg("profile at unit scale: %s", ct_error_message());
    const double h0_ref = built_h0(s);
    ct_surface_free(s);
    for (size_t a = 0; a < NSCALE; a++)
        for (size_t b = 0; b < NSCALE; b += 2)
            for (size_t c = 0; c < NSCALE; c += 3) {
                const double lz = scale_grid[a], lx = scale_grid[b], kap = scale_grid[c];
                char what[96];
                snprintf(what, sizeof what, "profile: heights %g, x %g, sigma_y %g", lz, lx, kap);
                s = scaled_profile(path, z, lz, lx, kap);
                if (sweep_timed(s, NULL, V, 3, r))
                    fail_msg("%s: %s", what, ct_error_message());
                rows_agree(r, built_h0(s), ref, h0_ref, 3, what);
                ct_surface_free(s);
            }
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(registry_complete),
        cmocka_unit_test(one_rod_closed_forms),
        cmocka_unit_test(lengths_set_the_crushed_limit),
        cmocka_unit_test(deep_rod_never_reached),
        cmocka_unit_test(rod_files),
        cmocka_unit_test(inline_rods),
        cmocka_unit_test(keys_of_other_kinds),
        cmocka_unit_test(every_rod_knows_its_footprint),
        cmocka_unit_test(one_rod_at_every_scale),
        cmocka_unit_test(rods_at_every_scale),
        cmocka_unit_test(rods_on_a_plane_at_every_scale),
        cmocka_unit_test(profile_at_every_scale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
