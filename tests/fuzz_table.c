/* libFuzzer target: hostile table files into include/cantact_table.h's loader and evaluator
 * (what a DEM code links): every file is refused with a message, or it loads and e is in
 * [0, 1] at every V* asked (between its interval's two nodes), exactly 1 at and below V*_c,
 * with a damping ratio that is not NaN. Never a crash, never e outside.
 * Build and run: scripts/fuzz [SECONDS] table. */
#include "cantact_table.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[] = "/tmp/cantact_fuzz_table_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0)
        return 0;
    if (write(fd, data, size) != (ssize_t)size) {
        close(fd);
        unlink(path);
        return 0;
    }
    close(fd);
    ct_tab t;
    char err[512];
    if (ct_tab_load(&t, path, err, sizeof err) == 0) {
        /* V* over the nodes and far beyond, at and around V*_c */
        const double lo = t.V_star[0], hi = t.V_star[t.n - 1];
        for (int k = -50; k <= 250; k++) {
            const double V = lo * pow(hi / lo, k / 200.0);
            const double e = ct_tab_eval(&t, V);
            if (!(e >= 0.0 && e <= 1.0))
                abort();
            if (V > lo && V < hi && V > t.V_star_crit) { /* between its interval's nodes */
                const size_t i = ct_tab_interval(t.n, t.ln_V_star, log(V));
                if (!(e >= fmin(t.e[i], t.e[i + 1]) && e <= fmax(t.e[i], t.e[i + 1])))
                    abort();
            }
            if (isnan(ct_tab_zeta_of_e(e, CT_TAB_TENSION)) ||
                isnan(ct_tab_zeta_of_e(e, CT_TAB_CLIPPED)))
                abort();
            if (V <= t.V_star_crit && e != 1.0)
                abort();
        }
        if (t.V_star_crit > 0.0 && ct_tab_eval(&t, t.V_star_crit) != 1.0)
            abort();
        ct_tab_free(&t);
    } else if (!err[0]) {
        abort(); /* a refusal says why */
    }
    unlink(path);
    return 0;
}
