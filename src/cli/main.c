/* cantact: the command-line program. Subcommands: run, table, geometry, fit, merge, kinds,
 * keys. Every subcommand parses its arguments with src/cli/args.c and asks the library's
 * tables (kinds of surface, scene keys, output columns) what exists. */
#include "args.h"
#include "fit.h"
#include "merge.h"
#include "output.h"
#include "ranks.h"
#include "run.h"
#include "scene.h"
#include "table.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CT_VERSION
#define CT_VERSION "unknown"
#endif

static const char *main_help =
    "Usage: cantact <subcommand> [options] [SCENE.ini]\n"
    "\n"
    "Coefficient of restitution e of a rough surface made of elastic-perfectly-plastic rods\n"
    "(a Cantor fractal built explicitly as rods, a random one, a measured profile, your rods).\n"
    "\n"
    "Subcommands:\n"
    "  run SCENE        compute what the scene's [output] what asks for (e, time, curve,\n"
    "                   history, profile, compare, bearing, bounce, ensemble, realisations,\n"
    "                   landings)\n"
    "  table SCENE      e(V*) as a table whose interpolation meets [table] tolerance (for DEM\n"
    "                   codes: include/cantact_table.h reads it)\n"
    "  geometry SCENE   print the Cantor geometry of the scene's surface\n"
    "  fit PROFILE      level a measured profile and fit the Cantor surface it looks like\n"
    "  merge SCENE PART.csv...  combine the parts of runs with --realisations or --landings\n"
    "  kinds            the kinds of surface and the outputs each gives (--csv: as a table)\n"
    "  keys             every scene key with its range, default and meaning (--markdown)\n"
    "\n"
    "Options:\n"
    "  -h, --help       this help (also: cantact <subcommand> --help)\n"
    "  --version        print the version\n"
    "\n"
    "Exit status: 0 done, 1 the computation failed, 2 bad input or usage.\n";

static const char *run_help_head =
    "Usage: cantact run SCENE.ini [--set section.key=value]... [-o FILE] [-q]\n"
    "                             [--realisations a:b | --landings a:b]\n"
    "\n"
    "Reads the scene, builds the surface as rods and, for each speed in input order, runs\n"
    "[impact] impacts impacts from the virgin surface (the rods' state carried from one\n"
    "impact to the next). Writes CSV with a header row; u in h0, P in P_Y = sigma_y l0, t in\n"
    "tau = sqrt(m h0 / (E l0)) (docs/model.md §13: each kind's h0 and l0). [output] what:\n";

static const char *run_help_tail =
    "  curve:   V_star,impact,u_over_h0,P_over_PY,branch (load|unload); with compare, the\n"
    "           kind's laws beside P (a Cantor surface: the paper's series and asymptotic)\n"
    "  profile: the surface after the impacts (cantact kinds: what each kind writes)\n"
    "  history: V_star,impact,t_over_tau,u_over_h0,udot_over_h0_per_tau,P_over_PY,branch,\n"
    "           event (every breakpoint and output.history_points uniform times)\n"
    "  bearing: a measured profile's bearing-area curve and its power-law fit\n"
    "With several items in [output] what, FILE holds e and the others go to FILE with\n"
    "_curve / _profile / _history / _bearing before its extension. Outputs appear only when\n"
    "complete, all of them or none (a killed run leaves no file behind). With [impact]\n"
    "sequence = bounce (mass, and velocity or drop_height): impacts at the previous rebound\n"
    "speed, the state carried, until impacts or below stop_speed (what = bounce). With\n"
    "surface.type = random_cantor and [ensemble] realisations: every realisation is built,\n"
    "swept and dropped; what = ensemble (statistics per speed) and realisations (every\n"
    "sample, for cantact merge). With a curved body and [body] landings = N: N apex positions\n"
    "drawn (seed) where the face stays on the surface, each struck at every speed; what = e\n"
    "(statistics over the landings) and landings (every landing with its apex x, y). Under\n"
    "mpirun the ranks share the realisations or the landings.\n"
    "An impact that cannot be computed ends the run (solver.on_error = stop), or is a row of\n"
    "its own with its reason in a last column, error (solver.on_error = skip); the curve and\n"
    "history then hold the impacts computed, the profile the last state computed of the last\n"
    "speed, each said in a note on stderr.\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (each once; key= unsets it)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  --realisations a:b        ensembles: only realisations a .. b-1, written as the\n"
    "                            realisations CSV (job arrays; then cantact merge)\n"
    "  --landings a:b            landings: only landings a .. b-1, written as the landings\n"
    "                            CSV (then cantact merge)\n"
    "  -h, --help                this help\n"
    "\n";

