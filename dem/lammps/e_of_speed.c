/* e_of_speed TABLE [--v-per-V-star S] V1 V2 ...: e_table(v) of a cantact table at the speeds,
 * one line each: "v e covered" (%.17g), through include/cantact_table.h only: the reference
 * test.sh compares LAMMPS's rebounds with. Build: cc -O2 -I../../include e_of_speed.c -lm
 * SPDX-License-Identifier: GPL-3.0-or-later */
#include "cantact_table.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    ct_tab t;
    char err[512];
    if (argc < 2) {
        fprintf(stderr, "usage: e_of_speed TABLE [--v-per-V-star S] V...\n");
        return 2;
    }
    if (ct_tab_load(&t, argv[1], err, sizeof err)) {
        fprintf(stderr, "e_of_speed: %s\n", err);
        return 2;
    }
    int k = 2;
    if (k + 1 < argc && !strcmp(argv[k], "--v-per-V-star")) {
        t.v_per_V_star = strtod(argv[k + 1], NULL);
        k += 2;
    }
    for (; k < argc; k++) {
        char *end;
        double v = strtod(argv[k], &end);
        if (*end) {
            fprintf(stderr, "e_of_speed: %s: not a number\n", argv[k]);
            ct_tab_free(&t);
            return 2;
        }
        printf("%.17g %.17g %d\n", v, ct_tab_e_of_speed(&t, v),
               ct_tab_covers(&t, v / t.v_per_V_star));
    }
    ct_tab_free(&t);
    return 0;
}
