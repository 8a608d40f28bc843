/* e(V*) tables with a checked interpolation error: nodes chosen adaptively so that the stated
 * interpolation (include/cantact_table.h, which evaluates them; the same code here) reproduces
 * the exact model within a tolerance at every checked point.
 *
 * Why the nodes go where they go: e(V*) is smooth (algebraic) between the speeds at which
 * u_max reaches a breakpoint of P(u) (a rod's contact or yield point): W(u) is piecewise
 * quadratic and the dissipation D(u) piecewise linear there, e = sqrt(1 - D(u_max)/W). At a
 * yield point D gains slope, so e has a kink; at a contact point its second derivative jumps;
 * at V*_c (the first yield) e leaves the constant 1 with a finite slope. So V*_c is always a
 * node (below it e = 1 exactly, not interpolated), and an interval that fails its checks is
 * split at a breakpoint's V* when it holds one: both halves are then smooth. */
#include "internal.h"
#include "number.h"

#include "cantact_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

_Static_assert((int)CT_INTERP_MONOTONE_CUBIC == CT_TAB_MONOTONE_CUBIC &&
                   (int)CT_INTERP_LINEAR == CT_TAB_LINEAR,
               "ct_interp and cantact_table.h's rules must agree");

struct ct_table {
    size_t n;
    double *V, *x, *e, *d; /* nodes, ln V*, e, de/dx */
    ct_interp rule;
    ct_table_info info;
    double q_tol, q_worst, q_worst_V; /* the quantile columns' tolerance and worst error */
    size_t nq;       /* quantile columns of a table of samples (0: of one surface) */
    double *p;       /* their probabilities */
    double *eq, *dq; /* column j at node i: [j * n + i], and its slopes */
    uint64_t samples;
};

const char *ct_interp_name(ct_interp rule)
{
    switch (rule) {
    case CT_INTERP_MONOTONE_CUBIC:
        return "monotone_cubic";
    case CT_INTERP_LINEAR:
        return "linear";
    }
    return NULL;
}

void ct_table_spec_default(ct_table_spec *spec)
{
    memset(spec, 0, sizeof *spec);
    spec->tolerance = 1e-6;
    spec->interpolation = CT_INTERP_MONOTONE_CUBIC;
    spec->max_nodes = 100000;
    spec->check_points = 16;
    ct_impact_opts_default(&spec->opts);
    spec->path = CT_PATH_AUTO;
}

static double sign_of(double v)
{
    return (v > 0.0) - (v < 0.0);
}

/* Fritsch and Carlson (1980) give the monotonicity region of a cubic Hermite piece: with the
 * secant delta, alpha = d_i/delta and beta = d_i+1/delta in [0, 3] suffice. The weighted
 * harmonic mean (Fritsch and Butland 1984) stays inside it and is local (no sweep order). */
void ct_pchip_slopes(size_t n, const double *x, const double *y, double *d)
{
    if (n < 2) {
        if (n == 1)
            d[0] = 0.0;
        return;
    }
    if (n == 2) {
        d[0] = d[1] = (y[1] - y[0]) / (x[1] - x[0]);
        return;
    }
    for (size_t i = 1; i + 1 < n; i++) {
        const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
        const double s0 = (y[i] - y[i - 1]) / h0, s1 = (y[i + 1] - y[i]) / h1;
        if (s0 * s1 <= 0.0) { /* a local extremum or a flat side: the piece must not overshoot */
            d[i] = 0.0;
            continue;
        }
        const double w1 = 2.0 * h1 + h0, w2 = h1 + 2.0 * h0;
        d[i] = (w1 + w2) / (w1 / s0 + w2 / s1);
    }
    /* ends: the three-point one-sided formula, kept to the secant's sign and to 3 secants */
    for (int end = 0; end < 2; end++) {
        const size_t a = end ? n - 1 : 0, b = end ? n - 2 : 1, c = end ? n - 3 : 2;
        const double h0 = fabs(x[b] - x[a]), h1 = fabs(x[c] - x[b]);
        const double s0 = (y[b] - y[a]) / (x[b] - x[a]), s1 = (y[c] - y[b]) / (x[c] - x[b]);
        double da = ((2.0 * h0 + h1) * s0 - h0 * s1) / (h0 + h1);
        if (sign_of(da) != sign_of(s0))
            da = 0.0;
        else if (sign_of(s0) != sign_of(s1) && fabs(da) > 3.0 * fabs(s0))
            da = 3.0 * s0;
        d[a] = da;
    }
}

/* Slopes of the table's nodes: nodes below V*_c stand for e = 1 and are not interpolated,
 * so the cubic starts at the first node at or above V*_c, an end there (a kink: e's slope
 * jumps from 0). */
static void table_slopes(ct_table *t)
{
    size_t c0 = 0;
    while (c0 < t->n && t->V[c0] < t->info.V_star_crit)
        c0++;
    for (size_t i = 0; i < t->n; i++)
        t->d[i] = 0.0;
    if (t->rule == CT_INTERP_MONOTONE_CUBIC && t->n - c0 >= 2)
        ct_pchip_slopes(t->n - c0, t->x + c0, t->e + c0, t->d + c0);
}

double ct_table_eval(const ct_table *t, double V_star)
{
    return ct_tab_interp(t->n, t->x, t->e, t->d, (int)t->rule, t->info.V_star_crit, V_star);
}

static int table_alloc(ct_table **out, size_t n)
{
    ct_table *t = calloc(1, sizeof *t);
    if (!t)
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    t->V = malloc(n * sizeof(double));
    t->x = malloc(n * sizeof(double));
    t->e = malloc(n * sizeof(double));
    t->d = malloc(n * sizeof(double));
    if (!t->V || !t->x || !t->e || !t->d) {
        ct_table_free(t);
        return ct_error_set(CT_ENOMEM, "table of %zu nodes: out of memory", n);
    }
    t->n = n;
    *out = t;
    return CT_OK;
}

void ct_table_free(ct_table *t)
{
    if (!t)
        return;
    free(t->V);
    free(t->x);
    free(t->e);
    free(t->d);
    free(t->p);
    free(t->eq);
    free(t->dq);
    free(t);
}

