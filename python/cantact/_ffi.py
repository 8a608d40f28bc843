"""The C side: libcantact's declarations (cffi, ABI mode: no compiler needed) and how the
shared library is found. The declarations mirror include/cantact.h without its comments and
macros; tests/test_layout.py compares every struct's size and every field's offset with what
the C compiler makes of the header, so a field added there and not here fails the suite (add
it here: the struct in the same order)."""
import os

import cffi

CDEF = r"""
enum {
    CT_OK = 0,
    CT_EINVAL = 1,
    CT_ENOMEM = 2,
    CT_ERANGE = 3,
    CT_ENOCONV = 4,
    CT_EIO = 5,
    CT_ESKIPPED = 6,
    CT_EINTR = 7,
};
const char *ct_strerror(int status);
const char *ct_error_message(void);
typedef struct {
    double fx;
    double fz;
    double l0;
    double h0;
    double Hstar;
    double E;
    double sigma_y;
} ct_params;
int ct_params_validate(const ct_params *p);
double ct_stage_length(const ct_params *p, double i);
double ct_stage_depth(const ct_params *p, double i);
double ct_stage_area(const ct_params *p, double i);
double ct_alpha(const ct_params *p);
double ct_beta(const ct_params *p);
double ct_one_minus_beta(const ct_params *p);
double ct_dimension(const ct_params *p);
double ct_sum_area(const ct_params *p, double n1, double n2);
double ct_sum_depth_area(const ct_params *p, double n1, double n2);
int ct_piece_extent(const ct_params *p, long depth, long stage, size_t j, double *x_left,
                    double *x_right);
double ct_energy_scale(const ct_params *p);
typedef struct ct_bundle ct_bundle;
typedef struct {
    double E;
    double sigma_y;
    double Hstar;
    double l0;
    double h0;
} ct_layer;
int ct_layer_validate(const ct_layer *layer);
int ct_bundle_from_rods(ct_bundle **out, const ct_layer *layer, size_t n, const double *top,
                        const double *area);
void ct_bundle_free(ct_bundle *b);
int ct_bundle_clone(ct_bundle **out, const ct_bundle *b);
void ct_bundle_reset(ct_bundle *b);
size_t ct_bundle_size(const ct_bundle *b);
size_t ct_bundle_omitted(const ct_bundle *b);
const ct_layer *ct_bundle_layer(const ct_bundle *b);
const char *ct_bundle_surface(const ct_bundle *b);
typedef struct {
    int shape;
    double x_lo, x_hi, y_lo, y_hi;
} ct_footprint;
typedef struct {
    double top, length, area, plastic_strain;
    double x_left, x_right;
    long stage;
    ct_footprint footprint;
} ct_rod_info;
int ct_bundle_rod(const ct_bundle *b, size_t k, ct_rod_info *info);
int ct_bundle_set_threads(ct_bundle *b, int threads);
int ct_default_threads(void);
double ct_bundle_force(const ct_bundle *b, double u);
int ct_bundle_force_many(const ct_bundle *b, const double *u, size_t m, double *P);
int ct_bundle_force_after(const ct_bundle *b, double u_adv, const double *u, size_t m, double *P);
int ct_bundle_work_many(const ct_bundle *b, double u_a, const double *u_b, size_t m, double *W);
double ct_bundle_work(const ct_bundle *b, double u_a, double u_b);
double ct_bundle_elastic_energy(const ct_bundle *b, double u);
double ct_bundle_first_contact(const ct_bundle *b);
double ct_bundle_release(const ct_bundle *b, double u_adv);
double ct_bundle_first_yield(const ct_bundle *b);
void ct_bundle_advance(ct_bundle *b, double u);
typedef struct ct_curve ct_curve;
int ct_curve_alloc(ct_curve **out);
void ct_curve_free(ct_curve *c);
int ct_curve_build(ct_curve *c, const ct_bundle *b);
size_t ct_curve_size(const ct_curve *c);
const double *ct_curve_points(const ct_curve *c);
double ct_curve_first_contact(const ct_curve *c);
double ct_curve_first_yield(const ct_curve *c);
double ct_curve_force(const ct_curve *c, double u);
double ct_curve_work(const ct_curve *c, double u);
double ct_curve_dissipation(const ct_curve *c, double u);
double ct_curve_release(const ct_curve *c, double u);
double ct_curve_inverse_work(const ct_curve *c, double W);
typedef enum {
    CT_QUAD_BREAKPOINTS = 0,
    CT_QUAD_TRAPEZOID = 1,
    CT_QUAD_SIMPSON = 2,
    CT_QUAD_GAUSS = 3,
    CT_QUAD_CLOSED = 4,
} ct_quad_rule;
typedef double (*ct_function)(double x, void *ctx);
int ct_integrate(ct_function f, void *ctx, double a, double b, ct_quad_rule rule, size_t nodes,
                 const double *points, size_t npoints, double *result, double *abserr);
typedef int (*ct_batch_function)(const double *x, size_t m, double *y, void *ctx);
int ct_integrate_batch(ct_batch_function f, void *ctx, double a, double b, ct_quad_rule rule,
                       size_t nodes, const double *points, size_t npoints, double *result,
                       double *abserr);
const char *ct_quad_rule_name(ct_quad_rule rule);
typedef struct {
    ct_quad_rule rule;
    size_t nodes;
    double tolerance;
    int check;
} ct_impact_opts;
typedef struct {
    double kinetic_energy;
    double V_star;
    double u_contact;
    double u_max;
    double u_release;
    double W_load;
    double W_unload;
    double W_load_closed;
    double W_unload_closed;
    double e;
    double e_closed;
    double quad_error;
    double e_rounding;
    double V_star_crit;
    int elastic;
} ct_impact_result;
typedef struct {
    double t_contact;
    double t_load;
    double t_unload;
    double P_peak;
    double v1, v2;
    double e_kinematic;
    double dissipated;
    double k_unload_max;
    double period_min;
} ct_dynamics;
void ct_impact_opts_default(ct_impact_opts *opts);
int ct_critical_energy(const ct_bundle *b, double *energy, double *u_yield);
int ct_impact(ct_bundle *b, double W, const ct_impact_opts *opts, ct_impact_result *res);
int ct_impact_eval(const ct_bundle *b, const ct_curve *c, double W, const ct_impact_opts *opts,
                   ct_impact_result *res);
int ct_solve_umax(const ct_bundle *b, double W, double tolerance, double *u_max);
typedef enum {
    CT_REP_STAGES = 0,
    CT_REP_SEGMENTS = 1,
} ct_representation;
void ct_cantor_layer(const ct_params *p, ct_layer *layer);
int ct_cantor_bundle(ct_bundle **out, const ct_params *p, ct_representation rep, long depth,
                     double u_reach);
long ct_cantor_depth(const ct_bundle *b);
int ct_cantor_representation(const ct_bundle *b);
typedef struct {
    ct_params params;
    long depth;
    ct_representation representation;
    double depth_tolerance;
    const double *V_star;
    size_t nvel;
    long impacts;
    ct_impact_opts opts;
    int keep_all_rods;
    int threads;
} ct_cantor_plan;
typedef struct {
    long depth;
    double bound;
    size_t rods;
    size_t omitted;
    double u_reach;
} ct_plan_info;
int ct_cantor_plan_build(const ct_cantor_plan *plan, ct_bundle **out, ct_plan_info *info);
typedef struct {
    size_t speed;
    long impact;
    double V_star;
    int status;
    union {
        char message[240];
        struct {
            char message_head[8];
            ct_impact_result r;
            ct_dynamics dyn;
        };
    };
} ct_sweep_row;
typedef void (*ct_progress_fn)(size_t done, size_t total, void *ctx);
typedef int (*ct_observer_fn)(const ct_sweep_row *row, int phase, const ct_bundle *b,
                              const ct_curve *c, void *ctx);
typedef enum { CT_PATH_AUTO = 0, CT_PATH_CURVE = 1, CT_PATH_RODS = 2, CT_PATH_LEAN = 3 } ct_sweep_path;
typedef struct {
    const double *V_star;
    size_t nvel;
    long impacts;
    ct_impact_opts opts;
    int stop_on_error;
    ct_progress_fn progress;
    void *progress_ctx;
    ct_observer_fn observe;
    void *observe_ctx;
    ct_sweep_path path;
    ct_curve *curve;
    int dynamics;
    const volatile int *interrupt;
} ct_sweep_spec;
int ct_sweep(const ct_bundle *b, const ct_sweep_spec *spec, ct_sweep_row *rows);
int ct_series_load(const ct_params *p, double u, double *P);
int ct_series_unload(const ct_params *p, double u_max, double u, double *P);
int ct_asym_load(const ct_params *p, double u, double *P);
int ct_asym_unload(const ct_params *p, double u_max, double u, int consistent, double *P);
int ct_asym_work_load(const ct_params *p, double u, double *W);
int ct_asym_work_unload(const ct_params *p, double u_max, int consistent, double *W);
typedef enum { CT_LAW_SERIES = 0, CT_LAW_ASYMPTOTIC = 1, CT_LAW_ASYMPTOTIC_CONSISTENT = 2 } ct_law;
int ct_law_impact(const ct_params *p, ct_law law, double W, double *u_max, double *e);
const char *ct_law_name(ct_law law);
typedef enum {
    CT_RATIO_UNIFORM = 0,
    CT_RATIO_LOGNORMAL = 1,
} ct_ratio_dist;
typedef struct {
    ct_params params;
    ct_ratio_dist dist;
    double fx_spread;
    double fz_spread;
    long depth;
    uint64_t seed;
} ct_random_cantor;
int ct_random_cantor_validate(const ct_random_cantor *rc);
int ct_random_cantor_ratios(const ct_random_cantor *rc, uint64_t realisation, uint64_t g,
                            double *fx_k, double *fz_k, int *clipped);
int ct_random_cantor_bundle(ct_bundle **out, const ct_random_cantor *rc, uint64_t realisation,
                            int threads);
int ct_random_cantor_piece(const ct_bundle *b, size_t k, uint64_t *g);
int ct_random_cantor_clipped(const ct_bundle *b, uint64_t *fx_clipped, uint64_t *fz_clipped,
                             uint64_t *draws);
typedef enum {
    CT_SPLIT_AUTO = 0,
    CT_SPLIT_REALISATIONS = 1,
    CT_SPLIT_RODS = 2,
} ct_ensemble_split;
typedef struct {
    ct_layer layer;
    ct_layer physical;
    double force_unit;
    double energy_unit;
    double energy_scale;
    double physical_energy_scale;
} ct_scales;
typedef struct {
    int shape;
    double radius;
    double position[2];
    int periodic;
    uint64_t landings;
    uint64_t seed;
} ct_body;
typedef struct {
    ct_random_cantor surface;
    uint64_t first;
    uint64_t count;
    const double *V_star;
    size_t nvel;
    long impacts;
    ct_impact_opts opts;
    ct_sweep_path path;
    int stop_on_error;
    int threads;
    ct_ensemble_split split;
    ct_progress_fn progress;
    void *progress_ctx;
    const volatile int *interrupt;
    const ct_body *body;
    ct_scales scales;
    const ct_bundle *rods;
} ct_ensemble_spec;
typedef struct {
    uint64_t first, count;
    size_t nrows;
    double *e, *u_max, *V_star_crit;
    int *status;
    uint64_t *fx_clipped, *fz_clipped;
    double *x, *y;
    uint64_t draws;
    double quad_error_max;
    uint64_t failed_realisation;
    size_t failed_row;
    char message[240];
} ct_ensemble_samples;
int ct_ensemble_samples_alloc(ct_ensemble_samples **out, uint64_t first, uint64_t count,
                              size_t nrows);
void ct_ensemble_samples_free(ct_ensemble_samples *s);
int ct_ensemble(const ct_ensemble_spec *spec, ct_ensemble_samples *samples);
typedef struct {
    size_t n;
    double mean;
    double sd;
    double sem;
    double q05, q50, q95;
} ct_stats;
int ct_sample_stats(const double *x, size_t n, size_t stride, double *work, ct_stats *out);
double ct_quantile_sorted(const double *sorted, size_t n, double p);
typedef enum {
    CT_INTERP_MONOTONE_CUBIC = 0,
    CT_INTERP_LINEAR = 1,
} ct_interp;
const char *ct_interp_name(ct_interp rule);
typedef struct {
    double V_min, V_max;
    double tolerance;
    ct_interp interpolation;
    size_t max_nodes;
    size_t check_points;
    ct_impact_opts opts;
    ct_sweep_path path;
    ct_progress_fn progress;
    void *progress_ctx;
    const volatile int *interrupt;
} ct_table_spec;
void ct_table_spec_default(ct_table_spec *spec);
typedef struct ct_table ct_table;
typedef struct {
    double V_star_crit;
    double worst_error;
    double worst_V_star;
    size_t checked;
    size_t kinks;
    size_t rounds;
    size_t evaluations;
} ct_table_info;
int ct_table_build(ct_table **out, const ct_bundle *b, const ct_table_spec *spec);
int ct_table_from_nodes(ct_table **out, size_t n, const double *V_star, const double *e,
                        const double *slope, ct_interp rule, double V_star_crit);
void ct_table_free(ct_table *t);
size_t ct_table_size(const ct_table *t);
const double *ct_table_V_star(const ct_table *t);
const double *ct_table_e(const ct_table *t);
const double *ct_table_slope(const ct_table *t);
ct_interp ct_table_interpolation(const ct_table *t);
void ct_table_get_info(const ct_table *t, ct_table_info *info);
size_t ct_table_quantile_count(const ct_table *t);
const double *ct_table_p(const ct_table *t);
const double *ct_table_e_quantile(const ct_table *t, size_t j);
const double *ct_table_slope_quantile(const ct_table *t, size_t j);
uint64_t ct_table_samples(const ct_table *t);
double ct_table_eval_quantile(const ct_table *t, double V_star, double p);
double ct_table_eval(const ct_table *t, double V_star);
void ct_pchip_slopes(size_t n, const double *x, const double *y, double *d);
typedef struct {
    double tolerance;
    double worst_error;
    double worst_V_star;
    double v_per_V_star;
} ct_table_file_info;
int ct_table_read(ct_table **out, const char *path, ct_table_file_info *file);
typedef struct {
    size_t n;
    size_t nx, ny;
    double *x;
    double *z;
    double dx, dy;
    size_t invalid;
    char source[128];
    double x_unit, z_unit;
} ct_profile;
typedef enum {
    CT_DETREND_NONE = 0,
    CT_DETREND_MEAN = 1,
    CT_DETREND_LINEAR = 2,
    CT_DETREND_QUADRATIC = 3,
} ct_detrend;
typedef struct {
    double x_unit, z_unit;
    double dx;
} ct_profile_read_opts;
int ct_profile_read(const char *path, const ct_profile_read_opts *opts, ct_profile **out);
int ct_profile_from_line(ct_profile **out, size_t n, const double *x, double dx, const double *z);
int ct_profile_from_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy,
                         const double *z);
void ct_profile_free(ct_profile *p);
int ct_profile_level(ct_profile *p, ct_detrend how);
int ct_profile_trim(ct_profile *p, double k, size_t *clipped);
typedef struct {
    double mean, Ra, Rq;
    double Rt;
    double length;
} ct_profile_stats;
int ct_profile_stats_of(const ct_profile *p, ct_profile_stats *s);
int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar);
int ct_profile_bearing(const ct_profile *p, size_t n, const double *d, double *phi);
typedef struct {
    double lo, hi;
    size_t n;
    double slope, intercept, r2, residual;
} ct_fit_line;
typedef enum {
    CT_DIM_VARIATION = 0,
    CT_DIM_STRUCTURE = 1,
    CT_DIM_SPECTRUM = 2,
} ct_dimension_method;
typedef struct {
    ct_dimension_method dimension;
    ct_fit_line bearing;
    double alpha, h0;
    ct_fit_line variation;
    ct_fit_line structure;
    ct_fit_line spectrum;
    double D_variation, D_structure, D_spectrum;
    double D;
    double fx, fz, l0;
    ct_profile_stats stats;
} ct_profile_fit;
int ct_profile_fit_of(const ct_profile *p, double d_lo, double d_hi, double tau_lo, double tau_hi,
                      ct_profile_fit *fit);
int ct_profile_fit_bearing(const ct_profile *p, double d_lo, double d_hi, ct_profile_fit *fit);
int ct_profile_fit_on_reach(const ct_profile *p, const ct_profile_fit *fit, const double *u_max,
                            size_t n, ct_profile_fit *out);
int ct_profile_fitted_e(const ct_profile *p, const ct_profile_fit *fit, const ct_layer *layer,
                        const double *W, size_t n, int threads, double *e_fit, double *e_asym,
                        double *V_fit);
typedef enum {
    CT_UNIT_ONE = 0,
    CT_UNIT_LENGTH = 1,
    CT_UNIT_FORCE = 2,
    CT_UNIT_ENERGY = 3,
    CT_UNIT_TIME = 4,
    CT_UNIT_COUNT = 5,
    CT_UNIT_SPEED = 6,
} ct_unit;
typedef struct {
    const char *name;
    const char *group;
    ct_unit unit;
    char type;
    int digits;
    const char *physical;
    double divisor;
    size_t offset;
    const char *doc;
} ct_column;
size_t ct_sweep_columns(const ct_column **cols);
double ct_column_value(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer);
void ct_column_values(const ct_column *c, const ct_sweep_row *rows, size_t n, const ct_layer *layer,
                      double *out);
typedef enum {
    CT_KEY_NUMBER = 0,
    CT_KEY_INTEGER,
    CT_KEY_COUNT,
    CT_KEY_WORD,
    CT_KEY_WORDS,
    CT_KEY_TEXT,
    CT_KEY_DEPTH,
    CT_KEY_SPEEDS,
    CT_KEY_RANGE,
    CT_KEY_POINT,
} ct_key_type;
enum {
    CT_KEY_LO_CLOSED = 1,
    CT_KEY_HI_CLOSED = 2,
    CT_KEY_REQUIRED = 4,
    CT_KEY_FILE = 8,
};
typedef struct {
    const char *section;
    const char *name;
    ct_key_type type;
    double lo, hi;
    unsigned flags;
    const char *words;
    const char *range;
    const char *def;
    const char *doc;
    size_t offset;
} ct_key;
typedef struct {
    double *v;
    size_t n;
} ct_speeds;
int ct_key_parse(const ct_key *row, const char *text, void *settings);
void ct_key_describe(const ct_key *row, char *buf, size_t len);
void ct_key_clear(const ct_key *row, void *settings);
int ct_word_index(const char *words, const char *word);
typedef struct {
    ct_speeds V_star, velocity;
    double mass, drop_height, gravity, stop_speed;
    long impacts;
    int sequence;
    int quadrature;
    long nodes;
    double tolerance, depth_tolerance;
    long threads;
    int on_error, check, path;
    double table_tolerance, table_range[2];
    int interpolation;
    long max_nodes, check_points;
    long realisations;
    int split;
    ct_speeds table_quantiles;
    long table_grid;
    double table_quantile_tolerance;
} ct_run_keys;
const ct_key *ct_run_keys_table(size_t *n);
void ct_run_keys_defaults(ct_run_keys *k);
void ct_run_keys_clear(ct_run_keys *k);
typedef struct {
    ct_impact_opts opts;
    ct_sweep_path path;
    int threads;
    int skip_failed;
    double depth_tolerance;
} ct_run_solver;
int ct_run_keys_solver(const ct_run_keys *k, ct_run_solver *out);
typedef struct ct_surface ct_surface;
size_t ct_surface_kind_count(void);
const char *ct_surface_kind_name(size_t k);
const char *ct_surface_kind_summary(size_t k);
const ct_key *ct_surface_kind_keys(size_t k, size_t *n);
int ct_surface_kind_supports(size_t k, const char *output, const char **why);
int ct_surface_new(ct_surface **out, const char *kind);
void ct_surface_free(ct_surface *s);
size_t ct_surface_kind_index(const ct_surface *s);
const char *ct_surface_kind(const ct_surface *s);
const ct_key *ct_surface_key(const ct_surface *s, const char *section, const char *name);
int ct_surface_set(ct_surface *s, const char *section, const char *name, const char *value,
                   const char *where);
int ct_surface_value(const ct_surface *s, const char *section, const char *name, double *out);
int ct_surface_is_set(const ct_surface *s, const char *section, const char *name);
int ct_surface_check(ct_surface *s, const char *scene);
int ct_surface_prepare(ct_surface *s, const char *dir);
void ct_surface_scales(const ct_surface *s, ct_scales *out);
double ct_V_star_of(double m, double v, double l0, double E, double h0);
double ct_time_scale(const ct_scales *sc, double m);
size_t ct_body_count(void);
const char *ct_body_name(size_t k);
const char *ct_body_summary(size_t k);
void ct_body_defaults(ct_body *body);
const ct_key *ct_body_keys_table(size_t *n);
void ct_body_describe(const ct_body *body, char *buf, size_t len);
double ct_body_gap(const ct_body *body, double r);
typedef struct {
    const double *V_star;
    size_t nvel;
    long impacts;
    ct_impact_opts opts;
    int keep_all_rods;
    int threads;
    double depth_tolerance;
    const ct_body *body;
} ct_build_request;
int ct_surface_build_unmet(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                           ct_plan_info *info);
int ct_body_landing_region(const ct_body *body, const ct_scales *scales, const ct_bundle *rods,
                           double lo[2], double hi[2]);
void ct_body_landing(const double lo[2], const double hi[2], uint64_t seed, uint64_t k,
                     double pos[2]);
int ct_surface_build(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                     ct_plan_info *info);
int ct_surface_set_rods(ct_surface *s, size_t n, const double *top, const double *area,
                        const double *length);
int ct_surface_set_rods_at(ct_surface *s, size_t n, const double *top, const double *area,
                           const double *length, const double *x, const double *y);
const char *ct_surface_note(ct_surface *s);
int ct_surface_random_cantor(const ct_surface *s, ct_random_cantor *rc, uint64_t *realisation);
int ct_surface_profile(const ct_surface *s, const ct_profile **p, ct_profile_fit *fit);
"""

