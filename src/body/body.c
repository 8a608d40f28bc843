/* The registry of bodies and what a body does to the rods (docs/model.md §14): each rod's top
 * is shifted by the gap of the face at the first point of the rod's footprint it reaches; the
 * rods it cannot reach before the layer crushes are left out. After that the rods are rods:
 * the load curve, e, the impact in time and every output run unchanged. */
#include "body/body.h"
#include "number.h"

#include <Random123/philox.h>

#include <math.h>
#include <stddef.h>
#include <stdio.h>
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
     "R of a cylinder or sphere, in the surface's length unit (metres for profiles, maps and "
     "rods given surface.unit, whatever unit their files use; else the rods' own unit; l0's "
     "unit for Cantor surfaces)",
     AT(radius)},
    {"body", "position", CT_KEY_POINT, 0, 0, 0, NULL, "must be x, or x and y (finite numbers)",
     "the middle of the surface",
     "where the apex lands: x on a line, x and y on a plane [length, as the radius]", AT(position)},
    {"body", "landings", CT_KEY_COUNT, 0, 0, 0, NULL, "must be an integer 0 <= n < 2^64", "0",
     "apex positions drawn uniformly where the face stays on the surface (anywhere in a period "
     "of one that repeats), each struck at every speed: the statistics of e over them (0: the "
     "one position)",
     AT(landings)},
    {"body", "seed", CT_KEY_COUNT, 0, 0, 0, NULL, "must be an integer 0 <= n < 2^64", "0",
     "the landings' generator key: landing k is a function of (seed, k) alone (Philox4x64)",
     AT(seed)},
    {"surface", "periodic", CT_KEY_WORD, 0, 0, 0, "false|true", "must be false or true", "false",
     "true: the surface repeats as measured (a Cantor surface with period l0) as far as a curved "
     "body's face reaches; false: a contact that reaches its border fails",
     AT(periodic)},
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
    body->periodic = 0;
    body->landings = 0;
    body->seed = 0;
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

/* The shifted bundle's metadata, per kept rod: where it stands (its footprint, moved to its
 * copy on a periodic surface), its stage and x-extent as its surface gave them, and the gap the
 * face met it with; the largest u_max the rods describe, and why. The bundle as built is not
 * kept: a map's million rods cost their memory once. */
typedef struct {
    size_t n;
    ct_footprint *foot;
    double *x_left, *x_right, *gap;
    long *stage;
    double reach;
    char why[240];
} body_meta;

static void body_meta_free(void *meta)
{
    body_meta *m = meta;
    if (m) {
        free(m->foot);
        free(m->x_left);
        free(m->x_right);
        free(m->gap);
        free(m->stage);
        free(m);
    }
}

static body_meta *body_meta_new(size_t n)
{
    body_meta *m = calloc(1, sizeof *m);
    const size_t k = n ? n : 1;
    if (!m || !(m->foot = malloc(k * sizeof *m->foot)) ||
        !(m->x_left = malloc(k * sizeof(double))) || !(m->x_right = malloc(k * sizeof(double))) ||
        !(m->gap = malloc(k * sizeof(double))) || !(m->stage = malloc(k * sizeof(long)))) {
        body_meta_free(m);
        return NULL;
    }
    m->n = n;
    return m;
}

static void *body_meta_clone(const void *meta)
{
    const body_meta *m = meta;
    body_meta *c = body_meta_new(m->n);
    if (!c)
        return NULL;
    const size_t k = m->n ? m->n : 1;
    memcpy(c->foot, m->foot, k * sizeof *c->foot);
    memcpy(c->x_left, m->x_left, k * sizeof(double));
    memcpy(c->x_right, m->x_right, k * sizeof(double));
    memcpy(c->gap, m->gap, k * sizeof(double));
    memcpy(c->stage, m->stage, k * sizeof(long));
    c->reach = m->reach;
    memcpy(c->why, m->why, sizeof c->why);
    return c;
}

static void body_rod_info(const void *meta, size_t k, ct_rod_info *info)
{
    const body_meta *m = meta;
    info->stage = m->stage[k];
    info->x_left = m->x_left[k];
    info->x_right = m->x_right[k];
    info->footprint = m->foot[k];
}

static double body_reach(const void *meta, char *why, size_t len)
{
    const body_meta *m = meta;
    snprintf(why, len, "%s", m->why);
    return m->reach;
}

static const ct_rod_meta_kind body_rods = {"body",         body_rod_info, body_meta_clone,
                                           body_meta_free, body_reach,    NULL};

/* The surface's extent (over every footprint) and whether it is a line (1), a plane (2), or
 * holds rods that stand at no single place (0); whether any rod is a point. */
typedef struct {
    double x_lo, x_hi, y_lo, y_hi;
    int dims, points;
    size_t placeless;
} extent;