size_t ct_table_size(const ct_table *t)
{
    return t->n;
}
const double *ct_table_V_star(const ct_table *t)
{
    return t->V;
}
const double *ct_table_e(const ct_table *t)
{
    return t->e;
}
const double *ct_table_slope(const ct_table *t)
{
    return t->d;
}
ct_interp ct_table_interpolation(const ct_table *t)
{
    return t->rule;
}
void ct_table_get_info(const ct_table *t, ct_table_info *info)
{
    *info = t->info;
}

int ct_table_from_nodes(ct_table **out, size_t n, const double *V_star, const double *e,
                        const double *slope, ct_interp rule, double V_star_crit)
{
    CT_NEED(out);
    CT_NEED(V_star);
    CT_NEED(e);
    CT_NEED(slope);
    *out = NULL;
    if (n < 2)
        return ct_error_set(CT_EINVAL, "table: %zu nodes: need at least 2", n);
    if (!ct_interp_name(rule))
        return ct_error_set(CT_EINVAL, "table: interpolation %d: unknown", (int)rule);
    if (!(V_star_crit >= 0.0) || !isfinite(V_star_crit))
        return ct_error_set(CT_EINVAL, "table: V*_c = %g: must be finite and >= 0", V_star_crit);
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(V_star[i]) || !(V_star[i] > 0.0) ||
            (i && !(log(V_star[i]) > log(V_star[i - 1]))))
            return ct_error_set(CT_EINVAL,
                                "table: V*[%zu] = %g: must be finite, > 0 and increasing (in "
                                "ln V*)",
                                i, V_star[i]);
        if (!(e[i] >= 0.0 && e[i] <= 1.0))
            return ct_error_set(CT_EINVAL, "table: e[%zu] = %g: must be in [0, 1]", i, e[i]);
        if (!isfinite(slope[i]))
            return ct_error_set(CT_EINVAL, "table: slope[%zu] = %g: must be finite", i, slope[i]);
    }
    ct_table *t;
    int st;
    if ((st = table_alloc(&t, n)))
        return st;
    for (size_t i = 0; i < n; i++) {
        t->V[i] = V_star[i];
        t->x[i] = log(V_star[i]);
        t->e[i] = e[i];
        t->d[i] = slope[i];
    }
    t->rule = rule;
    t->info.V_star_crit = V_star_crit;
    /* what a monotone cubic promises, by the rule the file reader applies (cantact_table.h) */
    ct_tab view = {.n = n,
                   .V_star = t->V,
                   .ln_V_star = t->x,
                   .e = t->e,
                   .slope = t->d,
                   .rule = rule == CT_INTERP_LINEAR ? CT_TAB_LINEAR : CT_TAB_MONOTONE_CUBIC,
                   .V_star_crit = V_star_crit};
    size_t bad;
    if (ct_tab_check_slopes(&view, &bad)) {
        ct_table_free(t);
        return ct_error_set(CT_EINVAL,
                            "table: nodes %zu and %zu: slopes %g and %g are not those of a "
                            "monotone cubic between e = %g and %g (a corrupted or foreign table)",
                            bad + 1, bad + 2, slope[bad], slope[bad + 1], e[bad], e[bad + 1]);
    }
    *out = t;
    return CT_OK;
}

/* ---- quantile columns (tables of samples) ---- */

size_t ct_table_quantile_count(const ct_table *t)
{
    return t->nq;
}
const double *ct_table_p(const ct_table *t)
{
    return t->p;
}
const double *ct_table_e_quantile(const ct_table *t, size_t j)
{
    return j < t->nq ? t->eq + j * t->n : NULL;
}
const double *ct_table_slope_quantile(const ct_table *t, size_t j)
{
    return j < t->nq ? t->dq + j * t->n : NULL;
}
uint64_t ct_table_samples(const ct_table *t)
{
    return t->samples;
}
double ct_table_quantile_tolerance(const ct_table *t)
{
    return t->q_tol;
}
double ct_table_quantile_worst_error(const ct_table *t)
{
    return t->q_worst;
}

double ct_table_eval_quantile(const ct_table *t, double V_star, double p)
{
    return ct_tab_quantile_interp(t->n, t->x, t->nq, t->p, t->eq, t->dq, (int)t->rule,
                                  t->info.V_star_crit, V_star, p);
}

/* Room for nq quantile columns in t (its n nodes). */
static int quantiles_alloc(ct_table *t, size_t nq)
{
    t->p = malloc(nq * sizeof(double));
    t->eq = malloc(nq * t->n * sizeof(double));
    t->dq = malloc(nq * t->n * sizeof(double));
    if (!t->p || !t->eq || !t->dq)
        return ct_error_set(CT_ENOMEM, "table: out of memory for %zu quantile columns", nq);
    t->nq = nq;
    return CT_OK;
}

/* ---- the build ---- */

/* Exact e of the first impact at m speeds, in chunks of rows (272 bytes each on x86-64). */
#define CHUNK 4096

typedef struct {
    const ct_bundle *b;
    const ct_table_spec *spec;
    ct_curve *curve; /* the sweep's workspace, reused */
    ct_sweep_row *rows;
    size_t evaluations;
    size_t planned; /* exact impacts asked for so far: the total the progress reports */
} exact_ctx;

/* A chunk's sweep progress as the table's: exact impacts computed of those planned. */
static void chunk_progress(size_t done, size_t total, void *ctx)
{
    (void)total;
    const exact_ctx *x = ctx;
    x->spec->progress(x->evaluations + done, x->planned, x->spec->progress_ctx);
}

static int exact_e(exact_ctx *x, const double *V, size_t m, double *e)
{
    x->planned += m;
    for (size_t k0 = 0; k0 < m; k0 += CHUNK) {
        const size_t k1 = k0 + CHUNK < m ? k0 + CHUNK : m;
        ct_sweep_spec s = {.V_star = V + k0,
                           .nvel = k1 - k0,
                           .impacts = 1,
                           .opts = x->spec->opts,
                           .stop_on_error = 1,
                           .progress = x->spec->progress ? chunk_progress : NULL,
                           .progress_ctx = x,
                           .path = x->spec->path,
                           .curve = x->curve,
                           .interrupt = x->spec->interrupt};
        int st = ct_sweep(x->b, &s, x->rows);
        if (st)
            return st;
        for (size_t k = k0; k < k1; k++)
            e[k] = x->rows[k - k0].r.e;
        x->evaluations += k1 - k0;
    }
    return CT_OK;
}

