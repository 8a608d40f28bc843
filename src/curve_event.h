/* The load curve's events (curve.c, curve_lean.c): what a run of identical rods adds to the
 * curve, their total order, and the run's summed area. One statement of each, so that the two
 * ways of holding a curve sweep the same events in the same order and get the same bits. */
#ifndef CT_CURVE_EVENT_H
#define CT_CURVE_EVENT_H

#include "internal.h"
#include "rod.h"

typedef struct {
    double x;    /* where [length] */
    double dk;   /* change of slope [force/length]: >= +0 at a contact, <= -0 at a yield */
    double dF;   /* change of the yielded rods' plateau force [force] */
    double jump; /* at a yield: F - k (y - c), the plateau less the elastic line's value.
                    0 but for rounding; a step when y and c round to the same double (a rod
                    so short and stiff that it is rigid-plastic at this resolution) */
    double L, c; /* at a yield: the rod's length and contact point (for the release point) */
} event;

/* The events' total order: x, then the slope change, the force change, the jump, the length
 * and the contact. Events equal in it are equal in every field. */
static inline int ct_event_less(const event *a, const event *b)
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

/* Whether rod k is rod k - 1 again (same top, length and plastic strain): one run. */
static inline int ct_same_rod(const double *top, const double *length, const double *eps_p,
                              size_t k)
{
    return top[k] == top[k - 1] && length[k] == length[k - 1] && eps_p[k] == eps_p[k - 1];
}

/* The run of identical rods that starts at k and ends before k1 at the latest (a block's
 * end): its summed area (compensated), *end its end. */
static inline double ct_run_area(const double *top, const double *length, const double *eps_p,
                                 const double *area, size_t k, size_t k1, size_t *end)
{
    double s = area[k], sc = 0.0;
    size_t l = k + 1;
    while (l < k1 && ct_same_rod(top, length, eps_p, l))
        ct_add_comp(&s, &sc, area[l++]);
    *end = l;
    return s + sc;
}

/* The contact event of a run of rods like rod k, of summed area s. */
static inline event ct_run_contact(double top, double length, double eps_p, double s, double E)
{
    return (event){ct_rod_contact(top, length, eps_p), E * s / length, 0.0, 0.0, 0.0, 0.0};
}

/* The contact and yield events of a run of rods like rod k, of summed area s. */
static inline void ct_run_events(double top, double length, double eps_p, double s, double E,
                                 double eps_y, event *contact_ev, event *yield_ev)
{
    *contact_ev = ct_run_contact(top, length, eps_p, s, E);
    const double contact = contact_ev->x, slope = contact_ev->dk;
    const double yield = ct_rod_yield(top, length, eps_p, eps_y);
    const double F = E * s * eps_y;
    *yield_ev = (event){yield, -slope, F, F - slope * (yield - contact), length, contact};
}

/* The largest j with v[j] <= u among v[0..n) sorted ascending (0 when none is): where a
 * breakpoint's x or W is sought, in either build (n >= 1). */
static inline size_t ct_last_at_most(const double *v, size_t n, double u)
{
    size_t lo = 0, hi = n; /* v[lo] <= u < v[hi] (v[n] = +inf) */
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (v[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The sweep over the sorted events, one statement for both builds: its state before a
 * breakpoint, and what a breakpoint holds. At each x: ct_sweep_to(x), ct_sweep_event for every
 * event at x in the events' order, ct_sweep_point. Every increment of P, W and D is >= 0 and
 * summed compensated (docs/model.md §4). */
typedef struct {
    double Ps, Pc, Ws, Wc, Ds, Dc; /* P, W and D */
    double ks, kc, As, Ac;         /* the slope and the yielded rods' force */
    double Lmax, P_prev, k_prev, A_prev, x_prev;
    ptrdiff_t active; /* rods between contact and yield */
    size_t j;         /* breakpoints swept */
    size_t ic, iy;    /* the lean curve's places in its contacts and yields */
} ct_sweep_state;

typedef struct {
    double x, P, W, D, slope, A; /* P, W, D at x; slope and yielded force on [x, next) */
    double Lmax;                 /* the longest rod yielded at x (0: none) */
} ct_point;

/* The piece from the last breakpoint to x: P, W and D at x before its events. */
static inline void ct_sweep_to(ct_sweep_state *s, double x)
{
    if (s->j > 0) {
        const double dx = x - s->x_prev;
        ct_add_comp(&s->Ps, &s->Pc, s->k_prev * dx);
        const double P = s->Ps + s->Pc;
        ct_add_comp(&s->Ws, &s->Wc, 0.5 * (s->P_prev + P) * dx);
        ct_add_comp(&s->Ds, &s->Dc, s->A_prev * dx);
        s->P_prev = P;
    }
}

/* The events at the current x. A contact adds its slope; a yield takes its slope back, adds
 * its plateau force and its jump. Adding +0 to a compensated sum that is never -0 (it starts
 * at +0, and neither its terms nor its errors are ever -0) leaves both words as they are, so a
 * zero jump is added like any other (no branch on it), and a contact, whose force change, jump
 * and length are +0, may take a yield's steps: ct_sweep_event does, without a branch on the
 * kind, for events that mix in no predictable order. P_prev is Ps + Pc after every event (set
 * so by ct_sweep_to and by each jump). */
static inline void ct_sweep_contact(ct_sweep_state *s, const event *e)
{
    ct_add_comp(&s->ks, &s->kc, e->dk);
    s->active++;
}

/* A yield's steps past its slope: its plateau force, its length, its jump. */
static inline void ct_sweep_plateau(ct_sweep_state *s, const event *e)
{
    ct_add_comp(&s->As, &s->Ac, e->dF);
    s->Lmax = e->L > s->Lmax ? e->L : s->Lmax;
    ct_add_comp(&s->Ps, &s->Pc, e->jump);
    s->P_prev = s->Ps + s->Pc;
}

static inline void ct_sweep_yield(ct_sweep_state *s, const event *e)
{
    ct_add_comp(&s->ks, &s->kc, e->dk);
    ct_sweep_plateau(s, e);
    s->active--;
}

/* Either kind; returns 1 for a yield (a rod of underflowed area yields at -0). */
static inline int ct_sweep_event(ct_sweep_state *s, const event *e)
{
    const int yield = signbit(e->dk) != 0;
    ct_add_comp(&s->ks, &s->kc, e->dk);
    ct_sweep_plateau(s, e);
    s->active += yield ? -1 : 1;
    return yield;
}

/* The breakpoint at x once its events are in: its values into p. */
static inline void ct_sweep_point(ct_sweep_state *s, double x, ct_point *p)
{
    /* no rod elastic: the slope is 0, not a rounding residue */
    s->ks = s->active == 0 ? 0.0 : s->ks;
    s->kc = s->active == 0 ? 0.0 : s->kc;
    p->x = x;
    p->P = s->P_prev;
    p->W = s->Ws + s->Wc;
    p->D = s->Ds + s->Dc;
    s->k_prev = s->ks + s->kc;
    s->k_prev = s->k_prev < 0.0 ? 0.0 : s->k_prev;
    s->A_prev = s->As + s->Ac;
    p->slope = s->k_prev;
    p->A = s->A_prev;
    p->Lmax = s->Lmax;
    s->x_prev = x;
    s->j++;
}

#endif
