/* The lean load curve (CT_PATH_LEAN): the same piecewise-linear P(u) as ct_curve_build, held as
 * the sorted events themselves instead of the breakpoints' arrays.
 *
 * An event is 16 bytes: where it is and, for a contact, its slope change (a contact has no
 * other field); for a yield, the first rod of its run, everything else (the run's summed area,
 * slope, plateau force, ...) recomputed from the bundle's rods by the same code the full build
 * uses (curve_event.h). So the sweep reads the bundle, in scattered order, for the yields
 * alone (on a large map those reads are what the sweep waits on: on threads, another thread
 * makes the yields whole ahead of it). Contacts and yields are sorted apart (by buckets of x,
 * then the ties in the events' total order) and merged as they are swept, which is the full
 * build's order. Every K-th breakpoint keeps the sweep's state (its compensated sums); a query
 * finds its breakpoint among those and sweeps on from there, so it gets the very doubles the
 * full curve holds, in O(log n + K). Threads change no bit.
 *
 * Memory: 32 bytes per run of rods (two events) plus a checkpoint per K breakpoints, and 16
 * more per run while sorting, against about 300 for the full curve. The bundle's arrays are
 * read, not copied: they must not change while the curve is used (the sweep's own curve). */
#include "curve_lean.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#define K 32 /* breakpoints per checkpoint */

typedef struct {
    double x; /* where */
    union {
        uint64_t k; /* a yield: the run's first rod */
        double dk;  /* a contact: its slope change, the only other field it has */
    };
} lev;

struct ct_lean {
    const double *top, *length, *area, *eps_p;
    size_t nrods;
    double E, eps_y;
    lev *con, *yie; /* contacts (whole) and yields (by rod), each in the events' order */
    size_t nruns;
    uint64_t *mk; /* runs of more than one rod: first rod (ascending) and summed area */
    double *ms;
    size_t nm;
    ct_sweep_state *cp; /* the state before breakpoint q K */
    double *cx, *cW;    /* x and W of breakpoint q K (for the searches) */
    double *ymin;       /* smallest contact of the yields after checkpoint q + 1's start */
    size_t ncp, n;
    double x0, first_yield;
};

/* The summed area of the run that starts at rod k. */
static inline double run_area(const ct_lean *L, size_t k)
{
    const size_t k1 = (k / CT_BLOCK + 1) * CT_BLOCK;
    if (!(k + 1 < L->nrods && k + 1 < k1 && ct_same_rod(L->top, L->length, L->eps_p, k + 1)))
        return L->area[k];
    size_t lo = 0, hi = L->nm; /* mk[lo] == k */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (L->mk[mid] <= k)
            lo = mid;
        else
            hi = mid;
    }
    return L->ms[lo];
}

/* The full event of a lean one (a yield when yield is set). */
static void materialise(const ct_lean *L, const lev *e, int yield, event *out)
{
    if (!yield) {
        *out = (event){e->x, e->dk, 0.0, 0.0, 0.0, 0.0}; /* ct_run_contact's fields */
        return;
    }
    const size_t k = (size_t)e->k;
    event c;
    ct_run_events(L->top[k], L->length[k], L->eps_p[k], run_area(L, k), L->E, L->eps_y, &c, out);
}

/* ---- sorting: by buckets of x, then each run of equal x in the total order ---- */

static uint64_t key_of(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return (u >> 63) ? ~u : u | (UINT64_C(1) << 63);
}

typedef struct {
    event e;
    lev l;
} tie;

static int tie_cmp(const void *a, const void *b)
{
    const event *x = &((const tie *)a)->e, *y = &((const tie *)b)->e;
    return ct_event_less(x, y) ? -1 : ct_event_less(y, x) ? 1 : 0;
}

