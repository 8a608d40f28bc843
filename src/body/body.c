/* The registry of bodies and what a body does to the rods (docs/model.md §12): each rod's top
 * is shifted by the gap of the face at the first point of the rod's footprint it reaches; the
 * rods it cannot reach before the layer crushes are left out. After that the rods are rods:
 * the load curve, e, the impact in time and every output run unchanged. */
#include "body/body.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static const ct_body_kind *const registry[] = {&ct_body_flat, &ct_body_cylinder, &ct_body_sphere};
#define NBODIES (sizeof registry / sizeof registry[0])

size_t ct_body_count(void)
{
    return NBODIES;
}

const char *ct_body_name(size_t k)
{
    return k < NBODIES ? registry[k]->name : NULL;
}

const char *ct_body_summary(size_t k)
{
    return k < NBODIES ? registry[k]->summary : NULL;
}

#define AT(field) offsetof(ct_body, field)
static const ct_key body_keys[] = {
    {"body", "shape", CT_KEY_WORD, 0, 0, 0, "flat|cylinder|sphere",
     "must be flat, cylinder or sphere", "flat",
     "what strikes the rods: the paper's flat strip, a cylinder across a line surface, a sphere "
     "over an areal one",
     AT(shape)},
    {"body", "radius", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "",
     "R of a cylinder or sphere, in the surface's length unit (metres for profiles and maps, "
     "the rods' unit, l0's unit for Cantor surfaces)",
     AT(radius)},
    {"body", "position", CT_KEY_POINT, 0, 0, 0, NULL, "must be x, or x and y (finite numbers)",
     "the middle of the surface", "where the apex lands: x on a line, x and y on a plane [length]",
     AT(position)},
};
#undef AT

const ct_key *ct_body_keys_table(size_t *n)
{
    *n = sizeof body_keys / sizeof body_keys[0];
    return body_keys;
}

void ct_body_defaults(ct_body *body)
{
    body->shape = 0;
    body->radius = 0.0;
    body->position[0] = body->position[1] = NAN;
}

double ct_body_gap(const ct_body *body, double r)
{
    if (!body || body->shape <= 0 || (size_t)body->shape >= NBODIES ||
        registry[body->shape]->dims == 0)
        return 0.0;
    const double R = body->radius;
    r = fabs(r);
    if (!(r <= R))
        return INFINITY;
    return r * r / (R + sqrt((R - r) * (R + r))); /* R - sqrt(R^2 - r^2), nothing cancels */
}

/* ---- the rods under a curved body ---- */

/* The shifted bundle's metadata: the bundle as built (the footprints, stages and x-extents of
 * its rods) and which of its rods each kept rod is. */
typedef struct {
    ct_bundle *built;
    size_t *index;
} body_meta;

static void body_meta_free(void *meta)
{
    body_meta *m = meta;
    if (m) {
        ct_bundle_free(m->built);
        free(m->index);
        free(m);
    }
}

static void *body_meta_clone(const void *meta)
{
    const body_meta *m = meta;
    body_meta *c = calloc(1, sizeof *c);
    const size_t n = ct_bundle_size(m->built);
    if (!c || ct_bundle_clone(&c->built, m->built) ||
        !(c->index = malloc((n ? n : 1) * sizeof *c->index))) {
        body_meta_free(c);
        return NULL;
    }
    memcpy(c->index, m->index, (n ? n : 1) * sizeof *c->index);
    return c;
}

static void body_rod_info(const void *meta, size_t k, ct_rod_info *info)
{
    const body_meta *m = meta;
    ct_rod_info built;
    ct_bundle_rod(m->built, m->index[k], &built);
    info->stage = built.stage;
    info->x_left = built.x_left;
    info->x_right = built.x_right;
    info->footprint = built.footprint;
}

static const ct_rod_meta_kind body_rods = {"body", body_rod_info, body_meta_clone, body_meta_free};

/* The surface's extent (over every footprint) and whether it is a line (1), a plane (2), or
 * holds rods that stand at no single place (0). */
typedef struct {
    double x_lo, x_hi, y_lo, y_hi;
    int dims;
    size_t placeless;
} extent;

static void extent_of(const ct_bundle *b, extent *e)
{
    *e = (extent){INFINITY, -INFINITY, INFINITY, -INFINITY, 0, 0};
    int line = 0, plane = 0;
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        const ct_footprint *f = &r.footprint;
        if (f->shape == CT_FOOTPRINT_NONE) {
            e->placeless++;
            continue;
        }
        const int areal = f->shape == CT_FOOTPRINT_RECTANGLE ||
                          (f->shape == CT_FOOTPRINT_POINT && !isnan(f->y_lo));
        plane |= areal;
        line |= !areal;
        e->x_lo = fmin(e->x_lo, f->x_lo);
        e->x_hi = fmax(e->x_hi, f->x_hi);
        if (areal) {
            e->y_lo = fmin(e->y_lo, f->y_lo);
            e->y_hi = fmax(e->y_hi, f->y_hi);
        }
    }
    e->dims = e->placeless || (line && plane) ? 0 : plane ? 2 : 1;
}

/* The distance [the rods' horizontal unit] from the apex (px, py) to the nearest point of f:
 * along x alone (dims 1) or in the plane (dims 2). 0 when f holds the apex. */
static double distance(const ct_footprint *f, int dims, double px, double py)
{
    const double dx = f->x_lo > px ? f->x_lo - px : f->x_hi < px ? px - f->x_hi : 0.0;
    if (dims == 1)
        return dx;
    const double dy = f->y_lo > py ? f->y_lo - py : f->y_hi < py ? py - f->y_hi : 0.0;
    return hypot(dx, dy);
}