/* A growing list of doubles. */
typedef struct {
    double *v;
    size_t n, cap;
} dlist;

static int dl_push(dlist *l, double v)
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        double *g = realloc(l->v, cap * sizeof(double));
        if (!g)
            return ct_error_set(CT_ENOMEM, "table: out of memory");
        l->v = g;
        l->cap = cap;
    }
    l->v[l->n++] = v;
    return CT_OK;
}

/* The kinks' list as a breakpoint's callback fills it. */
typedef struct {
    dlist *out;
    double lo, hi, scale;
    int st;
} kink_ctx;

static void kink_at(void *ctx, double x, double W)
{
    (void)x;
    kink_ctx *k = ctx;
    const double V = sqrt(W / k->scale);
    dlist *out = k->out;
    if (!k->st && V > k->lo && V < k->hi && (!out->n || log(V) > log(out->v[out->n - 1])))
        k->st = dl_push(out, V);
}

/* V* where u_max reaches each breakpoint of P(u) of b's state, strictly inside (lo, hi). From
 * CT_LEAN_RODS rods the breakpoints come from a lean curve of its own, freed after (about 48
 * bytes a rod instead of the full curve's 300 or so, which was then kept for the whole build:
 * 14 GB on 37 million rods, fx = fz = 1 + 1e-6), the same doubles. */
static int kink_speeds(const ct_bundle *b, ct_curve *c, double lo, double hi, dlist *out)
{
    int st;
    const ct_layer *L = ct_bundle_layer(b);
    kink_ctx k = {out, lo, hi, L->l0 * L->E * L->h0, CT_OK};
    if (ct_bundle_size(b) >= CT_LEAN_RODS) {
        ct_curve *lean;
        if ((st = ct_curve_alloc(&lean)))
            return st;
        st = ct_curve_build_lean(lean, b);
        if (!st)
            ct_curve_each_point(lean, kink_at, &k);
        ct_curve_free(lean);
        if (st == CT_ENOMEM)
            return CT_OK; /* no room for a curve: splits at middles only */
        if (st != CT_ESKIPPED)
            return st ? st : k.st;
    }
    if ((st = ct_curve_build(c, b)))
        return st == CT_ENOMEM ? CT_OK : st; /* no room for a curve: splits at middles only */
    const double *x = ct_curve_points(c);
    for (size_t j = 0; j < ct_curve_size(c); j++)
        kink_at(&k, x[j], ct_curve_work(c, x[j]));
    return k.st;
}

/* Where a failing interval [V0, V1] is split: the kink nearest its middle in ln V* (kinks
 * sorted), else the middle. 0 when nothing lies strictly between in ln V*. */
static double split_point(double V0, double V1, const dlist *kinks)
{
    const double x0 = log(V0), x1 = log(V1), mid = 0.5 * (x0 + x1);
    size_t lo = 0, hi = kinks->n; /* first kink > V0 */
    while (lo < hi) {
        size_t m = lo + (hi - lo) / 2;
        if (kinks->v[m] > V0)
            hi = m;
        else
            lo = m + 1;
    }
    double best = 0.0, best_dist = INFINITY;
    for (size_t k = lo; k < kinks->n && kinks->v[k] < V1; k++) {
        const double xk = log(kinks->v[k]);
        if (!(xk > x0 && xk < x1))
            continue;
        if (fabs(xk - mid) < best_dist) {
            best_dist = fabs(xk - mid);
            best = kinks->v[k];
        } else {
            break; /* sorted: farther from here on */
        }
    }
    if (best > 0.0)
        return best;
    const double V = exp(mid);
    return log(V) > x0 && log(V) < x1 ? V : 0.0;
}

/* The check points of [V0, V1]: K equally spaced inside, in ln V*. */
static void check_speeds(double V0, double V1, size_t K, double *out)
{
    const double x0 = log(V0), h = log(V1) - x0;
    for (size_t k = 0; k < K; k++)
        out[k] = exp(x0 + h * (double)(k + 1) / (double)(K + 1));
}

static int check_spec(const ct_table_spec *s)
{
    if (!(isfinite(s->V_min) && isfinite(s->V_max) && s->V_min > 0.0 && s->V_max > s->V_min))
        return ct_error_set(CT_EINVAL, "table: V* range %g .. %g: needs finite 0 < V_min < V_max",
                            s->V_min, s->V_max);
    if (!(log(s->V_max) > log(s->V_min)))
        return ct_error_set(CT_EINVAL, "table: V* range %.17g .. %.17g: too narrow", s->V_min,
                            s->V_max);
    if (!(s->tolerance >= 1e-13 && s->tolerance < 1.0))
        return ct_error_set(CT_EINVAL, "table: tolerance = %g: must satisfy 1e-13 <= tolerance < 1",
                            s->tolerance);
    if (!ct_interp_name(s->interpolation))
        return ct_error_set(CT_EINVAL, "table: interpolation %d: unknown", (int)s->interpolation);
    if (s->max_nodes < 2)
        return ct_error_set(CT_EINVAL, "table: max_nodes = %zu: must be >= 2", s->max_nodes);
    if (s->check_points < 1 || s->check_points > 100000)
        return ct_error_set(CT_EINVAL,
                            "table: check_points = %zu: must satisfy 1 <= check_points <= 100000",
                            s->check_points);
    return CT_OK;
}

/* Intervals narrower than this in ln V* are not split further: e's own rounding (~1e-15)
 * is then what fails the check, and no node can help. */
#define CT_TABLE_MIN_WIDTH 1e-9

/* A table while it is built: nodes and their e, K cached exact values per interval (chk;
 * nchk: the next round's), the kinks of e, this round's interpolant and its check. */
typedef struct {
    const ct_table_spec *spec;
    size_t K;
    double tol, Vc;
    exact_ctx ex;
    dlist kinks, nodes, ne, newV;
    double *chk, *nchk, *vals, *errs;
    ct_table *t;
    unsigned char *split;
} table_build;

static void table_build_free(table_build *B)
{
    ct_table_free(B->t);
    ct_curve_free(B->ex.curve);
    free(B->ex.rows);
    free(B->kinks.v);
    free(B->nodes.v);
    free(B->ne.v);
    free(B->newV.v);
    free(B->chk);
    free(B->nchk);
    free(B->vals);
    free(B->errs);
    free(B->split);
}

