/* cantact: the command-line program. Subcommands: run, geometry, merge. */
#include "cantact.h"
#include "ensemble.h"
#include "history.h"
#include "measured.h"
#include "ranks.h"
#include "number.h"
#include "output.h"
#include "scene.h"
#include "table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CT_VERSION
#define CT_VERSION "unknown"
#endif

enum { EXIT_DONE = 0, EXIT_FAILED = 1, EXIT_USAGE = 2 };

static const char *main_help =
    "Usage: cantact <subcommand> [options] [SCENE.ini]\n"
    "\n"
    "Coefficient of restitution e of a Cantor-fractal rough surface made of\n"
    "elastic-perfectly-plastic rods (Cantor stages built explicitly as rods).\n"
    "\n"
    "Subcommands:\n"
    "  run SCENE        compute what the scene's [output] what asks for (e, time, curve,\n"
    "                   history, profile, compare, bounce, ensemble, bearing)\n"
    "  geometry SCENE   print the Cantor geometry of the scene's surface\n"
    "  fit PROFILE      level a measured profile and fit the Cantor surface it looks like\n"
    "  merge SCENE PART.csv...  combine the realisations of runs with --realisations a:b\n"
    "  table SCENE      e(V*) as a table whose interpolation meets [table] tolerance (for DEM\n"
    "                   codes: include/cantact_table.h reads it)\n"
    "\n"
    "Options:\n"
    "  -h, --help       this help (also: cantact <subcommand> --help)\n"
    "  --version        print the version\n"
    "\n"
    "Exit status: 0 done, 1 the computation failed, 2 bad input or usage.\n";

static const char *run_help =
    "Usage: cantact run SCENE.ini [--set section.key=value]... [-o FILE]\n"
    "                             [--realisations a:b]\n"
    "\n"
    "Reads the scene, builds the surface as rods and, for each V* in input order, runs\n"
    "[impact] impacts impacts from the virgin surface (the rods' state carried from one\n"
    "impact to the next). Writes CSV (header row; u in h0, P in P_Y = sigma_y l0):\n"
    "  e:       impact,V_star,u_max_over_h0,e,e_closed_form,quadrature_error,\n"
    "           V_star_crit,u_release_over_h0,elastic\n"
    "  curve:   V_star,impact,u_over_h0,P_over_PY,branch (load|unload)\n"
    "  compare: adds e_series,e_asymptotic,e_asymptotic_consistent to e rows and the laws'\n"
    "           P(u) to curve rows (first impact; the laws model the virgin fractal)\n"
    "  profile: stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n"
    "  time:    adds the impact in time to e rows: t_contact_over_tau,t_load_over_tau,\n"
    "           t_unload_over_tau,P_peak_over_PY,e_kinematic,unload_period_over_tau,\n"
    "           dem_time_step_over_tau (tau = sqrt(m h0 / (E l0))); with [impact] mass also\n"
    "           t_contact_s,t_load_s,t_unload_s,P_peak_N_per_m,unload_period_s,\n"
    "           dem_time_step_s (scene in SI units). Every run checks e_kinematic = e.\n"
    "  history: V_star,impact,t_over_tau,u_over_h0,udot_over_h0_per_tau,P_over_PY,branch,\n"
    "           event (every breakpoint and output.history_points uniform times)\n"
    "With several items in [output] what, FILE holds e and the others go to FILE with\n"
    "_curve / _profile / _history before its extension. Outputs appear only when complete.\n"
    "\n"
    "With [impact] sequence = bounce (mass, and velocity or drop_height): impacts at the\n"
    "previous rebound speed, the state carried, until impacts or below stop_speed; what =\n"
    "bounce: bounce,V_star,v_in_m_per_s,e,v_out_m_per_s,u_max_over_h0,elastic,t_contact_s,\n"
    "P_peak_N_per_m,flight_s,height_m,time_s,v_out_constant_e_m_per_s,height_constant_e_m.\n"
    "\n";