#define TEAM_MIN (1u << 17) /* events from which a sort's buckets go to the threads */
#define MAX_BUCKETS 4096    /* a range's buckets: at most */
#define PER_BUCKET 4        /* a range's buckets: about this many events each */
#define SMALL 16            /* events a range of which is sorted by insertion */
#define BY_VALUE 4          /* levels of splits by x's spread; the keys' bits below them */
#define ON_STACK 512        /* buckets whose counts a level keeps on the stack */

/* How a range is split into buckets, in the keys' order: stretches of equal width between the
 * smallest and the largest x (shift < 0), or the top bits the keys differ in from bit shift
 * on: when x has no finite spread (infinities, NaN, -0 and +0 alone, a spread past the
 * doubles' range), and below the first BY_VALUE levels (a level by x's spread narrows the
 * largest bucket's spread by a factor of its bucket count only: x spread over the doubles'
 * 2098 binary orders took 175 levels, and their counts overflowed the stack; a level by the
 * keys' bits takes at least two of the 64, so at most 32 follow). */
typedef struct {
    double lo, scale;
    int shift;
    size_t nb;
} split;

typedef struct {
    double lo, hi;
    uint64_t klo, khi;
    int nan; /* some x is NaN (its key may lead or trail: no place by value) */
} extent;

static void extent_of(const lev *v, size_t n, extent *e)
{
    double lo = INFINITY, hi = -INFINITY;
    uint64_t klo = UINT64_MAX, khi = 0;
    int nan = 0;
    for (size_t i = 0; i < n; i++) {
        const double x = v[i].x;
        const uint64_t k = key_of(x);
        lo = x < lo ? x : lo;
        hi = x > hi ? x : hi;
        klo = k < klo ? k : klo;
        khi = k > khi ? k : khi;
        nan |= x != x;
    }
    *e = (extent){lo, hi, klo, khi, nan};
}

/* The split of n events of extent e at recursion level depth (0: every key the same, nothing
 * to sort). */
static int plan(const extent *e, size_t n, int depth, split *s)
{
    if (e->klo >= e->khi)
        return 0;
    s->nb = n / PER_BUCKET < MAX_BUCKETS ? n / PER_BUCKET : MAX_BUCKETS;
    s->lo = e->lo;
    s->scale = (double)s->nb / (e->hi - e->lo);
    s->shift = -1;
    if (e->nan || depth >= BY_VALUE ||
        !(isfinite(e->lo) && isfinite(e->hi) && e->lo < e->hi && isfinite(s->scale) &&
          s->scale > 0.0)) {
        const int bits = 64 - __builtin_clzll(e->klo ^ e->khi);
        int top = 1;
        while (top < 12 && ((size_t)1 << top) < s->nb)
            top++;
        s->shift = bits > top ? bits - top : 0;
        s->nb = (size_t)1 << (bits - s->shift);
    }
    return 1;
}

/* x's bucket: monotone in the key (a larger x is never in an earlier bucket). */
static inline size_t bucket_of(const split *s, double x)
{
    if (s->shift >= 0)
        return (size_t)((key_of(x) >> s->shift) & (s->nb - 1));
    const double t = (x - s->lo) * s->scale; /* >= 0; nb at the largest x */
    return t < (double)s->nb ? (size_t)t : s->nb - 1;
}

/* Sorts a[0..n) by key (stable) into a itself (into_a) or into b, b[0..n) free; depth: the
 * recursion's level. A range of a few events by insertion; a larger one scattered into b by
 * bucket, each bucket then sorted the same way with a as the free room. The buckets of a large
 * range fit the cache: the whole array goes through memory about twice, where a
 * least-significant-digit sort moves it once per digit. -1 when out of memory. */