/* The first nodes: the ends, V*_c, two per decade above V*_c. */
static int first_nodes(const ct_table_spec *spec, double Vc, dlist *nodes)
{
    int st;
    const double lo = fmax(spec->V_min, Vc);
    if ((st = dl_push(nodes, spec->V_min)))
        return st;
    if (Vc > spec->V_min && Vc < spec->V_max && log(Vc) > log(spec->V_min) &&
        (st = dl_push(nodes, Vc)))
        return st;
    if (lo < spec->V_max) {
        const double x0 = log(lo), x1 = log(spec->V_max);
        const size_t m = (size_t)ceil(2.0 * (x1 - x0) / log(10.0));
        for (size_t k = 1; k < m; k++) {
            const double V = exp(x0 + (x1 - x0) * (double)k / (double)m);
            if (log(V) > log(nodes->v[nodes->n - 1]) && log(V) < x1 && (st = dl_push(nodes, V)))
                return st;
        }
    }
    if ((st = dl_push(nodes, spec->V_max)))
        return st;
    if (nodes->n > spec->max_nodes)
        return ct_error_set(CT_ENOCONV,
                            "table: max_nodes = %zu is below the %zu first nodes (the ends, V*_c "
                            "and two per decade)",
                            spec->max_nodes, nodes->n);
    return CT_OK;
}

/* e at the first nodes (e = 1 at and below V*_c: not computed) and at their checks. */
static int first_values(table_build *B)
{
    const size_t n = B->nodes.n, K = B->K;
    const double Vc = B->Vc, *nodes = B->nodes.v;
    if (!(B->vals = malloc((n + (n - 1) * K) * sizeof(double))) ||
        !(B->chk = malloc((n - 1) * K * sizeof(double))))
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (nodes[i] > Vc)
            B->vals[m++] = nodes[i];
    for (size_t i = 0; i + 1 < n; i++)
        if (nodes[i] >= Vc) {
            check_speeds(nodes[i], nodes[i + 1], K, B->vals + m);
            m += K;
        }
    double *ev = malloc((m ? m : 1) * sizeof(double));
    if (!ev)
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    int st;
    if ((st = exact_e(&B->ex, B->vals, m, ev))) {
        free(ev);
        return st;
    }
    size_t q = 0;
    for (size_t i = 0; i < n; i++) {
        if ((st = dl_push(&B->ne, nodes[i] > Vc ? ev[q++] : 1.0)))
            break;
    }
    for (size_t i = 0; i + 1 < n && !st; i++)
        for (size_t k = 0; k < K; k++)
            B->chk[i * K + k] = nodes[i] >= Vc ? ev[q++] : 1.0;
    free(ev);
    return st;
}

/* The interpolant of this round's nodes, into B->t. */
static int round_table(table_build *B)
{
    const size_t n = B->nodes.n;
    int st;
    ct_table_free(B->t);
    B->t = NULL;
    if ((st = table_alloc(&B->t, n)))
        return st;
    ct_table *t = B->t;
    t->rule = B->spec->interpolation;
    t->info.V_star_crit = B->Vc;
    for (size_t i = 0; i < n; i++) {
        t->V[i] = B->nodes.v[i];
        t->x[i] = log(B->nodes.v[i]);
        t->e[i] = B->ne.v[i];
    }
    table_slopes(t);
    return CT_OK;
}

/* Every interval above V*_c checked against its cached exact values: its error into
 * B->errs, whether it fails into B->split (*nsplit of them), the worst into the table's
 * info. */
static int check_round(table_build *B, size_t round, size_t *nsplit)
{
    const size_t n = B->nodes.n, K = B->K;
    const double tol = B->tol, *nodes = B->nodes.v;
    ct_table *t = B->t;
    free(B->split);
    free(B->errs);
    B->split = calloc(n, 1);
    B->errs = malloc(n * sizeof(double));
    if (!B->split || !B->errs)
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    double *errs = B->errs, worst = 0.0, worst_V = NAN;
    size_t checked = 0;
    *nsplit = 0;
    double *pts = malloc(K * sizeof(double));
    if (!pts)
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    for (size_t i = 0; i + 1 < n; i++) {
        errs[i] = 0.0;
        if (nodes[i] < B->Vc)
            continue; /* e = 1 exactly there: the rule, not an interpolation */
        check_speeds(nodes[i], nodes[i + 1], K, pts);
        for (size_t k = 0; k < K; k++) {
            const double err = fabs(ct_table_eval(t, pts[k]) - B->chk[i * K + k]);
            checked++;
            if (!(err <= errs[i]))
                errs[i] = err; /* NaN is an error too */
            if (!(err <= worst)) {
                worst = err;
                worst_V = pts[k];
            }
        }
        if (!(errs[i] <= tol)) {
            B->split[i] = 1;
            (*nsplit)++;
        }
    }
    free(pts);
    t->info.worst_error = worst;
    t->info.worst_V_star = worst_V;
    t->info.checked = checked;
    t->info.rounds = round;
    t->info.evaluations = B->ex.evaluations;
    return CT_OK;
}

/* The old nodes with the split points after their interval, and the checks of the new
 * intervals (ev: per split point its e, then the checks of its two halves) beside the
 * cached ones; then the next round's checks become this round's. */
static int merge_nodes(table_build *B, const double *ev)
{
    const size_t n = B->nodes.n, K = B->K;
    dlist V2 = {0}, e2 = {0};
    size_t q = 0, j = 0;
    int st = CT_OK;
    for (size_t i = 0; i < n && !st; i++) {
        st = dl_push(&V2, B->nodes.v[i]);
        if (!st)
            st = dl_push(&e2, B->ne.v[i]);
        if (st || i + 1 == n)
            break;
        const size_t iv = V2.n - 1; /* the interval that starts at this node */
        if (!B->split[i]) {
            memcpy(B->nchk + iv * K, B->chk + i * K, K * sizeof(double));
            continue;
        }
        if ((st = dl_push(&V2, B->newV.v[j])) || (st = dl_push(&e2, ev[q])))
            break;
        memcpy(B->nchk + iv * K, ev + q + 1, K * sizeof(double));
        memcpy(B->nchk + (iv + 1) * K, ev + q + 1 + K, K * sizeof(double));
        q += 1 + 2 * K;
        j++;
    }
    free(B->nodes.v);
    free(B->ne.v);
    B->nodes = V2;
    B->ne = e2;
    if (st)
        return st;
    double *tmp = B->chk;
    B->chk = B->nchk;
    B->nchk = tmp;
    return CT_OK;
}

