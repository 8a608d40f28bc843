/* The load curve P(u) of a bundle's state (docs/model.md §4), held as the piecewise-linear
 * function it is.
 *
 * Each rod contributes two events: at its contact point c = top + eps_p L the slope of P
 * rises by k = E s / L, at its yield point y = c + eps_y L it falls by k and the plateau
 * force F = E s eps_y joins the yielded rods. One sweep over the sorted events gives, at
 * every distinct breakpoint x_j: P_j, the slope and yielded force on [x_j, x_{j+1}), the
 * cumulative work W_j (trapezoid on the breakpoints: exact, as P is linear between them)
 * and the dissipation D_j (loaded to x_j, the yielded rods have done sum F (x_j - y) of
 * plastic work). Every increment of P, W and D is non-negative and summed compensated, so
 * nothing cancels: the curve agrees with the rod-by-rod sums to a few ulps.
 *
 * Sorting: rods that follow each other with the same top, length and plastic strain (the
 * pieces of a Cantor stage) make one event pair. Contacts and yields are laid out in rod
 * order, then merged as monotone runs (natural merge sort): two runs for virgin Cantor
 * stages (O(n)), O(n log n) for arbitrary tops. Events are totally ordered (x, then the
 * slope change, then the force change), so the sorted sequence, and everything summed from
 * it, is the same for any thread count; only independent merges run in parallel. */
#include "curve_lean.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* On x86-64 the sweep over the events also gets an AVX2 clone, picked at load time: three-
 * operand instructions and blends for the compensated sums' selects, a quarter fewer
 * instructions an event. The same IEEE operations, so the same bits (no FMA: contraction is
 * off under -std=c11, as in bundle.c). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                             \
    !defined(__SANITIZE_ADDRESS__)
#define CT_CURVE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CT_CURVE_CLONES
#endif

struct ct_curve {
    size_t n, cap;
    double *x, *P, *W, *D, *slope, *A;
    double *Lmax; /* largest length of the rods yielded at x_j (0: none) */
    double *cmin; /* smallest contact of the rods not yielded at x_j (inf: none) */
    double first_yield, eps_y;
    event *ev, *tmp;
    size_t ecap, tcap;
    size_t *runs, rcap;
    size_t *block_runs, bcap;
    size_t ne;  /* events of the last build, sorted in ev */
    double *ux; /* an unloading curve's sorted events for its builder: x, then the slopes */
    size_t ucap;
    ct_lean *lean; /* not NULL: a lean curve (curve_lean.c), none of the arrays above */
};

int ct_curve_alloc(ct_curve **out)
{
    CT_NEED(out);
    *out = calloc(1, sizeof **out);
    if (!*out)
        return ct_error_set(CT_ENOMEM, "curve: out of memory");
    (*out)->first_yield = INFINITY;
    return CT_OK;
}

static void free_points(ct_curve *c)
{
    free(c->x);
    free(c->P);
    free(c->W);
    free(c->D);
    free(c->slope);
    free(c->A);
    free(c->Lmax);
    free(c->cmin);
    c->x = c->P = c->W = c->D = c->slope = c->A = c->Lmax = c->cmin = NULL;
    c->cap = 0;
}

static void free_work(ct_curve *c)
{
    free(c->ev);
    free(c->tmp);
    free(c->runs);
    free(c->block_runs);
    free(c->ux);
    c->ev = c->tmp = NULL;
    c->runs = c->block_runs = NULL;
    c->ux = NULL;
    c->ecap = c->tcap = c->rcap = c->bcap = c->ucap = 0;
}

void ct_curve_free(ct_curve *c)
{
    if (!c)
        return;
    ct_lean_free(c->lean);
    free_points(c);
    free_work(c);
    free(c);
}

size_t ct_curve_size(const ct_curve *c)
{
    return c->n;
}

const double *ct_curve_points(const ct_curve *c)
{
    return c->lean ? NULL : c->x; /* the sweep's own lean curves are never the caller's */
}

double ct_curve_first_contact(const ct_curve *c)
{
    if (c->lean)
        return ct_lean_first_contact(c->lean);
    return c->n ? c->x[0] : INFINITY;
}

double ct_curve_first_yield(const ct_curve *c)
{
    return c->first_yield;
}

static int less(const event *a, const event *b)
{
    return ct_event_less(a, b);
}

/* Merges the sorted runs [lo, mid) and [mid, hi) of src into dst. */
static void merge(const event *src, event *dst, size_t lo, size_t mid, size_t hi)
{
    size_t i = lo, j = mid, k = lo;
    while (i < mid && j < hi)
        dst[k++] = less(&src[j], &src[i]) ? src[j++] : src[i++];
    while (i < mid)
        dst[k++] = src[i++];
    while (j < hi)
        dst[k++] = src[j++];
}