static const char *geometry_help =
    "Usage: cantact geometry SCENE.ini [--set section.key=value]... [-o FILE]\n"
    "\n"
    "Prints alpha, beta, D and, per stage, l_i/l0, h_i/h0, s_i/l0 and the rod length\n"
    "(H* - h_i)/h0 of the scene's Cantor surface at its depth (auto: the depth the run would\n"
    "use). Other kinds of surface have no stages: cantact kinds says what to use instead.\n";

static const char *kinds_help = "Usage: cantact kinds [--csv]\n"
                                "\n"
                                "The kinds of surface ([surface] type), their keys, and for every "
                                "output and subcommand\nwhether the kind gives it, or why not and "
                                "what to use instead. --csv: kind,output,\ngiven,why.\n";

static const char *keys_help = "Usage: cantact keys [--markdown]\n"
                               "\n"
                               "Every scene key: section, name, the kinds of surface that take "
                               "it, type and range,\ndefault and meaning (--markdown: the table "
                               "of docs/scene-keys.md).\n";

/* ---- the key list of run --help, from the tables ---- */

/* The scene's rows that are not the surface's, in section order (surface.type first). */
static size_t scene_rows(ct_key *rows, size_t cap)
{
    size_t n = 0;
    for (const ct_key *r; n < cap && (r = ct_scene_key_row(n));)
        rows[n++] = *r;
    return n;
}

static void key_names(FILE *f, const ct_key *rows, size_t n, const char *section)
{
    for (size_t k = 0; k < n; k++)
        if (!strcmp(rows[k].section, section))
            fprintf(f, " %s", rows[k].name);
}

static void print_run_help(FILE *f)
{
    const ct_column *cols;
    const size_t ncol = ct_sweep_columns(&cols);
    fputs(run_help_head, f);
    const char *groups[] = {"e", "time"};
    for (int g = 0; g < 2; g++) {
        fprintf(f, "  %-8s %s", g ? "time:" : "e:", g ? "adds " : "");
        for (size_t k = 0, first = 1; k < ncol; k++)
            if (!strcmp(cols[k].group, groups[g])) {
                fprintf(f, "%s%s", first ? "" : ",", cols[k].name);
                first = 0;
            }
        fputs(g ? "\n           and with a mass their twins in the scene's units:"
                : "\n           and with a mass v_impact_m_per_s,v_rebound_m_per_s,t_contact_s,"
                  "P_peak_N_per_m\n           (P_peak_N on an areal surface; with time the last "
                  "two are time's)\n",
              f);
        for (size_t k = 0, first = 1; g && k < ncol; k++)
            if (!strcmp(cols[k].group, groups[g]) && cols[k].physical) {
                fprintf(f, "%s%s", first ? " " : ",", cols[k].physical);
                first = 0;
            }
        if (g)
            fputc('\n', f);
    }
    fputs(
        "  compare: adds the kind's comparison columns to e (a Cantor surface: e_series,\n"
        "           e_asymptotic,e_asymptotic_consistent; a profile: its fitted Cantor surface)\n",
        f);
    fputs(run_help_tail, f);
    fputs("Scene keys (cantact keys: with ranges, defaults and meanings):\n", f);
    ct_key cli[64];
    const size_t n = scene_rows(cli, sizeof cli / sizeof cli[0]);
    fputs("[surface] type: ", f);
    for (size_t k = 0; k < ct_surface_kind_count(); k++)
        fprintf(f, "%s%s", k ? " | " : "", ct_surface_kind_name(k));
    fputc('\n', f);
    for (size_t k = 0; k < ct_surface_kind_count(); k++) {
        size_t m;
        const ct_key *rows = ct_surface_kind_keys(k, &m);
        fprintf(f, "  %s:", ct_surface_kind_name(k));
        key_names(f, rows, m, "surface");
        fputs("; [material]", f);
        key_names(f, rows, m, "material");
        for (size_t r = 0; r < m; r++)
            if (!strcmp(rows[r].section, "fit") && (r == 0 || strcmp(rows[r - 1].section, "fit"))) {
                fputs("; [fit]", f);
                key_names(f, rows, m, "fit");
            }
        fputc('\n', f);
    }
    const char *sections[] = {"impact", "solver", "output", "table", "ensemble"};
    for (size_t s = 0; s < sizeof sections / sizeof sections[0]; s++) {
        fprintf(f, "[%s]", sections[s]);
        key_names(f, cli, n, sections[s]);
        fputc('\n', f);
    }
    fputs("See docs/scene-keys.md and docs/cli.md.\n", f);
}