/* The failing intervals split (at a kink of e when one lies inside, else in the middle), the
 * split points' e and the new intervals' checks in one batch, merged into the nodes. */
static int split_round(table_build *B, size_t nsplit)
{
    const size_t n = B->nodes.n, K = B->K;
    const double *nodes = B->nodes.v;
    int st;
    B->newV.n = 0;
    for (size_t i = 0; i + 1 < n; i++) {
        if (!B->split[i])
            continue;
        double s = log(nodes[i + 1]) - log(nodes[i]) > CT_TABLE_MIN_WIDTH
                       ? split_point(nodes[i], nodes[i + 1], &B->kinks)
                       : 0.0;
        if (!(s > 0.0))
            return ct_error_set(CT_ENOCONV,
                                "table: tolerance %.3g not met on [%.17g, %.17g], too short to "
                                "split (|e_table - e| = %.3g): below what e's rounding allows",
                                B->tol, nodes[i], nodes[i + 1], B->errs[i]);
        if ((st = dl_push(&B->newV, s)))
            return st;
    }
    const size_t n2 = n + nsplit, m = nsplit * (1 + 2 * K);
    free(B->vals);
    free(B->nchk);
    B->vals = malloc(m * sizeof(double));
    B->nchk = malloc((n2 - 1) * K * sizeof(double));
    double *ev = malloc(m * sizeof(double));
    if (!B->vals || !B->nchk || !ev) {
        free(ev);
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    }
    for (size_t j = 0, q = 0, i = 0; i + 1 < n; i++) {
        if (!B->split[i])
            continue;
        B->vals[q++] = B->newV.v[j];
        check_speeds(nodes[i], B->newV.v[j], K, B->vals + q);
        q += K;
        check_speeds(B->newV.v[j], nodes[i + 1], K, B->vals + q);
        q += K;
        j++;
    }
    if (!(st = exact_e(&B->ex, B->vals, m, ev)))
        st = merge_nodes(B, ev);
    free(ev);
    return st;
}

/* How many of the table's nodes are kinks of e (kinks sorted). */
static size_t kinks_at_nodes(const ct_table *t, const dlist *kinks)
{
    size_t count = 0;
    for (size_t i = 0; i < t->n; i++) {
        size_t lo_k = 0, hi_k = kinks->n;
        while (lo_k < hi_k) {
            size_t mk = lo_k + (hi_k - lo_k) / 2;
            if (kinks->v[mk] < t->V[i])
                lo_k = mk + 1;
            else
                hi_k = mk;
        }
        count += lo_k < kinks->n && kinks->v[lo_k] == t->V[i];
    }
    return count;
}

int ct_table_build(ct_table **out, const ct_bundle *b, const ct_table_spec *spec)
{
    CT_NEED(out);
    *out = NULL;
    CT_NEED(b);
    CT_NEED(spec);
    int st;
    if ((st = check_spec(spec)))
        return st;
    table_build B = {.spec = spec,
                     .K = spec->check_points,
                     .tol = spec->tolerance,
                     .ex = {.b = b, .spec = spec}};
    if (!(B.ex.rows = malloc(CHUNK * sizeof *B.ex.rows))) {
        st = ct_error_set(CT_ENOMEM, "table: out of memory");
        goto done;
    }
    /* V*_c as every sweep reports it (and V_max's impact must be computable at all) */
    double e_top;
    if ((st = ct_curve_alloc(&B.ex.curve)) || (st = exact_e(&B.ex, &spec->V_max, 1, &e_top)))
        goto done;
    B.Vc = B.ex.rows[0].r.V_star_crit;
    if ((st = kink_speeds(b, B.ex.curve, fmax(spec->V_min, B.Vc), spec->V_max, &B.kinks)) ||
        (st = first_nodes(spec, B.Vc, &B.nodes)) || (st = first_values(&B)))
        goto done;
    for (size_t round = 1;; round++) {
        size_t nsplit = 0;
        if (ct_interrupted(spec->interrupt)) {
            st = ct_error_interrupted();
            goto done;
        }
        if ((st = round_table(&B)) || (st = check_round(&B, round, &nsplit)))
            goto done;
        if (!nsplit)
            break;
        if (B.nodes.n + nsplit > spec->max_nodes) {
            st = ct_error_set(CT_ENOCONV,
                              "table: tolerance %.3g not met with max_nodes = %zu (%zu intervals "
                              "still fail; worst |e_table - e| = %.3g at V* = %.6g): raise "
                              "max_nodes or the tolerance",
                              B.tol, spec->max_nodes, nsplit, B.t->info.worst_error,
                              B.t->info.worst_V_star);
            goto done;
        }
        if ((st = split_round(&B, nsplit)))
            goto done;
    }
    B.t->info.kinks = kinks_at_nodes(B.t, &B.kinks);
    *out = B.t;
    B.t = NULL;
done:
    table_build_free(&B);
    return st;
}

/* ---- tables of samples: the mean and quantiles of e over realisations or landings ---- */

/* The samples' statistics on a grid of speeds: column 0 the mean, column 1 + j e at p[j]. */
typedef struct {
    size_t M;      /* grid points (V*_c inserted when inside the range) */
    double *V, *x; /* the grid, ln of it */
    double *y;     /* column c at grid point g: y[c * M + g] */
    size_t C;      /* 1 + quantiles */
    double Vc;     /* the least V*_c of the samples: every e is 1 at and below it */
} sample_grid;

static void sample_grid_free(sample_grid *G)
{
    free(G->V);
    free(G->x);
    free(G->y);
}

