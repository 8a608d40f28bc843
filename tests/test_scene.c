/* Scene files: every class of bad input gets CT_EINVAL (or CT_EIO) with file:line and the
 * key in the message; defaults and --set overrides. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cantact.h"
#include "scene.h"

static const char *good = "[surface]\n"
                          "fx = 1.5\n"
                          "fz = 1.3\n"
                          "H = 10\n"
                          "[material]\n"
                          "E = 500\n"
                          "[impact]\n"
                          "V_star = 1e-3\n";

static void expect_error(const char *text, const char *const *sets, size_t nsets,
                         const char *needle1, const char *needle2)
{
    ct_scene sc;
    int st = ct_scene_parse(&sc, "s.ini", text, sets, nsets);
    if (st == CT_OK) { /* what only the prepared surface can tell (V* and its energy) */
        st = ct_scene_prepare(&sc);
        ct_scene_free(&sc);
    }
    if (st != CT_EINVAL)
        fail_msg("expected CT_EINVAL, got %d for:\n%s", st, text);
    const char *msg = ct_scene_message();
    if (!strstr(msg, needle1) || (needle2 && !strstr(msg, needle2)))
        fail_msg("message '%s' lacks '%s' / '%s'", msg, needle1, needle2 ? needle2 : "");
}

static void with_line(char *buf, size_t n, const char *extra_surface_line)
{
    snprintf(buf, n,
             "[surface]\nfx = 1.5\nfz = 1.3\nH = 10\n%s\n[material]\nE = 500\n[impact]\n"
             "V_star = 1e-3\n",
             extra_surface_line);
}

/* A key's value as the surface parsed it. */
static double num(const ct_scene *sc, const char *section, const char *name)
{
    double v = NAN;
    if (ct_surface_value(sc->surface, section, name, &v))
        fail_msg("%s.%s: %s", section, name, ct_error_message());
    return v;
}

static void defaults_and_values(void **state)
{
    (void)state;
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, NULL, 0), CT_OK);
    assert_true(num(&sc, "surface", "fx") == 1.5 && num(&sc, "surface", "fz") == 1.3);
    assert_true(num(&sc, "surface", "h0") == 1.0 && num(&sc, "surface", "l0") == 1.0);
    assert_true(num(&sc, "material", "sigma_y") == 1.0);
    assert_true(num(&sc, "surface", "H") == 10.0 && num(&sc, "material", "E") == 500.0);
    assert_true(num(&sc, "surface", "depth") == CT_DEPTH_AUTO);
    assert_true(num(&sc, "surface", "representation") == CT_REP_STAGES);
    assert_string_equal(ct_surface_kind(sc.surface), "cantor");
    assert_int_equal(sc.nvel, 1);
    assert_true(sc.V_star[0] == 1e-3);
    assert_int_equal(sc.impacts, 1);
    assert_int_equal(sc.opts.rule, CT_QUAD_BREAKPOINTS);
    assert_string_equal(sc.output, "-");
    assert_int_equal(sc.what, CT_OUT_E);
    ct_scene_free(&sc);
}

static void velocity_lists(void **state)
{
    (void)state;
    ct_scene sc;
    const char *sets1[] = {"impact.V_star = 0.1, 0.3,0.2"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets1, 1), CT_OK);
    assert_int_equal(sc.nvel, 3);
    assert_true(sc.V_star[0] == 0.1 && sc.V_star[1] == 0.3 && sc.V_star[2] == 0.2);
    ct_scene_free(&sc);
    const char *sets2[] = {"impact.V_star=1e-4:1e-1:4:log"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets2, 1), CT_OK);
    assert_int_equal(sc.nvel, 4);
    assert_true(sc.V_star[0] == 1e-4 && sc.V_star[3] == 1e-1);
    assert_true(fabs(sc.V_star[1] - 1e-3) < 1e-17 && fabs(sc.V_star[2] - 1e-2) < 1e-16);
    ct_scene_free(&sc);
    const char *sets3[] = {"impact.V_star=1:2:5"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets3, 1), CT_OK);
    assert_true(sc.V_star[1] == 1.25 && sc.V_star[4] == 2.0);
    ct_scene_free(&sc);
    /* mass + velocity: V* = sqrt(m v^2 / (2 l0 E h0)) */
    const char *text = "[surface]\nfx=1.5\nfz=1.3\nH=10\nh0=2e-6\nl0=1e-3\n[material]\n"
                       "E=2e11\nsigma_y=4e8\n[impact]\nmass=0.5\nvelocity=0.2\n";
    assert_int_equal(ct_scene_parse(&sc, "s.ini", text, NULL, 0), CT_OK);
    assert_int_equal(ct_scene_prepare(&sc), CT_OK); /* the surface's l0, E, h0 turn v into V* */
    assert_true(fabs(sc.V_star[0] - sqrt(0.5 * 0.04 / (2 * 1e-3 * 2e11 * 2e-6))) <
                1e-15 * sc.V_star[0]);
    assert_true(sc.scales.physical.Hstar == 10 * 2e-6);
    assert_true(sc.scales.layer.Hstar == 10.0 && sc.scales.layer.h0 == 1.0);
    ct_scene_free(&sc);
}

