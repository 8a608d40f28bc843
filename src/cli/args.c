/* The one argument parser of the subcommands, and loading a subcommand's scene. */
#include "args.h"

#include "output.h"
#include "ranks.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ct_cli_fail(const char *fmt, ...)
{
    if (ct_mpi_rank() != 0) /* under mpirun every rank reads the scene: one line, not K */
        return;
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "cantact: %s\n", msg);
}

void ct_cli_fail_scene(const ct_scene *sc, int st, const char *msg)
{
    if (!sc || !(sc->mass > 0.0)) {
        ct_cli_fail("%s", msg);
        return;
    }
    /* the V* the message names, also as the speed the scene gave (speed = V* / v_per_V*); or
     * the impact energy it names [the layer's units], with both */
    char out[1024];
    const char *at = strstr(msg, "V* = "), *energy = strstr(msg, "impact energy ");
    const double per = ct_V_star_of(sc->mass, 1.0, sc->scales.physical.l0, sc->scales.physical.E,
                                    sc->scales.physical.h0);
    size_t n = 0;
    char *end;
    if (at && per > 0.0) {
        const double V = strtod(at + 5, &end);
        if (end != at + 5 && isfinite(V)) {
            n = (size_t)snprintf(out, sizeof out, "%.*simpact speed %.6g m/s (V* = %.*s)",
                                 (int)(at - msg), msg, V / per, (int)(end - at - 5), at + 5);
            msg = end;
        }
    } else if (energy && per > 0.0) {
        const double W = strtod(energy + 14, &end);
        const double V = sqrt(W / sc->scales.energy_scale);
        if (end != energy + 14 && isfinite(V) && V > 0.0) {
            n = (size_t)snprintf(out, sizeof out, "%.*s (impact speed %.6g m/s, V* = %.6g)",
                                 (int)(end - msg), msg, V / per, V);
            msg = end;
        }
    }
    if (n < sizeof out)
        n += (size_t)snprintf(out + n, sizeof out - n, "%s", msg);
    /* a crushed layer in SI units: most often E given in GPa or MPa, read in Pa */
    if (st == CT_ERANGE && strstr(msg, "would be crushed") && n < sizeof out)
        snprintf(out + n, sizeof out - n,
                 "; with mass and speeds in SI units (kg, m/s) material.E = %g is read in Pa: "
                 "check its unit",
                 sc->scales.physical.E);
    ct_cli_fail("%s", out);
}

int ct_cli_status_exit(int st)
{
    return (st == CT_EINVAL || st == CT_ERANGE || st == CT_EIO) ? EXIT_USAGE : EXIT_FAILED;
}

static char *own(ct_args *a, char *s)
{
    if (s)
        a->owned[a->nowned++] = s;
    return s;
}

static const ct_opt *find_opt(const ct_opt *opts, const char *name)
{
    for (const ct_opt *o = opts; o && o->name; o++)
        if (!strcmp(o->name, name))
            return o;
    return NULL;
}

/* The key a "section.key=value" override sets, trimmed, into buf ("" when malformed: the scene
 * says so). */
static void override_key(const char *set, char *buf, size_t len)
{
    const char *eq = strchr(set, '=');
    const char *a = set, *b = eq ? eq : set;
    while (a < b && isspace((unsigned char)*a))
        a++;
    while (b > a && isspace((unsigned char)b[-1]))
        b--;
    snprintf(buf, len, "%.*s", (int)(b - a), a);
}

/* How the user wrote override k: "--set surface.fz=1.6", "-o out.csv", "--unit um". */
static void override_shown(const ct_args *a, size_t k, char *buf, size_t len)
{
    const char *w = a->set_where[k], *eq = strchr(a->sets[k], '=');
    if (!strcmp(w, "--set") || !eq)
        snprintf(buf, len, "--set %s", a->sets[k]);
    else
        snprintf(buf, len, "%s %s", w, eq + 1);
}

/* Every key once on the command line (--set, -o, a subcommand's options), as in a scene file: a
 * second one is refused, naming both. -1, or EXIT_USAGE. */
static int repeated_keys(const ct_args *a)
{
    for (size_t j = 1; j < a->nsets; j++) {
        char kj[160], ki[160], sj[300], si[300];
        override_key(a->sets[j], kj, sizeof kj);
        for (size_t i = 0; kj[0] && i < j; i++) {
            override_key(a->sets[i], ki, sizeof ki);
            if (strcmp(ki, kj))
                continue;
            override_shown(a, j, sj, sizeof sj);
            override_shown(a, i, si, sizeof si);
            ct_cli_fail("%s: %s given twice on the command line (also by %s)", sj, kj, si);
            return EXIT_USAGE;
        }
    }
    return -1;
}