static int check_quantiles(const ct_table_quantiles *q)
{
    if (q->np < 1 || q->np > CT_TABLE_MAX_QUANTILES || !q->p)
        return ct_error_set(CT_EINVAL, "table: %zu quantiles: need 1 .. %d", q->np,
                            CT_TABLE_MAX_QUANTILES);
    for (size_t j = 0; j < q->np; j++) {
        char text[32];
        snprintf(text, sizeof text, "%.6g", q->p[j]);
        if (!(q->p[j] >= 0.0 && q->p[j] <= 1.0) || (j && !(q->p[j] > q->p[j - 1])))
            return ct_error_set(
                CT_EINVAL, "table: quantile %g: each p must be in [0, 1], increasing", q->p[j]);
        if (strtod(text, NULL) != q->p[j]) /* the file names a column by p in 6 digits */
            return ct_error_set(CT_EINVAL, "table: quantile %.17g: at most 6 significant digits",
                                q->p[j]);
    }
    if (!(q->tolerance == 0.0 || (q->tolerance >= 1e-13 && q->tolerance < 1.0)))
        return ct_error_set(CT_EINVAL,
                            "table: quantile tolerance = %g: must satisfy 1e-13 <= tolerance < 1 "
                            "(0: the table's)",
                            q->tolerance);
    if (q->grid < 2 || q->grid > 1000000)
        return ct_error_set(CT_EINVAL, "table: grid = %zu: must satisfy 2 <= grid <= 1e6", q->grid);
    return CT_OK;
}

/* Every sample at every grid speed (one ensemble: each sample's rods built or met once), then
 * the statistics per speed: the mean in sample order (compensated), the quantiles by type 7
 * of the sorted samples (ct_quantile_sorted). */
static int sample_columns(const ct_ensemble_spec *samples, const ct_table_spec *spec,
                          const ct_table_quantiles *q, sample_grid *G)
{
    const size_t M = q->grid;
    double *speeds = malloc(M * sizeof(double));
    ct_ensemble_samples *S = NULL;
    if (!speeds)
        return ct_error_set(CT_ENOMEM, "table: out of memory");
    const double x0 = log(spec->V_min), h = log(spec->V_max) - x0;
    for (size_t g = 0; g < M; g++)
        speeds[g] = g == 0       ? spec->V_min
                    : g == M - 1 ? spec->V_max
                                 : exp(x0 + h * (double)g / (double)(M - 1));
    ct_ensemble_spec es = *samples;
    es.V_star = speeds;
    es.nvel = M;
    es.impacts = 1;
    es.opts = spec->opts;
    es.path = spec->path;
    es.stop_on_error = 1;
    es.interrupt = spec->interrupt;
    es.progress = spec->progress;
    es.progress_ctx = spec->progress_ctx;
    int st = ct_ensemble_samples_alloc(&S, es.first, es.count, M);
    if (!st)
        st = ct_ensemble(&es, S);
    const size_t R = (size_t)es.count;
    double Vc = INFINITY;
    for (size_t k = 0; !st && k < R * M; k++)
        Vc = fmin(Vc, S->V_star_crit[k]);
    /* the grid with V*_c inserted when inside it: every sample's e is 1 there */
    const int with_c = !st && Vc > speeds[0] && Vc < speeds[M - 1];
    G->M = M + (size_t)with_c;
    G->C = 1 + q->np;
    G->Vc = Vc;
    double *work = NULL;
    if (!st &&
        (!(G->V = malloc(G->M * sizeof(double))) || !(G->x = malloc(G->M * sizeof(double))) ||
         !(G->y = malloc(G->C * G->M * sizeof(double))) || !(work = malloc(R * sizeof(double)))))
        st = ct_error_set(CT_ENOMEM, "table: out of memory for %zu x %zu statistics", G->C, G->M);
    for (size_t g = 0, m = 0; !st && g < M; g++, m++) {
        if (with_c && speeds[g] > Vc && (g == 0 || speeds[g - 1] < Vc)) {
            G->V[m] = Vc;
            for (size_t c = 0; c < G->C; c++)
                G->y[c * G->M + m] = 1.0;
            m++;
        }
        G->V[m] = speeds[g];
        double sum = 0.0, comp = 0.0;
        for (size_t r = 0; r < R; r++) {
            work[r] = S->e[r * M + g];
            ct_add_comp(&sum, &comp, work[r]);
        }
        G->y[m] = (sum + comp) / (double)R;
        qsort(work, R, sizeof(double), ct_cmp_double);
        for (size_t j = 0; j < q->np; j++)
            G->y[(1 + j) * G->M + m] = ct_quantile_sorted(work, R, q->p[j]);
    }
    for (size_t m = 0; !st && m < G->M; m++)
        G->x[m] = log(G->V[m]);
    free(work);
    free(speeds);
    ct_ensemble_samples_free(S);
    return st;
}

/* The table of the nodes (grid indices idx, n of them) with each column's slopes (above V*_c,
 * as table_slopes). */
static int grid_table(const sample_grid *G, const size_t *idx, size_t n, ct_interp rule,
                      const ct_table_quantiles *q, ct_table **out)
{
    ct_table *t;
    int st = table_alloc(&t, n);
    if (!st && (st = quantiles_alloc(t, q->np))) {
        ct_table_free(t);
        return st;
    }
    if (st)
        return st;
    memcpy(t->p, q->p, q->np * sizeof(double));
    t->rule = rule;
    t->info.V_star_crit = G->Vc;
    for (size_t i = 0; i < n; i++) {
        t->V[i] = G->V[idx[i]];
        t->x[i] = G->x[idx[i]];
        t->e[i] = G->y[idx[i]];
        for (size_t j = 0; j < q->np; j++)
            t->eq[j * n + i] = G->y[(1 + j) * G->M + idx[i]];
    }
    table_slopes(t);
    size_t c0 = 0;
    while (c0 < n && t->V[c0] < G->Vc)
        c0++;
    for (size_t j = 0; j < q->np; j++) {
        double *d = t->dq + j * n;
        for (size_t i = 0; i < n; i++)
            d[i] = 0.0;
        if (rule == CT_INTERP_MONOTONE_CUBIC && n - c0 >= 2)
            ct_pchip_slopes(n - c0, t->x + c0, t->eq + j * n + c0, d + c0);
    }
    *out = t;
    return CT_OK;
}

/* Every grid point between the nodes against the table: the worst error into t's info and, per
 * interval, whether it fails (split[i] for interval i). Returns how many fail. */