/* the rest of run's help (one literal would pass the 4095 characters C99 promises) */
static const char *run_help_more =
    "With surface.type = random_cantor and [ensemble] realisations = R, every realisation is\n"
    "built, swept and dropped, and what lists:\n"
    "  ensemble:     impact,V_star,realisations, then mean, sd, sem (standard error of the\n"
    "                mean), q05, q50, q95 of e, u_max_over_h0 and V_star_crit, then\n"
    "                e_deterministic (the surface with spread 0)\n"
    "  realisations: realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,\n"
    "                fz_clipped (every sample, for cantact merge)\n"
    "Under mpirun the ranks share the realisations; the output is the same bytes.\n"
    "\n"
    "With surface.type = profile (a measured line profile or X3P grid; E, sigma_y in Pa;\n"
    "mass per unit depth, or mass for a grid, in kg; velocity in m/s), every sample is a rod,\n"
    "h0 = Rt and l0 = the length (area) after levelling, V* = v sqrt(m / (2 l0 E h0)), and:\n"
    "  compare: adds e_cantor_fit,e_asymptotic_fit,V_star_cantor_fit to e rows (the fitted\n"
    "           Cantor surface, exact rods, and the paper's law with the fitted parameters)\n"
    "  bearing: d_m,d_over_Rt,phi,phi_fit (the bearing-area curve and its power-law fit)\n"
    "  profile: x_m,z_m (a grid: x_m,y_m,z_m), the heights after levelling\n"
    "\n"
    "An impact that cannot be computed (a crushed layer, an unresolvable penetration) ends the\n"
    "run with its V* and impact (solver.on_error = stop), or, with solver.on_error = skip,\n"
    "is a row of its own: its numbers empty and the reason in a last column, error.\n"
    "\n"
    "Options:\n"
    "  --set section.key=value   override a scene key (repeatable)\n"
    "  -o FILE                   same as --set output.file=FILE ('-' for stdout)\n"
    "  -q                        no summary on stderr\n"
    "  --realisations a:b        ensembles: only realisations a .. b-1, written as the\n"
    "                            realisations CSV (job arrays; then cantact merge)\n"
    "  -h, --help                this help\n"
    "\n"
    "Scene keys: [surface] type (cantor|random_cantor|profile) fx fz H h0 l0 depth\n"
    "representation;\n"
    "random_cantor: distribution (uniform|lognormal) fx_spread fz_spread seed realisation;\n"
    "[ensemble] realisations split (auto|realisations|rods);\n"
    "type = profile: file unit x_unit z_unit (m|mm|um|nm) spacing detrend\n"
    "(none|mean|linear|quadratic) trim (none|rq) trim_k, H (x Rt) | Hstar (z unit);\n"
    "[fit] dimension (variation|structure|spectrum) depth_lo depth_hi lag_lo lag_hi;\n"
    "[material] E sigma_y;\n"
    "[impact] V_star | mass velocity | mass drop_height, impacts, sequence (sweep|bounce)\n"
    "gravity stop_speed; [solver] quadrature nodes tolerance\n"
    "depth_tolerance threads on_error (stop|skip) check (closed|none) path (auto|curve|rods);\n"
    "[output] file what history_points; [table] tolerance V_star interpolation max_nodes\n"
    "check_points\n"
    "(cantact table).\n"
    "See README.md.\n";

static const char *geometry_help =
    "Usage: cantact geometry SCENE.ini [--set section.key=value]...\n"
    "\n"
    "Prints alpha, beta, D and, per stage, l_i/l0, h_i/h0, s_i/l0 and the rod length\n"
    "(H* - h_i)/h0 of the scene's surface at its depth (auto: the depth the run would use).\n";

static void fail_line(const char *msg)
{
    if (ct_mpi_rank() == 0) /* under mpirun every rank reads the scene: one line, not K */
        fprintf(stderr, "cantact: %s\n", msg);
}

static int status_exit(int st)
{
    return (st == CT_EINVAL || st == CT_ERANGE || st == CT_EIO) ? EXIT_USAGE : EXIT_FAILED;
}

typedef struct {
    const char *scene;
    const char **sets;
    size_t nsets;
    int quiet;
    int help;
    const char *output;       /* -o FILE */
    char *output_set;         /* "output.file=FILE", allocated */
    const char *realisations; /* --realisations a:b */
} cli_args;

static int parse_args(int argc, char **argv, cli_args *a)
{
    memset(a, 0, sizeof *a);
    a->sets = calloc((size_t)argc + 1, sizeof(char *));
    if (!a->sets) {
        fail_line("out of memory");
        return EXIT_FAILED;
    }
    for (int k = 0; k < argc; k++) {
        const char *s = argv[k];
        if (!strcmp(s, "-h") || !strcmp(s, "--help")) {
            a->help = 1;
        } else if (!strcmp(s, "-q")) {
            a->quiet = 1;
        } else if (!strcmp(s, "--set") || !strcmp(s, "-o")) {
            if (k + 1 >= argc) {
                fprintf(stderr, "cantact: %s needs a value\n", s);
                return EXIT_USAGE;
            }
            if (!strcmp(s, "-o")) {
                a->output = argv[++k]; /* applied last, as a --set output.file */
            } else {
                a->sets[a->nsets++] = argv[++k];
            }
        } else if (!strncmp(s, "--set=", 6)) {
            a->sets[a->nsets++] = s + 6;
        } else if (!strcmp(s, "--realisations")) {
            if (k + 1 >= argc) {
                fprintf(stderr, "cantact: %s needs a value\n", s);
                return EXIT_USAGE;
            }
            a->realisations = argv[++k];
        } else if (s[0] == '-' && s[1]) {
            fprintf(stderr, "cantact: unknown option %s (see --help)\n", s);
            return EXIT_USAGE;
        } else if (!a->scene) {
            a->scene = s;
        } else {
            fprintf(stderr, "cantact: only one scene file, got %s and %s\n", a->scene, s);
            return EXIT_USAGE;
        }
    }
    if (a->output) {
        size_t n = strlen(a->output) + sizeof "output.file=";
        if (!(a->output_set = malloc(n))) {
            fail_line("out of memory");
            return EXIT_FAILED;
        }
        snprintf(a->output_set, n, "output.file=%s", a->output);
        a->sets[a->nsets++] = a->output_set;
    }
    return EXIT_DONE;
}