int ct_args_parse(ct_args *a, int argc, char **argv, const char *cmd, const ct_opt *opts,
                  size_t max_pos)
{
    memset(a, 0, sizeof *a);
    const size_t cap = (size_t)argc + 2;
    a->sets = calloc(cap, sizeof *a->sets);
    a->set_where = calloc(cap, sizeof *a->set_where);
    a->owned = calloc(cap, sizeof *a->owned);
    if (!a->sets || !a->set_where || !a->owned) {
        ct_cli_fail("out of memory");
        return EXIT_FAILED;
    }
    const char *output = NULL;
    for (int k = 0; k < argc; k++) {
        const char *s = argv[k];
        const ct_opt *o = find_opt(opts, s);
        const int needs = !strcmp(s, "--set") || !strcmp(s, "-o") || o;
        if (needs && k + 1 >= argc) {
            ct_cli_fail("%s needs a value", s);
            return EXIT_USAGE;
        }
        if (!strcmp(s, "-h") || !strcmp(s, "--help")) {
            a->help = 1;
        } else if (!strcmp(s, "-q")) {
            a->quiet = 1;
        } else if (!strcmp(s, "--set")) {
            a->set_where[a->nsets] = "--set";
            a->sets[a->nsets++] = argv[++k];
        } else if (!strncmp(s, "--set=", 6)) {
            a->set_where[a->nsets] = "--set";
            a->sets[a->nsets++] = s + 6;
        } else if (!strcmp(s, "-o")) {
            if (output) {
                ct_cli_fail("-o %s: the output given twice (also -o %s)", argv[k + 1], output);
                return EXIT_USAGE;
            }
            output = argv[++k]; /* applied last, as a --set output.file */
        } else if (o && o->key) {
            const char *v = argv[++k];
            size_t n = strlen(o->key) + strlen(v) + 2;
            char *set = own(a, malloc(n));
            if (!set) {
                ct_cli_fail("out of memory");
                return EXIT_FAILED;
            }
            snprintf(set, n, "%s=%s", o->key, v);
            a->set_where[a->nsets] = o->name;
            a->sets[a->nsets++] = set;
        } else if (o) {
            if (a->nextra == sizeof a->extra_name / sizeof a->extra_name[0]) {
                ct_cli_fail("%s: too many options", cmd);
                return EXIT_USAGE;
            }
            const char *before = ct_args_extra(a, o->name);
            if (before) { /* once, as every key */
                ct_cli_fail("%s %s: %s given twice on the command line (also %s %s)", o->name,
                            argv[k + 1], o->name, o->name, before);
                return EXIT_USAGE;
            }
            a->extra_name[a->nextra] = o->name;
            a->extra_value[a->nextra++] = argv[++k];
        } else if (s[0] == '-' && s[1]) {
            ct_cli_fail("unknown option %s (see cantact %s --help)", s, cmd);
            return EXIT_USAGE;
        } else if (a->npos < max_pos && a->npos < sizeof a->positional / sizeof a->positional[0]) {
            a->positional[a->npos++] = s;
        } else if (max_pos == 1) {
            ct_cli_fail("only one scene file, got %s and %s", a->positional[0], s);
            return EXIT_USAGE;
        } else {
            ct_cli_fail("%s: too many arguments (%s)", cmd, s);
            return EXIT_USAGE;
        }
    }
    if (output) {
        size_t n = strlen(output) + sizeof "output.file=";
        char *set = own(a, malloc(n));
        if (!set) {
            ct_cli_fail("out of memory");
            return EXIT_FAILED;
        }
        snprintf(set, n, "output.file=%s", output);
        a->set_where[a->nsets] = "-o";
        a->sets[a->nsets++] = set;
    }
    return repeated_keys(a);
}

void ct_args_free(ct_args *a)
{
    for (size_t k = 0; k < a->nowned; k++)
        free(a->owned[k]);
    free(a->owned);
    free(a->sets);
    free(a->set_where);
    memset(a, 0, sizeof *a);
}

