/* libFuzzer target: scene parsing plus validation on arbitrary bytes, with and without an
 * override. Build and run: scripts/fuzz [SECONDS]. */
#include "cantact.h"
#include "scene.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    ct_scene sc;
    if (ct_scene_parse(&sc, "fuzz.ini", text, NULL, 0) == CT_OK) {
        /* a valid scene has a surface and finite, positive speeds; prepared (when it reads no
         * file: the fuzzer's file names are not read), its layer is valid and every speed is a
         * V* whose impact energy is a finite positive number */
        char path[64];
        if (!sc.surface || sc.nvel == 0)
            abort();
        for (size_t k = 0; k < sc.nvel; k++)
            if (!(sc.V_star[k] > 0.0) || sc.V_star[k] != sc.V_star[k])
                abort();
        if (!ct_surface_input(sc.surface, 0, NULL, path, sizeof path) &&
            ct_scene_prepare(&sc) == CT_OK) {
            if (ct_layer_validate(&sc.scales.layer) != CT_OK)
                abort();
            for (size_t k = 0; k < sc.nvel; k++) {
                double W = sc.V_star[k] * sc.V_star[k] * sc.scales.energy_scale;
                if (!(W > 0.0) || !(W < INFINITY))
                    abort();
            }
        }
        ct_scene_free(&sc);
    }
    /* the same text as an override value */
    const char *set[1];
    char *o = malloc(size + 32);
    if (o) {
        memcpy(o, "impact.V_star=", 14);
        memcpy(o + 14, text, strlen(text) + 1);
        set[0] = o;
        if (ct_scene_parse(&sc, "fuzz.ini",
                           "[surface]\nfx=1.5\nfz=1.3\nH=10\n[material]\nE=500\n[impact]\n"
                           "V_star=1\n",
                           set, 1) == CT_OK)
            ct_scene_free(&sc);
        free(o);
    }
    free(text);
    return 0;
}
