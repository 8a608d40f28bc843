/* A rigid cylinder of radius R with its axis across a line surface (a line profile, a Cantor
 * or random Cantor surface), per unit depth like the paper's strip: its face's gap at x from
 * the apex is R - sqrt(R^2 - x^2) (docs/model.md §14). */
#include "body/body.h"

const ct_body_kind ct_body_cylinder = {
    .name = "cylinder",
    .summary = "a rigid cylinder, its axis across a line surface (per unit depth)",
    .dims = 1,
    .needs = "a cylinder needs a line surface (a line profile, a Cantor or random Cantor surface "
             "with representation = segments, or rods with x); an areal one carries a sphere",
};
