/* `cantact fit PROFILE|SCENE.ini`: a measured profile levelled and the Cantor surface it looks
 * like (docs/model.md §9), written as a table. A profile file is a surface of kind profile
 * made from the options (each the scene key it stands for); a scene names its surface. */
#include "fit.h"

#include "args.h"
#include "output.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *fit_help =
    "Usage: cantact fit PROFILE [options]\n"
    "       cantact fit SCENE.ini [--set section.key=value]... [-o FILE]\n"
    "\n"
    "Levels a measured profile (text/CSV, Dektak export or X3P) and fits the Cantor surface it\n"
    "looks like (docs/model.md section 9): Rq, Ra, Rt; alpha and h0 from the bearing-area\n"
    "curve phi(d) = (d / h0)^alpha; D from the variation (box-counting) method, the structure\n"
    "function S(tau) ~ tau^(2 (2 - D)) and the power spectrum C(q) ~ q^-(5 - 2D) (all three\n"
    "reported, one used); then fx, fz by Eq. 3 and l0.\n"
    "Writes CSV: quantity,value,band_lo,band_hi,points,r2,rms_residual_ln (lengths in m).\n"
    "\n"
    "Options (with a PROFILE; each is the scene key in brackets, which a scene gives instead):\n"
    "  --unit U        [surface] unit: the file's length unit for x and z: m, mm, um, nm\n"
    "                  (default: the one its column names state; X3P: none, metres)\n"
    "  --x-unit U, --z-unit U   [surface] x_unit, z_unit: each on its own\n"
    "  --spacing DX    [surface] spacing: one column of heights at spacing DX (x unit)\n"
    "  --detrend D     [surface] detrend: none, mean, linear (default), quadratic\n"
    "  --trim K        [surface] trim = rq, trim_k = K: clip heights above mean + K Rq\n"
    "  --dimension M   [fit] dimension: the D that enters Eq. 3: variation (default),\n"
    "                  structure, spectrum\n"
    "  --depths A:B    [fit] depth_lo, depth_hi: the bearing fit's depth band in the z unit\n"
    "                  (default: from the 20th highest point to where phi = 0.1)\n"
    "  --lags A:B      [fit] lag_lo, lag_hi: the lag band of the dimension estimators in the\n"
    "                  x unit (default: 2 spacings to a tenth of the length)\n"
    "  --set section.key=value   any key of the profile ([surface], [fit])\n"
    "  -o FILE         write the table there ('-': stdout, the default)\n"
    "  -h, --help      this help\n";

/* "A:B" into two keys' values; -1 when it is not two fields. */
static int band(ct_surface *s, const char *opt, const char *v, const char *lo_key,
                const char *hi_key)
{
    const char *colon = strchr(v, ':');
    char lo[128];
    if (!colon || (size_t)(colon - v) >= sizeof lo) {
        ct_cli_fail("%s %s: expected A:B (two numbers, 0 < A < B)", opt, v);
        return -1;
    }
    snprintf(lo, sizeof lo, "%.*s", (int)(colon - v), v);
    if (ct_surface_set(s, "fit", lo_key, lo, opt) ||
        ct_surface_set(s, "fit", hi_key, colon + 1, opt)) {
        ct_cli_fail("%s", ct_error_message());
        return -1;
    }
    return 0;
}

/* The options of a PROFILE and the keys they set ("--unit" for "surface.unit"). */
static const ct_opt fit_opts[] = {
    {"--unit", "surface.unit"},
    {"--x-unit", "surface.x_unit"},
    {"--z-unit", "surface.z_unit"},
    {"--spacing", "surface.spacing"},
    {"--detrend", "surface.detrend"},
    {"--dimension", "fit.dimension"},
    {"--trim", NULL},
    {"--depths", NULL},
    {"--lags", NULL},
    {NULL, NULL},
};

/* A message about a PROFILE given on the command line: the keys its options set named as those
 * options ("give --unit (m, mm, um or nm; ...)"), as the user typed them. */
static void fail_in_options(const char *msg)
{
    char out[1024];
    size_t n = 0;
    for (const char *p = msg; *p && n + 1 < sizeof out;) {
        const ct_opt *hit = NULL;
        for (const ct_opt *o = fit_opts; o->name && !hit; o++) {
            const size_t len = o->key ? strlen(o->key) : 0;
            if (len && !strncmp(p, o->key, len) && !isalnum((unsigned char)p[len]) &&
                p[len] != '_' && (p == msg || !isalnum((unsigned char)p[-1])))
                hit = o;
        }
        if (hit) {
            n += (size_t)snprintf(out + n, sizeof out - n, "%s", hit->name);
            p += strlen(hit->key);
        } else {
            out[n++] = *p++;
        }
    }
    out[n < sizeof out ? n : sizeof out - 1] = '\0';
    ct_cli_fail("%s", out);
}