/* Natural merge sort of c->ev[0..n): the result is in c->ev. */
static int sort_events(ct_curve *c, size_t n, int team)
{
    event *a = c->ev, *b = c->tmp;
    if (n < 2)
        return CT_OK;
    /* runs: ascending, or strictly descending (reversed in place) */
    size_t nr = 0;
    c->runs[nr++] = 0;
    size_t i = 0;
    while (i < n) {
        size_t j = i + 1;
        if (j < n && less(&a[j], &a[i])) {
            while (j < n && less(&a[j], &a[j - 1]))
                j++;
            for (size_t l = i, r = j - 1; l < r; l++, r--) {
                event t = a[l];
                a[l] = a[r];
                a[r] = t;
            }
        } else {
            while (j < n && !less(&a[j], &a[j - 1]))
                j++;
        }
        c->runs[nr++] = j;
        i = j;
    }
    size_t count = nr - 1; /* runs; boundaries runs[0..count] */
    (void)team;
    while (count > 1) {
        size_t pairs = count / 2;
        if (team > 1 && pairs > 1) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
            for (ptrdiff_t p = 0; p < (ptrdiff_t)pairs; p++) {
                size_t lo = c->runs[2 * p], mid = c->runs[2 * p + 1], hi = c->runs[2 * p + 2];
                merge(a, b, lo, mid, hi);
            }
        } else { /* no thread team for small sorts: entering one costs more than the merge */
            for (size_t p = 0; p < pairs; p++)
                merge(a, b, c->runs[2 * p], c->runs[2 * p + 1], c->runs[2 * p + 2]);
        }
        if (count % 2) { /* the odd run out is copied */
            size_t lo = c->runs[count - 1], hi = c->runs[count];
            memcpy(b + lo, a + lo, (hi - lo) * sizeof(event));
        }
        size_t nc = 0;
        for (size_t r = 0; r <= count; r += 2)
            c->runs[nc++] = c->runs[r];
        if (count % 2 == 0)
            ; /* the last boundary (runs[count]) was kept by the loop */
        else
            c->runs[nc++] = c->runs[count];
        count = nc - 1;
        event *t = a;
        a = b;
        b = t;
    }
    if (a != c->ev) { /* swap the buffers with their capacities */
        size_t cap = c->ecap;
        c->tmp = c->ev;
        c->ev = a;
        c->ecap = c->tcap;
        c->tcap = cap;
    }
    return CT_OK;
}

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 16;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * size);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

double ct_curve_bytes(size_t events)
{
    /* events twice (the merge's buffer), run bounds, and 8 doubles per breakpoint */
    return (double)events * (2.0 * sizeof(event) + sizeof(size_t) + 8.0 * sizeof(double));
}

typedef struct {
    const double *top, *length, *area, *eps_p;
    size_t n;
    double E, eps_y;
    size_t nruns;
} rods_in;

/* Pass 1 of a build for block j: the runs of identical rods in it. */
static void count_runs(ct_curve *c, const rods_in *r, size_t j)
{
    size_t k0 = j * CT_BLOCK, k1 = k0 + CT_BLOCK < r->n ? k0 + CT_BLOCK : r->n, runs = 1;
    for (size_t k = k0 + 1; k < k1; k++)
        runs += !ct_same_rod(r->top, r->length, r->eps_p, k);
    c->block_runs[j + 1] = runs;
}

/* The events of the run of identical rods that starts at rod k (and ends before k1, the end
 * of its block): its contact and its yield. Returns the rod after the run. */
static inline size_t run_events(const rods_in *r, size_t k, size_t k1, event *contact_ev,
                                event *yield_ev)
{
    size_t l;
    const double s = ct_run_area(r->top, r->length, r->eps_p, r->area, k, k1, &l);
    ct_run_events(r->top[k], r->length[k], r->eps_p[k], s, r->E, r->eps_y, contact_ev, yield_ev);
    return l;
}

/* Pass 2 for block j: a contact and a yield event per run, contacts first. */
static void block_events(ct_curve *c, const rods_in *r, size_t j)
{
    size_t k0 = j * CT_BLOCK, k1 = k0 + CT_BLOCK < r->n ? k0 + CT_BLOCK : r->n;
    size_t out = c->block_runs[j];
    event *ev = c->ev;
    for (size_t k = k0; k < k1; out++)
        k = run_events(r, k, k1, &ev[out], &ev[r->nruns + out]);
}

/* The next run's contact (yields = 0) or yield event, from rod *k; *end is the end of its
 * block (a block's start begins a run). */
static inline void next_event(const rods_in *r, int yields, size_t *k, size_t *end, event *e)
{
    event unused;
    /* every run one rod (a random Cantor realisation): ct_run_area's sum of one area, without
     * looking for a next rod like it nor for the block's end (with longer runs, rod by rod
     * would give the merge equal x and send it to the general passes) */
    if (r->nruns == r->n) {
        const size_t l = (*k)++;
        const double s = r->area[l] + 0.0;
        ct_run_events(r->top[l], r->length[l], r->eps_p[l], s, r->E, r->eps_y, yields ? &unused : e,
                      yields ? e : &unused);
        return;
    }
    if (*k == *end)
        *end = *k + CT_BLOCK < r->n ? *k + CT_BLOCK : r->n;
    *k = yields ? run_events(r, *k, *end, &unused, e) : run_events(r, *k, *end, e, &unused);
}