static void set_overrides(void **state)
{
    (void)state;
    ct_scene sc;
    const char *sets[] = {"surface.fz=1.7", "material.sigma_y = 2", "output.what = e, curve",
                          "surface.fz=1.6"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets, 4), CT_OK);
    assert_true(num(&sc, "surface", "fz") == 1.6 && num(&sc, "material", "sigma_y") == 2.0);
    assert_int_equal(sc.what, CT_OUT_E | CT_OUT_CURVE);
    ct_scene_free(&sc);
    const char *bad1[] = {"surfacefz=1.7"};
    expect_error(good, bad1, 1, "--set", "section.key=value");
    const char *bad2[] = {"surface.fz=7"};
    expect_error(good, bad2, 1, "--set: surface.fz = 7", "1 < fz < 2");
    const char *bad3[] = {"surface.colour=red"};
    expect_error(good, bad3, 1, "--set: surface.colour", "unknown key");
}

static void unknown_section_and_key(void **state)
{
    (void)state;
    char buf[512];
    expect_error("[surface]\nfx=1.5\n[weather]\nrain=1\n", NULL, 0, "s.ini:3: [weather]",
                 "unknown section");
    with_line(buf, sizeof buf, "colour = red");
    expect_error(buf, NULL, 0, "s.ini:5: surface.colour", "unknown key");
    expect_error("fx = 1.5\n", NULL, 0, "s.ini:1", "outside any section");
}

/* "Did you mean": the known name nearest to a slip (one edit in a name of up to 3 characters
 * after its last dot, two beyond; a swap of neighbours is one edit), none when it is farther. */
static void nearest_names(void **state)
{
    (void)state;
    const char *names[] = {"surface.fx",
                           "surface.fz",
                           "surface.H",
                           "impact.V_star",
                           "solver.depth_tolerance",
                           "ensemble.realisations",
                           "surface"};
    const size_t n = sizeof names / sizeof names[0];
    struct {
        const char *given;
        size_t want; /* n: none */
    } cases[] = {
        {"surface.fzz", 1},            /* an extra letter */
        {"surface.f", 0},              /* a letter lost: fx and fz tie, the first */
        {"surface.zf", 1},             /* two letters swapped: one edit */
        {"surface.h", 2},              /* the case of a letter */
        {"surface.xy", n},             /* two edits in a short name: no slip */
        {"surface.fx", 1},             /* the name itself passed over: the next nearest */
        {"impact.V_str", 3},           /* a letter lost */
        {"impact.v_sta", 3},           /* two edits in a longer name */
        {"impact.velocity", n},        /* far from everything */
        {"solver.depth_tolerence", 4}, /* a vowel */
        {"ensemble.realizations", 5},  /* the spelling */
        {"surfce", 6},                 /* a section */
        {"srfce", 6},                  /* two edits in a name of over 3 characters */
        {"srfc", n},                   /* three */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const size_t got = ct_nearest_name(cases[k].given, names, n);
        if (got != cases[k].want)
            fail_msg("%s: got %s, want %s", cases[k].given, got < n ? names[got] : "none",
                     cases[k].want < n ? names[cases[k].want] : "none");
    }
    assert_int_equal(ct_nearest_name("x", NULL, 3), 3);
}

