/* The paper's body: a rigid flat strip as long as the surface. Its face has no gap anywhere,
 * so it meets every rod at its own top: the rods are used as built, bit for bit. */
#include "body/body.h"

const ct_body_kind ct_body_flat = {
    .name = "flat",
    .summary = "the paper's rigid flat strip as long as the surface (per unit depth)",
    .dims = 0,
    .needs = "",
};