/* Pass 2 in one, when the contacts in rod order have strictly increasing x, so do the yields,
 * and no contact shares its x with a yield (a virgin bundle sorted by top, such as a random
 * Cantor realisation): the two are merged as they are made, into the only order `less` then
 * allows, which sort_events finds as one run; without laying them out and merging them
 * after. Returns 0 at the first x out of order, shared or NaN, leaving ev to the general
 * pass. (A branch-free merge, both candidates made into both events and the earlier written
 * by a select, took twice the instructions and more than twice the time: docs/benchmarks.md.) */
CT_CURVE_CLONES
static int merged_events(ct_curve *c, const rods_in *r)
{
    const size_t nruns = r->nruns;
    event *ev = c->ev, ce, ye;
    size_t kc = 0, endc = 0, ky = 0, endy = 0, nc = 0, ny = 0, out = 0;
    double last_c = -INFINITY, last_y = -INFINITY;
    next_event(r, 0, &kc, &endc, &ce);
    next_event(r, 1, &ky, &endy, &ye);
    while (ny < nruns) {
        if (nc < nruns && ce.x < ye.x) {
            if (!(ce.x > last_c))
                return 0;
            last_c = ce.x;
            ev[out++] = ce;
            if (++nc < nruns)
                next_event(r, 0, &kc, &endc, &ce);
        } else if (nc == nruns || ye.x < ce.x) {
            if (!(ye.x > last_y))
                return 0;
            last_y = ye.x;
            ev[out++] = ye;
            if (++ny < nruns)
                next_event(r, 1, &ky, &endy, &ye);
        } else {
            return 0;
        }
    }
    return nc == nruns;
}

/* Runs a pass (count_runs or block_events) over the nb blocks, by the thread team when there
 * is one (it pays only on large bundles: entering one costs more than a small curve). Pass 2
 * without a team first tries the events merged as they are made; returns 1 when they were
 * (sorted already: every x distinct). */
static int block_pass(ct_curve *c, const rods_in *r, size_t nb, int team,
                      void (*pass)(ct_curve *c, const rods_in *r, size_t j))
{
    if (pass == block_events && team <= 1 && merged_events(c, r))
        return 1;
    if (team > 1) {
#pragma omp parallel for schedule(static) num_threads(team)
        for (ptrdiff_t j = 0; j < (ptrdiff_t)nb; j++)
            pass(c, r, (size_t)j);
    } else {
        for (size_t j = 0; j < nb; j++)
            pass(c, r, j);
    }
    return 0;
}

size_t ct_curve_events(const ct_bundle *b)
{
    const size_t n = ct_bundle_size(b);
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    size_t runs = 0;
    for (size_t k = 0; k < n; k++) /* block starts begin runs, as in ct_curve_build */
        runs += k % CT_BLOCK == 0 || !ct_same_rod(top, length, eps_p, k);
    return 2 * runs;
}

/* Makes room for n breakpoints (the arrays of the sweep). */
static int reserve_points(ct_curve *c, size_t n)
{
    if (n <= c->cap)
        return 0;
    free_points(c);
    c->x = malloc(n * sizeof(double));
    c->P = malloc(n * sizeof(double));
    c->W = malloc(n * sizeof(double));
    c->D = malloc(n * sizeof(double));
    c->slope = malloc(n * sizeof(double));
    c->A = malloc(n * sizeof(double));
    c->Lmax = malloc(n * sizeof(double));
    c->cmin = malloc(n * sizeof(double));
    if (!c->x || !c->P || !c->W || !c->D || !c->slope || !c->A || !c->Lmax || !c->cmin) {
        free_points(c);
        return -1;
    }
    c->cap = n;
    return 0;
}

/* Room for ne events of a curve of n rods (-1: out of memory), or CT_ENOMEM when the memory
 * available cannot hold the build. */
static int room_for_events(ct_curve *c, size_t n, size_t ne)
{
    /* the memory check reads /proc/meminfo: only for curves where it can matter */
    const double need = ct_curve_bytes(ne);
    const double have = need < 64e6 ? INFINITY
                                    : (double)ct_available_memory() +
                                          (double)(c->ecap + c->tcap) * sizeof(event) +
                                          8.0 * sizeof(double) * c->cap;
    if (need > 0.9 * have)
        return ct_error_set(CT_ENOMEM,
                            "load curve of %zu rods (%zu events): needs %.3g GiB, more than the "
                            "%.3g GiB of memory available",
                            n, ne, need / 1073741824.0, have / 1073741824.0);
    if (grow((void **)&c->ev, &c->ecap, ne, sizeof(event)) ||
        grow((void **)&c->tmp, &c->tcap, ne, sizeof(event)) ||
        grow((void **)&c->runs, &c->rcap, ne + 1, sizeof(size_t)))
        return -1;
    return CT_OK;
}

/* The sweep's breakpoint at x = ev[i].x: the events there (from i on, before end), then its
 * values and, into cmin, the smallest contact of the rods that yield there, for
 * contacts_below. Returns the event after them. */
