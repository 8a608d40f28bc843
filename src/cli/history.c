/* The impact in time in the CLI: the e table's time columns (what = time), histories
 * (what = history) and bounce sequences (impact.sequence = bounce).
 *
 * The sweep's times are t / tau, tau = sqrt(m h0 / (E l0)), and its forces and lengths are in
 * the units the rods were built in (the surface's layer: dimensionless for a Cantor scene,
 * metres and newtons per metre for a measured one). Outputs divide by the layer's h0 and
 * P_Y = sigma_y l0; when the scene gives the mass, the same quantities are also written in
 * the scene's units (the surface's physical layer): seconds, metres and N/m for SI scenes. */
#include "history.h"

#include "number.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void field(FILE *f, double x)
{
    fputc(',', f);
    if (isfinite(x))
        ct_put_double(f, x);
}

static void line_field(ct_line *l, double x)
{
    ct_line_char(l, ',');
    if (isfinite(x))
        ct_line_double(l, x);
}

static int is_time(const ct_column *c)
{
    return !strcmp(c->group, "time");
}

int ct_cli_bundle_areal(const ct_bundle *b)
{
    if (!ct_bundle_size(b))
        return 0;
    ct_rod_info r;
    ct_bundle_rod(b, 0, &r);
    return r.footprint.shape == CT_FOOTPRINT_RECTANGLE ||
           (r.footprint.shape == CT_FOOTPRINT_POINT && !isnan(r.footprint.y_lo));
}

const char *ct_cli_physical_name(const ct_column *c, const ct_scene *sc)
{
    return sc->areal && !strcmp(c->physical, "P_peak_N_per_m") ? "P_peak_N" : c->physical;
}

void ct_cli_time_header(FILE *f, const ct_scene *sc)
{
    const ct_column *cols;
    const size_t n = ct_sweep_columns(&cols);
    for (size_t k = 0; k < n; k++)
        if (is_time(&cols[k]))
            fprintf(f, ",%s", cols[k].name);
    for (size_t k = 0; k < n && sc->mass > 0.0; k++)
        if (is_time(&cols[k]) && cols[k].physical)
            fprintf(f, ",%s", ct_cli_physical_name(&cols[k], sc));
}

int ct_cli_columns_of(ct_cli_columns *c, const char *group)
{
    const size_t n = ct_sweep_columns(&c->cols);
    c->n = c->nphys = 0;
    for (size_t k = 0; k < n; k++) {
        const ct_column *col = &c->cols[k];
        if (strcmp(col->group, group) || !strcmp(col->name, "impact") ||
            !strcmp(col->name, "V_star"))
            continue;
        if (c->n == CT_CLI_COLUMNS)
            return -1;
        c->at[c->n++] = k;
        if (col->physical)
            c->phys[c->nphys++] = k;
    }
    return 0;
}

void ct_cli_time_row(ct_line *l, const ct_scene *sc, const ct_cli_columns *tc,
                     const ct_sweep_row *row)
{
    const ct_layer *L = &sc->scales.layer;
    const double tau = sc->mass > 0.0 ? ct_time_scale(&sc->scales, sc->mass) : NAN;
    for (size_t q = 0; q < tc->n; q++)
        line_field(l, row->status ? NAN : ct_column_value(&tc->cols[tc->at[q]], row, L));
    for (size_t q = 0; q < tc->nphys && sc->mass > 0.0; q++)
        line_field(l, row->status ? NAN
                                  : ct_column_physical(&tc->cols[tc->phys[q]], row, L,
                                                       &sc->scales.physical, tau));
}

int ct_cli_time_check(const ct_sweep_row *row, char *err, size_t errlen)
{
    /* the kinematic e (v2 from the unloading curve's own work) and the energy e agree */
    if (row->status || fabs(row->dyn.e_kinematic - row->r.e) <= 1e-12 + 4.0 * row->r.e_rounding)
        return 0;
    snprintf(err, errlen,
             "V* = %g, impact %ld: e_kinematic = %.17g and e = %.17g differ by more than 1e-12",
             row->V_star, row->impact, row->dyn.e_kinematic, row->r.e);
    return -1;
}

void ct_cli_history_header(FILE *f, const ct_scene *sc)
{
    fputs("V_star,impact,t_over_tau,u_over_h0,udot_over_h0_per_tau,P_over_PY,branch,event", f);
    if (sc->mass > 0.0)
        fputs(sc->areal ? ",t_s,u_m,udot_m_per_s,P_N" : ",t_s,u_m,udot_m_per_s,P_N_per_m", f);
    fputc('\n', f);
}