static int sort_range(lev *a, lev *b, size_t n, int into_a, int depth)
{
    lev *const out = into_a ? a : b;
    extent e;
    split s;
    if (n > SMALL)
        extent_of(a, n, &e);
    if (n <= SMALL || !plan(&e, n, depth, &s)) { /* by insertion, stable: a later event passes
                                                    only larger keys (none when all are equal) */
        if (out != a)
            memcpy(out, a, n * sizeof *a);
        for (size_t i = 1; n <= SMALL && i < n; i++) {
            const lev v = out[i];
            const uint64_t k = key_of(v.x);
            size_t j = i;
            for (; j > 0 && key_of(out[j - 1].x) > k; j--)
                out[j] = out[j - 1];
            out[j] = v;
        }
        return 0;
    }
    size_t small[ON_STACK + 1], *end = s.nb <= ON_STACK ? small : malloc(s.nb * sizeof *end);
    if (!end)
        return -1;
    memset(end, 0, s.nb * sizeof *end);
    for (size_t i = 0; i < n; i++)
        end[bucket_of(&s, a[i].x)]++;
    for (size_t k = 1; k < s.nb; k++) /* end[k]: where bucket k + 1 starts */
        end[k] += end[k - 1];
    for (size_t i = n; i-- > 0;) /* backwards: each bucket's events keep their order */
        b[--end[bucket_of(&s, a[i].x)]] = a[i];
    int st = 0; /* end[k] is now where bucket k starts */
    for (size_t k = 0; k < s.nb && !st; k++) {
        const size_t k0 = end[k], k1 = k + 1 < s.nb ? end[k + 1] : n;
        st = sort_range(b + k0, a + k0, k1 - k0, !into_a, depth + 1);
    }
    if (end != small)
        free(end);
    return st;
}

/* sort_range(v, tmp, n, 1) on team threads: each scatters its share of v (in v's order, the
 * shares in turn: the same places for any number of threads), then the buckets are shared.
 * Every bucket's result is the same whoever sorts it. -1 when out of memory. */
static int sort_team(lev *v, lev *tmp, size_t n, int team)
{
    extent *ext = malloc((size_t)team * sizeof *ext);
    size_t *count = calloc((size_t)team * MAX_BUCKETS, sizeof *count);
    size_t *start = malloc((MAX_BUCKETS + 1) * sizeof *start);
    int st = ext && count && start ? 0 : -1, sorted = 0;
    split s = {0};
    if (st)
        goto done;
#pragma omp parallel num_threads(team)
    {
        int t = 0, T = 1;
#ifdef _OPENMP
        t = omp_get_thread_num();
        T = omp_get_num_threads();
#endif
        const size_t i0 = n / (size_t)T * (size_t)t,
                     i1 = t == T - 1 ? n : n / (size_t)T * (size_t)(t + 1);
        extent_of(v + i0, i1 - i0, &ext[t]);
#pragma omp barrier
#pragma omp single
        {
            extent e = ext[0];
            for (int u = 1; u < T; u++) {
                e.lo = ext[u].lo < e.lo ? ext[u].lo : e.lo;
                e.hi = ext[u].hi > e.hi ? ext[u].hi : e.hi;
                e.klo = ext[u].klo < e.klo ? ext[u].klo : e.klo;
                e.khi = ext[u].khi > e.khi ? ext[u].khi : e.khi;
                e.nan |= ext[u].nan;
            }
            sorted = !plan(&e, n, 0, &s);
        }
        if (!sorted) {
            size_t *c = count + (size_t)t * MAX_BUCKETS;
            for (size_t i = i0; i < i1; i++)
                c[bucket_of(&s, v[i].x)]++;
#pragma omp barrier
#pragma omp single
            {
                size_t sum = 0;
                for (size_t k = 0; k < s.nb; k++) {
                    start[k] = sum;
                    for (int u = 0; u < T; u++) {
                        const size_t m = count[(size_t)u * MAX_BUCKETS + k];
                        count[(size_t)u * MAX_BUCKETS + k] = sum;
                        sum += m;
                    }
                }
                start[s.nb] = sum;
            }
            for (size_t i = i0; i < i1; i++)
                tmp[c[bucket_of(&s, v[i].x)]++] = v[i];
#pragma omp barrier
#pragma omp for schedule(dynamic, 16)
            for (ptrdiff_t k = 0; k < (ptrdiff_t)s.nb; k++) {
                const int f =
                    sort_range(tmp + start[k], v + start[k], start[k + 1] - start[k], 0, 1);
                if (f) {
#pragma omp atomic write
                    st = f;
                }
            }
        }
    }
done:
    free(ext);
    free(count);
    free(start);
    return st;
}

