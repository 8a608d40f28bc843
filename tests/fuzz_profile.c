/* libFuzzer target: the profile readers (text/CSV, Dektak, X3P by its zip magic) on arbitrary
 * bytes, then what a run does with a profile that reads: levelling, statistics, rods, one
 * impact and the fit. A profile that reads must hold at least 3 finite points with x
 * increasing; a run on it gives e in [0, 1] or an error, never a crash or a NaN result.
 * Build and run: scripts/fuzz [SECONDS] profile. */
#include "cantact.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

static void check_profile(ct_profile *p)
{
    if (p->n < 3 || p->n + p->invalid != p->nx * p->ny)
        abort();
    for (size_t j = 0; j < p->nx * p->ny; j++)
        if (!isfinite(p->z[j]) && !(p->ny > 1 && isnan(p->z[j])))
            abort();
    if (p->x)
        for (size_t j = 1; j < p->nx; j++)
            if (!(p->x[j] > p->x[j - 1]) || !isfinite(p->x[j]))
                abort();
    ct_profile_stats s;
    if (ct_profile_level(p, CT_DETREND_LINEAR) || ct_profile_stats_of(p, &s))
        return;
    if (!(s.Rt >= 0.0) || !(s.Rq >= 0.0) || !(s.length > 0.0))
        abort();
    ct_bundle *b;
    if (s.Rt > 0.0 && ct_profile_bundle(&b, p, 500.0, 1.0, 10.0 * s.Rt) == CT_OK) {
        const double V = 1e-3;
        ct_sweep_spec spec = {.V_star = &V, .nvel = 1, .impacts = 1};
        ct_impact_opts_default(&spec.opts);
        ct_sweep_row row;
        if (ct_sweep(b, &spec, &row) == CT_OK && row.status == CT_OK &&
            !(row.r.e >= 0.0 && row.r.e <= 1.0))
            abort();
        ct_bundle_free(b);
    }
    ct_profile_fit f = {0};
    if (ct_profile_fit_of(p, 0, 0, 0, 0, &f) == CT_OK &&
        !(isfinite(f.alpha) && isfinite(f.h0) && isfinite(f.D)))
        abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static char path[64];
    if (!path[0])
        snprintf(path, sizeof path, "/tmp/cantact_fuzz_profile_%ld", (long)getpid());
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    if (fwrite(data, 1, size, f) != size) {
        fclose(f);
        return 0;
    }
    fclose(f);
    /* the units from the column names, then given (um), then one column at a spacing */
    const ct_profile_read_opts opts[3] = {{0, 0, 0}, {1e-6, 1e-6, 0}, {1e-6, 1e-9, 0.5}};
    for (int k = 0; k < 3; k++) {
        ct_profile *p;
        if (ct_profile_read(path, &opts[k], &p) == CT_OK) {
            check_profile(p);
            ct_profile_free(p);
        }
    }
    unlink(path);
    return 0;
}