/* ---- kinds and keys ---- */

static int cmd_kinds(int argc, char **argv)
{
    int csv = 0;
    for (int k = 0; k < argc; k++)
        if (!strcmp(argv[k], "--csv"))
            csv = 1;
        else if (!strcmp(argv[k], "-h") || !strcmp(argv[k], "--help")) {
            fputs(kinds_help, stdout);
            return EXIT_DONE;
        } else {
            ct_cli_fail("kinds: unknown argument %s (see cantact kinds --help)", argv[k]);
            return EXIT_USAGE;
        }
    const char *outputs = ct_surface_outputs();
    if (csv)
        puts("kind,output,given,why");
    for (size_t k = 0; k < ct_surface_kind_count(); k++) {
        if (!csv)
            printf("%s: %s\n", ct_surface_kind_name(k), ct_surface_kind_summary(k));
        char buf[256];
        snprintf(buf, sizeof buf, "%s", outputs);
        char *save = NULL;
        for (char *o = strtok_r(buf, " ", &save); o; o = strtok_r(NULL, " ", &save)) {
            const char *why;
            int given = ct_surface_kind_supports(k, o, &why);
            if (csv)
                printf("%s,%s,%d,\"%s\"\n", ct_surface_kind_name(k), o, given, given ? "" : why);
            else
                printf("  %-13s %s%s\n", o, given ? "yes" : "no: ", given ? "" : why);
        }
    }
    return EXIT_DONE;
}

static void print_key(const ct_key *r, const char *kinds, int markdown)
{
    char type[300];
    ct_key_describe(r, type, sizeof type);
    if (!strcmp(r->section, "surface") && !strcmp(r->name, "type")) { /* the registry's kinds */
        const size_t nk = ct_surface_kind_count();
        size_t n = 0;
        for (size_t k = 0; k < nk && n < sizeof type; k++)
            n += (size_t)snprintf(type + n, sizeof type - n, "%s%s",
                                  k == 0        ? ""
                                  : k + 1 == nk ? " or "
                                                : ", ",
                                  ct_surface_kind_name(k));
    }
    if (markdown)
        printf("| `%s` | `%s` | %s | %s | %s | %s |\n", r->section, r->name,
               kinds[0] ? kinds : "all", type,
               r->flags & CT_KEY_REQUIRED ? "required" : (r->def[0] ? r->def : "–"), r->doc);
    else
        printf("%s.%s%s%s%s: %s; %s%s. %s\n", r->section, r->name, kinds[0] ? " (" : "", kinds,
               kinds[0] ? ")" : "", type, r->flags & CT_KEY_REQUIRED ? "required" : "default ",
               r->flags & CT_KEY_REQUIRED ? "" : (r->def[0] ? r->def : "none"), r->doc);
}

static int cmd_keys(int argc, char **argv)
{
    int markdown = 0;
    for (int k = 0; k < argc; k++)
        if (!strcmp(argv[k], "--markdown"))
            markdown = 1;
        else if (!strcmp(argv[k], "-h") || !strcmp(argv[k], "--help")) {
            fputs(keys_help, stdout);
            return EXIT_DONE;
        } else {
            ct_cli_fail("keys: unknown argument %s (see cantact keys --help)", argv[k]);
            return EXIT_USAGE;
        }
    if (markdown)
        puts("# Scene keys\n\n"
             "Generated by `cantact keys --markdown` from the key tables (the CLI's own sections "
             "in\n"
             "`src/cli/scene.c`, each kind of surface's keys in its file under `src/surface/`); a\n"
             "test checks that this page is what the program prints. A scene is an INI file:\n"
             "`[section]` headers, `key = value` lines, `;` or `#` comments; `--set "
             "section.key=value`\n"
             "overrides a key. A key a kind of surface does not take is refused with the kinds "
             "that\n"
             "take it; a value outside its range is refused with the range. Lengths are in the\n"
             "scene's units unless a unit key says otherwise (docs/model.md §13).\n\n"
             "| section | key | kinds | type and range | default | meaning |\n"
             "|---|---|---|---|---|---|");
    ct_key cli[64];
    const size_t n = scene_rows(cli, sizeof cli / sizeof cli[0]);
    print_key(&cli[0], "", markdown); /* surface.type */
    for (size_t k = 0; k < ct_surface_kind_count(); k++) {
        size_t m;
        const ct_key *rows = ct_surface_kind_keys(k, &m);
        for (size_t r = 0; r < m; r++) {
            /* a key several kinds share once per (kind, row), so each kind's range shows */
            char kinds[32];
            snprintf(kinds, sizeof kinds, "%s", ct_surface_kind_name(k));
            print_key(&rows[r], kinds, markdown);
        }
    }
    for (size_t k = 1; k < n; k++)
        print_key(&cli[k], "", markdown);
    return EXIT_DONE;
}