/* Sorts v[0..n) by key (stable; tmp: room for n), on team threads when it is large. */
static int sort_keys(lev *v, lev *tmp, size_t n, int team)
{
    if (n >= TEAM_MIN && team > 1)
        return sort_team(v, tmp, n, team);
    return sort_range(v, tmp, n, 1, 0);
}

/* Sorts v[0..n) (tmp: room for n) into the events' order (team: threads for the buckets of a
 * large sort); -1 when out of memory. */
static int sort_lean(const ct_lean *L, lev *v, lev *tmp, size_t n, int yield, int team)
{
    if (sort_keys(v, tmp, n, team))
        return -1;
    /* runs of equal x (-0 and +0 are adjacent keys) in the total order */
    tie *t = NULL;
    size_t tcap = 0;
    for (size_t i = 0; i < n;) {
        size_t j = i + 1;
        while (j < n && v[j].x == v[i].x)
            j++;
        if (j - i > 1) {
            if (j - i > tcap) {
                free(t);
                tcap = j - i;
                if (!(t = malloc(tcap * sizeof *t)))
                    return -1;
            }
            for (size_t q = i; q < j; q++) {
                t[q - i].l = v[q];
                materialise(L, &v[q], yield, &t[q - i].e);
            }
            qsort(t, j - i, sizeof *t, tie_cmp); /* equal events are equal in every field */
            for (size_t q = i; q < j; q++)
                v[q] = t[q - i].l;
        }
        i = j;
    }
    free(t);
    return 0;
}

int ct_lean_sort_records(void *rec, size_t n, int team)
{
    lev *tmp = malloc((n ? n : 1) * sizeof *tmp);
    const int st = tmp ? sort_keys(rec, tmp, n, team) : -1;
    free(tmp);
    return st;
}

/* ---- the sweep (curve.c's sweep_events, a breakpoint at a time) ---- */

static double next_x(const ct_lean *L, const ct_sweep_state *s)
{
    const double a = s->ic < L->nruns ? L->con[s->ic].x : INFINITY;
    const double b = s->iy < L->nruns ? L->yie[s->iy].x : INFINITY;
    return a < b ? a : b;
}

#define AHEAD 24 /* yields prefetched ahead of the sweep */

/* The rod behind yield i of v (of n) asked into the cache: in x's order the rods are
 * scattered over the bundle, and a large map's sweep would otherwise wait on each one's four
 * arrays (docs/benchmarks.md). Only a hint: it changes no value. */
static inline void prefetch_rod(const ct_lean *L, const lev *v, size_t i, size_t n)
{
#if defined(__GNUC__)
    if (i < n) {
        const size_t k = (size_t)v[i].k;
        __builtin_prefetch(L->top + k);
        __builtin_prefetch(L->length + k);
        __builtin_prefetch(L->eps_p + k);
        __builtin_prefetch(L->area + k);
    }
#else
    (void)L, (void)v, (void)i, (void)n;
#endif
}

/* Yields [base, end) made whole ahead of the sweep (by another thread). */
typedef struct {
    const event *ev;
    size_t base, end;
} made;

/* Yield i, from m when m holds it. */
static inline void yield_at(const ct_lean *L, const made *m, size_t i, event *out)
{
    if (m && i >= m->base && i < m->end)
        *out = m->ev[i - m->base];
    else
        materialise(L, &L->yie[i], 1, out);
}