/* Depth the run uses: the scene's, or auto for the smallest impact energy. */
static int choose_depth(const ct_scene *sc, long *depth, double *bound)
{
    *bound = 0.0;
    if (sc->depth >= 0) {
        *depth = sc->depth;
        return CT_OK;
    }
    double vmin = INFINITY;
    for (size_t k = 0; k < sc->nvel; k++)
        vmin = sc->V_star[k] < vmin ? sc->V_star[k] : vmin;
    double W_min = vmin * vmin * ct_energy_scale(&sc->params);
    if (sc->depth == CT_DEPTH_FRACTAL)
        return ct_fractal_depth(&sc->params, W_min, depth, bound);
    return ct_auto_depth(&sc->params, W_min, sc->depth_tolerance, depth, bound);
}

static char *derived_path(const char *path, const char *tag)
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

static void put_field(FILE *f, double x)
{
    fputc(',', f);
    ct_put_double(f, x);
}

/* The paper's laws at u (unloading from hi when unload): series, asymptotic, consistent
 * asymptotic; NaN where a law does not apply. */
static void law_forces(const ct_params *p, int unload, double hi, double u, double out[3])
{
    double ps = 0.0, pa = 0.0, pc = 0.0;
    int ss = unload ? ct_series_unload(p, hi, u, &ps) : ct_series_load(p, u, &ps);
    int sa = unload ? ct_asym_unload(p, hi, u, 0, &pa) : ct_asym_load(p, u, &pa);
    int sc = unload ? ct_asym_unload(p, hi, u, 1, &pc) : sa;
    out[0] = ss ? NAN : ps;
    out[1] = sa ? NAN : pa;
    out[2] = sc ? NAN : unload ? pc : pa;
}

/* A curve branch: the breakpoints in [lo, hi] (when fewer than 1e5) and a uniform grid, P
 * from the state's load curve. */
static int write_branch(FILE *f, const ct_curve *c, const ct_params *p, double V, long impact,
                        double lo, double hi, const char *branch, int compare)
{
    enum { GRID = 200 };
    const double *x = ct_curve_points(c), h0 = p->h0, PY = p->sigma_y * p->l0;
    size_t n = ct_curve_size(c), a = 0, z = n;
    while (a < n && !(x[a] > lo))
        a++;
    while (z > a && !(x[z - 1] < hi))
        z--;
    size_t use = z - a < 100000 ? z - a : 0;
    double *u = malloc((use + GRID + 1) * sizeof(double));
    if (!u)
        return CT_ENOMEM;
    /* merge the (sorted) breakpoints with the (sorted) grid */
    size_t m = 0, i = a, g = 0;
    while (i < a + use || g <= GRID) {
        double ug = g <= GRID ? lo + (hi - lo) * g / GRID : INFINITY;
        double ub = i < a + use ? x[i] : INFINITY;
        double next = ub < ug ? ub : ug;
        if (ub < ug)
            i++;
        else
            g++;
        if (!m || next != u[m - 1])
            u[m++] = next;
    }
    int unload = !strcmp(branch, "unload");
    for (size_t j = 0; j < m; j++) {
        size_t k = unload ? m - 1 - j : j;
        ct_put_double(f, V);
        fprintf(f, ",%ld,", impact);
        ct_put_double(f, u[k] / h0);
        fputc(',', f);
        ct_put_double(f, ct_curve_force(c, u[k]) / PY);
        fprintf(f, ",%s", branch);
        if (compare && impact == 1) {
            /* the laws at the same u, unloading from the exact u_max (hi) */
            double laws[3];
            law_forces(p, unload, hi, u[k], laws);
            for (int l = 0; l < 3; l++) {
                if (isfinite(laws[l]))
                    put_field(f, laws[l] / PY);
                else
                    fputc(',', f); /* outside the law (asymptotic beyond u = h0) */
            }
        } else if (compare) {
            fputs(",,,", f);
        }
        fputc('\n', f);
    }
    free(u);
    return CT_OK;
}

