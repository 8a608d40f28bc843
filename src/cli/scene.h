/* Scene files (INI, parsed with inih): the CLI's input. The keys are rows of tables: the
 * CLI's own sections here (src/cli/scene.c) and each kind of surface's keys in the library
 * (ct_surface_kind_keys); the library never sees INI. */
#ifndef CT_CLI_SCENE_H
#define CT_CLI_SCENE_H

#include "cantact.h"

/* [output] what: bit k is word k of CT_OUTPUT_WORDS */
#define CT_OUTPUT_WORDS                                                                            \
    "e|curve|profile|compare|ensemble|realisations|time|history|bounce|bearing|landings"
#define CT_OUTPUT_NWORDS 11
enum { CT_OUT_E = 1, CT_OUT_CURVE = 2, CT_OUT_PROFILE = 4, CT_OUT_COMPARE = 8 };
enum { CT_OUT_ENSEMBLE = 16, CT_OUT_REALISATIONS = 32 };
enum { CT_OUT_TIME = 64, CT_OUT_HISTORY = 128, CT_OUT_BOUNCE = 256 };
enum { CT_OUT_BEARING = 512, CT_OUT_LANDINGS = 1024 };

/* The values of the scene's keys that are not the surface's: the library's run keys
 * (ct_run_keys_table) first, so that their rows' offsets point here too, then the CLI's own. */
typedef struct {
    ct_run_keys run;
    char *type;
    char *file;
    unsigned what;
    long history_points;
} ct_scene_keys;

typedef struct {
    ct_surface *surface; /* its kind and keys; prepared by ct_scene_prepare */
    ct_scales scales;    /* the surface's units, once prepared */
    double *V_star;      /* speeds, dimensionless once prepared (velocities before), input order */
    size_t nvel;
    long impacts; /* impacts per speed, >= 1 */
    ct_impact_opts opts;
    double depth_tolerance;    /* relative tolerance of depth auto */
    int threads;               /* 0: OpenMP default */
    int skip_failed;           /* solver.on_error = skip: a failed impact is a row, not the end */
    ct_sweep_path path;        /* solver.path: auto, curve or rods */
    char *output;              /* CSV path, "-" for stdout */
    unsigned what;             /* CT_OUT_* bits */
    int what_given;            /* output.what was set */
    int areal;                 /* the rods built stand on a plane (a force is in N, not N/m) */
    double mass;               /* [impact] mass per unit depth (0: the scene gave V*) */
    int speeds_are_velocities; /* V_star holds velocities until ct_scene_prepare */
    char *scene_dir;           /* the scene file's directory with its '/' (NULL: stdin, cwd) */
    int bounce;                /* [impact] sequence = bounce */
    double gravity;            /* [impact] gravity [length/time^2] */
    double stop_speed;         /* [impact] stop_speed: a bounce sequence ends below it */
    size_t history_points;     /* [output] history_points */
    uint64_t realisations;     /* [ensemble] realisations; 0: no ensemble */
    ct_ensemble_split split;
    /* [table] (cantact table) */
    double table_tolerance;
    double table_V_min, table_V_max; /* 0: the range of the speeds */
    ct_interp table_interpolation;
    long table_max_nodes, table_check_points;
    double table_p[CT_TABLE_MAX_QUANTILES]; /* a table of samples: its probabilities */
    size_t table_np;
    long table_grid;
    double table_qtol; /* 0: table_tolerance */
    ct_body body;      /* [body]: what strikes the rods (flat by default) */
    char *inputs[8];   /* the files this run reads: the scene, the surface's files */
    const char *input_what[8];
    size_t ninputs;
    char name[300];         /* the scene's name in messages */
    char where_speeds[300]; /* where the speeds were given, for messages */
    const char *speeds_key; /* "V_star" or "velocity" */
} ct_scene;

/* Reads a scene file, then applies overrides "section.key=value"; on error returns
 * CT_EINVAL (or CT_EIO) with "file:line: section.key = value: reason" in ct_scene_message(). */
int ct_scene_load(ct_scene *scene, const char *path, const char *const *overrides,
                  size_t noverrides);
/* Same from a string (name is used in messages). */
int ct_scene_parse(ct_scene *scene, const char *name, const char *text,
                   const char *const *overrides, size_t noverrides);
/* Reads what the surface needs (files beside the scene), fixes its scales, turns mass and
 * velocity into V* and checks that every impact energy is a number, and makes ready what
 * each output asked for needs (refusing outputs the surface's kind does not give). */
int ct_scene_prepare(ct_scene *scene);
void ct_scene_free(ct_scene *scene);
/* Returns the message of the last scene error in this thread. */
const char *ct_scene_message(void);
/* Row i of the scene's keys that are not the surface's, in section order (surface.type, then
 * body, impact, solver, output, table, ensemble): the library's body and run keys and the
 * CLI's output keys. NULL past the last. */
const ct_key *ct_scene_key_row(size_t i);
/* The build request of a scene for its speeds (keep_all: the whole surface is written). */
void ct_scene_request(const ct_scene *sc, int keep_all, ct_build_request *req);

#endif