static inline size_t sweep_breakpoint(ct_curve *c, ct_sweep_state *st, const event *ev, size_t i,
                                      size_t end)
{
    const double x = ev[i].x;
    double yc = INFINITY; /* of equal contacts the last, as contacts_below's scan takes */
    ct_sweep_to(st, x);
    for (; i < end && ev[i].x == x; i++) {
        const int yield = ct_sweep_event(st, &ev[i]);
        c->first_yield = yield && x < c->first_yield ? x : c->first_yield; /* selects */
        yc = yield && ev[i].c <= yc ? ev[i].c : yc;
    }
    const size_t j = st->j;
    ct_point p;
    ct_sweep_point(st, x, &p);
    c->x[j] = p.x;
    c->P[j] = p.P;
    c->W[j] = p.W;
    c->D[j] = p.D;
    c->slope[j] = p.slope;
    c->A[j] = p.A;
    c->Lmax[j] = p.Lmax;
    c->cmin[j] = yc;
    return i;
}

/* The sweep over the sorted events c->ev[0..ne): the breakpoints and their P, W, D, slope,
 * yielded force and longest yielded rod; into cmin, the smallest contact of the rods that yield
 * at each breakpoint, for contacts_below (-1: out of memory). distinct: every x differs (the
 * merged events), so that there are ne breakpoints of one event each. */
CT_CURVE_CLONES
static int sweep_events(ct_curve *c, size_t ne, int distinct)
{
    const event *ev = c->ev;
    size_t nx = ne;
    if (!distinct) {
        nx = 1;
        for (size_t i = 1; i < ne; i++)
            nx += ev[i].x != ev[i - 1].x;
    }
    if (reserve_points(c, nx))
        return -1;
    ct_sweep_state st = {0};
    if (distinct) {
        for (size_t i = 0; i < ne; i++)
            sweep_breakpoint(c, &st, ev, i, i + 1);
    } else {
        for (size_t i = 0; i < ne;)
            i = sweep_breakpoint(c, &st, ev, i, ne);
    }
    c->n = st.j;
    return 0;
}

/* At every breakpoint, the smallest contact of the rods still below their yield point: a
 * suffix minimum over the yields after it, from the sweep's smallest contact yielding at each
 * breakpoint (in place: of equal contacts the one yielding last, as a scan back over the
 * events would take). */
static void contacts_below(ct_curve *c)
{
    double cm = INFINITY;
    for (size_t q = c->n; q-- > 0;) {
        const double yc = c->cmin[q];
        c->cmin[q] = cm;
        if (yc < cm)
            cm = yc;
    }
}

int ct_curve_build(ct_curve *c, const ct_bundle *b)
{
    CT_NEED(c);
    CT_NEED(b);
    const size_t n = ct_bundle_size(b);
    const ct_layer *L = ct_bundle_layer(b);
    const double eps_y = L->sigma_y / L->E;
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    /* a thread team from 64x the rod threshold (262 144 rods): below it two threads build
     * more slowly than one, and in a short run the team's start and its spinning workers
     * also slow what follows (docs/benchmarks.md has the figures) */
    const int team = ct_bundle_team_from(b, 64);
    const size_t nb = (n + CT_BLOCK - 1) / CT_BLOCK;
    int st;
    ct_lean_free(c->lean);
    c->lean = NULL;
    c->n = 0;
    c->ne = 0;
    c->first_yield = INFINITY;
    c->eps_y = eps_y;
    if (grow((void **)&c->block_runs, &c->bcap, nb + 1, sizeof(size_t)))
        goto oom;
    rods_in rods = {top, length, area, eps_p, n, L->E, eps_y, 0};
    (void)block_pass(c, &rods, nb, team, count_runs); /* pass 1: rod runs per block */
    c->block_runs[0] = 0;
    for (size_t j = 0; j < nb; j++)
        c->block_runs[j + 1] += c->block_runs[j];
    rods.nruns = nb ? c->block_runs[nb] : 0;
    const size_t ne = 2 * rods.nruns;
    if (ne == 0)
        return CT_OK;
    if ((st = room_for_events(c, n, ne)) > 0)
        return st;
    if (st)
        goto oom;
    /* pass 2: contacts in rod order, then yields; sorted unless merged as they were made */
    const int merged = block_pass(c, &rods, nb, team, block_events);
    if (!merged)
        sort_events(c, ne, team);
    c->ne = ne;
    if (sweep_events(c, ne, merged))
        goto oom;
    contacts_below(c);
    return CT_OK;
oom:
    c->n = 0;
    return ct_error_set(CT_ENOMEM, "curve of %zu rods: out of memory", n);
}

/* Largest j with x_j <= u (u >= x_0). */
static size_t piece(const ct_curve *c, double u)
{
    return ct_last_at_most(c->x, c->n, u);
}

/* The lean curve's breakpoint at u (u > its first contact). */
static ct_point lean_piece(const ct_curve *c, double u, double *cmin)
{
    ct_point p;
    ct_lean_piece(c->lean, u, &p, cmin);
    return p;
}

double ct_curve_force(const ct_curve *c, double u)
{
    if (!c->n || !(u > ct_curve_first_contact(c)))
        return 0.0;
    if (c->lean) {
        const ct_point p = lean_piece(c, u, NULL);
        return p.P + p.slope * (u - p.x);
    }
    size_t j = piece(c, u);
    return c->P[j] + c->slope[j] * (u - c->x[j]);
}