/* ---- geometry ---- */

static int cmd_geometry(int argc, char **argv)
{
    ct_args a;
    ct_scene sc;
    int rc = ct_args_parse(&a, argc, argv, "geometry", NULL, 1);
    if (rc < 0 && a.help) {
        fputs(geometry_help, stdout);
        rc = EXIT_DONE;
    }
    if (rc < 0)
        rc = ct_cli_load_scene(&a, "geometry", &sc);
    if (rc >= 0) {
        ct_args_free(&a);
        return rc;
    }
    /* to output.file (-o FILE), written whole or not at all, like every output */
    ct_out out;
    char err[512];
    const char *path = sc.output;
    rc = EXIT_DONE;
    if (ct_cli_outputs_not_inputs(&sc, &path, 1, NULL, 0) >= 0) {
        rc = EXIT_USAGE;
    } else if (ct_out_open(&out, sc.output, err, sizeof err)) {
        ct_cli_fail("%s", err);
        rc = EXIT_USAGE;
    } else {
        ct_build_request req;
        ct_scene_request(&sc, 0, &req);
        int st = ct_surface_write_geometry(sc.surface, &req, out.f);
        if (st) {
            ct_out_abort(&out);
            ct_cli_fail("%s", ct_error_message());
            rc = ct_cli_status_exit(st);
        } else if (ct_out_commit(&out, err, sizeof err)) {
            ct_cli_fail("%s", err);
            rc = EXIT_USAGE;
        }
    }
    ct_scene_free(&sc);
    ct_args_free(&a);
    return rc;
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        fputs("cantact: missing subcommand (try cantact --help)\n", stderr);
        return EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "-h") || !strcmp(cmd, "--help") || !strcmp(cmd, "help")) {
        fputs(main_help, stdout);
        return EXIT_DONE;
    }
    if (!strcmp(cmd, "--version")) {
        printf("cantact %s\n", CT_VERSION);
        return EXIT_DONE;
    }
    if (!strcmp(cmd, "run")) {
        if (ct_mpi_init(&argc, &argv)) /* only under an MPI launcher */
            return EXIT_FAILED;
        char *help = NULL;
        size_t len = 0;
        FILE *h = open_memstream(&help, &len);
        if (h) {
            print_run_help(h);
            fclose(h);
        }
        int rc = ct_cli_run(argc - 2, argv + 2, help ? help : "");
        free(help);
        ct_mpi_finalize();
        return rc;
    }
    if (!strcmp(cmd, "merge"))
        return ct_cli_merge(argc - 2, argv + 2);
    if (!strcmp(cmd, "table"))
        return ct_cli_table(argc - 2, argv + 2);
    if (!strcmp(cmd, "geometry"))
        return cmd_geometry(argc - 2, argv + 2);
    if (!strcmp(cmd, "fit"))
        return ct_cli_fit(argc - 2, argv + 2);
    if (!strcmp(cmd, "kinds"))
        return cmd_kinds(argc - 2, argv + 2);
    if (!strcmp(cmd, "keys"))
        return cmd_keys(argc - 2, argv + 2);
    fprintf(stderr, "cantact: unknown subcommand '%s' (try cantact --help)\n", cmd);
    return EXIT_USAGE;
}

int main(int argc, char **argv)
{
    ct_out_guard_std();
    int rc = dispatch(argc, argv);
    /* what went to standard output through stdio (help, geometry) must have arrived */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "cantact: standard output: write failed\n");
        return rc ? rc : EXIT_USAGE;
    }
    return rc;
}
