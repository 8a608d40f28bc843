/* e(V*) of a Cantor surface through the library: plan, sweep, read the rows.
 * Build: cc sweep.c $(pkg-config --cflags --libs cantact) */
#include <cantact.h>
#include <math.h>
#include <stdio.h>

int main(void)
{
    double V[5] = {1e-4, 3e-4, 1e-3, 3e-3, 1e-2};
    ct_cantor_plan plan = {
        .params = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1},
        .depth = CT_DEPTH_FRACTAL, /* the fractal limit to double precision */
        .representation = CT_REP_STAGES,
        .depth_tolerance = 1e-12,
        .V_star = V,
        .nvel = 5,
        .impacts = 2,
    };
    ct_impact_opts_default(&plan.opts);
    ct_bundle *b;
    ct_plan_info info;
    if (ct_cantor_plan_build(&plan, &b, &info)) {
        fprintf(stderr, "plan: %s\n", ct_error_message());
        return 1;
    }
    ct_sweep_spec spec = {.V_star = V, .nvel = 5, .impacts = 2, .opts = plan.opts};
    ct_sweep_row rows[10];
    int st = ct_sweep(b, &spec, rows); /* b is only read: several threads may share it */
    if (st) {
        fprintf(stderr, "sweep: %s\n", ct_error_message());
        ct_bundle_free(b);
        return 1;
    }
    printf("depth %ld, %zu rods\nV*,impact,e,u_max/h0\n", info.depth, info.rods);
    for (int k = 0; k < 10; k++) {
        if (rows[k].status) /* a failed impact is its own row, with its reason */
            printf("%g,%ld,failed: %s\n", rows[k].V_star, rows[k].impact, rows[k].message);
        else
            printf("%g,%ld,%.15f,%.6g\n", rows[k].V_star, rows[k].impact, rows[k].r.e,
                   rows[k].r.u_max);
    }
    ct_bundle_free(b);
    return 0;
}