static size_t grid_check(const sample_grid *G, const size_t *idx, size_t n, ct_table *t, double tol,
                         double qtol, unsigned char *split)
{
    size_t fails = 0;
    t->info.worst_error = t->q_worst = 0.0;
    t->info.worst_V_star = t->q_worst_V = NAN;
    t->info.checked = 0;
    t->q_tol = qtol;
    for (size_t i = 0; i + 1 < n; i++) {
        split[i] = 0;
        for (size_t g = idx[i] + 1; g < idx[i + 1]; g++) {
            if (!(G->V[g] > G->Vc))
                continue; /* e = 1 by the rule */
            t->info.checked++;
            for (size_t c = 0; c < G->C; c++) {
                const double v =
                    c ? ct_tab_interp(n, t->x, t->eq + (c - 1) * n, t->dq + (c - 1) * n,
                                      (int)t->rule, t->info.V_star_crit, G->V[g])
                      : ct_table_eval(t, G->V[g]);
                const double err = fabs(v - G->y[c * G->M + g]);
                double *worst = c ? &t->q_worst : &t->info.worst_error,
                       *where = c ? &t->q_worst_V : &t->info.worst_V_star;
                if (err > *worst || isnan(err)) {
                    *worst = err;
                    *where = G->V[g];
                }
                if (!(err <= (c ? qtol : tol)))
                    split[i] = 1;
            }
        }
        fails += split[i];
    }
    return fails;
}

/* 1 when grid point g may be a node: the ends, V*_c, every second point. The others are
 * never nodes, so that every interval keeps a point to be checked at. */
static int grid_node_allowed(const sample_grid *G, size_t g)
{
    return g == 0 || g + 1 == G->M || G->V[g] == G->Vc || g % 2 == 0;
}

/* The first nodes: the ends, V*_c, and the allowed grid points nearest two per decade. */
static size_t grid_first_nodes(const sample_grid *G, size_t *idx)
{
    size_t n = 0;
    const double step = 0.5 * log(10.0);
    double last = -1.0;
    for (size_t g = 0; g < G->M; g++) {
        const int end = g == 0 || g + 1 == G->M, critical = G->V[g] == G->Vc;
        const double k = floor((G->x[g] - G->x[0]) / step);
        if (end || critical || (k != last && grid_node_allowed(G, g))) {
            idx[n++] = g;
            last = k;
        }
    }
    return n;
}

/* The allowed grid point nearest the middle of (a, b), strictly inside; 0 when there is none. */
static size_t grid_split(const sample_grid *G, size_t a, size_t b)
{
    const size_t mid = a + (b - a) / 2;
    for (size_t d = 0; mid - d > a || mid + d < b; d++) {
        if (mid - d > a && grid_node_allowed(G, mid - d))
            return mid - d;
        if (mid + d < b && grid_node_allowed(G, mid + d))
            return mid + d;
    }
    return 0;
}

int ct_table_build_samples(ct_table **out, const ct_ensemble_spec *samples,
                           const ct_table_spec *spec, const ct_table_quantiles *q)
{
    CT_NEED(out);
    *out = NULL;
    CT_NEED(samples);
    CT_NEED(spec);
    CT_NEED(q);
    int st;
    if ((st = check_spec(spec)) || (st = check_quantiles(q)))
        return st;
    sample_grid G = {0};
    size_t *idx = NULL, *next = NULL, n;
    unsigned char *split = NULL;
    ct_table *t = NULL;
    if ((st = sample_columns(samples, spec, q, &G)))
        goto done;
    idx = malloc(G.M * sizeof *idx);
    next = malloc(G.M * sizeof *next);
    split = malloc(G.M);
    if (!idx || !next || !split) {
        st = ct_error_set(CT_ENOMEM, "table: out of memory");
        goto done;
    }
    n = grid_first_nodes(&G, idx);
    for (size_t round = 1;; round++) {
        ct_table_free(t);
        t = NULL;
        if ((st = grid_table(&G, idx, n, spec->interpolation, q, &t)))
            goto done;
        const double qtol = q->tolerance > 0.0 ? q->tolerance : spec->tolerance;
        const size_t fails = grid_check(&G, idx, n, t, spec->tolerance, qtol, split);
        t->info.rounds = round;
        if (!fails)
            break;
        if (n + fails > spec->max_nodes) {
            st = ct_error_set(CT_ENOCONV,
                              "table: tolerance %.3g not met with max_nodes = %zu (%zu intervals "
                              "still fail; worst error %.3g at V* = %.6g): raise max_nodes or "
                              "the tolerance",
                              spec->tolerance, spec->max_nodes, fails, t->info.worst_error,
                              t->info.worst_V_star);
            goto done;
        }
        /* a failing interval is split at the allowed grid point in its middle; one that has
         * none left (its check points are all it holds) cannot be made to pass */
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            next[m++] = idx[i];
            if (i + 1 < n && split[i] && !(next[m] = grid_split(&G, idx[i], idx[i + 1]))) {
                st = ct_error_set(CT_ENOCONV,
                                  "table: tolerance %.3g (quantiles %.3g) not met at the "
                                  "grid's resolution: between the grid points next to V* = "
                                  "%.6g (worst error of the mean %.3g, of a quantile %.3g); "
                                  "raise table.grid or the tolerances",
                                  spec->tolerance, t->q_tol, G.V[idx[i]], t->info.worst_error,
                                  t->q_worst);
                goto done;
            }
            m += i + 1 < n && split[i];
        }
        memcpy(idx, next, m * sizeof *idx);
        n = m;
    }
    t->samples = samples->count;
    t->info.evaluations = (size_t)samples->count * (size_t)q->grid;
    *out = t;
    t = NULL;
done:
    ct_table_free(t);
    free(idx);
    free(next);
    free(split);
    sample_grid_free(&G);
    return st;
}

/* ---- the table file: written here, read by include/cantact_table.h ---- */

static void put_value(FILE *f, const char *key, double v)
{
    fprintf(f, "# %s = ", key);
    ct_put_double(f, v);
    fputc('\n', f);
}

