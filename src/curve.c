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
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#define CT_BLOCK                                                                                   \
    2048 /* as bundle.c: runs are merged within blocks, so the events (and                         \
            everything after them) do not depend on the thread count */

typedef struct {
    double x;    /* where [length] */
    double dk;   /* change of slope [force/length]: >= +0 at a contact, <= -0 at a yield */
    double dF;   /* change of the yielded rods' plateau force [force] */
    double jump; /* at a yield: F - k (y - c), the plateau less the elastic line's value.
                    0 but for rounding; a step when y and c round to the same double (a rod
                    so short and stiff that it is rigid-plastic at this resolution) */
    double L, c; /* at a yield: the rod's length and contact point (for the release point) */
} event;

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
    size_t ne; /* events of the last build, sorted in ev */
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
    c->ev = c->tmp = NULL;
    c->runs = c->block_runs = NULL;
    c->ecap = c->tcap = c->rcap = c->bcap = 0;
}

void ct_curve_free(ct_curve *c)
{
    if (!c)
        return;
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
    return c->x;
}

double ct_curve_first_contact(const ct_curve *c)
{
    return c->n ? c->x[0] : INFINITY;
}

double ct_curve_first_yield(const ct_curve *c)
{
    return c->first_yield;
}

static int less(const event *a, const event *b)
{
    if (a->x != b->x)
        return a->x < b->x;
    if (a->dk != b->dk)
        return a->dk < b->dk;
    if (a->dF != b->dF)
        return a->dF < b->dF;
    if (a->jump != b->jump)
        return a->jump < b->jump;
    if (a->L != b->L)
        return a->L < b->L;
    return a->c < b->c;
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

static int same_rod(const double *top, const double *length, const double *eps_p, size_t k)
{
    return top[k] == top[k - 1] && length[k] == length[k - 1] && eps_p[k] == eps_p[k - 1];
}

/* Neumaier: s + c carries a sum whose terms may cancel. */
static void add_comp(double *s, double *c, double x)
{
    double t = *s + x;
    *c += fabs(*s) >= fabs(x) ? (*s - t) + x : (x - t) + *s;
    *s = t;
}

double ct_curve_bytes(size_t events)
{
    /* events twice (the merge's buffer), run bounds, and 8 doubles per breakpoint */
    return (double)events * (2.0 * sizeof(event) + sizeof(size_t) + 8.0 * sizeof(double));
}

/* Pass 1 of a build for block j: the runs of identical rods in it. */
static void count_runs(ct_curve *c, const double *top, const double *length, const double *eps_p,
                       size_t n, size_t j)
{
    size_t k0 = j * CT_BLOCK, k1 = k0 + CT_BLOCK < n ? k0 + CT_BLOCK : n, r = 1;
    for (size_t k = k0 + 1; k < k1; k++)
        r += !same_rod(top, length, eps_p, k);
    c->block_runs[j + 1] = r;
}

typedef struct {
    const double *top, *length, *area, *eps_p;
    size_t n;
    double E, eps_y;
    size_t nruns;
} rods_in;

/* Pass 2 for block j: a contact and a yield event per run, contacts first. */
static void block_events(ct_curve *c, const rods_in *r, size_t j)
{
    const double *top = r->top, *length = r->length, *area = r->area, *eps_p = r->eps_p;
    const double E = r->E, eps_y = r->eps_y;
    size_t k0 = j * CT_BLOCK, k1 = k0 + CT_BLOCK < r->n ? k0 + CT_BLOCK : r->n;
    size_t out = c->block_runs[j];
    event *ev = c->ev;
    for (size_t k = k0; k < k1;) {
        double s = area[k], sc = 0.0;
        size_t l = k + 1;
        while (l < k1 && same_rod(top, length, eps_p, l))
            add_comp(&s, &sc, area[l++]);
        s += sc;
        double contact = top[k] + eps_p[k] * length[k];
        double yield = top[k] + (eps_p[k] + eps_y) * length[k];
        double slope = E * s / length[k];
        const double F = E * s * eps_y;
        ev[out] = (event){contact, slope, 0.0, 0.0, 0.0, 0.0};
        ev[r->nruns + out] =
            (event){yield, -slope, F, F - slope * (yield - contact), length[k], contact};
        out++;
        k = l;
    }
}

size_t ct_curve_events(const ct_bundle *b)
{
    const size_t n = ct_bundle_size(b);
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    size_t runs = 0;
    for (size_t k = 0; k < n; k++) /* block starts begin runs, as in ct_curve_build */
        runs += k % CT_BLOCK == 0 || !same_rod(top, length, eps_p, k);
    return 2 * runs;
}

int ct_curve_build(ct_curve *c, const ct_bundle *b)
{
    CT_NEED(c);
    CT_NEED(b);
    const size_t n = ct_bundle_size(b);
    const ct_layer *L = ct_bundle_layer(b);
    const double E = L->E, eps_y = L->sigma_y / L->E;
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    /* a thread team from 64x the rod threshold (262 144 rods): measured in one process
     * (min of 15 builds, quasi-random tops, 2026-11-23) two threads were 13-16 % slower up to
     * 65 536 rods and 10 % faster from 262 144; in a short run the team's start and spinning
     * workers also slow what follows (a 9600-rod profile x 2000 speeds: 22 ms whole process
     * with a team, 12 ms without) */
    const int team = ct_bundle_team_from(b, 64);
    const size_t nb = (n + CT_BLOCK - 1) / CT_BLOCK;
    c->n = 0;
    c->ne = 0;
    c->first_yield = INFINITY;
    c->eps_y = eps_y;
    if (grow((void **)&c->block_runs, &c->bcap, nb + 1, sizeof(size_t)))
        goto oom;

    /* pass 1: rod runs per block (a thread team only where it pays: entering one costs more
     * than a small curve) */
    if (team > 1) {
#pragma omp parallel for schedule(static) num_threads(team)
        for (ptrdiff_t j = 0; j < (ptrdiff_t)nb; j++)
            count_runs(c, top, length, eps_p, n, (size_t)j);
    } else {
        for (size_t j = 0; j < nb; j++)
            count_runs(c, top, length, eps_p, n, j);
    }
    c->block_runs[0] = 0;
    for (size_t j = 0; j < nb; j++)
        c->block_runs[j + 1] += c->block_runs[j];
    const size_t nruns = nb ? c->block_runs[nb] : 0, ne = 2 * nruns;
    if (ne == 0)
        return CT_OK;
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
        goto oom;

    /* pass 2: contacts in rod order, then yields in rod order */
    event *ev = c->ev;
    const rods_in rods = {top, length, area, eps_p, n, E, eps_y, nruns};
    if (team > 1) {
#pragma omp parallel for schedule(static) num_threads(team)
        for (ptrdiff_t j = 0; j < (ptrdiff_t)nb; j++)
            block_events(c, &rods, (size_t)j);
    } else {
        for (size_t j = 0; j < nb; j++)
            block_events(c, &rods, j);
    }
    sort_events(c, ne, team);
    ev = c->ev;
    c->ne = ne;

    /* the sweep */
    size_t nx = 1;
    for (size_t i = 1; i < ne; i++)
        nx += ev[i].x != ev[i - 1].x;
    if (nx > c->cap) {
        free_points(c);
        c->x = malloc(nx * sizeof(double));
        c->P = malloc(nx * sizeof(double));
        c->W = malloc(nx * sizeof(double));
        c->D = malloc(nx * sizeof(double));
        c->slope = malloc(nx * sizeof(double));
        c->A = malloc(nx * sizeof(double));
        c->Lmax = malloc(nx * sizeof(double));
        c->cmin = malloc(nx * sizeof(double));
        if (!c->x || !c->P || !c->W || !c->D || !c->slope || !c->A || !c->Lmax || !c->cmin)
            goto oom;
        c->cap = nx;
    }
    double ks = 0.0, kc = 0.0, As = 0.0, Ac = 0.0; /* slope and yielded force */
    double Ps = 0.0, Pc = 0.0, Ws = 0.0, Wc = 0.0, Ds = 0.0, Dc = 0.0;
    ptrdiff_t active = 0; /* rods between contact and yield */
    double Lmax = 0.0;
    size_t j = 0, i = 0;
    double P_prev = 0.0, k_prev = 0.0, A_prev = 0.0, x_prev = ev[0].x;
    while (i < ne) {
        const double x = ev[i].x;
        if (j > 0) {
            const double dx = x - x_prev;
            add_comp(&Ps, &Pc, k_prev * dx);
            const double P = Ps + Pc;
            add_comp(&Ws, &Wc, 0.5 * (P_prev + P) * dx);
            add_comp(&Ds, &Dc, A_prev * dx);
            P_prev = P;
        }
        for (; i < ne && ev[i].x == x; i++) {
            add_comp(&ks, &kc, ev[i].dk);
            if (signbit(ev[i].dk)) { /* a yield (a rod of underflowed area: -0) */
                add_comp(&As, &Ac, ev[i].dF);
                Lmax = ev[i].L > Lmax ? ev[i].L : Lmax;
                if (ev[i].jump != 0.0) {
                    add_comp(&Ps, &Pc, ev[i].jump);
                    P_prev = Ps + Pc;
                }
                active--;
                if (x < c->first_yield)
                    c->first_yield = x;
            } else {
                active++;
            }
        }
        if (active == 0) { /* no rod elastic: the slope is 0, not a rounding residue */
            ks = kc = 0.0;
        }
        c->x[j] = x;
        c->P[j] = P_prev;
        c->W[j] = Ws + Wc;
        c->D[j] = Ds + Dc;
        k_prev = ks + kc;
        if (k_prev < 0.0)
            k_prev = 0.0;
        A_prev = As + Ac;
        c->slope[j] = k_prev;
        c->A[j] = A_prev;
        c->Lmax[j] = Lmax;
        x_prev = x;
        j++;
    }
    c->n = j;
    /* contacts of the rods still below their yield point: a suffix minimum over yields */
    double cm = INFINITY;
    size_t e = ne;
    for (size_t q = j; q-- > 0;) {
        c->cmin[q] = cm;
        while (e > 0 && ev[e - 1].x >= c->x[q]) {
            e--;
            if (signbit(ev[e].dk) && ev[e].c < cm)
                cm = ev[e].c;
        }
    }
    return CT_OK;
oom:
    c->n = 0;
    return ct_error_set(CT_ENOMEM, "curve of %zu rods: out of memory", n);
}

/* Largest j with x_j <= u (u >= x_0). */
static size_t piece(const ct_curve *c, double u)
{
    size_t lo = 0, hi = c->n; /* x[lo] <= u < x[hi] (x[n] = +inf) */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->x[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

double ct_curve_force(const ct_curve *c, double u)
{
    if (!c->n || !(u > c->x[0]))
        return 0.0;
    size_t j = piece(c, u);
    return c->P[j] + c->slope[j] * (u - c->x[j]);
}

double ct_curve_work(const ct_curve *c, double u)
{
    if (!c->n || !(u > c->x[0]))
        return 0.0;
    size_t j = piece(c, u);
    double t = u - c->x[j];
    return c->W[j] + t * (c->P[j] + 0.5 * c->slope[j] * t);
}

double ct_curve_dissipation(const ct_curve *c, double u)
{
    if (!c->n || !(u > c->x[0]))
        return 0.0;
    size_t j = piece(c, u);
    return c->D[j] + c->A[j] * (u - c->x[j]);
}

double ct_curve_release(const ct_curve *c, double u)
{
    if (!c->n)
        return INFINITY;
    if (!(u > c->x[0]))
        return c->x[0];
    size_t j = piece(c, u);
    double r = c->cmin[j];
    if (c->Lmax[j] > 0.0) {
        double y = u - c->eps_y * c->Lmax[j]; /* the yielded rods' new contacts */
        r = y < r ? y : r;
    }
    return r;
}

double ct_curve_inverse_work(const ct_curve *c, double W)
{
    if (!c->n || !(W >= 0.0))
        return NAN;
    if (W == 0.0)
        return c->x[0];
    size_t lo = 0, hi = c->n; /* W[lo] <= W < W[hi] (W[n] = +inf) */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->W[mid] <= W)
            lo = mid;
        else
            hi = mid;
    }
    /* W_j + P_j t + k t^2 / 2 = W: t = 2R / (P_j + sqrt(P_j^2 + 2 k R)), no cancellation */
    const double R = W - c->W[lo], P = c->P[lo], k = c->slope[lo];
    const double disc = P * P + 2.0 * k * R, den = P + sqrt(disc > 0.0 ? disc : 0.0);
    double t = den > 0.0 ? 2.0 * R / den : 0.0;
    if (hi < c->n && t > c->x[hi] - c->x[lo])
        t = c->x[hi] - c->x[lo];
    return c->x[lo] + t;
}

void ct_curve_view_of(const ct_curve *c, ct_curve_view *v)
{
    v->n = c->n;
    v->x = c->x;
    v->P = c->P;
    v->W = c->W;
    v->slope = c->slope;
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

/* The unloading curve (Eq. 11 rod by rod): loaded from c's state to u_max, every rod in
 * contact unloads along its elastic line, k (u - r), from its release point r: its contact
 * if it did not yield, u_max - eps_y L if it did (r = contact + (u_max - yield)). In terms of
 * c's sorted events below u_max: each contact adds its slope at its contact, and each yield
 * takes that slope back at the rod's contact and adds it again at its release. The three
 * sequences are merged as runs (monotone for Cantor stages), then swept like a loading curve
 * without yields; the last breakpoint is u_max. */
int ct_curve_unload(const ct_curve *c, double u_max, ct_curve *out)
{
    CT_NEED(c);
    CT_NEED(out);
    out->n = out->ne = 0;
    out->first_yield = INFINITY;
    out->eps_y = c->eps_y;
    size_t nc = 0, ny = 0;
    for (size_t i = 0; i < c->ne && c->ev[i].x <= u_max; i++)
        signbit(c->ev[i].dk) ? ny++ : nc++;
    const size_t m = nc + 2 * ny;
    if (m == 0)
        return CT_OK;
    if (grow((void **)&out->ev, &out->ecap, m, sizeof(event)) ||
        grow((void **)&out->tmp, &out->tcap, m, sizeof(event)) ||
        grow((void **)&out->runs, &out->rcap, m + 1, sizeof(size_t)))
        return ct_error_set(CT_ENOMEM, "unloading curve of %zu events: out of memory", m);
    /* three runs, each in c's event order: contacts, the yielded rods' contacts taken back,
     * their releases */
    size_t qc = 0, qy = nc, qr = nc + ny;
    for (size_t i = 0; i < c->ne && c->ev[i].x <= u_max; i++) {
        const event *e = &c->ev[i];
        if (!signbit(e->dk)) {
            out->ev[qc++] = (event){e->x, e->dk, 0.0, 0.0, 0.0, 0.0};
        } else {
            double release = u_max - c->eps_y * e->L;
            release = release < e->c ? e->c : release;
            out->ev[qy++] = (event){e->c, e->dk, 0.0, 0.0, 0.0, 0.0};
            out->ev[qr++] = (event){release, -e->dk, 0.0, 0.0, 0.0, 0.0};
        }
    }
    sort_events(out, m, 1);
    const event *ev = out->ev;
    size_t nx = 2;
    for (size_t i = 1; i < m; i++)
        nx += ev[i].x != ev[i - 1].x;
    if (reserve_points(out, nx))
        return ct_error_set(CT_ENOMEM, "unloading curve: out of memory");
    double ks = 0.0, kc = 0.0, Ps = 0.0, Pc = 0.0, Ws = 0.0, Wc = 0.0, k_prev = 0.0, P_prev = 0.0;
    size_t j = 0, i = 0;
    ptrdiff_t touching = 0; /* rods in contact: the curve starts at the first release */
    while (i < m) {
        const double x = ev[i].x;
        if (j > 0) {
            const double dx = x - out->x[j - 1];
            add_comp(&Ps, &Pc, k_prev * dx);
            const double P = Ps + Pc;
            add_comp(&Ws, &Wc, 0.5 * (P_prev + P) * dx);
            P_prev = P;
        }
        for (; i < m && ev[i].x == x; i++) {
            add_comp(&ks, &kc, ev[i].dk);
            touching += signbit(ev[i].dk) ? -1 : 1;
        }
        if (touching == 0) /* no rod touches: slope 0, not a rounding residue */
            ks = kc = 0.0;
        k_prev = ks + kc > 0.0 ? ks + kc : 0.0;
        if (j == 0 && touching == 0)
            continue; /* before the first release: no contact, no point */
        out->x[j] = x;
        out->P[j] = P_prev;
        out->W[j] = Ws + Wc;
        out->slope[j] = k_prev;
        j++;
    }
    if (out->x[j - 1] < u_max) { /* the top of the unloading branch */
        const double dx = u_max - out->x[j - 1];
        add_comp(&Ps, &Pc, k_prev * dx);
        add_comp(&Ws, &Wc, 0.5 * (P_prev + Ps + Pc) * dx);
        out->x[j] = u_max;
        out->P[j] = Ps + Pc;
        out->W[j] = Ws + Wc;
        out->slope[j] = k_prev;
        j++;
    }
    for (size_t k = 0; k < j; k++) {
        out->D[k] = out->A[k] = out->Lmax[k] = 0.0;
        out->cmin[k] = INFINITY;
    }
    out->n = j;
    return CT_OK;
}

size_t ct_curve_event_count(const ct_curve *c)
{
    return c->ne;
}

void ct_curve_split_events(const ct_curve *c, double *cx, double *ck, size_t *nc, double *yy,
                           double *yc, double *yL, double *yk, size_t *ny)
{
    size_t a = 0, b = 0;
    for (size_t i = 0; i < c->ne; i++) {
        const event *e = &c->ev[i];
        if (!signbit(e->dk)) {
            cx[a] = e->x;
            ck[a++] = e->dk;
        } else {
            yy[b] = e->x;
            yc[b] = e->c;
            yL[b] = e->L;
            yk[b++] = -e->dk;
        }
    }
    *nc = a;
    *ny = b;
}