/* The breakpoint s stands before: its values into p, s advanced past it. *cm (not NULL): the
 * smallest contact of the yields swept. m (not NULL): yields made ahead. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void
sweep_step(const ct_lean *L, ct_sweep_state *s, ct_point *p, double *cm, const made *m)
{
    const size_t n = L->nruns;
    if (!m)
        prefetch_rod(L, L->yie, s->iy + AHEAD, n);
    const double cx = s->ic < n ? L->con[s->ic].x : INFINITY;
    const double yx = s->iy < n ? L->yie[s->iy].x : INFINITY;
    const double x = cx < yx ? cx : yx;
    event ce = {0}, ye = {0};
    ct_sweep_to(s, x);
    if (cx != yx) { /* one kind of event at x (most breakpoints): in its own order */
        if (cx == x) {
            do {
                materialise(L, &L->con[s->ic++], 0, &ce);
                ct_sweep_contact(s, &ce);
            } while (s->ic < n && L->con[s->ic].x == x);
        } else {
            do {
                yield_at(L, m, s->iy++, &ye);
                ct_sweep_yield(s, &ye);
                if (cm && ye.c < *cm)
                    *cm = ye.c;
            } while (s->iy < n && L->yie[s->iy].x == x);
        }
        ct_sweep_point(s, x, p);
        return;
    }
    int have_c = 0, have_y = 0;
    for (;;) { /* contacts and yields at x, merged in the total order */
        if (!have_c && s->ic < n && L->con[s->ic].x == x) {
            materialise(L, &L->con[s->ic], 0, &ce);
            have_c = 1;
        }
        if (!have_y && s->iy < n && L->yie[s->iy].x == x) {
            yield_at(L, m, s->iy, &ye);
            have_y = 1;
        }
        if (!have_c && !have_y)
            break;
        if (have_y && (!have_c || !ct_event_less(&ce, &ye))) {
            ct_sweep_yield(s, &ye);
            if (cm && ye.c < *cm)
                *cm = ye.c;
            s->iy++;
            have_y = 0;
        } else {
            ct_sweep_contact(s, &ce);
            s->ic++;
            have_c = 0;
        }
    }
    ct_sweep_point(s, x, p);
}

static void step(const ct_lean *L, ct_sweep_state *s, ct_point *p, double *cm, const made *m)
{
    sweep_step(L, s, p, cm, m);
}

void ct_lean_free(ct_lean *L)
{
    if (!L)
        return;
    free(L->con);
    free(L->yie);
    free(L->mk);
    free(L->ms);
    free(L->cp);
    free(L->cx);
    free(L->cW);
    free(L->ymin);
    free(L);
}

double ct_lean_bytes(size_t runs)
{
    /* two events per run, the sort's buffer for one of the two, the checkpoints */
    return (double)runs *
           (3.0 * sizeof(lev) + 2.0 * (sizeof(ct_sweep_state) + 3 * sizeof(double)) / K);
}

/* Pass over the rods: the runs' events in rod order and the summed areas of the long runs. */
#define FILL_BLOCKS 64 /* blocks of rods per chunk of the pass over the rods */

/* Runs of rods [k0, k1) (block aligned) holds: all (*runs), of more than one rod (*multi). */
static void count_runs(const ct_lean *L, size_t k0, size_t k1, size_t *runs, size_t *multi)
{
    size_t r = 0, m = 0;
    for (size_t k = k0; k < k1; k++) { /* block starts begin runs, as in ct_curve_build */
        const int starts = k % CT_BLOCK == 0 || !ct_same_rod(L->top, L->length, L->eps_p, k);
        r += starts;
        m += starts && k + 1 < k1 && (k + 1) % CT_BLOCK != 0 &&
             ct_same_rod(L->top, L->length, L->eps_p, k + 1);
    }
    *runs = r, *multi = m;
}