double ct_curve_work(const ct_curve *c, double u)
{
    if (!c->n || !(u > ct_curve_first_contact(c)))
        return 0.0;
    if (c->lean) {
        const ct_point p = lean_piece(c, u, NULL);
        const double t = u - p.x;
        return p.W + t * (p.P + 0.5 * p.slope * t);
    }
    size_t j = piece(c, u);
    double t = u - c->x[j];
    return c->W[j] + t * (c->P[j] + 0.5 * c->slope[j] * t);
}

double ct_curve_dissipation(const ct_curve *c, double u)
{
    if (!c->n || !(u > ct_curve_first_contact(c)))
        return 0.0;
    if (c->lean) {
        const ct_point p = lean_piece(c, u, NULL);
        return p.D + p.A * (u - p.x);
    }
    size_t j = piece(c, u);
    return c->D[j] + c->A[j] * (u - c->x[j]);
}

double ct_curve_release(const ct_curve *c, double u)
{
    if (!c->n)
        return INFINITY;
    const double x0 = ct_curve_first_contact(c);
    if (!(u > x0))
        return x0;
    double r, Lmax;
    if (c->lean) {
        Lmax = lean_piece(c, u, &r).Lmax;
    } else {
        size_t j = piece(c, u);
        r = c->cmin[j];
        Lmax = c->Lmax[j];
    }
    if (Lmax > 0.0) {
        double y = u - c->eps_y * Lmax; /* the yielded rods' new contacts */
        r = y < r ? y : r;
    }
    return r;
}

typedef struct {
    void (*fn)(void *ctx, double x, double W);
    void *ctx;
} each_ctx;

static void each_lean_point(void *ctx, const ct_point *p)
{
    const each_ctx *e = ctx;
    e->fn(e->ctx, p->x, p->W);
}

/* The root u >= x of W(u) = W on the piece from x (its W_x, P and slope k; the next breakpoint
 * at x_next, INFINITY: none). W_x + P t + k t^2 / 2 = W: t = 2R / (P + sqrt(P^2 + 2 k R)), no
 * cancellation. The root as hypot(P, sqrt(2R) sqrt(k)): P^2 and k R underflow on deep Cantor
 * tips at tiny speeds (P ~ 1e-206 at V* = 1e-130) where the energies themselves do not. Near
 * the top of the doubles (R above DBL_MAX / 2, or P or k R near DBL_MAX) 2R or the denominator
 * overflow (sqrt(inf) sqrt(0) is NaN: the root was 0, the piece's start returned as a wrong
 * finite u): the same root with R, P and k quartered, which nothing overflows. A root beyond
 * the doubles is inf, never a finite number. */
static double inverse_on(double x, double W_x, double P, double k, double x_next, double W)
{
    const double R = W - W_x, R_root = R > 0.0 ? R : 0.0, k_root = k > 0.0 ? k : 0.0;
    double den = P + hypot(P, sqrt(2.0 * R_root) * sqrt(k_root));
    double t = den > 0.0 ? 2.0 * R / den : 0.0;
    if (!isfinite(den) || !isfinite(2.0 * R)) {
        const double P_q = 0.25 * P, R_q = 0.25 * R;
        den = P_q + hypot(P_q, sqrt(2.0 * (0.25 * R_root)) * sqrt(0.25 * k_root));
        t = den > 0.0 ? 2.0 * R_q / den : 0.0;
    }
    if (t > x_next - x)
        t = x_next - x;
    return x + t;
}

double ct_curve_inverse_work(const ct_curve *c, double W)
{
    if (!c->n || !(W >= 0.0))
        return NAN;
    if (W == 0.0)
        return ct_curve_first_contact(c);
    if (c->lean) {
        ct_point p;
        double x_next;
        ct_lean_piece_of_work(c->lean, W, &p, &x_next);
        return inverse_on(p.x, p.W, p.P, p.slope, x_next, W);
    }
    const size_t lo = ct_last_at_most(c->W, c->n, W), hi = lo + 1; /* W[lo] <= W < W[hi] */
    return inverse_on(c->x[lo], c->W[lo], c->P[lo], c->slope[lo], hi < c->n ? c->x[hi] : INFINITY,
                      W);
}

void ct_curve_each_point(const ct_curve *c, void (*fn)(void *ctx, double x, double W), void *ctx)
{
    if (c->lean) {
        each_ctx e = {fn, ctx};
        ct_lean_each_point(c->lean, each_lean_point, &e);
        return;
    }
    for (size_t j = 0; j < c->n; j++)
        fn(ctx, c->x[j], c->W[j]);
}

double ct_curve_lean_bytes(size_t events)
{
    return ct_lean_bytes(events / 2);
}

int ct_curve_build_lean(ct_curve *c, const ct_bundle *b)
{
    CT_NEED(c);
    CT_NEED(b);
    ct_lean *L;
    int st = ct_lean_build(&L, b);
    if (st)
        return st;
    ct_lean_free(c->lean);
    c->lean = L;
    c->n = ct_lean_size(L);
    c->ne = 0;
    c->first_yield = ct_lean_first_yield(L);
    c->eps_y = ct_bundle_layer(b)->sigma_y / ct_bundle_layer(b)->E;
    return CT_OK;
}

