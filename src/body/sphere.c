/* A rigid sphere of radius R over an areal surface (an X3P map, rods with x and y): its face's
 * gap at distance r from the apex is R - sqrt(R^2 - r^2) (docs/model.md §14). */
#include "body/body.h"

const ct_body_kind ct_body_sphere = {
    .name = "sphere",
    .summary = "a rigid sphere over an areal surface",
    .dims = 2,
    .needs = "a sphere needs an areal surface (an X3P map) or rods with x and y; a line carries "
             "a cylinder",
};