/* The events of the runs of rods [k0, k1) (block aligned) from run r and long run m on. */
static void fill_runs(ct_lean *L, size_t k0, size_t k1, size_t r, size_t m)
{
    for (size_t k = k0; k < k1;) {
        const size_t e = (k / CT_BLOCK + 1) * CT_BLOCK < k1 ? (k / CT_BLOCK + 1) * CT_BLOCK : k1;
        size_t l;
        const double s = ct_run_area(L->top, L->length, L->eps_p, L->area, k, e, &l);
        if (l - k > 1) {
            L->mk[m] = k;
            L->ms[m++] = s;
        }
        event c, y;
        ct_run_events(L->top[k], L->length[k], L->eps_p[k], s, L->E, L->eps_y, &c, &y);
        L->con[r] = (lev){c.x, .dk = c.dk};
        L->yie[r] = (lev){y.x, .k = k};
        r++;
        k = l;
    }
}

/* Pass over the rods: the runs' events in rod order and the summed areas of the long runs. In
 * chunks of whole blocks (a run never crosses a block): counted, then filled from each chunk's
 * place, on team threads (the same arrays for any number). */
static int fill_events(ct_lean *L, int team)
{
    const size_t n = L->nrods, chunk = (size_t)FILL_BLOCKS * CT_BLOCK, nc = (n + chunk - 1) / chunk;
    size_t *at = calloc(2 * (nc + 1), sizeof *at); /* runs, then long runs, before chunk c */
    if (!at)
        return -1;
    size_t *mat = at + nc + 1;
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1 && nc > 1)
    for (size_t c = 0; c < nc; c++)
        count_runs(L, c * chunk, (c + 1) * chunk < n ? (c + 1) * chunk : n, &at[c + 1],
                   &mat[c + 1]);
    for (size_t c = 0; c < nc; c++) {
        at[c + 1] += at[c];
        mat[c + 1] += mat[c];
    }
    const size_t runs = at[nc];
    L->nruns = runs;
    L->nm = mat[nc];
    /* the memory check reads /proc/meminfo: only for curves where it can matter */
    const double need = ct_lean_bytes(runs);
    int st = 0;
    if (need >= 64e6 && need > 0.9 * (double)ct_available_memory())
        st = -2;
    else if (!(L->con = malloc((runs ? runs : 1) * sizeof *L->con)) ||
             !(L->yie = malloc((runs ? runs : 1) * sizeof *L->yie)) ||
             !(L->mk = malloc((L->nm ? L->nm : 1) * sizeof *L->mk)) ||
             !(L->ms = malloc((L->nm ? L->nm : 1) * sizeof *L->ms)))
        st = -1;
    if (!st) {
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1 && nc > 1)
        for (size_t c = 0; c < nc; c++)
            fill_runs(L, c * chunk, (c + 1) * chunk < n ? (c + 1) * chunk : n, at[c], mat[c]);
    }
    free(at);
    return st;
}

/* The sweep over every breakpoint: the checkpoints, the first yield, the count, and after each
 * checkpoint's block the smallest contact of the yields still to come. The arrays are sized
 * for the most breakpoints there can be (two per run): the pages never reached are never
 * touched. */
/* The checkpoints' sweep between calls: its state, the last W, the block's smallest contact. */
typedef struct {
    ct_sweep_state s;
    double W_prev, cm;
} cp_sweep;

/* Sweeps on until the next yield is yield yend (to the end when yend is the last); 1 when W is
 * not monotone. m (not NULL): the yields made ahead. */
