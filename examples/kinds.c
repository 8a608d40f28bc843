/* Any kind of surface through the library's seam: a kind by name, its scene keys as text,
 * checked, prepared, built into rods for the speeds asked, swept. The same path as the CLI.
 * Build: cc kinds.c $(pkg-config --cflags --libs cantact) */
#include <cantact.h>
#include <stdio.h>

/* Sets each "section", "key", "value" triple; returns the first failure. */
static int set_all(ct_surface *s, const char *const (*keys)[3], size_t n)
{
    for (size_t k = 0; k < n; k++) {
        int st = ct_surface_set(s, keys[k][0], keys[k][1], keys[k][2], "example");
        if (st)
            return st;
    }
    return CT_OK;
}

static int run(const char *kind, const char *const (*keys)[3], size_t nkeys)
{
    double V[3] = {1e-4, 1e-3, 1e-2};
    ct_surface *s;
    ct_bundle *b = NULL;
    ct_plan_info info;
    ct_build_request req = {.V_star = V, .nvel = 3, .impacts = 1, .depth_tolerance = 1e-12};
    ct_impact_opts_default(&req.opts);
    int st = ct_surface_new(&s, kind);
    if (!st)
        st = set_all(s, keys, nkeys);
    if (!st)
        st = ct_surface_check(s, kind);
    if (!st)
        st = ct_surface_prepare(s, NULL); /* files relative to the working directory */
    if (!st)
        st = ct_surface_build(s, &req, &b, &info);
    ct_sweep_row rows[3];
    ct_sweep_spec spec = {.V_star = V, .nvel = 3, .impacts = 1, .opts = req.opts};
    if (!st)
        st = ct_sweep(b, &spec, rows);
    if (st) {
        fprintf(stderr, "%s: %s\n", kind, ct_error_message());
    } else {
        char what[300];
        ct_surface_describe(s, &info, what, sizeof what);
        printf("%s (%s)\n", kind, what);
        for (int k = 0; k < 3; k++)
            printf("  V* = %g: e = %.12f\n", V[k], rows[k].r.e);
    }
    ct_bundle_free(b);
    ct_surface_free(s);
    return st;
}

int main(void)
{
    static const char *const cantor[][3] = {{"surface", "fx", "1.5"},
                                            {"surface", "fz", "1.3"},
                                            {"surface", "H", "10"},
                                            {"material", "E", "500"}};
    static const char *const rods[][3] = {/* one rod 1 deep in a layer 10 deep, E/sigma_y 500 */
                                          {"surface", "rods", "0:1, 1:1"},
                                          {"surface", "Hstar", "10"},
                                          {"material", "E", "500"}};
    int st = run("cantor", cantor, 4);
    return st ? st : run("rods", rods, 3);
}
