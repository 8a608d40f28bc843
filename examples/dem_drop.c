/* A minimal DEM loop: a sphere dropped on a flat wall, with a linear spring-dashpot normal
 * contact whose damping is set, per contact, from e(v_impact) of a cantact table.
 *
 * Build: cc -O2 dem_drop.c -lm -I/path/to/include   (cantact_table.h only: no libcantact)
 * Usage: dem_drop TABLE.csv [--height H] [--speed V0] [--gravity G] [--bounces N]
 *                 [--v-per-V-star S] [--steps-per-contact K] [--law tension|clipped]
 *                 [--check TOL]     (dem_drop --help: the options and their defaults)
 *
 * The contact, per contact (the three lines a DEM code needs, marked below):
 *   at first touch, with the normal approach speed v_impact:
 *     e    = ct_tab_e_of_speed(&table, v_impact)   (the table's e(V*), V* = v / S)
 *     zeta = ct_tab_zeta_of_e(e, law)              (the linear spring-dashpot's damping ratio
 *                                                   that rebounds with e under the law)
 *     c_n  = 2 zeta sqrt(m_eff k_n)
 *   then F_n = k_n delta + c_n d(delta)/dt (delta: the overlap) until the contact ends:
 *     --law tension (the default): F_n may pull; the contact ends at delta = 0, and without
 *       gravity the sphere leaves with e v_impact exactly for zeta = -ln e / sqrt(pi^2 +
 *       ln^2 e) (the inverse of e = exp(-pi zeta / sqrt(1 - zeta^2)));
 *     --law clipped: F_n = max(0, ...) as in Yade (Law2_ScGeom_ViscElPhys_Basic) or LAMMPS
 *       (limit_damping): the sphere separates when k_n delta + c_n d(delta)/dt reaches 0,
 *       with delta still > 0, and flies out of the overlap freely; without gravity it leaves
 *       with e v_impact for the zeta of e = exp(-2 zeta h(zeta)) (cantact_table.h's top).
 *   Each law needs its own relation: the tension one's zeta under the clipped law rebounds
 *   faster (e too high), the clipped one's under tension slower.
 *
 * The loop: fixed steps dt = (damped contact time) / K. In flight the motion is ballistic
 * (exact); in contact the step is classical Runge-Kutta (RK4); a step that crosses first touch
 * or separation is cut there (the touch time from the ballistic quadratic, the separation by
 * regula falsi on the RK4 step length: where delta, or for the clipped law the force, reaches
 * 0; then, clipped, the ballistic flight out of the overlap to delta = 0), so that v_impact
 * and v_rebound are not blurred by the step. Prints one CSV row per contact: the rebound speed
 * against e_table v_impact. With --check TOL it exits 1 when some |v_rebound / v_impact - e_table|
 * exceeds TOL (the test runs it without gravity: the difference is then the integrator's error
 * alone; with gravity, the weight acting during the contact adds about g t_contact / v_impact). */
#include "cantact_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* The sphere: steel, radius 2 mm; the contact's normal stiffness. */
typedef struct {
    double mass;    /* kg */
    double k_n;     /* N/m */
    double g;       /* m/s^2, pulls towards the wall */
    double c_n;     /* N s/m, set per contact */
    double v_per_V; /* impact speed per unit V* (m/s) */
    int law;        /* CT_TAB_TENSION or CT_TAB_CLIPPED */
} sim;

/* What ends the contact, as a function of the state (z < 0 in contact): tension, the overlap
 * -z reaching 0; clipped, the force k_n (-z) + c_n (-v) reaching 0. < 0 while in contact. */
static double contact_end(const sim *s, double z, double v)
{
    return s->law == CT_TAB_TENSION ? z : s->k_n * z + s->c_n * v;
}

/* d/dt (z, v) in contact: z < 0 is the overlap delta = -z. */
static void deriv(const sim *s, double z, double v, double *dz, double *dv)
{
    const double force = s->k_n * (-z) + s->c_n * (-v); /* F_n = k_n delta + c_n d(delta)/dt */
    *dz = v;
    *dv = force / s->mass - s->g;
}