static int write_profile(FILE *f, const ct_bundle *b, const ct_params *p)
{
    long N = ct_cantor_depth(b);
    size_t n = ct_bundle_size(b);
    ct_rod_info first;
    long first_stage = N + 1;
    if (n && !ct_bundle_rod(b, 0, &first))
        first_stage = first.stage;
    /* stage rods stand for all pieces of their stage */
    for (long i = 0; i <= N; i++) {
        double top = ct_stage_depth(p, (double)i), residual = top;
        if (i >= first_stage) {
            ct_rod_info info;
            size_t k = ct_cantor_representation(b) == CT_REP_STAGES
                           ? (size_t)(i - first_stage)
                           : ((size_t)1 << i) - ((size_t)1 << first_stage);
            if (ct_bundle_rod(b, k, &info) == CT_OK)
                residual = info.top + info.plastic_strain * info.length;
        }
        for (size_t j = 0; j < ((size_t)1 << i); j++) {
            double xl, xr;
            ct_piece_extent(p, N, i, j, &xl, &xr);
            if (ct_cantor_representation(b) == CT_REP_SEGMENTS && i >= first_stage) {
                ct_rod_info info;
                size_t k = ((size_t)1 << i) - 1 + j - (((size_t)1 << first_stage) - 1);
                if (ct_bundle_rod(b, k, &info) == CT_OK)
                    residual = info.top + info.plastic_strain * info.length;
            }
            fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g\n", i, xl / p->l0, xr / p->l0, top / p->h0,
                    residual / p->h0);
        }
    }
    return CT_OK;
}

/* Parses a subcommand's arguments and loads its scene. Returns -1 when the scene is loaded
 * into *sc (the caller goes on), else the exit status to return (help shown, or an error). */
static int load_scene_args(int argc, char **argv, const char *cmd, const char *help, ct_scene *sc,
                           int *quiet, const char **realisations)
{
    cli_args a;
    int rc = parse_args(argc, argv, &a);
    if (!rc && !a.help && a.realisations && !realisations) {
        fprintf(stderr, "cantact: %s: --realisations is an option of run\n", cmd);
        rc = EXIT_USAGE;
    }
    if (rc || a.help) {
        if (a.help)
            fputs(help, stdout);
        free(a.sets);
        free(a.output_set);
        return rc;
    }
    if (!a.scene) {
        fprintf(stderr, "cantact: %s: missing SCENE.ini (see cantact %s --help)\n", cmd, cmd);
        free(a.sets);
        free(a.output_set);
        return EXIT_USAGE;
    }
    int st = ct_scene_load(sc, a.scene, a.sets, a.nsets);
    free(a.sets);
    if (st) {
        free(a.output_set);
        fail_line(ct_scene_message());
        return EXIT_USAGE;
    }
    if (ct_out_same_file(a.scene, sc->output)) {
        fprintf(stderr, "cantact: output.file = %s: is the scene file itself\n", sc->output);
        free(a.output_set);
        ct_scene_free(sc);
        return EXIT_USAGE;
    }
    free(a.output_set);
    ct_scene_make_dimensionless(sc);
    if ((sc->surface_type == CT_SURFACE_CANTOR || sc->surface_type == CT_SURFACE_RANDOM_CANTOR) &&
        (st = ct_params_validate(&sc->params))) {
        /* E/sigma_y times H* / h0 may overflow */
        fprintf(stderr, "cantact: %s: %s\n", a.scene, ct_error_message());
        ct_scene_free(sc);
        return EXIT_USAGE;
    }
    *quiet = a.quiet;
    if (realisations)
        *realisations = a.realisations;
    return -1;
}

/* The scene's surface as a bundle of rods. Each kind of surface (src/surface/) has its
 * builder; the library plans (depth, and which rods no impact of the scene can reach).
 * keep_all: leave out nothing (the profile shows the whole surface). */
static int build_surface(const ct_scene *sc, int keep_all, ct_bundle **b, ct_plan_info *info)
{
    switch (sc->surface_type) {
    case CT_SURFACE_RANDOM_CANTOR: /* one realisation (src/cli/ensemble.c): nothing left out */
        return ct_cli_random_surface(sc, b, info);
    case CT_SURFACE_PROFILE: /* measured (src/cli/measured.c), read by ct_cli_profile_prepare */
        (void)keep_all;
        return ct_cli_profile_bundle(sc, b, info);
    case CT_SURFACE_CANTOR:
    default: {
        ct_cantor_plan plan = {
            .params = sc->params,
            .depth = sc->depth,
            .representation = sc->representation,
            .depth_tolerance = sc->depth_tolerance,
            .V_star = sc->V_star,
            .nvel = sc->nvel,
            .impacts = sc->impacts,
            .opts = sc->opts,
            .keep_all_rods = keep_all,
            .threads = sc->threads,
        };
        return ct_cantor_plan_build(&plan, b, info);
    }
    }
}

/* What the run writes while the sweep goes: curve branches and, after the last impact of
 * the last speed, the profile of the surface in that state. */
typedef struct {
    const ct_scene *sc;
    FILE *curve, *profile, *history;
    int compare;
    ct_curve *post; /* the post-impact state's curve (the unloading branch) */
    char err[300];
} run_observer;