int ct_cli_history_rows(FILE *f, const ct_scene *sc, const ct_sweep_row *row, const ct_bundle *b)
{
    /* the sweep's units: mass E l0 / h0 so that tau = 1, v1 = sqrt(2) V* h0 */
    const ct_layer *L = ct_bundle_layer(b);
    const double m = L->E * L->l0 / L->h0, v1 = sqrt(2.0) * row->V_star * L->h0;
    ct_impact_result r;
    ct_dynamics d;
    ct_history h;
    int st = ct_impact_history(b, m, v1, sc->history_points, &r, &d, &h);
    if (st)
        return st;
    const ct_layer *p = &sc->scales.physical;
    const double tau = sc->mass > 0.0 ? ct_time_scale(&sc->scales, sc->mass) : NAN;
    for (size_t i = 0; i < h.n; i++) {
        const ct_history_point *q = &h.points[i];
        ct_put_double(f, row->V_star);
        fprintf(f, ",%ld", row->impact);
        field(f, q->t);
        field(f, q->u / L->h0);
        field(f, q->v / L->h0);
        field(f, q->P / (L->sigma_y * L->l0));
        fprintf(f, ",%s,%d", q->unloading ? "unload" : "load", q->event);
        if (sc->mass > 0.0) {
            field(f, q->t * tau);
            field(f, q->u / L->h0 * p->h0);
            field(f, q->v / L->h0 * p->h0 / tau);
            field(f, q->P / (L->sigma_y * L->l0) * p->sigma_y * p->l0);
        }
        fputc('\n', f);
    }
    ct_history_free(&h);
    return CT_OK;
}

int ct_cli_bounce(FILE *f, const ct_scene *sc, const ct_bundle *b, char *err, size_t errlen)
{
    const ct_layer *L = ct_bundle_layer(b), *p = &sc->scales.physical;
    const double m = L->E * L->l0 / L->h0, tau = ct_time_scale(&sc->scales, sc->mass);
    /* a speed of the sweep (layer lengths per tau) in the scene's units: / h0, * h0 / tau */
    const double speed = p->h0 / L->h0 / tau;
    const double v1 = sqrt(2.0) * sc->V_star[0] * L->h0;
    const size_t nmax = (size_t)sc->impacts;
    ct_impact_result *res = malloc(nmax * sizeof *res);
    ct_dynamics *dyn = malloc(nmax * sizeof *dyn);
    size_t n = 0;
    int st =
        res && dyn ? ct_bounce(b, m, v1, nmax, sc->stop_speed / speed, res, dyn, &n) : CT_ENOMEM;
    if (st && n == 0) {
        snprintf(err, errlen, "bounce 1: %s",
                 st == CT_ENOMEM ? "out of memory" : ct_error_message());
        free(res);
        free(dyn);
        return st;
    }
    fprintf(f,
            "bounce,V_star,v_in_m_per_s,e,v_out_m_per_s,u_max_over_h0,elastic,t_contact_s,"
            "%s,flight_s,height_m,time_s,v_out_constant_e_m_per_s,height_constant_e_m\n",
            ct_cli_bundle_areal(b) ? "P_peak_N" : "P_peak_N_per_m");
    const double g = sc->gravity, e1 = dyn[0].e_kinematic;
    double t = 0.0, v_const = v1 * speed;
    for (size_t k = 0; k < n; k++) {
        const double v_in = dyn[k].v1 * speed, v_out = dyn[k].v2 * speed;
        const double flight = 2.0 * v_out / g, tc = dyn[k].t_contact * tau;
        v_const *= e1; /* the same bounce with e fixed at the first impact's */
        fprintf(f, "%zu,", k + 1);
        ct_put_double(f, res[k].V_star);
        field(f, v_in);
        field(f, res[k].e);
        field(f, v_out);
        field(f, res[k].u_max / L->h0);
        fprintf(f, ",%d", res[k].elastic);
        field(f, tc);
        field(f, dyn[k].P_peak / (L->sigma_y * L->l0) * p->sigma_y * p->l0);
        field(f, flight);
        field(f, v_out * v_out / (2.0 * g));
        t += tc + flight;
        field(f, t);
        field(f, v_const);
        field(f, v_const * v_const / (2.0 * g));
        fputc('\n', f);
    }
    if (st)
        snprintf(err, errlen, "bounce %zu: %s", n + 1, ct_error_message());
    free(res);
    free(dyn);
    return st;
}