void ct_curve_view_of(const ct_curve *c, ct_curve_view *v)
{
    v->n = c->lean ? 0 : c->n; /* a lean curve has no arrays to view (the sweep never asks) */
    v->x = c->x;
    v->P = c->P;
    v->W = c->W;
    v->slope = c->slope;
}

/* ---- unloading curves ---- */

/* The unloading curve (Eq. 11 rod by rod): loaded from a state to u_max, every rod in contact
 * unloads along its elastic line, k (u - r), from its release point r: its contact if it did
 * not yield, u_max - eps_y L if it did (r = contact + (u_max - yield)). In terms of the
 * state's sorted events below u_max: each contact adds its slope at its contact, and each
 * yield takes that slope back at the rod's contact and adds it again at its release. Those
 * three sequences of events, swept like a loading curve without yields, give the curve; its
 * last breakpoint is u_max. unload_sweep below builds one: ct_curve_unload hands it the three
 * sequences sorted into one, ct_unload_split (the sweep's fast path) the sequences themselves
 * when each is already in order. unload_sweep_nested is that sweep for the nested case (every
 * virgin layer: two sequences of increments >= +0, plain sums), the one the sweep's time
 * columns and a single history run per impact. */

/* The release point of a yielded rod of contact c and eps_y L = eL (never below c). */
static double release_point(double u_max, double eL, double c)
{
    const double r = u_max - eL;
    return r < c ? c : r;
}

/* A sequence of unloading events in x order: at x[i] the slope changes by sign k[i] (sign
 * -1: contacts taken back). */
typedef struct {
    const double *x, *k;
    double sign; /* 1 or -1: the product is exact */
    size_t n;
} run;

/* The slope (ks + kc) and the count of rods in contact after run r's events at x, from
 * its next event at[0] (at x: head); returns the run's next x (inf: none left). */
static double take(const run *r, size_t *at, double head, double x, double *ks, double *kc,
                   ptrdiff_t *touching)
{
    while (head == x) {
        const double dk = r->sign * r->k[*at];
        ct_add_comp(ks, kc, dk);
        *touching += signbit(dk) ? -1 : 1;
        head = ++*at < r->n ? r->x[*at] : INFINITY;
    }
    return head;
}

/* The builder. Sweeps the events of the three runs in x order (at equal x run by run, each
 * in its own order): a slope change dk >= +0 brings a rod into contact, dk <= -0 takes one
 * out (a rod of underflowed area: -0). Writes x, P, W and the slope on [x_j, x_j+1) at every
 * distinct x from the first where a rod touches (the first release), then at u_max, the top
 * of the branch; returns how many (at most the distinct x + 1; 0: no rod in contact). */
static size_t unload_sweep(const run r[3], double u_max, double *x, double *P, double *W,
                           double *slope)
{
    size_t a0 = 0, a1 = 0, a2 = 0, j = 0;
    double h0 = r[0].n ? r[0].x[0] : INFINITY, h1 = r[1].n ? r[1].x[0] : INFINITY,
           h2 = r[2].n ? r[2].x[0] : INFINITY;
    double ks = 0.0, kc = 0.0, Ps = 0.0, Pc = 0.0, Ws = 0.0, Wc = 0.0, k_prev = 0.0, P_prev = 0.0;
    double x_prev = 0.0;    /* the last point's x */
    ptrdiff_t touching = 0; /* rods in contact: the curve starts at the first release */
    for (;;) {
        const double xj = h0 < h1 ? (h0 < h2 ? h0 : h2) : (h1 < h2 ? h1 : h2);
        if (xj == INFINITY)
            break;
        if (j > 0) {
            const double dx = xj - x_prev;
            ct_add_comp(&Ps, &Pc, k_prev * dx);
            const double Pj = Ps + Pc;
            ct_add_comp(&Ws, &Wc, 0.5 * (P_prev + Pj) * dx);
            P_prev = Pj;
        }
        h0 = take(&r[0], &a0, h0, xj, &ks, &kc, &touching);
        h1 = take(&r[1], &a1, h1, xj, &ks, &kc, &touching);
        h2 = take(&r[2], &a2, h2, xj, &ks, &kc, &touching);
        if (touching == 0) /* no rod touches: slope 0, not a rounding residue */
            ks = kc = 0.0;
        k_prev = ks + kc > 0.0 ? ks + kc : 0.0;
        if (j == 0 && touching == 0)
            continue; /* before the first release: no contact, no point */
        x[j] = x_prev = xj;
        P[j] = P_prev;
        W[j] = Ws + Wc;
        slope[j] = k_prev;
        j++;
    }
    if (j > 0 && x_prev < u_max) { /* the top of the unloading branch */
        const double dx = u_max - x_prev;
        ct_add_comp(&Ps, &Pc, k_prev * dx);
        ct_add_comp(&Ws, &Wc, 0.5 * (P_prev + Ps + Pc) * dx);
        x[j] = u_max;
        P[j] = Ps + Pc;
        W[j] = Ws + Wc;
        slope[j] = k_prev;
        j++;
    }
    return j;
}