static int observe(const ct_sweep_row *row, int phase, const ct_bundle *b, const ct_curve *c,
                   void *ctx)
{
    run_observer *o = ctx;
    const ct_scene *sc = o->sc;
    const ct_params *p = &sc->params;
    int st = CT_OK;
    if (phase == 0 && o->history && (st = ct_cli_history_rows(o->history, sc, row, b)))
        return st;
    if (phase == 0 && o->curve)
        st = write_branch(o->curve, c, p, row->V_star, row->impact, row->r.u_contact, row->r.u_max,
                          "load", o->compare);
    if (phase == 1 && o->curve && !(st = ct_curve_build(o->post, b)))
        st = write_branch(o->curve, o->post, p, row->V_star, row->impact, row->r.u_release,
                          row->r.u_max, "unload", o->compare);
    if (phase == 1 && o->profile && row->speed + 1 == sc->nvel && row->impact == sc->impacts)
        st = sc->surface_type == CT_SURFACE_RANDOM_CANTOR ? ct_cli_write_rod_profile(o->profile, b)
                                                          : write_profile(o->profile, b, p);
    return st;
}

static void show_progress(size_t done, size_t total, void *ctx)
{
    (void)total;
    ct_progress *prog = ctx;
    while (prog->done < done)
        ct_progress_step(prog);
}

static void write_e_row(FILE *f, const ct_scene *sc, const ct_sweep_row *row, int compare,
                        const double *fitted)
{
    const ct_params *p = &sc->params;
    const ct_impact_result *r = &row->r;
    if (row->status) {
        /* a failed impact (solver.on_error = skip): its numbers stay empty, the reason is
         * the last field */
        fprintf(f, "%ld,", row->impact);
        ct_put_double(f, row->V_star);
        fprintf(f, ",,,,,,,%s", compare ? ",,," : "");
        if (sc->what & CT_OUT_TIME)
            ct_cli_time_row(f, sc, row);
        fputs(",\"", f);
        for (const char *m = row->message; *m; m++)
            fputc(*m == '"' ? '\'' : *m, f);
        fputs("\"\n", f);
        return;
    }
    ct_put_long(f, row->impact);
    fputc(',', f);
    ct_put_double(f, row->V_star);
    put_field(f, r->u_max / p->h0);
    put_field(f, r->e);
    if (isfinite(r->e_closed)) {
        put_field(f, r->e_closed);
        fputc(',', f);
        ct_put_g3(f, r->quad_error);
    } else {
        fputs(",,", f); /* solver.check = none */
    }
    put_field(f, r->V_star_crit);
    put_field(f, r->u_release / p->h0);
    fputc(',', f);
    ct_put_long(f, r->elastic);
    if (compare && fitted) { /* a measured surface: its fitted Cantor surface and law */
        for (int q = 0; q < 3; q++) {
            if (isfinite(fitted[q]))
                put_field(f, fitted[q]);
            else
                fputc(',', f);
        }
    } else if (compare && row->impact == 1) {
        /* the paper's laws model the first impact on the virgin fractal; where a law does
         * not apply (u_max > h0, e > 1) its field stays empty */
        for (int law = CT_LAW_SERIES; law <= CT_LAW_ASYMPTOTIC_CONSISTENT; law++) {
            double um, el;
            if (ct_law_impact(p, (ct_law)law, r->kinetic_energy, &um, &el) == CT_OK)
                put_field(f, el);
            else
                fputc(',', f);
        }
    } else if (compare) {
        fputs(",,,", f);
    }
    if (sc->what & CT_OUT_TIME)
        ct_cli_time_row(f, sc, row);
    if (sc->skip_failed)
        fputc(',', f);
    fputc('\n', f);
}

/* impact.sequence = bounce: impacts at falling speeds, the state carried (src/cli/history.c). */
static int run_bounce(ct_scene *sc, int quiet)
{
    ct_out out;
    char err[512];
    ct_bundle *b = NULL;
    ct_plan_info info;
    int st;
    if (ct_out_open(&out, sc->output, err, sizeof err)) {
        fail_line(err);
        return EXIT_USAGE;
    }
    if ((st = build_surface(sc, 0, &b, &info))) {
        ct_out_abort(&out);
        fail_line(ct_error_message());
        return status_exit(st);
    }
    if (!quiet)
        fprintf(stderr, "cantact: bounce sequence on %zu rods (depth %ld), at most %ld impacts\n",
                info.rods, info.depth, sc->impacts);
    st = ct_cli_bounce(out.f, sc, b, err, sizeof err);
    ct_bundle_free(b);
    if (st) {
        ct_out_abort(&out);
        fail_line(err);
        return status_exit(st);
    }
    if (ct_out_commit(&out, err, sizeof err)) {
        fail_line(err);
        return EXIT_USAGE;
    }
    return EXIT_DONE;
}