static int checkpoints_to(ct_lean *L, cp_sweep *c, size_t yend, const made *m)
{
    ct_sweep_state s = c->s; /* in registers, not through a pointer, while it sweeps */
    double cm = c->cm, W_prev = c->W_prev, first_yield = L->first_yield;
    int st = 0;
    while ((s.ic < L->nruns || s.iy < L->nruns) && (s.iy < yend || yend >= L->nruns)) {
        const size_t q = s.j / K;
        if (s.j % K == 0) {
            L->cp[q] = s;
            cm = INFINITY;
        }
        const size_t iy = s.iy;
        ct_point p;
        sweep_step(L, &s, &p, &cm, m);
        L->ymin[q] = cm; /* the block's own, so far */
        if (s.iy > iy && p.x < first_yield)
            first_yield = p.x;
        if (s.j - 1 == q * K) {
            L->cx[q] = p.x;
            L->cW[q] = p.W;
        }
        if (!(p.W >= W_prev)) { /* W not monotone (rounding): it cannot be searched */
            st = 1;
            break;
        }
        W_prev = p.W;
    }
    c->s = s;
    c->cm = cm;
    c->W_prev = W_prev;
    L->first_yield = first_yield;
    return st;
}

#define MADE (1u << 14)     /* yields made whole per part of a two-thread sweep */
#define MADE_MIN (1u << 18) /* runs from which the sweep takes a second thread */

/* Yields [base, end) whole into ev. */
static void make_yields(const ct_lean *L, event *ev, size_t base, size_t end)
{
    for (size_t i = base; i < end; i++) {
        prefetch_rod(L, L->yie, i + AHEAD, end);
        materialise(L, &L->yie[i], 1, &ev[i - base]);
    }
}

/* The sweep over every breakpoint: the checkpoints, the first yield, the count, and after each
 * checkpoint's block the smallest contact of the yields still to come. The arrays are sized
 * for the most breakpoints there can be (two per run): the pages never reached are never
 * touched. On team threads (a large curve): one makes the yields whole from their rods (the
 * bundle's scattered reads) a part ahead while the other sweeps the part before; the same
 * events, so the same bits. */
static int checkpoints(ct_lean *L, int team)
{
    cp_sweep c = {.W_prev = 0.0, .cm = INFINITY};
    const size_t cap = 2 * L->nruns / K + 2, n = L->nruns;
    if (!(L->cp = malloc(cap * sizeof *L->cp)) || !(L->cx = malloc(cap * sizeof *L->cx)) ||
        !(L->cW = malloc(cap * sizeof *L->cW)) || !(L->ymin = malloc(cap * sizeof *L->ymin)))
        return -1;
    L->first_yield = INFINITY;
    event *ev = team > 1 && n >= MADE_MIN ? malloc(2 * (size_t)MADE * sizeof *ev) : NULL;
    int st = 0;
    if (!ev) {
        st = checkpoints_to(L, &c, n, NULL);
    } else {
        const size_t parts = (n + MADE - 1) / MADE;
        int stp[2] = {0, 0}; /* part k's status in stp[k % 2]: written before barrier k, read
                                after it, written again only after barrier k + 1 */
#pragma omp parallel num_threads(2)
        {
            int t = 0, T = 1;
#ifdef _OPENMP
            t = omp_get_thread_num();
            T = omp_get_num_threads();
#endif
            if (t == T - 1)
                make_yields(L, ev, 0, n < MADE ? n : MADE);
#pragma omp barrier
            for (size_t k = 0; k < parts; k++) {
                const size_t base = k * MADE, end = base + MADE < n ? base + MADE : n;
                if (t == 0) {
                    const made m = {ev + (k % 2) * MADE, base, end};
                    stp[k % 2] = checkpoints_to(L, &c, end, &m);
                }
                if (t == T - 1 && end < n)
                    make_yields(L, ev + ((k + 1) % 2) * MADE, end, end + MADE < n ? end + MADE : n);
#pragma omp barrier
                if (stp[k % 2]) /* read by all after the barrier: all leave together */
                    break;
            }
        }
        st = stp[0] || stp[1];
        free(ev);
    }
    if (st)
        return 1;
    L->n = c.s.j;
    L->ncp = (c.s.j + K - 1) / K;
    L->x0 = L->n ? L->cx[0] : INFINITY;
    double m = INFINITY; /* each block's minimum becomes the minimum over the blocks after it */
    for (size_t q = L->ncp; q-- > 0;) {
        const double own = L->ymin[q];
        L->ymin[q] = m;
        m = own < m ? own : m;
    }
    return 0;
}