static void rk4(const sim *s, double z, double v, double h, double *z1, double *v1)
{
    double k1z, k1v, k2z, k2v, k3z, k3v, k4z, k4v;
    deriv(s, z, v, &k1z, &k1v);
    deriv(s, z + 0.5 * h * k1z, v + 0.5 * h * k1v, &k2z, &k2v);
    deriv(s, z + 0.5 * h * k2z, v + 0.5 * h * k2v, &k3z, &k3v);
    deriv(s, z + h * k3z, v + h * k3v, &k4z, &k4v);
    *z1 = z + h / 6.0 * (k1z + 2.0 * k2z + 2.0 * k3z + k4z);
    *v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

static const char help[] =
    "Usage: dem_drop TABLE.csv [--height H] [--speed V0] [--gravity G] [--bounces N]\n"
    "                [--v-per-V-star S] [--steps-per-contact K] [--law tension|clipped]\n"
    "                [--check TOL]\n"
    "\n"
    "A minimal DEM loop: a steel sphere (radius 2 mm) dropped on a flat wall, its linear\n"
    "spring-dashpot normal contact (k_n = 1e5 N/m) damped per contact from e(v_impact) of a\n"
    "cantact table (cantact table SCENE.ini -o TABLE.csv; read with include/cantact_table.h):\n"
    "e = ct_tab_e_of_speed(v_impact), zeta = ct_tab_zeta_of_e(e, law), c_n = 2 zeta\n"
    "sqrt(m k_n). Prints one CSV row per contact, the rebound speed beside e_table v_impact:\n"
    "contact,t_s,v_impact_m_s,V_star,e_table,zeta,v_rebound_m_s,e_measured,\n"
    "e_measured_minus_e_table,covered (covered 0: V* outside the table, its nearest end's e\n"
    "used), and a summary line on stderr.\n"
    "\n"
    "Options:\n"
    "  --height H            drop height [m], >= 0 (default 1)\n"
    "  --speed V0            initial downward speed [m/s], >= 0 (default 0)\n"
    "  --gravity G           [m/s^2], >= 0 (default 9.81; 0: the rebound is e v_impact up to\n"
    "                        the integrator's error)\n"
    "  --bounces N           contacts to run, >= 1 (default 8)\n"
    "  --v-per-V-star S      impact speed per unit V* [m/s] (default: the table's v_per_V_star,\n"
    "                        written when its scene gives [impact] mass; one of them is needed)\n"
    "  --steps-per-contact K RK4 steps per damped contact time, >= 4 (default 400)\n"
    "  --law tension|clipped the contact law: tension (F_n may pull; the default) or clipped\n"
    "                        (F_n = max(0, ...), as Yade's and LAMMPS's limit_damping)\n"
    "  --check TOL           exit 1 when some |v_rebound / v_impact - e_table| exceeds TOL\n"
    "  -h, --help            this help\n"
    "\n"
    "Exit status: 0 done, 1 a --check failed, 2 bad input or usage.\n";

static double arg_value(int argc, char **argv, int *k)
{
    if (*k + 1 >= argc) {
        fprintf(stderr, "dem_drop: %s needs a value\n", argv[*k]);
        exit(2);
    }
    char *end;
    double v = strtod(argv[++*k], &end);
    if (*end || !isfinite(v)) {
        fprintf(stderr, "dem_drop: %s %s: not a number\n", argv[*k - 1], argv[*k]);
        exit(2);
    }
    return v;
}

int main(int argc, char **argv)
{
    const char *path = NULL;
    double height = 1.0, speed = 0.0, tol = -1.0, v_per_V = NAN, steps = 400.0, bounces = 8.0;
    sim s = {.mass = 7850.0 * 4.0 / 3.0 * M_PI * 0.002 * 0.002 * 0.002,
             .k_n = 1e5,
             .g = 9.81,
             .law = CT_TAB_TENSION};
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "-h") || !strcmp(argv[k], "--help")) {
            fputs(help, stdout);
            return fflush(stdout) || ferror(stdout) ? 2 : 0;
        } else if (!strcmp(argv[k], "--height"))
            height = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--speed"))
            speed = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--gravity"))
            s.g = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--bounces"))
            bounces = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--v-per-V-star"))
            v_per_V = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--steps-per-contact"))
            steps = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--check"))
            tol = arg_value(argc, argv, &k);
        else if (!strcmp(argv[k], "--law")) {
            const char *law = k + 1 < argc ? argv[++k] : "";
            if (!strcmp(law, "tension"))
                s.law = CT_TAB_TENSION;
            else if (!strcmp(law, "clipped"))
                s.law = CT_TAB_CLIPPED;
            else {
                fprintf(stderr, "dem_drop: --law %s: must be tension or clipped\n", law);
                return 2;
            }
        } else if (argv[k][0] == '-') {
            fprintf(stderr, "dem_drop: unknown option %s\n", argv[k]);
            return 2;
        } else {
            path = argv[k];
        }
    }
    if (!path || !(height >= 0.0) || !(speed >= 0.0) || !(s.g >= 0.0) || !(steps >= 4.0) ||
        !(bounces >= 1.0)) {
        fprintf(stderr, "usage: dem_drop TABLE.csv [--height H >= 0] [--speed V0 >= 0] "
                        "[--gravity G >= 0] [--bounces N >= 1] [--v-per-V-star S] "
                        "[--steps-per-contact K >= 4] [--law tension|clipped] [--check TOL] "
                        "(dem_drop --help)\n");
        return 2;
    }
    ct_tab table;
    char err[512];
    if (ct_tab_load(&table, path, err, sizeof err)) {
        fprintf(stderr, "dem_drop: %s\n", err);
        return 2;
    }
    if (isfinite(v_per_V))
        table.v_per_V_star = v_per_V;
    s.v_per_V = table.v_per_V_star;
    if (!(s.v_per_V > 0.0)) {
        fprintf(stderr,
                "dem_drop: %s has no v_per_V_star (give [impact] mass in the scene, or "
                "--v-per-V-star)\n",
                path);
        ct_tab_free(&table);
        return 2;
    }
    /* the time step: the undamped contact time pi/omega_n over K (damping only lengthens it) */
    const double omega = sqrt(s.k_n / s.mass), dt = M_PI / omega / steps;
    double z = height, v = -speed, t = 0.0, v_in = 0.0, e = 1.0;
    int in_contact = 0, contacts = 0, status = 0;
    double worst = 0.0;
    printf("contact,t_s,v_impact_m_s,V_star,e_table,zeta,v_rebound_m_s,e_measured,"
           "e_measured_minus_e_table,covered\n");
    const double t_end = 1e3; /* s: a bound, never reached by a bouncing sphere */
    while (contacts < (int)bounces && t < t_end) {
        if (!in_contact) {
            if (s.g == 0.0 && v >= 0.0)
                break; /* leaves for good */
            /* ballistic step; first touch (z = 0) inside it cuts it */
            double z1 = z + v * dt - 0.5 * s.g * dt * dt;
            if (z1 > 0.0) {
                z = z1;
                v -= s.g * dt;
                t += dt;
                continue;
            }
            /* z + v h - g h^2 / 2 = 0: the smaller positive root, without cancellation */
            double h;
            if (s.g > 0.0) {
                const double disc = sqrt(v * v + 2.0 * s.g * z);
                h = 2.0 * z / (disc - v); /* = (v + disc) / g */
            } else {
                h = z / -v;
            }
            v -= s.g * h;
            t += h;
            z = 0.0;
            /* ---- the contact starts: e from the table, then the damping (3 lines) ---- */
            v_in = -v;
            e = ct_tab_e_of_speed(&table, v_in);
            const double zeta = ct_tab_zeta_of_e(e, s.law);
            s.c_n = 2.0 * zeta * sqrt(s.mass * s.k_n);
            in_contact = 1;
            continue;
        }
        double z1, v1;
        rk4(&s, z, v, dt, &z1, &v1);
        if (contact_end(&s, z1, v1) < 0.0) {
            z = z1;
            v = v1;
            t += dt;
            continue;
        }
        /* separation inside this step: contact_end(h) = 0 by regula falsi (Illinois) on the
         * step length, bracketed by contact_end(a) <= 0 <= contact_end(b) */
        double a = 0.0, za = contact_end(&s, z, v), b = dt, zb = contact_end(&s, z1, v1), h = dt;
        for (int it = 0, side = 0; it < 200 && b - a > 4e-16 * dt; it++) {
            h = (a * zb - b * za) / (zb - za);
            if (!(h > a && h < b))
                h = 0.5 * (a + b);
            double zh, vh;
            rk4(&s, z, v, h, &zh, &vh);
            zh = contact_end(&s, zh, vh);
            if (zh == 0.0)
                break;
            if (zh < 0.0) {
                a = h;
                za = zh;
                if (side < 0)
                    zb *= 0.5;
                side = -1;
            } else {
                b = h;
                zb = zh;
                if (side > 0)
                    za *= 0.5;
                side = 1;
            }
        }
        rk4(&s, z, v, h, &z1, &v1);
        t += h;
        z = s.law == CT_TAB_TENSION ? 0.0 : fmin(z1, 0.0);
        v = v1;
        if (z < 0.0) {
            /* clipped: no force from here on (k_n delta + c_n d(delta)/dt only falls); the
             * ballistic flight out of the overlap, z + v h - g h^2 / 2 = 0 (v > 0, z < 0) */
            const double disc = v * v + 2.0 * s.g * z;
            if (!(disc >= 0.0)) {
                fprintf(stderr,
                        "dem_drop: contact %d: the sphere falls back before it leaves "
                        "the overlap (not modelled)\n",
                        contacts + 1);
                status = 1;
                break;
            }
            h = -2.0 * z / (v + sqrt(disc));
            v -= s.g * h;
            t += h;
            z = 0.0;
        }
        in_contact = 0;
        contacts++;
        const double V = v_in / s.v_per_V, measured = v / v_in;
        const double diff = measured - e;
        worst = fmax(worst, fabs(diff));
        printf("%d,%.9g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.3g,%d\n", contacts, t, v_in, V, e,
               ct_tab_zeta_of_e(e, s.law), v, measured, diff, ct_tab_covers(&table, V));
        if (!ct_tab_covers(&table, V))
            fprintf(stderr,
                    "dem_drop: contact %d: V* = %g is outside the table (e of its nearest "
                    "end used)\n",
                    contacts, V);
        if (tol >= 0.0 && !(fabs(diff) <= tol)) {
            fprintf(stderr,
                    "dem_drop: contact %d: v_rebound / v_impact = %.17g, e_table = %.17g: differ "
                    "by %.3g > %.3g\n",
                    contacts, measured, e, diff, tol);
            status = 1;
        }
    }
    fprintf(stderr, "dem_drop: %d contacts, largest |v_rebound / v_impact - e_table| = %.3g\n",
            contacts, worst);
    if (tol >= 0.0 && contacts == 0) {
        fprintf(stderr, "dem_drop: --check: no contact happened\n");
        status = 1;
    }
    ct_tab_free(&table);
    return status;
}