static int cmd_run(int argc, char **argv)
{
    ct_scene sc;
    int quiet, st = CT_OK;
    const char *range = NULL;
    static char help[8192];
    snprintf(help, sizeof help, "%s%s", run_help, run_help_more);
    int rc = load_scene_args(argc, argv, "run", help, &sc, &quiet, &range);
    if (rc >= 0)
        return rc;
    if (sc.realisations) { /* an ensemble of random realisations (src/cli/ensemble.c) */
        rc = ct_cli_ensemble_run(&sc, quiet, range);
        ct_scene_free(&sc);
        return rc;
    }
    if (range || ct_mpi_size() > 1) {
        if (ct_mpi_rank() == 0)
            fail_line(range ? "--realisations: the scene has no [ensemble] realisations"
                            : "under MPI only ensembles ([ensemble] realisations) are shared "
                              "among processes");
        ct_scene_free(&sc);
        return EXIT_USAGE;
    }
    if (sc.bounce) { /* a bounce sequence: its own table */
        rc = run_bounce(&sc, quiet);
        ct_scene_free(&sc);
        return rc;
    }
    int nitems = !!(sc.what & CT_OUT_E) + !!(sc.what & CT_OUT_CURVE) +
                 !!(sc.what & CT_OUT_PROFILE) + !!(sc.what & CT_OUT_HISTORY) +
                 !!(sc.what & CT_OUT_BEARING);
    if (nitems > 1 && !strcmp(sc.output, "-")) {
        fail_line("output.what names several outputs: set output.file (or -o FILE) to a path");
        ct_scene_free(&sc);
        return EXIT_USAGE;
    }

    /* the result rows (speeds x impacts) are held in memory: refuse up front what would not
     * fit, with the figure (1e6 speeds x 1e6 impacts are allowed by the scene's ranges) */
    {
        double bytes = (double)sc.nvel * (double)sc.impacts * (double)sizeof(ct_sweep_row);
        long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
        double avail = pages > 0 && page > 0 ? (double)pages * (double)page : INFINITY;
        if (bytes > 0.9 * avail) {
            fprintf(stderr,
                    "cantact: %zu speeds x %ld impacts = %.3g result rows need %.3g GiB, more "
                    "than the %.3g GiB of memory available: split the scene\n",
                    sc.nvel, sc.impacts, (double)sc.nvel * (double)sc.impacts, bytes / 1073741824.0,
                    avail / 1073741824.0);
            ct_scene_free(&sc);
            return EXIT_FAILED;
        }
    }

    /* open every output first: an unwritable path fails before any work is done */
    ct_out out_e = {0}, out_curve = {0}, out_profile = {0}, out_history = {0}, out_bearing = {0};
    double *fitted = NULL; /* a measured surface's compare columns, 3 per row */
    ct_bundle *b = NULL;
    ct_sweep_row *rows = NULL;
    run_observer obs = {0};
    char err[512];
    int opened_e = 0, opened_c = 0, opened_p = 0, opened_h = 0, opened_b = 0;
    char *curve_path = NULL, *profile_path = NULL, *history_path = NULL, *bearing_path = NULL;
    rc = EXIT_DONE;
    if (sc.what & CT_OUT_E) {
        if (ct_out_open(&out_e, sc.output, err, sizeof err))
            goto io_fail;
        opened_e = 1;
    }
    if (sc.what & CT_OUT_CURVE) {
        curve_path = nitems > 1 ? derived_path(sc.output, "curve") : strdup(sc.output);
        if (!curve_path || ct_out_open(&out_curve, curve_path, err, sizeof err))
            goto io_fail;
        opened_c = 1;
    }
    if (sc.what & CT_OUT_PROFILE) {
        profile_path = nitems > 1 ? derived_path(sc.output, "profile") : strdup(sc.output);
        if (!profile_path || ct_out_open(&out_profile, profile_path, err, sizeof err))
            goto io_fail;
        opened_p = 1;
    }
    if (sc.what & CT_OUT_BEARING) {
        bearing_path = nitems > 1 ? derived_path(sc.output, "bearing") : strdup(sc.output);
        if (!bearing_path || ct_out_open(&out_bearing, bearing_path, err, sizeof err))
            goto io_fail;
        opened_b = 1;
    }
    if (sc.what & CT_OUT_HISTORY) {
        history_path = nitems > 1 ? derived_path(sc.output, "history") : strdup(sc.output);
        if (!history_path || ct_out_open(&out_history, history_path, err, sizeof err))
            goto io_fail;
        opened_h = 1;
    }

    ct_plan_info info;
    const int measured = sc.surface_type == CT_SURFACE_PROFILE;
    if (measured && (st = ct_cli_profile_prepare(&sc, quiet))) {
        fail_line(ct_cli_measured_message());
        rc = status_exit(st);
        goto cleanup;
    }
    if ((st = build_surface(&sc, !!(sc.what & CT_OUT_PROFILE), &b, &info)))
        goto lib_fail;
    if (opened_p && info.depth > 20) {
        snprintf(err, sizeof err,
                 "profile: depth %ld has 2^%ld pieces; the profile is written for depth <= 20 "
                 "(set surface.depth)",
                 info.depth, info.depth + 1);
        fail_line(err);
        rc = EXIT_USAGE;
        goto cleanup;
    }
    if (!quiet) {
        char how[96];
        if (sc.depth >= 0)
            snprintf(how, sizeof how, "given");
        else
            snprintf(how, sizeof how, "%s: truncation bound %.2g",
                     sc.depth == CT_DEPTH_FRACTAL ? "fractal limit" : "auto", info.bound);
        if (measured)
            fprintf(stderr, "cantact: measured surface, %zu rods, %d thread(s)\n", info.rods,
                    ct_bundle_set_threads(b, sc.threads));
        else
            fprintf(stderr,
                    "cantact: %s, depth %ld (%s), %zu rods, %zu left out as never touched, "
                    "%d thread(s)\n",
                    sc.surface_type == CT_SURFACE_RANDOM_CANTOR ? "random cantor rods"
                    : sc.representation == CT_REP_STAGES        ? "stage rods"
                                                                : "segment rods",
                    info.depth, how, info.rods, info.omitted, ct_bundle_set_threads(b, sc.threads));
    }

    int compare = !!(sc.what & CT_OUT_COMPARE);
    if (opened_e)
        fprintf(out_e.f,
                "impact,V_star,u_max_over_h0,e,e_closed_form,quadrature_error,"
                "V_star_crit,u_release_over_h0,elastic%s",
                !compare ? ""
                : sc.surface_type == CT_SURFACE_PROFILE
                    ? ",e_cantor_fit,e_asymptotic_fit,"
                      "V_star_cantor_fit"
                    : ",e_series,e_asymptotic,e_asymptotic_consistent");
    if (opened_e && (sc.what & CT_OUT_TIME))
        ct_cli_time_header(out_e.f, &sc);
    if (opened_e)
        fprintf(out_e.f, "%s\n", sc.skip_failed ? ",error" : "");
    if (opened_h)
        ct_cli_history_header(out_history.f, &sc);
    if (opened_c)
        fprintf(out_curve.f, "V_star,impact,u_over_h0,P_over_PY,branch%s\n",
                compare ? ",P_series_over_PY,P_asymptotic_over_PY,P_asymptotic_consistent_over_PY"
                        : "");
    size_t nrows = sc.nvel * (size_t)sc.impacts;
    rows = malloc(nrows * sizeof *rows);
    if (!rows) {
        st = CT_ENOMEM;
        snprintf(err, sizeof err, "%zu result rows: out of memory", nrows);
        fail_line(err);
        rc = EXIT_FAILED;
        goto cleanup;
    }
    obs.sc = &sc;
    obs.curve = opened_c ? out_curve.f : NULL;
    obs.profile = opened_p && !measured ? out_profile.f : NULL;
    obs.history = opened_h ? out_history.f : NULL;
    obs.compare = compare;
    if (opened_c && (st = ct_curve_alloc(&obs.post)))
        goto lib_fail;
    if (opened_p && !measured)
        fprintf(out_profile.f,
                "stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n");
    if (opened_p && measured)
        ct_cli_write_levelled(out_profile.f, &sc);
    ct_progress prog;
    ct_progress_start(&prog, sc.nvel);
    ct_sweep_spec spec = {
        .V_star = sc.V_star,
        .nvel = sc.nvel,
        .impacts = sc.impacts,
        .opts = sc.opts,
        .stop_on_error = !sc.skip_failed,
        .progress = show_progress,
        .progress_ctx = &prog,
        .observe = (opened_c || (opened_p && !measured) || opened_h) ? observe : NULL,
        .observe_ctx = &obs,
        .path = sc.path,
        .dynamics = !!(sc.what & CT_OUT_TIME),
    };
    st = ct_sweep(b, &spec, rows);
    ct_progress_end(&prog);
    if (st)
        goto lib_fail;
    if (measured && (st = ct_cli_profile_refit(&sc, rows, nrows, quiet)))
        goto lib_fail;
    if (opened_b && (st = ct_cli_write_bearing(out_bearing.f, &sc)))
        goto lib_fail;
    if (measured && compare) { /* the fitted Cantor surface and law beside the rods */
        if (!(fitted = malloc((nrows ? 3 * nrows : 1) * sizeof(double)))) {
            fail_line("compare: out of memory");
            rc = EXIT_FAILED;
            goto cleanup;
        }
        if (ct_cli_profile_compare(&sc, rows, nrows, fitted) && !quiet)
            fprintf(stderr, "cantact: compare: %s (its columns stay empty)\n",
                    ct_cli_measured_message());
    }
    size_t failed = 0;
    const ct_sweep_row *first_failed = NULL;
    for (size_t k = 0; k < nrows; k++) {
        if (rows[k].status == CT_OK && !(isfinite(rows[k].r.e) && isfinite(rows[k].r.u_max))) {
            snprintf(err, sizeof err, "V* = %g impact %ld: a non-finite result", rows[k].V_star,
                     rows[k].impact);
            fail_line(err);
            rc = EXIT_FAILED;
            goto cleanup;
        }
        if ((sc.what & CT_OUT_TIME) && ct_cli_time_check(&rows[k], err, sizeof err)) {
            fail_line(err); /* two computations of the rebound disagree: a defect, not a row */
            rc = EXIT_FAILED;
            goto cleanup;
        }
        if (rows[k].status && !failed++)
            first_failed = &rows[k];
        if (opened_e)
            write_e_row(out_e.f, &sc, &rows[k], compare, fitted ? fitted + 3 * k : NULL);
    }
    if (failed && !quiet)
        fprintf(stderr,
                "cantact: %zu of %zu impacts failed or not run (first: V* = %g, impact %ld: %s)\n",
                failed, nrows, first_failed->V_star, first_failed->impact, first_failed->message);
    /* all outputs land together or none does */
    ct_out *outs[5];
    size_t nouts = 0;
    if (opened_e)
        outs[nouts++] = &out_e;
    if (opened_c)
        outs[nouts++] = &out_curve;
    if (opened_p)
        outs[nouts++] = &out_profile;
    if (opened_h)
        outs[nouts++] = &out_history;
    if (opened_b)
        outs[nouts++] = &out_bearing;
    opened_e = opened_c = opened_p = opened_h = opened_b = 0; /* commit: all or none */
    if (ct_out_commit_all(outs, nouts, err, sizeof err)) {
        fail_line(err);
        rc = EXIT_USAGE;
    }
    goto cleanup;

lib_fail:
    fail_line(ct_error_message());
    rc = status_exit(st);
    goto cleanup;
io_fail:
    fail_line(err);
    rc = EXIT_USAGE;
cleanup:
    if (opened_e)
        ct_out_abort(&out_e);
    if (opened_c)
        ct_out_abort(&out_curve);
    if (opened_p)
        ct_out_abort(&out_profile);
    if (opened_h)
        ct_out_abort(&out_history);
    if (opened_b)
        ct_out_abort(&out_bearing);
    free(history_path);
    free(bearing_path);
    free(fitted);
    ct_curve_free(obs.post);
    ct_bundle_free(b);
    free(rows);
    free(curve_path);
    free(profile_path);
    ct_scene_free(&sc);
    return rc;
}