static void did_you_mean(void **state)
{
    (void)state;
    char buf[512];
    with_line(buf, sizeof buf, "fzz = 1.3");
    expect_error(buf, NULL, 0, "s.ini:5: surface.fzz: unknown key (did you mean surface.fz?)",
                 NULL);
    expect_error("[surfce]\nfx=1.5\n", NULL, 0,
                 "s.ini:1: [surfce]: unknown section (did you mean [surface]?) (known: ", NULL);
    const char *sets[] = {"impakt.V_star=1"};
    expect_error(good, sets, 1, "--set: [impakt]: unknown section (did you mean [impact]?)", NULL);
    const char *sets2[] = {"output.wat=e"};
    expect_error(good, sets2, 1, "--set: output.wat: unknown key (did you mean output.what?)",
                 NULL);
    const char *sets3[] = {"surface.colour=red"};
    expect_error(good, sets3, 1, "--set: surface.colour: unknown key", NULL);
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets3, 1), CT_EINVAL);
    assert_null(strstr(ct_scene_message(), "did you mean"));
    /* the library's own, for a key of another kind (Python's Surface takes this path) */
    ct_surface *s;
    assert_int_equal(ct_surface_new(&s, "cantor"), CT_OK);
    assert_int_equal(ct_surface_set(s, "surface", "uint", "mm", "here"), CT_EINVAL);
    assert_string_equal(ct_error_message(), "here: surface.uint: unknown key (did you mean "
                                            "surface.unit? only for surface.type = profile or "
                                            "rods)");
    assert_int_equal(ct_surface_set(s, "surface", "fzz", "1.3", ""), CT_EINVAL);
    assert_string_equal(ct_error_message(), "surface.fzz: unknown key (did you mean surface.fz?)");
    ct_surface_free(s);
}

/* One rule for a reversed range, a run's speeds and a table's: refused, the range turned round
 * in the message (a run's speeds in another order are a list). */
static void reversed_ranges(void **state)
{
    (void)state;
    const char *a[] = {"impact.V_star=1e-2:1e-5:31:log"};
    expect_error(good, a, 1,
                 "--set: impact.V_star = 1e-2:1e-5:31:log: expected from:to:count[:log] with 0 < "
                 "from < to: a range runs upwards (1e-5:1e-2:31:log; speeds in another order as "
                 "a list a, b, c)",
                 NULL);
    const char *b[] = {"table.V_star=1e-2:1e-5"};
    expect_error(good, b, 1,
                 "--set: table.V_star = 1e-2:1e-5: expected from:to with 0 < from < to: a range "
                 "runs upwards (1e-5:1e-2)",
                 NULL);
    const char *c[] = {"impact.V_star=1e-2:1e-2:2"};
    expect_error(good, c, 1, "with 0 < from < to (or one speed: count 1)", NULL);
    ct_scene sc; /* one speed, from = to; and a list in any order */
    const char *d[] = {"impact.V_star=1e-2:1e-2:1"}, *e[] = {"impact.V_star=1e-2, 1e-5"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, d, 1), CT_OK);
    assert_true(sc.nvel == 1 && sc.V_star[0] == 1e-2);
    ct_scene_free(&sc);
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, e, 1), CT_OK);
    assert_true(sc.nvel == 2 && sc.V_star[0] == 1e-2 && sc.V_star[1] == 1e-5);
    ct_scene_free(&sc);
}

/* An override with an empty value unsets the key (its default applies); unsetting what the scene
 * does not give changes nothing; an unknown key is refused as when set. */
static void empty_override_unsets(void **state)
{
    (void)state;
    const char *by_mass = "[surface]\nfx = 1.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n"
                          "[impact]\nmass = 1e-3\nvelocity = 0.5\n";
    const char *sets[] = {"impact.mass=", "impact.velocity =", "impact.V_star=2e-3",
                          "solver.nodes="};
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", by_mass, sets, 4), CT_OK);
    assert_true(sc.nvel == 1 && sc.V_star[0] == 2e-3 && sc.mass == 0.0 &&
                !sc.speeds_are_velocities);
    ct_scene_free(&sc);
    const char *h[] = {"surface.H="};
    expect_error(good, h, 1, "surface.H: required key missing", NULL);
    const char *u[] = {"surface.Hh="};
    expect_error(good, u, 1, "--set: surface.Hh: unknown key (did you mean surface.H?)", NULL);
}

static void duplicate_key(void **state)
{
    (void)state;
    char buf[512];
    with_line(buf, sizeof buf, "fx = 1.6");
    expect_error(buf, NULL, 0, "s.ini:5: surface.fx", "duplicate key (first set at s.ini:2)");
}

