// cantact_table.h from C++ (DEM codes such as LIGGGHTS and LAMMPS are C++): it compiles as
// C++11 without warnings, loads a table and evaluates the rule (linear here, checked by hand).
#include "cantact_table.h"

#include <cstdio>

int main()
{
    char path[] = "/tmp/ct_table_cxx_XXXXXX";
    int fd = mkstemp(path);
    if (fd < 0)
        return 1;
    FILE *f = fdopen(fd, "w");
    std::fputs("# interpolation = linear\n# V_star_crit = 0.5\n# nodes = 2\n"
               "V_star,e,de_dlnV_star\n1,0.8,0\n4,0.4,0\n",
               f);
    std::fclose(f);
    ct_tab t;
    char err[256];
    int bad = ct_tab_load(&t, path, err, sizeof err);
    std::remove(path);
    if (bad) {
        std::fprintf(stderr, "%s\n", err);
        return 1;
    }
    // half way in ln V*: V* = 2 gives the mean of the nodes
    const double mid = ct_tab_eval(&t, 2.0), below = ct_tab_eval(&t, 0.25);
    ct_tab_free(&t);
    if (!(std::fabs(mid - 0.6) < 1e-15 && below == 1.0)) {
        std::fprintf(stderr, "e(2) = %.17g, e(0.25) = %.17g\n", mid, below);
        return 1;
    }
    return 0;
}