const char *ct_args_extra(const ct_args *a, const char *name)
{
    const char *v = NULL;
    for (size_t k = 0; k < a->nextra; k++)
        if (!strcmp(a->extra_name[k], name))
            v = a->extra_value[k];
    return v;
}

void ct_cli_notes(ct_surface *s, int quiet)
{
    const char *note = s ? ct_surface_note(s) : "";
    for (const char *p = note; !quiet && *p;) {
        const char *nl = strchr(p, '\n');
        int n = nl ? (int)(nl - p) : (int)strlen(p);
        if (ct_mpi_rank() == 0)
            fprintf(stderr, "cantact: %.*s\n", n, p);
        p += n + (nl != NULL);
    }
    if (s)
        ct_surface_note_clear(s);
}

char *ct_cli_derived_path(const char *path, const char *tag)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    size_t n = strlen(path);
    char *out = malloc(n + strlen(tag) + 2);
    if (!out)
        return NULL;
    if (dot && (!slash || dot > slash) && dot != path)
        sprintf(out, "%.*s_%s%s", (int)(dot - path), path, tag, dot);
    else
        sprintf(out, "%s_%s", path, tag);
    return out;
}

int ct_cli_outputs_not_inputs(const ct_scene *sc, const char *const *outputs, size_t n,
                              const char *const *extra, size_t nextra)
{
    const size_t nin = sc ? sc->ninputs : 0;
    for (size_t o = 0; o < n; o++) {
        for (size_t i = 0; i < nin + nextra; i++) {
            const char *in = i < nin ? sc->inputs[i] : extra[i - nin];
            if (outputs[o] && ct_out_is_input(outputs[o], in)) {
                ct_cli_fail("output %s is %s (%s): an output may not replace an input; nothing "
                            "was computed or written",
                            outputs[o], i < nin ? sc->input_what[i] : "an input of this run", in);
                return EXIT_USAGE;
            }
        }
    }
    return -1;
}

/* The files the loaded scene reads: itself and its surface's. */
static int note_inputs(ct_scene *sc, const char *path)
{
    char buf[4096];
    sc->ninputs = 0;
    if (!(sc->inputs[0] = strdup(path)))
        return CT_ENOMEM;
    sc->input_what[sc->ninputs++] = "the scene";
    for (size_t k = 0; sc->ninputs < sizeof sc->inputs / sizeof sc->inputs[0] &&
                       ct_surface_input(sc->surface, k, sc->scene_dir, buf, sizeof buf);
         k++) {
        if (!(sc->inputs[sc->ninputs] = strdup(buf)))
            return CT_ENOMEM;
        sc->input_what[sc->ninputs++] = "a file of the surface";
    }
    return CT_OK;
}

int ct_cli_load_scene(const ct_args *a, const char *cmd, ct_scene *sc)
{
    if (!a->npos) {
        ct_cli_fail("%s: missing SCENE.ini (see cantact %s --help)", cmd, cmd);
        return EXIT_USAGE;
    }
    const char *path = a->positional[0];
    if (ct_scene_load(sc, path, a->sets, a->nsets)) {
        ct_cli_fail("%s", ct_scene_message());
        return EXIT_USAGE;
    }
    if (note_inputs(sc, path)) {
        ct_cli_fail("out of memory");
        ct_scene_free(sc);
        return EXIT_FAILED;
    }
    const char *out = sc->output;
    if (ct_cli_outputs_not_inputs(sc, &out, 1, NULL, 0) >= 0) {
        ct_scene_free(sc);
        return EXIT_USAGE;
    }
    /* a subcommand the kind of surface does not give: said before any file is read */
    const char *why;
    char list[256];
    snprintf(list, sizeof list, " %s ", ct_surface_outputs());
    char word[64];
    snprintf(word, sizeof word, " %s ", cmd);
    /* landings are merged as an ensemble's realisations are, on any surface that has them */
    const int landings_merge = !strcmp(cmd, "merge") && sc->body.landings;
    if (strstr(list, word) && !landings_merge &&
        !ct_surface_kind_supports(ct_surface_kind_index(sc->surface), cmd, &why)) {
        ct_cli_fail("%s: %s", cmd, why);
        ct_scene_free(sc);
        return EXIT_USAGE;
    }
    int st = ct_scene_prepare(sc);
    ct_cli_notes(sc->surface, a->quiet);
    if (st) {
        ct_cli_fail("%s", ct_scene_message());
        ct_scene_free(sc);
        return ct_cli_status_exit(st);
    }
    return -1;
}
