/* Scene files (INI, parsed with inih): the CLI's input. The library never sees INI. */
#ifndef CT_CLI_SCENE_H
#define CT_CLI_SCENE_H

#include "cantact.h"

#define CT_MAX_VELOCITIES 1000000

enum { CT_OUT_E = 1, CT_OUT_CURVE = 2, CT_OUT_PROFILE = 4, CT_OUT_COMPARE = 8 };
/* [ensemble] outputs (src/cli/ensemble.c) */
enum { CT_OUT_ENSEMBLE = 16, CT_OUT_REALISATIONS = 32 };
/* the impact in time: columns of the e table, histories, a bounce sequence */
enum { CT_OUT_TIME = 64, CT_OUT_HISTORY = 128, CT_OUT_BOUNCE = 256 };
/* a measured surface: its bearing-area curve against the fitted one */
enum { CT_OUT_BEARING = 512 };

/* [surface] type: which kind of surface makes the rods (src/surface/). */
typedef enum {
    CT_SURFACE_CANTOR = 0,
    CT_SURFACE_RANDOM_CANTOR = 1,
    CT_SURFACE_PROFILE = 2 /* a measured line profile or areal topography */
} ct_surface_type;

typedef struct {
    ct_surface_type surface_type;
    ct_params params;   /* as given; the CLI computes a Cantor scene in dimensionless form */
    ct_params physical; /* the parameters as given, once the CLI made params dimensionless */
    long depth;         /* >= 0, CT_DEPTH_AUTO or CT_DEPTH_FRACTAL */
    ct_representation representation;
    double *V_star; /* velocities, dimensionless, in input order */
    size_t nvel;
    long impacts; /* impacts per velocity, >= 1 */
    ct_impact_opts opts;
    double depth_tolerance; /* relative tolerance of depth auto */
    int threads;            /* 0: OpenMP default */
    int skip_failed;        /* solver.on_error = skip: a failed impact is a row, not the end */
    ct_sweep_path path;     /* solver.path: auto, curve or rods */
    char *output;           /* CSV path, "-" for stdout */
    unsigned what;          /* CT_OUT_* bits */
    double mass;            /* [impact] mass per unit depth (0: the scene gave V*) */
    /* type = profile (src/cli/measured.c) */
    char *profile_file;             /* [surface] file */
    ct_profile_read_opts read_opts; /* units [m / file unit], spacing */
    ct_detrend detrend;             /* [surface] detrend (default linear) */
    double trim_k;                  /* [surface] trim = rq: clip at mean + trim_k Rq; 0: none */
    double Hstar_given;             /* [surface] Hstar [file z unit, as m after units]; 0: H * Rt */
    double H_over_Rt;               /* [surface] H: H* as a multiple of the peak-to-valley depth */
    int speeds_are_velocities;      /* V_star holds velocities until the profile gives l0, h0 */
    ct_dimension_method fit_dimension; /* [fit] dimension: the estimator D comes from */
    double fit_band[4];        /* [fit] depth_lo depth_hi lag_lo lag_hi [m]; 0: the default */
    ct_profile *profile;       /* the levelled profile, once read (ct_cli_profile_prepare) */
    ct_profile_fit fit;        /* its Cantor fit (have_fit) */
    int fit_band_from_impacts; /* the bearing fit is on the depths the impacts reached */
    int have_fit;
    char *scene_dir;       /* the scene file's directory with its '/' (NULL: stdin, cwd) */
    int bounce;            /* [impact] sequence = bounce */
    double gravity;        /* [impact] gravity [length/time^2] (bounce flights, drop_height) */
    double stop_speed;     /* [impact] stop_speed: a bounce sequence ends below it */
    size_t history_points; /* [output] history_points: uniform grid points per impact */
    /* type = random_cantor (params.fx, fz are the centres) and [ensemble] */
    ct_ratio_dist ratio_dist;
    double fx_spread, fz_spread;
    uint64_t seed;
    uint64_t realisation;    /* the one realisation of a run without [ensemble] */
    uint64_t realisations;   /* [ensemble] realisations; 0: no ensemble */
    ct_ensemble_split split; /* [ensemble] split */
    /* [table] (cantact table, src/cli/table.c) */
    double table_tolerance;          /* largest |e_table - e|, absolute */
    double table_V_min, table_V_max; /* the table's V* range */
    ct_interp table_interpolation;
    long table_max_nodes, table_check_points;
} ct_scene;

/* The scene's random Cantor surface (type = random_cantor). */
void ct_scene_random_cantor(const ct_scene *scene, ct_random_cantor *rc);

/* Reads a scene file, then applies overrides "section.key=value"; on error returns
 * CT_EINVAL (or CT_EIO) with "file:line: section.key = value: reason" in ct_scene_message(). */
int ct_scene_load(ct_scene *scene, const char *path, const char *const *overrides,
                  size_t noverrides);
/* Same from a string (name is used in messages). */
int ct_scene_parse(ct_scene *scene, const char *name, const char *text,
                   const char *const *overrides, size_t noverrides);
void ct_scene_free(ct_scene *scene);
/* The model depends on its dimensionless groups alone (MODEL.md §1): a (random) Cantor scene
 * is computed with l0 = h0 = sigma_y = 1, H* = H* / h0 and E = E / sigma_y, whatever its scale
 * (an l0 of 1e200 or a sigma_y of 1e-250 would otherwise leave the range of doubles); its
 * outputs are dimensionless already. The values as given stay in scene->physical. */
void ct_scene_make_dimensionless(ct_scene *scene);
/* Returns the message of the last scene error in this thread. */
const char *ct_scene_message(void);

/* The ct_dimension_method named variation, structure or spectrum; -1 for another name. */
int ct_scene_dimension_of(const char *name);

#endif