static void missing_required(void **state)
{
    (void)state;
    expect_error("[surface]\nfx=1.5\nfz=1.3\n[material]\nE=500\n[impact]\nV_star=1\n", NULL, 0,
                 "surface.H", "required key missing");
    expect_error("[surface]\nfx=1.5\nfz=1.3\nH=10\n[material]\nE=500\n", NULL, 0, "[impact]",
                 "V_star");
}

static void unparsable_numbers(void **state)
{
    (void)state;
    const char *lines[] = {"h0 = 1.5x", "h0 = ",      "h0 = nan", "h0 = inf",
                           "h0 = -inf", "h0 = 1e999", "h0 = 0x",  "h0 = 1 2"};
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++) {
        char buf[512];
        with_line(buf, sizeof buf, lines[k]);
        expect_error(buf, NULL, 0, "s.ini:5: surface.h0",
                     strstr(lines[k], "1e999") ? "overflows" : "not a finite number");
    }
    char buf[512];
    with_line(buf, sizeof buf, "depth = 12.5");
    expect_error(buf, NULL, 0, "s.ini:5: surface.depth", "integer");
}

static void out_of_range(void **state)
{
    (void)state;
    struct {
        const char *line, *key, *why;
    } cases[] = {
        {"h0 = -1", "surface.h0", "> 0"},
        {"l0 = 0", "surface.l0", "> 0"},
        {"depth = -3", "surface.depth", "depth"},
        {"representation = voxels", "surface.representation", "stages or segments"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char buf[512];
        with_line(buf, sizeof buf, cases[k].line);
        expect_error(buf, NULL, 0, cases[k].key, cases[k].why);
    }
    const char *sets_fz[] = {"surface.fz=2.5"};
    expect_error(good, sets_fz, 1, "surface.fz = 2.5", "1 < fz < 2");
    const char *sets_fx[] = {"surface.fx=1"};
    expect_error(good, sets_fx, 1, "surface.fx = 1", "fx > 1");
    const char *sets_H[] = {"surface.H=0.5"};
    expect_error(good, sets_H, 1, "surface.H", "H > 1");
    const char *sets_E[] = {"material.E=0.5"};
    expect_error(good, sets_E, 1, "material.E = 0.5", "sigma_y");
    const char *sets_V[] = {"impact.V_star=0.1,-2"};
    expect_error(good, sets_V, 1, "impact.V_star", "> 0");
    const char *sets_r[] = {"impact.V_star=1:2:0"};
    expect_error(good, sets_r, 1, "impact.V_star", "count");
    const char *sets_i[] = {"impact.impacts=0"};
    expect_error(good, sets_i, 1, "impact.impacts", "1 <= impacts");
    const char *sets_q[] = {"solver.quadrature=magic"};
    expect_error(good, sets_q, 1, "solver.quadrature", "breakpoints");
    const char *sets_w[] = {"output.what=e,pictures"};
    expect_error(good, sets_w, 1, "output.what", "e, time, curve");
    const char *sets_s[] = {"surface.representation=segments"};
    expect_error(good, sets_s, 1, "segments", "integer surface.depth");
    const char *sets_both[] = {"impact.mass=1"};
    expect_error(good, sets_both, 1, "impact.V_star", "not both");
}

static void malformed_line(void **state)
{
    (void)state;
    expect_error("[surface]\nfx = 1.5\nthis line has no equals sign\n", NULL, 0, "s.ini:3",
                 "malformed");
    expect_error("[surface\nfx = 1.5\n", NULL, 0, "s.ini:1", "malformed");
}

static void files_missing_and_binary(void **state)
{
    (void)state;
    ct_scene sc;
    assert_int_equal(ct_scene_load(&sc, "/nonexistent/dir/x.ini", NULL, 0), CT_EIO);
    assert_non_null(strstr(ct_scene_message(), "/nonexistent/dir/x.ini: cannot open"));
    char path[] = "/tmp/ct_scene_binXXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    const unsigned char junk[] = {'[', 's', ']', '\n', 0x00, 0xff, 0x13, '\n'};
    fwrite(junk, 1, sizeof junk, f);
    fclose(f);
    assert_int_equal(ct_scene_load(&sc, path, NULL, 0), CT_EINVAL);
    assert_non_null(strstr(ct_scene_message(), "binary"));
    remove(path);
    /* the shipped default scene loads */
    assert_int_equal(ct_scene_load(&sc, CT_SOURCE_DIR "/scripts/scenes/default.ini", NULL, 0),
                     CT_OK);
    ct_scene_free(&sc);
}

/* Lines longer than inih's 200-byte buffer are read whole: a long comment whose tail looks
 * like a key sets nothing, a long list keeps every value, a long key line keeps its value. */
static void long_lines_read_whole(void **state)
{
    (void)state;
    char text[8192], comment[400], list[4096];
    memset(comment, 'x', sizeof comment);
    memcpy(comment, "; ", 2);
    snprintf(comment + 300, 100, " depth = 3 output.file = pwned.csv");
    size_t n = 0;
    n += (size_t)snprintf(list + n, sizeof list - n, "V_star = ");
    for (int k = 1; k <= 60; k++)
        n += (size_t)snprintf(list + n, sizeof list - n, "%s%.6e", k > 1 ? ", " : "", 1e-4 * k);
    size_t bare = n; /* the list without its comment */
    snprintf(list + n, sizeof list - n, "   ; a comment after the list");
    snprintf(text, sizeof text,
             "[surface]\n%s\nfx = 1.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n[impact]\n%s\n",
             comment, list);
    ct_scene sc;
    if (ct_scene_parse(&sc, "s.ini", text, NULL, 0) != CT_OK)
        fail_msg("%s", ct_scene_message());
    assert_true(num(&sc, "surface", "depth") == CT_DEPTH_AUTO); /* the comment's tail set nothing */
    assert_string_equal(sc.output, "-");
    assert_int_equal(sc.nvel, 60);
    for (int k = 1; k <= 60; k++)
        assert_true(fabs(sc.V_star[k - 1] - 1e-4 * k) <= 1e-6 * 1e-4 * k);
    ct_scene_free(&sc);
    /* a bad value on a long line is reported with that line, its value shortened */
    list[bare] = '\0';
    snprintf(text, sizeof text,
             "[surface]\nfx = 1.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n[impact]\n%s, -1\n",
             list);
    expect_error(text, NULL, 0, "s.ini:8: impact.V_star = ", "value 61: must be > 0");
    assert_true(strlen(ct_scene_message()) < 300);
}

/* Section headers are checked whole; empty unknown sections are errors too. */
static void section_headers_checked(void **state)
{
    (void)state;
    char buf[512];
    with_line(buf, sizeof buf, "[surface]junk");
    expect_error(buf, NULL, 0, "s.ini:5:", "text after the section header");
    with_line(buf, sizeof buf, "[surface]]");
    expect_error(buf, NULL, 0, "s.ini:5:", "text after the section header");
    with_line(buf, sizeof buf, "[nonsense]");
    expect_error(buf, NULL, 0, "s.ini:5: [nonsense]: unknown section", NULL);
    with_line(buf, sizeof buf, "[]");
    expect_error(buf, NULL, 0, "s.ini:5:", "not a section name");
    with_line(buf, sizeof buf, "[surface] ; a comment is fine");
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", buf, NULL, 0), CT_OK);
    ct_scene_free(&sc);
}

/* List forms: every field present, nothing after log. */
static void list_fields_checked(void **state)
{
    (void)state;
    const char *bad_lists[] = {
        "1e-3::1e-2:3",     "1e-3:1e-2::log",   ":1e-2:3",    "1e-3:1e-2:3:log x",
        "1e-3:1e-2:3:logx", "1e-3:1e-2:3:log:", "1e-3,,1e-2", "1e-3,"};
    for (size_t k = 0; k < sizeof bad_lists / sizeof *bad_lists; k++) {
        char set[128];
        snprintf(set, sizeof set, "impact.V_star=%s", bad_lists[k]);
        const char *sets[] = {set};
        expect_error(good, sets, 1, "impact.V_star", NULL);
    }
    const char *sets[] = {"impact.V_star= 1e-3 : 1e-2 : 3 : log "};
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, sets, 1), CT_OK);
    assert_int_equal(sc.nvel, 3);
    assert_true(fabs(sc.V_star[1] - sqrt(1e-5)) < 1e-15);
    ct_scene_free(&sc);
    /* one rule for every list: an empty field (a separator at either end included) is refused,
     * naming the key and the field */
    const char *empty[][2] = {
        {"impact.V_star=1e-3,,1e-2", "impact.V_star = 1e-3,,1e-2: field 2 of the list is empty"},
        {"impact.V_star=1e-3,", "field 2 of the list is empty"},
        {"impact.V_star=,1e-3", "field 1 of the list is empty"},
        {"impact.V_star=1e-3::1e-2:3", "field 2 of from:to:count[:log] is empty"},
        {"impact.V_star=1e-3:1e-2:3:log:", "field 5 of from:to:count[:log] is empty"},
        {"output.what=e,,time", "output.what = e,,time: field 2 of the list is empty"},
        {"output.what=e,", "output.what = e,: field 2 of the list is empty"},
        {"output.what=,e", "field 1 of the list is empty"},
        {"output.what=e , ,time", "field 2 of the list is empty"},
        {"table.V_star=1e-3:", "table.V_star = 1e-3:: field 2 of from:to is empty"},
        {"table.V_star=:1e-3", "field 1 of from:to is empty"},
    };
    for (size_t k = 0; k < sizeof empty / sizeof *empty; k++) {
        const char *set[] = {empty[k][0]};
        expect_error(good, set, 1, "--set: ", empty[k][1]);
    }
    expect_error("[surface]\ntype = rods\nrods = 0:1,,1:1,\nHstar = 2\n[material]\nE = 100\n"
                 "[impact]\nV_star = 1e-3\n",
                 NULL, 0, "s.ini:3: surface.rods = 0:1,,1:1,: rod 2 (field 2 of the list) is empty",
                 NULL);
    expect_error("[surface]\ntype = rods\nrods = 0:1, 1e-320:1\nHstar = 2\n[material]\n"
                 "E = 100\n[impact]\nV_star = 1e-3\n",
                 NULL, 0, "s.ini:3: surface.rods = 0:1, 1e-320:1: rod 2: field 1 (top) = 1e-320",
                 "underflows");
    /* words separated by commas or blanks */
    const char *words[] = {"output.what = e  time,curve"};
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, words, 1), CT_OK);
    assert_int_equal(sc.what, CT_OUT_E | CT_OUT_TIME | CT_OUT_CURVE);
    ct_scene_free(&sc);
}