/* The apex in the rods' horizontal unit: the position given (the body's unit, hx of it per
 * rods' unit), else the middle of the surface. */
static int apex_of(const ct_body *body, const ct_body_kind *d, const extent *e, double hx,
                   double *px, double *py)
{
    const double *pos = body->position;
    if (!isnan(pos[1]) && d->dims == 1)
        return ct_error_set(CT_EINVAL,
                            "body.position = %g, %g: a cylinder's apex is placed by x alone "
                            "(its axis lies across the line)",
                            pos[0], pos[1]);
    if (!isnan(pos[0]) && isnan(pos[1]) && d->dims == 2)
        return ct_error_set(CT_EINVAL, "body.position = %g: a sphere's apex needs x and y", pos[0]);
    *px = isnan(pos[0]) ? 0.5 * (e->x_lo + e->x_hi) : pos[0] / hx;
    *py = d->dims < 2 ? 0.0 : isnan(pos[1]) ? 0.5 * (e->y_lo + e->y_hi) : pos[1] / hx;
    return CT_OK;
}

static int check_body(const ct_body *body, const ct_body_kind **d)
{
    if (body->shape < 0 || (size_t)body->shape >= NBODIES)
        return ct_error_set(CT_EINVAL, "body.shape = %d: not a body", body->shape);
    *d = registry[body->shape];
    if ((*d)->dims && !(isfinite(body->radius) && body->radius > 0.0))
        return ct_error_set(CT_EINVAL, "body.radius = %g: a %s needs a radius, finite and > 0",
                            body->radius, (*d)->name);
    for (int i = 0; i < 2; i++)
        if (isinf(body->position[i]))
            return ct_error_set(CT_EINVAL, "body.position: %g is not a place", body->position[i]);
    return CT_OK;
}

/* The kept rods of b (gap[k] < INFINITY and top + gap below the crushed limit H) into a new
 * bundle whose layer's H* is H. */
static int shifted(ct_bundle *b, const double *gap, double H, ct_bundle **out, size_t *kept)
{
    const size_t n = ct_bundle_size(b);
    size_t m = 0;
    for (size_t k = 0; k < n; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        m += r.top + gap[k] < H;
    }
    ct_layer layer = *ct_bundle_layer(b);
    layer.Hstar = H;
    body_meta *meta = calloc(1, sizeof *meta);
    if (!meta || !(meta->index = malloc((m ? m : 1) * sizeof *meta->index))) {
        body_meta_free(meta);
        return ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", m);
    }
    int st = ct_bundle_create(out, &layer, m, "rods under the body");
    if (st) {
        body_meta_free(meta);
        return st;
    }
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(*out, &top, &length, &area, &eps_p);
    size_t j = 0;
    for (size_t k = 0; k < n; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        if (!(r.top + gap[k] < H))
            continue;
        top[j] = r.top + gap[k];
        length[j] = r.length;
        area[j] = r.area;
        eps_p[j] = r.plastic_strain;
        meta->index[j++] = k;
    }
    meta->built = b;
    ct_bundle_set_surface(*out, &body_rods, meta, ct_bundle_omitted(b) + (n - m));
    *kept = m;
    return CT_OK;
}

int ct_body_apply(const ct_body *body, const ct_scales *sc, ct_bundle **bp, ct_plan_info *info)
{
    const ct_body_kind *d = &ct_body_flat;
    int st;
    if (!body)
        return CT_OK;
    if ((st = check_body(body, &d)) || d->dims == 0)
        return st;
    ct_bundle *b = *bp;
    const size_t n = ct_bundle_size(b);
    extent e;
    extent_of(b, &e);
    if (e.placeless)
        return ct_error_set(CT_EINVAL,
                            "body.shape = %s: %zu of the %zu rods stand at no single place (a "
                            "Cantor surface's stage rods merge the pieces of a stage: give "
                            "surface.representation = segments)",
                            d->name, e.placeless, n);
    if (e.dims != d->dims)
        return ct_error_set(CT_EINVAL, "body.shape = %s: %s", d->name, d->needs);
    /* the rods' units against the body's: x in the rods' unit is hx of the body's, a gap in
     * the body's unit is hz of the rods' (a Cantor surface is built per l0 and h0) */
    const double hx = sc->physical.l0 / sc->layer.l0, hz = sc->layer.h0 / sc->physical.h0;
    double px = 0.0, py = 0.0;
    if ((st = apex_of(body, d, &e, hx, &px, &py)))
        return st;
    double *gap = malloc((n ? n : 1) * sizeof *gap);
    if (!gap)
        return ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", n);
    double H = INFINITY; /* the crushed limit: the first rod bottom the face reaches */
    for (size_t k = 0; k < n; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        gap[k] = ct_body_gap(body, distance(&r.footprint, d->dims, px, py) * hx) * hz;
        H = fmin(H, r.top + gap[k] + r.length);
    }
    size_t kept = 0;
    ct_bundle *out = NULL;
    st = isfinite(H) ? shifted(b, gap, H, &out, &kept)
                     : ct_error_set(CT_EINVAL,
                                    "body.shape = %s: the face (R = %g) reaches no rod from its "
                                    "apex at x = %g",
                                    d->name, body->radius, px * hx);
    free(gap);
    if (st)
        return st;
    *bp = out; /* at least the rod whose bottom fixes H is kept; b belongs to out's metadata */
    if (info) {
        info->rods = kept;
        info->omitted = ct_bundle_omitted(out);
    }
    return CT_OK;
}