/* The profile surface of a file and the options; its output path in *out. */
static int file_surface(const ct_args *a, const char *file, ct_surface **s, const char **out)
{
    static const char *const layer[][3] = {{"material", "E", "2"},
                                           {"material", "sigma_y", "1"},
                                           {"surface", "H", "2"}}; /* no rods: any layer */
    int st = ct_surface_new(s, "profile");
    if (!st)
        st = ct_surface_set(*s, "surface", "file", file, "");
    for (int k = 0; k < 3 && !st; k++)
        st = ct_surface_set(*s, layer[k][0], layer[k][1], layer[k][2], "");
    for (size_t k = 0; k < a->nsets && !st; k++) {
        const char *set = a->sets[k], *dot = strchr(set, '.'), *eq = strchr(set, '=');
        if (!dot || !eq || eq < dot) {
            ct_cli_fail("--set %s: expected section.key=value", set);
            return EXIT_USAGE;
        }
        char section[64], key[64];
        snprintf(section, sizeof section, "%.*s", (int)(dot - set), set);
        snprintf(key, sizeof key, "%.*s", (int)(eq - dot - 1), dot + 1);
        if (!strcmp(section, "output") && !strcmp(key, "file"))
            *out = eq + 1;
        else
            st = ct_surface_set(*s, section, key, eq + 1, a->set_where[k]);
    }
    const char *trim = ct_args_extra(a, "--trim"), *v;
    if (!st && trim && (st = ct_surface_set(*s, "surface", "trim", "rq", "--trim")) == CT_OK)
        st = ct_surface_set(*s, "surface", "trim_k", trim, "--trim");
    if (st) {
        ct_cli_fail("%s", ct_error_message());
        return ct_cli_status_exit(st);
    }
    if (((v = ct_args_extra(a, "--depths")) && band(*s, "--depths", v, "depth_lo", "depth_hi")) ||
        ((v = ct_args_extra(a, "--lags")) && band(*s, "--lags", v, "lag_lo", "lag_hi")))
        return EXIT_USAGE;
    if ((st = ct_surface_check(*s, file)) || (st = ct_surface_prepare(*s, NULL))) {
        fail_in_options(ct_error_message());
        return ct_cli_status_exit(st);
    }
    return -1;
}

int ct_cli_fit(int argc, char **argv)
{
    ct_args a;
    ct_scene sc;
    memset(&sc, 0, sizeof sc);
    ct_surface *s = NULL;
    const char *out_path = "-";
    int rc = ct_args_parse(&a, argc, argv, "fit", fit_opts, 1);
    if (rc < 0 && a.help) {
        fputs(fit_help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0 && !a.npos) {
        ct_cli_fail("fit: missing PROFILE or SCENE.ini (see cantact fit --help)");
        rc = EXIT_USAGE;
    }
    const char *input = a.npos ? a.positional[0] : "";
    const size_t len = strlen(input);
    const int scene = len > 4 && !strcmp(input + len - 4, ".ini");
    int file_opts = a.nextra > 0;
    for (size_t k = 0; k < a.nsets; k++)
        file_opts |= strcmp(a.set_where[k], "--set") && strcmp(a.set_where[k], "-o");
    if (rc < 0 && scene && file_opts) {
        ct_cli_fail("fit: with a scene, give the profile's options as its keys (--set)");
        rc = EXIT_USAGE;
    }
    a.quiet = 1; /* the table is the answer: nothing on stderr */
    if (rc < 0 && scene && (rc = ct_cli_load_scene(&a, "fit", &sc)) < 0) {
        s = sc.surface;
        out_path = sc.output;
    } else if (rc < 0 && !scene) {
        rc = file_surface(&a, input, &s, &out_path);
    }
    char err[512];
    ct_out out;
    int st;
    if (rc < 0)
        rc = ct_cli_outputs_not_inputs(scene ? &sc : NULL, &out_path, 1, scene ? NULL : &input,
                                       scene ? 0 : 1);
    if (rc < 0 && ct_out_open(&out, out_path, err, sizeof err)) {
        ct_cli_fail("%s", err);
        rc = EXIT_USAGE;
    }
    if (rc < 0 && (st = ct_surface_write_fit(s, out.f))) {
        ct_cli_fail("%s", ct_error_message());
        ct_out_abort(&out);
        rc = ct_cli_status_exit(st);
    }
    ct_profile_fit fit;
    char warning[512];
    if (rc < 0 && !ct_surface_profile(s, NULL, &fit) &&
        ct_profile_fit_warning(&fit, warning, sizeof warning))
        ct_cli_fail("warning: %s", warning); /* said even under -q: the table is suspect */
    if (rc < 0)
        rc =
            ct_out_commit(&out, err, sizeof err) ? (ct_cli_fail("%s", err), EXIT_USAGE) : EXIT_DONE;
    if (scene)
        ct_scene_free(&sc);
    else
        ct_surface_free(s);
    ct_args_free(&a);
    return rc;
}