int ct_lean_build(ct_lean **out, const ct_bundle *b)
{
    *out = NULL;
    ct_lean *L = calloc(1, sizeof *L);
    if (!L)
        return ct_error_set(CT_ENOMEM, "lean curve: out of memory");
    const ct_layer *lay = ct_bundle_layer(b);
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays((ct_bundle *)b, &top, &length, &area, &eps_p); /* read only */
    L->top = top;
    L->length = length;
    L->area = area;
    L->eps_p = eps_p;
    L->nrods = ct_bundle_size(b);
    L->E = lay->E;
    L->eps_y = lay->sigma_y / lay->E;
    const int team = ct_bundle_team(b);
    int st = fill_events(L, team);
    if (!st) {
        lev *tmp = malloc((L->nruns ? L->nruns : 1) * sizeof *tmp);
        st = !tmp || sort_lean(L, L->con, tmp, L->nruns, 0, team) ||
                     sort_lean(L, L->yie, tmp, L->nruns, 1, team)
                 ? -1
                 : 0;
        free(tmp);
    }
    if (!st)
        st = checkpoints(L, team);
    if (st) {
        const size_t runs = L->nruns;
        ct_lean_free(L);
        if (st > 0)
            return CT_ESKIPPED;
        if (st == -2)
            return ct_error_set(CT_ENOMEM,
                                "lean curve of %zu rods: needs %.3g GiB, more than the %.3g GiB "
                                "of memory available",
                                ct_bundle_size(b), ct_lean_bytes(runs) / 1073741824.0,
                                (double)ct_available_memory() / 1073741824.0);
        return ct_error_set(CT_ENOMEM, "lean curve of %zu rods: out of memory", ct_bundle_size(b));
    }
    *out = L;
    return CT_OK;
}

size_t ct_lean_size(const ct_lean *L)
{
    return L->n;
}

double ct_lean_first_contact(const ct_lean *L)
{
    return L->x0;
}

double ct_lean_first_yield(const ct_lean *L)
{
    return L->first_yield;
}

void ct_lean_piece(const ct_lean *L, double u, ct_point *p, double *cmin)
{
    const size_t q = ct_last_at_most(L->cx, L->ncp, u);
    ct_sweep_state s = L->cp[q];
    double cm = INFINITY;
    step(L, &s, p, NULL, NULL);
    while (s.j < L->n && next_x(L, &s) <= u)
        step(L, &s, p, NULL, NULL);
    if (cmin) { /* the yields after this breakpoint: to the end of the block, then ymin */
        ct_point t;
        while (s.j < L->n && s.j < (q + 1) * K)
            step(L, &s, &t, &cm, NULL);
        *cmin = cm < L->ymin[q] ? cm : L->ymin[q];
    }
}

void ct_lean_each_point(const ct_lean *L, void (*fn)(void *ctx, const ct_point *p), void *ctx)
{
    if (!L->ncp)
        return;
    ct_sweep_state s = L->cp[0];
    while (s.j < L->n) {
        ct_point p;
        step(L, &s, &p, NULL, NULL);
        fn(ctx, &p);
    }
}

void ct_lean_piece_of_work(const ct_lean *L, double W, ct_point *p, double *x_next)
{
    const size_t q = ct_last_at_most(L->cW, L->ncp, W);
    ct_sweep_state s = L->cp[q];
    step(L, &s, p, NULL, NULL);
    *x_next = INFINITY;
    while (s.j < L->n) {
        ct_point t;
        step(L, &s, &t, NULL, NULL);
        if (!(t.W <= W)) {
            *x_next = t.x;
            break;
        }
        *p = t;
    }
}