ffi = cffi.FFI()
ffi.cdef(CDEF)

# The header's macros (cffi's cdef takes no expressions)
CT_DEPTH_AUTO = -1
CT_DEPTH_FRACTAL = -2
CT_MAX_STAGES_DEPTH = 100000000
CT_MAX_SEGMENTS_DEPTH = 40
CT_MAX_RANDOM_DEPTH = 30
CT_MAX_THREADS = 1024


def _candidates():
    """Where libcantact.so.0 may be, in order: $CANTACT_LIBRARY (a path: the build tree's
    tests set it); installed, the path meson wrote in _config (relative to this package: the
    prefix's libdir, or the library inside the package of a pip install); in the source tree
    (no _config), the build directory build/ beside python/; then the dynamic loader's search."""
    env = os.environ.get("CANTACT_LIBRARY")
    if env:
        yield env
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        from . import _config  # written by meson at install time
    except ImportError:
        _config = None
    if _config is not None:
        if _config.LIBRARY:
            yield os.path.normpath(os.path.join(here, _config.LIBRARY))
    else:
        yield os.path.join(os.path.dirname(os.path.dirname(here)), "build", "libcantact.so.0")
    yield "libcantact.so.0"


# Loaded never to be unloaded (RTLD_NODELETE): cffi closes the library when its handle is
# collected, at the latest when Python exits, and that would unmap libcantact and the OpenMP
# runtime it brings while the runtime's worker threads still run (spinning between parallel
# regions, e.g. under OMP_WAIT_POLICY=ACTIVE): they crash in unmapped code and the process
# dies with SIGSEGV after its work is done. python/tests/test_exit.py runs such processes.
DLOPEN_FLAGS = ffi.RTLD_NOW | ffi.RTLD_NODELETE


def _load():
    errors = []
    for path in _candidates():
        try:
            return ffi.dlopen(path, DLOPEN_FLAGS), path
        except OSError as exc:
            errors.append(f"{path}: {exc}")
        if path == os.environ.get("CANTACT_LIBRARY"):
            break  # an explicit path that fails is an error, not a hint
    raise ImportError(
        "cantact: libcantact.so.0 not found (set CANTACT_LIBRARY to its path, or install "
        "cantact: pip install . or meson install): " + "; ".join(errors)
    )


lib, LIBRARY_PATH = _load()