/* Messages that say what happened: an indented key is a key (not a continuation of the
 * previous value), a BOM file counts lines from 1, CR-only line ends are line ends, a
 * denormal underflows, an impact energy that underflows names its key and line. */
static void messages_say_what_happened(void **state)
{
    (void)state;
    char buf[512];
    ct_scene sc;
    with_line(buf, sizeof buf, "    depth = 7");
    assert_int_equal(ct_scene_parse(&sc, "s.ini", buf, NULL, 0), CT_OK);
    assert_true(num(&sc, "surface", "depth") == 7);
    ct_scene_free(&sc);
    expect_error("\xEF\xBB\xBF[surface]\nfx = 0.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n"
                 "[impact]\nV_star = 1e-3\n",
                 NULL, 0, "s.ini:2: surface.fx = 0.5", NULL);
    assert_int_equal(ct_scene_parse(&sc, "s.ini",
                                    "\xEF\xBB\xBF[surface]\rfx = 1.5\rfz = 1.3\rH = 10\r"
                                    "[material]\rE = 500\r[impact]\rV_star = 1e-3\r",
                                    NULL, 0),
                     CT_OK);
    assert_true(num(&sc, "surface", "fz") == 1.3 && sc.nvel == 1);
    ct_scene_free(&sc);
    expect_error("[surface]\rfx = 1.5\rfz = 2.5\rH = 10\r[material]\rE = 500\r[impact]\r"
                 "V_star = 1e-3\r",
                 NULL, 0, "s.ini:3: surface.fz = 2.5", NULL);
    with_line(buf, sizeof buf, "h0 = 1e-310");
    expect_error(buf, NULL, 0, "s.ini:5: surface.h0 = 1e-310", "underflows");
    with_line(buf, sizeof buf, "l0 = 1e999");
    expect_error(buf, NULL, 0, "s.ini:5: surface.l0 = 1e999", "overflows");
    with_line(buf, sizeof buf,
              "depth = \x01"
              "0");
    expect_error(buf, NULL, 0, "s.ini:5: control character 0x01", NULL);
    const char *tiny[] = {"impact.V_star=1e-200"};
    expect_error(good, tiny, 1, "--set: impact.V_star: V* = 1e-200 (speed 1 of the list)",
                 "impact energy");
}