static void extent_of(const ct_bundle *b, extent *e)
{
    *e = (extent){INFINITY, -INFINITY, INFINITY, -INFINITY, 0, 0, 0};
    int line = 0, plane = 0;
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        const ct_footprint *f = &r.footprint;
        if (f->shape == CT_FOOTPRINT_NONE) {
            e->placeless++;
            continue;
        }
        e->points |= f->shape == CT_FOOTPRINT_POINT;
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
    if (e->dims < 2)
        e->y_lo = e->y_hi = 0.0;
}

/* The distance [the rods' horizontal unit] from the apex (px, py) to the nearest point of f
 * moved by (sx, sy): along x alone (dims 1) or in the plane (dims 2); 0 when f holds it. */
static double distance(const ct_footprint *f, int dims, double px, double py, double sx, double sy)
{
    const double lo = f->x_lo + sx, hi = f->x_hi + sx;
    const double dx = lo > px ? lo - px : hi < px ? px - hi : 0.0;
    if (dims == 1)
        return dx;
    const double ylo = f->y_lo + sy, yhi = f->y_hi + sy;
    const double dy = ylo > py ? ylo - py : yhi < py ? py - yhi : 0.0;
    return hypot(dx, dy);
}

/* The apex in the rods' horizontal unit: the position given (the body's unit, hx of it per
 * rods' unit), else the middle of the surface; on the surface unless it repeats. */