int ct_table_write(FILE *f, const ct_table *t, const ct_table_meta *meta)
{
    CT_NEED(f);
    CT_NEED(t);
    CT_NEED(meta);
    ct_table_info in;
    ct_table_get_info(t, &in);
    fprintf(f, "# cantact %s table: e of the first impact on the virgin surface against V*%s\n",
            meta->version ? meta->version : "",
            t->nq ? ", the mean and quantiles over samples" : "");
    if (meta->scene)
        fprintf(f, "# scene = %s\n", meta->scene);
    if (meta->surface)
        fprintf(f, "# surface = %s\n", meta->surface);
    fputs("# units: V_star = sqrt(m v^2 / (2 l0 E h0)) dimensionless; e dimensionless; "
          "de_dlnV_star = de/d(ln V_star) dimensionless\n",
          f);
    fprintf(f, "# interpolation = %s\n", ct_interp_name(ct_table_interpolation(t)));
    if (ct_table_interpolation(t) == CT_INTERP_LINEAR)
        fputs("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, t = (x - x_i) / "
              "(x_i+1 - x_i): e = e_i + (e_i+1 - e_i) t, kept between e_i and e_i+1 (against "
              "rounding; de_dlnV_star is not used: 0)\n",
              f);
    else
        fputs("# rule: in x = ln V_star on the interval [x_i, x_i+1] holding x, h = x_i+1 - x_i, "
              "t = (x - x_i) / h, d = de_dlnV_star: e = e_i + (e_i+1 - e_i) t^2 (3 - 2 t) + "
              "h t (1 - t) ((1 - t) d_i - t d_i+1), kept between e_i and e_i+1 (against "
              "rounding)\n",
              f);
    fputs("# rule: e = 1 exactly for V_star <= V_star_crit; outside the nodes above it, the "
          "nearest end's e (the table does not cover it)\n",
          f);
    put_value(f, "V_star_crit", in.V_star_crit);
    put_value(f, "tolerance", meta->tolerance);
    put_value(f, "worst_error", in.worst_error);
    if (isfinite(in.worst_V_star))
        put_value(f, "worst_error_at_V_star", in.worst_V_star);
    else
        fputs("# worst_error_at_V_star = none (no point above V_star_crit in the range)\n", f);
    if (t->nq)
        fprintf(f,
                "# checked = %zu points, every column (the mean and each quantile) against the "
                "samples' own statistics there (a grid of %zu speeds equally spaced in ln V_star "
                "at which every sample was computed; the nodes are grid points)\n",
                in.checked, meta->grid);
    else
        fprintf(f,
                "# checked = %zu points against the exact model (%zu equally spaced in ln V_star "
                "inside every interval above V_star_crit; the nodes are exact)\n",
                in.checked, meta->check_points);
    /* the number of rows: the reader refuses a file with another number (a cut one) */
    if (t->nq)
        fprintf(f, "# nodes = %zu (grid points)\n", ct_table_size(t));
    else
        fprintf(f,
                "# nodes = %zu (%zu at kinks of e, where u_max reaches a rod's contact or yield "
                "point)\n",
                ct_table_size(t), in.kinks);
    if (isfinite(meta->v_per_V_star))
        fprintf(f,
                "# v_per_V_star = %.17g (impact speed = V_star * v_per_V_star, in the units of "
                "the scene's mass, l0, E and h0)\n",
                meta->v_per_V_star);
    if (t->nq) {
        fprintf(f,
                "# quantiles = %zu (e at each p over the %llu samples%s%s: the columns e_p<p>)\n",
                t->nq, (unsigned long long)t->samples, meta->samples ? ", " : "",
                meta->samples ? meta->samples : "");
        put_value(f, "quantile_tolerance", t->q_tol);
        put_value(f, "quantile_worst_error", t->q_worst);
        fputs("# rule: e at (V_star, p): each column e_p<p> at V_star by the rule above, kept "
              "non-decreasing in p (a running maximum), then linear in p between the two "
              "columns about p (outside the first and last p, the nearest column); e is the "
              "mean over the samples\n",
              f);
    }
    fputs("V_star,e,de_dlnV_star", f);
    for (size_t j = 0; j < t->nq; j++)
        fprintf(f, ",e_p%.6g,de_p%.6g_dlnV_star", t->p[j], t->p[j]);
    fputc('\n', f);
    const double *V = ct_table_V_star(t), *e = ct_table_e(t), *d = ct_table_slope(t);
    for (size_t i = 0; i < ct_table_size(t); i++) {
        ct_put_double(f, V[i]);
        fputc(',', f);
        ct_put_double(f, e[i]);
        fputc(',', f);
        ct_put_double(f, d[i]);
        for (size_t j = 0; j < t->nq; j++) {
            fputc(',', f);
            ct_put_double(f, t->eq[j * t->n + i]);
            fputc(',', f);
            ct_put_double(f, t->dq[j * t->n + i]);
        }
        fputc('\n', f);
    }
    return ferror(f) ? ct_error_set(CT_EIO, "table: write error") : CT_OK;
}

int ct_table_read(ct_table **out, const char *path, ct_table_file_info *file)
{
    CT_NEED(out);
    *out = NULL;
    CT_NEED(path);
    ct_tab tab;
    char err[700];
    const int why = ct_tab_read(&tab, path, err, sizeof err);
    if (why)
        return ct_error_set(why == CT_TAB_IO_ERROR    ? CT_EIO
                            : why == CT_TAB_NO_MEMORY ? CT_ENOMEM
                                                      : CT_EINVAL,
                            "%s", err);
    /* the reader has checked what ct_table_from_nodes checks (and more) */
    int st = ct_table_from_nodes(
        out, tab.n, tab.V_star, tab.e, tab.slope,
        tab.rule == CT_TAB_LINEAR ? CT_INTERP_LINEAR : CT_INTERP_MONOTONE_CUBIC, tab.V_star_crit);
    if (!st && tab.nq && (st = quantiles_alloc(*out, tab.nq))) {
        ct_table_free(*out);
        *out = NULL;
    }
    if (!st && tab.nq) { /* checked by the reader as the nodes are */
        memcpy((*out)->p, tab.p, tab.nq * sizeof(double));
        memcpy((*out)->eq, tab.e_q, tab.nq * tab.n * sizeof(double));
        memcpy((*out)->dq, tab.slope_q, tab.nq * tab.n * sizeof(double));
    }
    if (!st && file) {
        file->tolerance = tab.tolerance;
        file->worst_error = tab.worst_error;
        file->worst_V_star = tab.worst_V_star;
        file->v_per_V_star = tab.v_per_V_star;
    }
    ct_tab_free(&tab);
    return st;
}