/* A de_DE locale (decimal comma) for the test below: compiled once with localedef into a
 * scratch directory that later runs reuse (made aside and renamed into place, so concurrent
 * runs cannot see half of it). Returns the directory for LOCPATH, or NULL. */
static const char *german_locale_dir(void)
{
    static const char cache[] = "/tmp/cantact-test-locale";
    char probe[256], tmp[] = "/tmp/cantact-test-locale.XXXXXX", cmd[512];
    snprintf(probe, sizeof probe, "%s/de_DE.UTF-8/LC_NUMERIC", cache);
    if (access(probe, R_OK) == 0)
        return cache;
    if (!mkdtemp(tmp))
        return NULL;
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -c -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", tmp);
    int rc = system(cmd);
    snprintf(probe, sizeof probe, "%s/de_DE.UTF-8/LC_NUMERIC", tmp);
    if (access(probe, R_OK) != 0 || rename(tmp, cache) != 0) {
        snprintf(cmd, sizeof cmd, "rm -rf %s", tmp);
        (void)!system(cmd);
    }
    (void)rc;
    snprintf(probe, sizeof probe, "%s/de_DE.UTF-8/LC_NUMERIC", cache);
    return access(probe, R_OK) == 0 ? cache : NULL;
}

/* The C locale whatever the caller's: a German LC_NUMERIC (decimal comma) changes nothing. */
static void numbers_in_the_c_locale(void **state)
{
    (void)state;
    const char *dir = german_locale_dir();
    if (dir)
        setenv("LOCPATH", dir, 1);
    const char *set = dir ? setlocale(LC_NUMERIC, "de_DE.UTF-8") : NULL;
    if (!set)
        fail_msg("cannot make a de_DE locale (localedef, package locales)");
    assert_true(strtod("1,5", NULL) == 1.5); /* the locale does bite */
    ct_scene sc;
    assert_int_equal(ct_scene_parse(&sc, "s.ini", good, NULL, 0), CT_OK);
    assert_true(num(&sc, "surface", "fx") == 1.5 && num(&sc, "surface", "fz") == 1.3);
    ct_scene_free(&sc);
    const char *comma[] = {"surface.fx=1,5"};
    expect_error(good, comma, 1, "surface.fx = 1,5", "not a finite number");
    /* a rod set's numbers too: tops 0.5 and 0.25 */
    assert_int_equal(ct_scene_parse(&sc, "s.ini",
                                    "[surface]\ntype = rods\nrods = 0.5:1, 0.25:1.5\n"
                                    "Hstar = 2\n[material]\nE = 100\n[impact]\nV_star = 1e-3\n",
                                    NULL, 0),
                     CT_OK);
    if (ct_scene_prepare(&sc))
        fail_msg("rods in a de_DE locale: %s", ct_scene_message());
    assert_true(sc.scales.layer.h0 == 0.5 && sc.scales.layer.l0 == 2.5);
    ct_scene_free(&sc);
    assert_true(strtod("1,5", NULL) == 1.5); /* and the caller's locale is back */
    setlocale(LC_NUMERIC, "C");
    unsetenv("LOCPATH");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(defaults_and_values),
        cmocka_unit_test(velocity_lists),
        cmocka_unit_test(set_overrides),
        cmocka_unit_test(unknown_section_and_key),
        cmocka_unit_test(duplicate_key),
        cmocka_unit_test(missing_required),
        cmocka_unit_test(unparsable_numbers),
        cmocka_unit_test(out_of_range),
        cmocka_unit_test(malformed_line),
        cmocka_unit_test(files_missing_and_binary),
        cmocka_unit_test(long_lines_read_whole),
        cmocka_unit_test(section_headers_checked),
        cmocka_unit_test(list_fields_checked),
        cmocka_unit_test(messages_say_what_happened),
        cmocka_unit_test(numbers_in_the_c_locale),
        cmocka_unit_test(nearest_names),
        cmocka_unit_test(did_you_mean),
        cmocka_unit_test(reversed_ranges),
        cmocka_unit_test(empty_override_unsets),
    };
    return cmocka_run_group_tests_name("scene", tests, NULL, NULL);
}