static int apex_of(const ct_body *body, const ct_body_kind *d, const extent *e, double hx,
                   double *px, double *py)
{
    const double *pos = body->position;
    if (!isnan(pos[1]) && d->dims == 1)
        return ct_error_set(CT_EINVAL,
                            "body.position = %g, %g: a cylinder's apex is placed by x alone "
                            "(its axis lies across the line)",
                            pos[0], pos[1]);
    if (isnan(pos[0]) && !isnan(pos[1]))
        return ct_error_set(CT_EINVAL, "body.position: y = %g without x", pos[1]);
    if (!isnan(pos[0]) && isnan(pos[1]) && d->dims == 2)
        return ct_error_set(CT_EINVAL, "body.position = %g: a sphere's apex needs x and y", pos[0]);
    *px = isnan(pos[0]) ? 0.5 * (e->x_lo + e->x_hi) : pos[0] / hx;
    *py = d->dims < 2 ? 0.0 : isnan(pos[1]) ? 0.5 * (e->y_lo + e->y_hi) : pos[1] / hx;
    if (!body->periodic && !e->points &&
        (*px < e->x_lo || *px > e->x_hi || (d->dims == 2 && (*py < e->y_lo || *py > e->y_hi))))
        return ct_error_set(CT_EINVAL,
                            "body.position: the apex lands off the surface, which spans x %g .. "
                            "%g%s (surface.periodic = true if it repeats)",
                            e->x_lo * hx, e->x_hi * hx, d->dims == 2 ? " and y as given" : "");
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

/* How a curved body meets a bundle: the apex, the units, the copies of a periodic surface
 * (offsets -K .. K periods each way), and the rods as read once (footprint, top, length, area,
 * plastic strain: reading them through ct_bundle_rod for every copy was most of the time). */
typedef struct {
    const ct_body *body;
    const ct_body_kind *d;
    const ct_bundle *b;
    extent e;
    double hx, hz, px, py;
    double period_x, period_y;
    double reach; /* how far from its apex the face can meet a rod [the body's length unit] */
    int kx, ky;
    size_t n;
    double *rods; /* 8 per rod: x_lo, x_hi, y_lo, y_hi, top, length, area, plastic strain */
} meeting;

enum { X_LO, X_HI, Y_LO, Y_HI, TOP, LENGTH, AREA, EPS_P, NFIELDS };

static void rod_fields(const meeting *m, size_t k, double *v, ct_rod_info *out)
{
    ct_rod_info r;
    ct_bundle_rod(m->b, k, &r);
    v[X_LO] = r.footprint.x_lo;
    v[X_HI] = r.footprint.x_hi;
    v[Y_LO] = m->d->dims == 2 ? r.footprint.y_lo : 0.0;
    v[Y_HI] = m->d->dims == 2 ? r.footprint.y_hi : 0.0;
    v[TOP] = r.top;
    v[LENGTH] = r.length;
    v[AREA] = r.area;
    v[EPS_P] = r.plastic_strain;
    if (out)
        *out = r;
}

/* The rods as read once, when the surface repeats (each copy reads them again) or is met at many
 * apexes (table: landings); a surface met once goes to the bundle itself (no copy of a million
 * rods' footprints). */
static int read_rods(meeting *m, int table)
{
    m->n = ct_bundle_size(m->b);
    m->rods = NULL;
    if (!table && !m->kx && !m->ky)
        return CT_OK;
    m->rods = malloc((m->n ? m->n : 1) * NFIELDS * sizeof(double));
    if (!m->rods)
        return ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", m->n);
    for (size_t k = 0; k < m->n; k++)
        rod_fields(m, k, m->rods + k * NFIELDS, NULL);
    return CT_OK;
}

/* Rod k's fields (and, when r is not NULL, all it is) from the table or the bundle. */
static const double *rod_of(const meeting *m, size_t k, double *v, ct_rod_info *r)
{
    if (m->rods && !r)
        return m->rods + k * NFIELDS;
    rod_fields(m, k, v, r);
    return v;
}

/* The gap [the rods' vertical unit] at the nearest point of the box [x_lo, x_hi] x [y_lo, y_hi]
 * moved by copy (cx, cy). */
static double box_gap(const meeting *m, double x_lo, double x_hi, double y_lo, double y_hi, int cx,
                      int cy)
{
    const ct_footprint f = {CT_FOOTPRINT_RECTANGLE, x_lo, x_hi, y_lo, y_hi};
    const double r_apex =
        distance(&f, m->d->dims, m->px, m->py, cx * m->period_x, cy * m->period_y);
    return ct_body_gap(m->body, r_apex * m->hx) * m->hz;
}

/* The gap at a rod's footprint (its fields v) in copy (cx, cy). */
static double gap_of(const meeting *m, const double *v, int cx, int cy)
{
    return box_gap(m, v[X_LO], v[X_HI], v[Y_LO], v[Y_HI], cx, cy);
}

/* 0 when no rod of copy (cx, cy) can lie above H: the face's gap at the copy's extent is H or
 * more, and every top is >= 0. */
static int copy_reached(const meeting *m, int cx, int cy, double H)
{
    return box_gap(m, m->e.x_lo, m->e.x_hi, m->e.y_lo, m->e.y_hi, cx, cy) < H;
}

/* 1 when a rod (its fields v) touches the border of the surface (not periodic). */
static int on_border(const meeting *m, const double *v)
{
    return v[X_LO] <= m->e.x_lo || v[X_HI] >= m->e.x_hi ||
           (m->d->dims == 2 && (v[Y_LO] <= m->e.y_lo || v[Y_HI] >= m->e.y_hi));
}

/* A site's rods by place (landings): the surface's extent cut into cells, each with its rods
 * (by their footprint's centre), the box of their footprints and their lowest top and bottom, so
 * that a cell the face cannot reach below H is passed over whole: its box's gap is at most any
 * of its rods' (the gap grows with the distance). Results are those of reading every rod. */
typedef struct {
    size_t nx, ny;
    size_t *start; /* cell c holds idx[start[c] .. start[c + 1] - 1], in increasing order */
    size_t *idx;
    double *box; /* 4 per cell: x_lo, x_hi, y_lo, y_hi */
    double *top_min, *bottom_min;
} cells;

static int in_cell(const meeting *m, const cells *c, size_t c_id, int cx, int cy, double floor_,
                   double H)
{
    const double *bx = c->box + 4 * c_id;
    return c->start[c_id] < c->start[c_id + 1] &&
           box_gap(m, bx[0], bx[1], bx[2], bx[3], cx, cy) + floor_ < H;
}

/* The crushed limit over the rods of cell c_id in copy (cx, cy), lowering *H. */
static void cell_limit(const meeting *m, const cells *c, size_t c_id, int cx, int cy, double *H)
{
    if (!in_cell(m, c, c_id, cx, cy, c->bottom_min[c_id], *H))
        return;
    double buf[NFIELDS];
    for (size_t i = c->start[c_id]; i < c->start[c_id + 1]; i++) {
        const double *v = rod_of(m, c->idx[i], buf, NULL);
        *H = fmin(*H, v[TOP] + gap_of(m, v, cx, cy) + v[LENGTH]);
    }
}

/* The cell that holds the point (px, py) [the rods' unit], clamped to the grid. */
static size_t cell_at(const meeting *m, const cells *c, double px, double py)
{
    const double wx = (m->e.x_hi - m->e.x_lo) / (double)c->nx,
                 wy = (m->e.y_hi - m->e.y_lo) / (double)c->ny;
    double fx = wx > 0.0 ? (px - m->e.x_lo) / wx : 0.0, fy = wy > 0.0 ? (py - m->e.y_lo) / wy : 0.0;
    fx = fmin(fmax(fx, 0.0), (double)c->nx - 1.0);
    fy = fmin(fmax(fy, 0.0), (double)c->ny - 1.0);
    return (size_t)fy * c->nx + (size_t)fx;
}

/* Pass 1: the crushed limit H, the first rod bottom the face reaches: over the apex's own copy,
 * then the copies that can still lower it (a minimum: exact in any order). */
static double crushed_limit(const meeting *m, const cells *c)
{
    double H = INFINITY, buf[NFIELDS];
    if (c) { /* the apex's cell first: H falls at once, and most cells are passed over */
        const size_t ncells = c->nx * c->ny, first = cell_at(m, c, m->px, m->py);
        cell_limit(m, c, first, 0, 0, &H);
        for (int cy = -m->ky; cy <= m->ky; cy++)
            for (int cx = -m->kx; cx <= m->kx; cx++)
                for (size_t k = 0; copy_reached(m, cx, cy, H) && k < ncells; k++)
                    cell_limit(m, c, k, cx, cy, &H);
        return H;
    }
    for (size_t k = 0; k < m->n; k++) {
        const double *v = rod_of(m, k, buf, NULL);
        H = fmin(H, v[TOP] + gap_of(m, v, 0, 0) + v[LENGTH]);
    }
    for (int cy = -m->ky; cy <= m->ky; cy++)
        for (int cx = -m->kx; cx <= m->kx; cx++)
            for (size_t k = 0; (cx || cy) && copy_reached(m, cx, cy, H) && k < m->n; k++) {
                const double *v = rod_of(m, k, buf, NULL);
                H = fmin(H, v[TOP] + gap_of(m, v, cx, cy) + v[LENGTH]);
            }
    return H;
}

/* The kept rods in order (copy by copy, each in rod order): rod, copy and the face's gap. */
typedef struct {
    size_t k;
    int cx, cy;
    double gap;
} kept_rod;

typedef struct {
    kept_rod *r;
    size_t n, cap;
} kept_list;

static int keep(kept_list *l, size_t k, int cx, int cy, double g)
{
    if (l->n == l->cap) {
        const size_t cap = l->cap ? 2 * l->cap : 1024;
        kept_rod *r = realloc(l->r, cap * sizeof *r);
        if (!r)
            return ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", cap);
        l->r = r;
        l->cap = cap;
    }
    l->r[l->n++] = (kept_rod){k, cx, cy, g};
    return CT_OK;
}

/* The rods of copy (cx, cy) whose top the face shifts to below H, in rod order: with cells, the
 * reached cells' rods marked (mark[k], their gap in g[k]) and the marks read in rod order. */
static int kept_in_copy(const meeting *m, const cells *c, int cx, int cy, double H,
                        unsigned char *mark, double *g, kept_list *l)
{
    double buf[NFIELDS];
    int st = CT_OK;
    if (!c) {
        for (size_t k = 0; !st && k < m->n; k++) {
            const double *v = rod_of(m, k, buf, NULL), gk = gap_of(m, v, cx, cy);
            if (v[TOP] + gk < H)
                st = keep(l, k, cx, cy, gk);
        }
        return st;
    }
    size_t lo = SIZE_MAX, hi = 0; /* the marked range */
    for (size_t q = 0; q < c->nx * c->ny; q++) {
        if (!in_cell(m, c, q, cx, cy, c->top_min[q], H))
            continue;
        for (size_t i = c->start[q]; i < c->start[q + 1]; i++) {
            const size_t k = c->idx[i];
            const double *v = rod_of(m, k, buf, NULL), gk = gap_of(m, v, cx, cy);
            if (v[TOP] + gk < H) {
                mark[k] = 1;
                g[k] = gk;
                lo = k < lo ? k : lo;
                hi = k > hi ? k : hi;
            }
        }
    }
    for (size_t k = lo; k <= hi && lo != SIZE_MAX; k++)
        if (mark[k]) {
            mark[k] = 0;
            if (!st)
                st = keep(l, k, cx, cy, g[k]);
        }
    return st;
}

/* Every copy's kept rods into l, in order. */
static int kept_rods(const meeting *m, const cells *c, double H, kept_list *l)
{
    unsigned char *mark = NULL;
    double *g = NULL;
    if (c &&
        (!(mark = calloc(m->n ? m->n : 1, 1)) || !(g = malloc((m->n ? m->n : 1) * sizeof *g)))) {
        free(mark);
        return ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", m->n);
    }
    int st = CT_OK;
    for (int cy = -m->ky; !st && cy <= m->ky; cy++)
        for (int cx = -m->kx; !st && cx <= m->kx; cx++)
            if (copy_reached(m, cx, cy, H))
                st = kept_in_copy(m, c, cx, cy, H, mark, g, l);
    free(mark);
    free(g);
    return st;
}

/* Pass 2: the kept rods (their top below H) into *out (layer H* = H) with their metadata, and
 * the reach: on a surface that does not repeat, the face may go on until it touches a border
 * rod where it would reach past the surface's edge. */
static int shifted(const meeting *m, const cells *c, double H, ct_bundle **out)
{
    double buf[NFIELDS];
    kept_list l = {0};
    int st = kept_rods(m, c, H, &l);
    const size_t kept = l.n;
    ct_layer layer = *ct_bundle_layer(m->b);
    layer.Hstar = H;
    body_meta *meta = st ? NULL : body_meta_new(kept);
    if (!st && !meta)
        st = ct_error_set(CT_ENOMEM, "body: out of memory for %zu rods", kept);
    if (!st && (st = ct_bundle_create(out, &layer, kept, "rods under the body")))
        body_meta_free(meta);
    if (st) {
        free(l.r);
        return st;
    }
    double *top, *length, *area, *eps_p, border = INFINITY;
    ct_bundle_arrays(*out, &top, &length, &area, &eps_p);
    for (size_t j = 0; j < kept; j++) {
        const kept_rod *kr = &l.r[j];
        const double g = kr->gap;
        ct_rod_info r;
        rod_of(m, kr->k, buf, &r); /* its stage and extent as its surface gives them */
        const double sx = kr->cx * m->period_x, sy = kr->cy * m->period_y;
        top[j] = r.top + g;
        length[j] = r.length;
        area[j] = r.area;
        eps_p[j] = r.plastic_strain;
        meta->gap[j] = g;
        meta->stage[j] = r.stage;
        meta->x_left[j] = r.x_left + sx;
        meta->x_right[j] = r.x_right + sx;
        meta->foot[j] = r.footprint;
        meta->foot[j].x_lo += sx;
        meta->foot[j].x_hi += sx;
        meta->foot[j].y_lo += sy;
        meta->foot[j].y_hi += sy;
        if (!m->kx && !m->ky && on_border(m, buf))
            border = fmin(border, top[j]);
    }
    free(l.r);
    /* the face reaches past the surface once u_max passes its gap at the nearest edge and a
     * border rod is touched */
    double edge = fmin(m->px - m->e.x_lo, m->e.x_hi - m->px);
    if (m->d->dims == 2)
        edge = fmin(edge, fmin(m->py - m->e.y_lo, m->e.y_hi - m->py));
    edge = fmax(edge, 0.0); /* an apex off a set of points: the border is already reached */
    meta->reach =
        m->kx || m->ky ? INFINITY : fmax(border, ct_body_gap(m->body, edge * m->hx) * m->hz);
    snprintf(meta->why, sizeof meta->why,
             "the %s's contact reaches the border of the surface (x %.6g .. %.6g%s): beyond it "
             "the surface is not known (surface.periodic = true if it repeats)",
             m->d->name, m->e.x_lo * m->hx, m->e.x_hi * m->hx,
             m->d->dims == 2 ? ", y as well" : "");
    const size_t placed = m->n * (size_t)(2 * m->kx + 1) * (size_t)(2 * m->ky + 1);
    ct_bundle_set_surface(*out, &body_rods, meta, ct_bundle_omitted(m->b) + (placed - kept));
    return CT_OK;
}

/* d modulo the period P, in [0, P] (fmod is exact) */
static double in_period(double d, double P)
{
    const double r = fmod(d, P);
    return r < 0.0 ? r + P : r;
}

/* The copies of a periodic surface the face can reach: K periods each way with K P > R, about
 * the apex moved into the base period (the copies lie about the base, and an apex periods away
 * would find some of its surface missing). */
static int copies_of(meeting *m)
{
    if (!m->body->periodic)
        return CT_OK;
    if (m->e.points)
        return ct_error_set(CT_EINVAL,
                            "surface.periodic = true: rods given by points have no extent to "
                            "repeat (a profile or a map does)");
    m->period_x = m->e.x_hi - m->e.x_lo;
    m->period_y = m->d->dims == 2 ? m->e.y_hi - m->e.y_lo : 0.0;
    double px, py; /* a map's grid, its invalid edge points included */
    if (ct_bundle_period(m->b, &px, &py)) {
        m->period_x = px;
        m->period_y = m->d->dims == 2 ? py : 0.0;
    }
    const double R = m->reach / m->hx;
    /* one period more than the reach: the apex anywhere in its period */
    const double kx = ceil(R / m->period_x) + 1.0,
                 ky = m->d->dims == 2 ? ceil(R / m->period_y) + 1.0 : 0.0;
    if (!(kx < 1e4 && ky < 1e4 && (2 * kx + 1) * (2 * ky + 1) * (double)ct_bundle_size(m->b) < 1e9))
        return ct_error_set(CT_EINVAL,
                            "surface.periodic = true: a face of R = %g reaching %g over a period "
                            "of %g needs %.3g copies of the surface: too many",
                            m->body->radius, R * m->hx, m->period_x * m->hx,
                            (2 * kx + 1) * (2 * ky + 1));
    m->kx = (int)kx;
    m->ky = (int)ky;
    return CT_OK;
}

/* The face's reach [the body's length unit]: no rod farther from the apex than where its gap
 * passes the deepest rod bottom h (nothing below it can be kept): sqrt(h (2R - h)), R itself
 * when h >= R. */
static double reach_of(const meeting *m)
{
    double h = 0.0;
    for (size_t k = 0; k < ct_bundle_size(m->b); k++) {
        ct_rod_info r;
        ct_bundle_rod(m->b, k, &r);
        h = fmax(h, r.top + r.length);
    }
    const double Rb = m->body->radius, hb = h / m->hz; /* in the body's unit */
    return hb < Rb ? sqrt(hb * (2.0 * Rb - hb)) : Rb;
}

/* What every apex on a surface shares: the checks, the extent, the units, the copies of a
 * periodic surface and (table) the rods read once. m->d stays the flat body's for a flat body
 * (nothing to meet). */
static int site_init(meeting *m, const ct_body *body, const ct_scales *sc, const ct_bundle *b,
                     int table)
{
    *m = (meeting){.body = body, .d = &ct_body_flat, .b = b};
    int st;
    if ((st = check_body(body, &m->d)) || m->d->dims == 0)
        return st;
    const size_t n = ct_bundle_size(b);
    extent_of(b, &m->e);
    if (m->e.placeless)
        return ct_error_set(CT_EINVAL,
                            "body.shape = %s: %zu of the %zu rods stand at no single place (a "
                            "Cantor surface's stage rods merge the pieces of a stage: give "
                            "surface.representation = segments)",
                            m->d->name, m->e.placeless, n);
    if (m->e.dims != m->d->dims)
        return ct_error_set(CT_EINVAL, "body.shape = %s: %s", m->d->name, m->d->needs);
    /* the rods' units against the body's: x in the rods' unit is hx of the body's, a gap in
     * the body's unit is hz of the rods' (a Cantor surface is built per l0 and h0; l0 is an
     * area on a plane, whose positions are built in its square root's unit) */
    m->hx = m->e.dims == 2 ? sqrt(sc->physical.l0 / sc->layer.l0) : sc->physical.l0 / sc->layer.l0;
    m->hz = sc->layer.h0 / sc->physical.h0;
    m->reach = reach_of(m);
    if ((st = copies_of(m)))
        return st;
    return read_rods(m, table);
}

/* The rods of site as the body meets them with its apex at (px, py) [the rods' horizontal
 * unit] into *out. */
static int meet_at(const meeting *site, const cells *c, double px, double py, ct_bundle **out)
{
    meeting m = *site;
    m.px = px;
    m.py = py;
    if (m.kx || m.ky) { /* about the base period: the copies lie about it */
        m.px = m.e.x_lo + in_period(m.px - m.e.x_lo, m.period_x);
        if (m.d->dims == 2)
            m.py = m.e.y_lo + in_period(m.py - m.e.y_lo, m.period_y);
    }
    const double H = crushed_limit(&m, c);
    if (!isfinite(H))
        return ct_error_set(CT_EINVAL,
                            "body.shape = %s: the face (R = %g) reaches no rod from its apex at "
                            "x = %g",
                            m.d->name, m.body->radius, m.px * m.hx);
    return shifted(&m, c, H, out); /* at least the rod whose bottom fixes H is kept */
}

int ct_body_apply(const ct_body *body, const ct_scales *sc, ct_bundle **bp, ct_plan_info *info)
{
    meeting m;
    int st;
    if (!body)
        return CT_OK;
    if ((st = site_init(&m, body, sc, *bp, 0)) || m.d->dims == 0)
        return st;
    double px = 0.0, py = 0.0;
    ct_bundle *out = NULL;
    if (!(st = apex_of(body, m.d, &m.e, m.hx, &px, &py)))
        st = meet_at(&m, NULL, px, py, &out);
    free(m.rods);
    if (st)
        return st;
    ct_bundle_free(*bp); /* what the body needs of it is in out's metadata */
    *bp = out;
    if (info) {
        info->rods = ct_bundle_size(out);
        info->omitted = ct_bundle_omitted(out);
    }
    return CT_OK;
}

/* ---- landings ---- */

struct ct_body_site {
    meeting m;
    ct_body body;
    cells c;
};

static void cells_free(cells *c)
{
    free(c->start);
    free(c->idx);
    free(c->box);
    free(c->top_min);
    free(c->bottom_min);
}

/* The site's rods (read into m->rods) by cell: about 64 rods to a cell. */
static int cells_build(const meeting *m, cells *c)
{
    const size_t n = m->n, per = 64;
    const int plane = m->d->dims == 2;
    c->nx = plane ? (size_t)ceil(sqrt((double)n / per)) : (n + per - 1) / per;
    c->nx = c->nx ? c->nx : 1;
    c->ny = plane ? c->nx : 1;
    const size_t nc = c->nx * c->ny;
    c->start = calloc(nc + 1, sizeof *c->start);
    c->idx = malloc((n ? n : 1) * sizeof *c->idx);
    c->box = malloc(4 * nc * sizeof *c->box);
    c->top_min = malloc(nc * sizeof *c->top_min);
    c->bottom_min = malloc(nc * sizeof *c->bottom_min);
    size_t *cell = malloc((n ? n : 1) * sizeof *cell);
    if (!c->start || !c->idx || !c->box || !c->top_min || !c->bottom_min || !cell) {
        free(cell);
        return ct_error_set(CT_ENOMEM, "body: out of memory for the cells of %zu rods", n);
    }
    for (size_t q = 0; q < nc; q++) {
        double *bx = c->box + 4 * q;
        bx[0] = bx[2] = INFINITY;
        bx[1] = bx[3] = -INFINITY;
        c->top_min[q] = c->bottom_min[q] = INFINITY;
    }
    for (size_t k = 0; k < n; k++) { /* counting sort by cell: rods in increasing order */
        const double *v = m->rods + k * NFIELDS;
        cell[k] = cell_at(m, c, 0.5 * (v[X_LO] + v[X_HI]), 0.5 * (v[Y_LO] + v[Y_HI]));
        c->start[cell[k] + 1]++;
    }
    for (size_t q = 0; q < nc; q++)
        c->start[q + 1] += c->start[q];
    size_t *next = malloc((nc ? nc : 1) * sizeof *next);
    if (!next) {
        free(cell);
        return ct_error_set(CT_ENOMEM, "body: out of memory for the cells of %zu rods", n);
    }
    memcpy(next, c->start, nc * sizeof *next);
    for (size_t k = 0; k < n; k++) {
        const double *v = m->rods + k * NFIELDS;
        const size_t q = cell[k];
        double *bx = c->box + 4 * q;
        c->idx[next[q]++] = k;
        bx[0] = fmin(bx[0], v[X_LO]);
        bx[1] = fmax(bx[1], v[X_HI]);
        bx[2] = fmin(bx[2], v[Y_LO]);
        bx[3] = fmax(bx[3], v[Y_HI]);
        c->top_min[q] = fmin(c->top_min[q], v[TOP]);
        c->bottom_min[q] = fmin(c->bottom_min[q], v[TOP] + v[LENGTH]);
    }
    free(next);
    free(cell);
    return CT_OK;
}

int ct_body_site_new(const ct_body *body, const ct_scales *sc, const ct_bundle *b,
                     ct_body_site **out)
{
    *out = NULL;
    ct_body_site *s = calloc(1, sizeof *s);
    if (!s)
        return ct_error_set(CT_ENOMEM, "body: out of memory");
    s->body = *body;
    int st = site_init(&s->m, &s->body, sc, b, 1);
    if (!st && s->m.d->dims == 0)
        st = ct_error_set(CT_EINVAL, "body.landings: the flat strip lands everywhere alike: "
                                     "landings need a curved body (body.shape)");
    if (!st)
        st = cells_build(&s->m, &s->c);
    if (st) {
        ct_body_site_free(s);
        return st;
    }
    *out = s;
    return CT_OK;
}

void ct_body_site_free(ct_body_site *s)
{
    if (s) {
        free(s->m.rods);
        cells_free(&s->c);
        free(s);
    }
}

int ct_body_site_region(const ct_body_site *s, double lo[2], double hi[2])
{
    const meeting *m = &s->m;
    const int plane = m->d->dims == 2;
    const double rho = m->body->periodic ? 0.0 : m->reach;
    const double x0 = m->e.x_lo * m->hx, y0 = m->e.y_lo * m->hx;
    lo[0] = x0 + rho;
    hi[0] = m->body->periodic ? x0 + m->period_x * m->hx : m->e.x_hi * m->hx - rho;
    lo[1] = plane ? y0 + rho : NAN;
    hi[1] = !plane ? NAN : m->body->periodic ? y0 + m->period_y * m->hx : m->e.y_hi * m->hx - rho;
    if (!(lo[0] <= hi[0]) || (plane && !(lo[1] <= hi[1])))
        return ct_error_set(CT_EINVAL,
                            "body.landings: a %s of R = %g reaches %g from its apex before the "
                            "layer crushes: on a surface of x %g .. %g%s no apex keeps its face "
                            "on the surface (a smaller radius, a larger surface, or "
                            "surface.periodic = true if it repeats)",
                            m->d->name, m->body->radius, m->reach, x0, m->e.x_hi * m->hx,
                            plane ? " (and y)" : "");
    return CT_OK;
}

int ct_body_site_meet(const ct_body_site *s, const double pos[2], ct_bundle **out)
{
    const meeting *m = &s->m;
    return meet_at(m, &s->c, pos[0] / m->hx, m->d->dims == 2 ? pos[1] / m->hx : 0.0, out);
}

int ct_body_landing_region(const ct_body *body, const ct_scales *scales, const ct_bundle *rods,
                           double lo[2], double hi[2])
{
    CT_NEED(body);
    CT_NEED(scales);
    CT_NEED(rods);
    meeting m;
    int st = site_init(&m, body, scales, rods, 0);
    if (!st && m.d->dims == 0)
        st = ct_error_set(CT_EINVAL, "body.landings: the flat strip lands everywhere alike: "
                                     "landings need a curved body (body.shape)");
    ct_body_site s = {.m = m, .body = *body};
    s.m.body = &s.body;
    if (!st)
        st = ct_body_site_region(&s, lo, hi);
    free(m.rods);
    return st;
}

void ct_body_landing(const double lo[2], const double hi[2], uint64_t seed, uint64_t k,
                     double pos[2])
{
    /* one Philox4x64-10 block per landing: key (seed, "landings"), counter k; a uniform in
     * [0, 1) from the top 53 bits of a word */
    const philox4x64_key_t key = {{seed, UINT64_C(0x6c616e64696e6773)}};
    const philox4x64_ctr_t ctr = {{k, 0, 0, 0}};
    const philox4x64_ctr_t r = philox4x64(ctr, key);
    for (int i = 0; i < 2; i++) {
        const double u = (double)(r.v[i] >> 11) * 0x1p-53;
        pos[i] = isnan(lo[i]) ? NAN : lo[i] + u * (hi[i] - lo[i]);
    }
}

int ct_body_write_rods(const ct_bundle *b, const ct_scales *sc, FILE *f)
{
    const body_meta *m = ct_bundle_surface_meta(b, &body_rods);
    if (!m)
        return ct_error_set(CT_EINVAL, "what = profile: the rods were not met by a curved body");
    const double h0 = sc->layer.h0, l0 = sc->layer.l0;
    int areal = 0;
    for (size_t k = 0; k < ct_bundle_size(b) && !areal; k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        areal = !isnan(r.footprint.y_lo);
    }
    const double hx = areal ? sqrt(sc->physical.l0 / l0) : sc->physical.l0 / l0; /* as applied */
    fputs(areal ? "rod,x_lo,x_hi,y_lo,y_hi," : "rod,x_lo,x_hi,", f);
    fputs("top_over_h0,gap_over_h0,area_over_l0,length_over_h0,residual_top_over_h0\n", f);
    for (size_t k = 0; k < ct_bundle_size(b); k++) {
        ct_rod_info r;
        ct_bundle_rod(b, k, &r);
        const double v[9] = {r.footprint.x_lo * hx,
                             r.footprint.x_hi * hx,
                             r.footprint.y_lo * hx,
                             r.footprint.y_hi * hx,
                             (r.top - m->gap[k]) / h0,
                             m->gap[k] / h0,
                             r.area / l0,
                             r.length / h0,
                             (r.top - m->gap[k] + r.plastic_strain * r.length) / h0};
        ct_put_long(f, (long)k + 1);
        for (int i = 0; i < 9; i++) {
            if (!areal && (i == 2 || i == 3))
                continue;
            fputc(',', f);
            ct_put_double(f, v[i]);
        }
        fputc('\n', f);
    }
    return CT_OK;
}

int ct_body_met(const ct_bundle *b)
{
    return ct_bundle_surface_meta(b, &body_rods) != NULL;
}

void ct_body_describe(const ct_body *body, char *buf, size_t len)
{
    if (!len)
        return;
    buf[0] = '\0';
    if (!body || body->shape <= 0 || (size_t)body->shape >= NBODIES)
        return;
    const double *p = body->position;
    char at[96];
    if (isnan(p[0]))
        snprintf(at, sizeof at, "the middle of the surface");
    else if (isnan(p[1]))
        snprintf(at, sizeof at, "x = %g", p[0]);
    else
        snprintf(at, sizeof at, "x = %g, y = %g", p[0], p[1]);
    snprintf(buf, len, "under a %s of R = %g, its apex at %s%s", registry[body->shape]->name,
             body->radius, at, body->periodic ? ", the surface repeating" : "");
}

int ct_body_curved(const ct_body *body)
{
    return body && body->shape > 0 && (size_t)body->shape < NBODIES &&
           registry[body->shape]->dims > 0;
}

int ct_body_meet(const ct_body *body, const ct_scales *scales, ct_bundle **b)
{
    CT_NEED(scales);
    CT_NEED(b);
    CT_NEED(*b);
    return ct_body_apply(body, scales, b, NULL);
}