static int cmd_geometry(int argc, char **argv)
{
    ct_scene sc;
    int quiet, st;
    int rc = load_scene_args(argc, argv, "geometry", geometry_help, &sc, &quiet, NULL);
    if (rc >= 0)
        return rc;
    (void)quiet;
    const ct_params *p = &sc.params;
    long depth;
    double bound;
    if ((st = choose_depth(&sc, &depth, &bound))) {
        fail_line(ct_error_message());
        ct_scene_free(&sc);
        return status_exit(st);
    }
    printf("# fx = %g, fz = %g, H*/h0 = %g, E/sigma_y = %g\n", p->fx, p->fz, p->Hstar / p->h0,
           p->E / p->sigma_y);
    printf("# alpha = %.17g, beta = %.17g, D = %.17g, depth = %ld\n", ct_alpha(p), ct_beta(p),
           ct_dimension(p), depth);
    printf("stage,l_over_l0,h_over_h0,s_over_l0,rod_length_over_h0\n");
    long shown = depth < 60 ? depth : 60;
    for (long i = 0; i <= shown; i++) {
        double s = i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i);
        double h = ct_stage_depth(p, (double)i);
        printf("%ld,%.17g,%.17g,%.17g,%.17g\n", i, ct_stage_length(p, (double)i) / p->l0, h / p->h0,
               s / p->l0, (p->Hstar - h) / p->h0);
    }
    if (shown < depth)
        printf("# ... %ld more stages\n", depth - shown);
    ct_scene_free(&sc);
    return EXIT_DONE;
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
        int rc = cmd_run(argc - 2, argv + 2);
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
        return ct_cli_fit_main(argc - 2, argv + 2);
    fprintf(stderr, "cantact: unknown subcommand '%s' (try cantact --help)\n", cmd);
    return EXIT_USAGE;
}

int main(int argc, char **argv)
{
    int rc = dispatch(argc, argv);
    /* what went to standard output through stdio (help, geometry) must have arrived */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "cantact: standard output: write failed\n");
        return rc ? rc : EXIT_USAGE;
    }
    return rc;
}