/* The nested sweep's P and W from its last point across dx at slope k: plain sums (every
 * term >= +0, so P and W never decrease). */
static void nested_step(double dx, double k, double *P, double *W)
{
    const double P_prev = *P;
    *P += k * dx;
    *W += 0.5 * (P_prev + *P) * dx;
}

/* unload_sweep of two runs of sign 1 whose slope changes are all >= +0 (the nested case),
 * with plain sums: a rod touches from the first event on, so the count of rods in contact
 * and the compensations are left out; the runs are swept in the same order. */
static size_t unload_sweep_nested(const run r[2], double u_max, double *x, double *P, double *W,
                                  double *slope)
{
    const double *x0 = r[0].x, *k0 = r[0].k, *x1 = r[1].x, *k1 = r[1].k;
    const size_t n0 = r[0].n, n1 = r[1].n;
    size_t a0 = 0, a1 = 0, j = 0;
    double ks = 0.0, Ps = 0.0, Ws = 0.0, k_prev = 0.0;
    /* from the first event: the step to the first point adds +0 to P and W, which stay +0 */
    double x_prev = n0 && (!n1 || x0[0] < x1[0]) ? x0[0] : n1 ? x1[0] : INFINITY;
    if (x_prev == INFINITY)
        return 0;
    for (;;) {
        const double h0 = a0 < n0 ? x0[a0] : INFINITY;
        /* the points of run 1 alone, below run 0's next event (most of them: run 0 holds the
         * contacts of the few rods still elastic) */
        while (a1 < n1 && x1[a1] < h0) {
            const double xj = x1[a1];
            nested_step(xj - x_prev, k_prev, &Ps, &Ws);
            do
                ks += k1[a1];
            while (++a1 < n1 && x1[a1] == xj);
            k_prev = ks > 0.0 ? ks : 0.0;
            x[j] = x_prev = xj;
            P[j] = Ps;
            W[j] = Ws;
            slope[j] = k_prev;
            j++;
        }
        if (h0 == INFINITY)
            break;
        /* a point at run 0's event: its events there, then run 1's */
        nested_step(h0 - x_prev, k_prev, &Ps, &Ws);
        for (; a0 < n0 && x0[a0] == h0; a0++)
            ks += k0[a0];
        for (; a1 < n1 && x1[a1] == h0; a1++)
            ks += k1[a1];
        k_prev = ks > 0.0 ? ks : 0.0;
        x[j] = x_prev = h0;
        P[j] = Ps;
        W[j] = Ws;
        slope[j] = k_prev;
        j++;
    }
    if (x_prev < u_max) { /* the top of the unloading branch */
        nested_step(u_max - x_prev, k_prev, &Ps, &Ws);
        x[j] = u_max;
        P[j] = Ps;
        W[j] = Ws;
        slope[j] = k_prev;
        j++;
    }
    return j;
}

/* Into out->ev[0..*m): c's events up to u_max as the three sequences, sorted into one (a
 * natural merge sort: they are its runs, monotone for Cantor stages). */
static int unload_events(const ct_curve *c, double u_max, ct_curve *out, size_t *m)
{
    size_t nc = 0, ny = 0;
    for (size_t i = 0; i < c->ne && c->ev[i].x <= u_max; i++)
        signbit(c->ev[i].dk) ? ny++ : nc++;
    *m = nc + 2 * ny;
    if (*m == 0)
        return CT_OK;
    if (grow((void **)&out->ev, &out->ecap, *m, sizeof(event)) ||
        grow((void **)&out->tmp, &out->tcap, *m, sizeof(event)) ||
        grow((void **)&out->runs, &out->rcap, *m + 1, sizeof(size_t)))
        return ct_error_set(CT_ENOMEM, "unloading curve of %zu events: out of memory", *m);
    /* three runs, each in c's event order: contacts, the yielded rods' contacts taken back,
     * their releases */
    size_t qc = 0, qy = nc, qr = nc + ny;
    for (size_t i = 0; i < c->ne && c->ev[i].x <= u_max; i++) {
        const event *e = &c->ev[i];
        if (!signbit(e->dk)) {
            out->ev[qc++] = (event){e->x, e->dk, 0.0, 0.0, 0.0, 0.0};
        } else {
            const double release = release_point(u_max, c->eps_y * e->L, e->c);
            out->ev[qy++] = (event){e->c, e->dk, 0.0, 0.0, 0.0, 0.0};
            out->ev[qr++] = (event){release, -e->dk, 0.0, 0.0, 0.0, 0.0};
        }
    }
    sort_events(out, *m, 1);
    return CT_OK;
}

int ct_curve_unload(const ct_curve *c, double u_max, ct_curve *out)
{
    CT_NEED(c);
    CT_NEED(out);
    out->n = out->ne = 0;
    out->first_yield = INFINITY;
    out->eps_y = c->eps_y;
    size_t m;
    int st = unload_events(c, u_max, out, &m);
    if (st || m == 0)
        return st;
    size_t nx = 2;
    for (size_t i = 1; i < m; i++)
        nx += out->ev[i].x != out->ev[i - 1].x;
    if (reserve_points(out, nx) || grow((void **)&out->ux, &out->ucap, 2 * m, sizeof(double)))
        return ct_error_set(CT_ENOMEM, "unloading curve: out of memory");
    for (size_t i = 0; i < m; i++) {
        out->ux[i] = out->ev[i].x;
        out->ux[m + i] = out->ev[i].dk;
    }
    const run sorted[3] = {{.x = out->ux, .k = out->ux + m, .sign = 1.0, .n = m}};
    const size_t n = unload_sweep(sorted, u_max, out->x, out->P, out->W, out->slope);
    for (size_t k = 0; k < n; k++) {
        out->D[k] = out->A[k] = out->Lmax[k] = 0.0;
        out->cmin[k] = INFINITY;
    }
    out->n = n;
    return CT_OK;
}

void ct_unload_events_free(ct_unload_events *e)
{
    free(e->buf);
    memset(e, 0, sizeof *e);
}

int ct_unload_events_of(const ct_curve *c, ct_unload_events *e)
{
    const size_t ne = c->ne, need = 8 * (ne ? ne : 1);
    if (need > e->cap) {
        double *buf = realloc(e->buf, need * sizeof(double));
        if (!buf)
            return ct_error_set(CT_ENOMEM, "impact in time: out of memory");
        e->buf = buf;
        e->cap = need;
    }
    double *cx = e->buf, *ck = cx + ne, *yy = ck + ne, *yc = yy + ne, *yL = yc + ne, *yk = yL + ne,
           *eL = yk + ne;
    e->rel = eL + ne;
    size_t a = 0, b = 0;
    for (size_t i = 0; i < ne; i++) {
        const event *v = &c->ev[i];
        if (!signbit(v->dk)) {
            cx[a] = v->x;
            ck[a++] = v->dk;
        } else {
            yy[b] = v->x;
            yc[b] = v->c;
            yL[b] = v->L;
            eL[b] = c->eps_y * v->L;
            yk[b++] = -v->dk;
        }
    }
    e->cx = cx, e->ck = ck, e->yy = yy, e->yc = yc, e->eL = eL, e->yk = yk;
    e->nc = a;
    e->ny = b;
    e->monotone = 1;
    for (size_t i = 1; i < b && e->monotone; i++)
        e->monotone = yc[i] >= yc[i - 1] && yL[i] <= yL[i - 1];
    /* nested: the rods yield in the order they touch (every virgin layer: yield = top (1 -
     * eps_y) + eps_y H* rises with the top), each contact paired with its own yield */
    e->nested = e->monotone && a == b;
    for (size_t i = 0; i < b && e->nested; i++)
        e->nested = cx[i] == yc[i] && ck[i] == yk[i];
    return CT_OK;
}

void ct_unload_events_scale(ct_unload_events *e, double sx, double sk)
{
    /* the arrays are e->buf's, laid out by ct_unload_events_of */
    double *cx = (double *)e->cx, *ck = (double *)e->ck, *yy = (double *)e->yy,
           *yc = (double *)e->yc, *eL = (double *)e->eL, *yk = (double *)e->yk;
    for (size_t i = 0; i < e->nc; i++) {
        cx[i] *= sx;
        ck[i] *= sk;
    }
    for (size_t i = 0; i < e->ny; i++) {
        yy[i] *= sx;
        yc[i] *= sx;
        eL[i] *= sx;
        yk[i] *= sk;
    }
}

/* Count of sorted values <= u. */
static size_t count_upto(const double *v, size_t n, double u)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] <= u)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

size_t ct_unload_split_room(const ct_unload_events *e, double u_max)
{
    return count_upto(e->cx, e->nc, u_max) + 2 * count_upto(e->yy, e->ny, u_max) + 2;
}

size_t ct_unload_split(const ct_unload_events *e, double u_max, double *x, double *P, double *W,
                       double *slope)
{
    const size_t nc = count_upto(e->cx, e->nc, u_max), ny = count_upto(e->yy, e->ny, u_max);
    double *rel = e->rel; /* the yielded rods' releases: in order, e being monotone */
    for (size_t i = 0; i < ny; i++)
        rel[i] = release_point(u_max, e->eL[i], e->yc[i]);
    run r[3] = {{.n = 0}};
    if (e->nested) {
        /* the yielded rods are the first ny to touch, so their contacts and the contacts taken
         * back cancel exactly (the same x, the same slope) and only two runs are left, of
         * slopes that only add: the contacts of the rods still elastic (ny .. nc) and the
         * yielded rods' releases. All increments are positive: plain sums. */
        r[0] = (run){.x = e->cx + ny, .k = e->ck + ny, .sign = 1.0, .n = nc - ny};
        r[1] = (run){.x = rel, .k = e->yk, .sign = 1.0, .n = ny};
        return unload_sweep_nested(r, u_max, x, P, W, slope);
    }
    r[0] = (run){.x = e->cx, .k = e->ck, .sign = 1.0, .n = nc};
    r[1] = (run){.x = e->yc, .k = e->yk, .sign = -1.0, .n = ny};
    r[2] = (run){.x = rel, .k = e->yk, .sign = 1.0, .n = ny};
    return unload_sweep(r, u_max, x, P, W, slope);
}
