/* Rod sets (docs/model.md §3-4): rods as arrays, rod-by-rod force assembly, state advance,
 * closed-form energies. A bundle knows nothing of the surface that made it. This file and
 * the event sort of curve.c are the only ones with OpenMP pragmas.
 *
 * Determinism: every sum over rods is split into fixed blocks of CT_BLOCK rods, each block
 * summed in rod order, and the block sums combined pairwise in a fixed tree. Threads only
 * decide who computes which block, so results are bitwise identical for any thread count,
 * and the serial path (small bundles) uses the very same blocks and tree.
 *
 * Reentrancy: nothing here that takes a const bundle writes to it; workspaces live on the
 * stack or are allocated per call, so several threads may evaluate one bundle at once. */
#define _DEFAULT_SOURCE /* madvise(MADV_HUGEPAGE) */
#include "internal.h"
#include "rod.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

struct ct_bundle {
    ct_layer layer;
    size_t n;       /* rods held */
    size_t omitted; /* rods the surface left out */
    double E, eps_y;
    double *top, *length, *area, *plastic_strain;
    size_t nblocks;
    int threads;         /* 0: the OpenMP default */
    size_t parallel_min; /* sums of fewer rods run on one thread */
    const ct_rod_meta_kind *kind;
    void *meta;
};

int ct_layer_validate(const ct_layer *l)
{
    if (!l)
        return ct_error_set(CT_EINVAL, "layer: NULL");
    const double v[] = {l->E, l->sigma_y, l->Hstar, l->l0, l->h0};
    const char *names[] = {"E", "sigma_y", "H*", "l0", "h0"};
    for (int k = 0; k < 5; k++)
        if (!isfinite(v[k]) || !(v[k] >= DBL_MIN))
            return ct_error_set(CT_EINVAL,
                                "%s = %g: must be finite and > 0, a normal double (>= %g)",
                                names[k], v[k], DBL_MIN);
    if (!(l->sigma_y < l->E))
        return ct_error_set(CT_EINVAL,
                            "sigma_y = %g: yield strain sigma_y/E must satisfy 0 < eps_y < 1 "
                            "(E = %g)",
                            l->sigma_y, l->E);
    if (!isfinite(l->l0 * l->E * l->h0) || !(l->l0 * l->E * l->h0 >= DBL_MIN))
        return ct_error_set(CT_EINVAL, "l0 E h0 = %g: must be a finite positive number",
                            l->l0 * l->E * l->h0);
    /* E s L (a rod's stiffness times its length) bounds every work term: it must be finite,
     * else energies overflow (E l0 H* in units of sigma_y l0 h0 is E/sigma_y times H* / h0) */
    if (!isfinite(l->E * l->l0 * l->Hstar))
        return ct_error_set(CT_EINVAL,
                            "E l0 H* = %g * %g * %g overflows double precision: energies of this "
                            "layer cannot be represented (lower E/sigma_y or H*/h0)",
                            l->E, l->l0, l->Hstar);
    return CT_OK;
}

void ct_bundle_set_parallel_min(ct_bundle *b, size_t rods)
{
    b->parallel_min = rods;
}

int ct_bundle_set_threads(ct_bundle *b, int threads)
{
    /* a team larger than the OpenMP runtime can create ends the process (libgomp aborts) */
    b->threads = threads > CT_MAX_THREADS ? CT_MAX_THREADS : threads > 0 ? threads : 0;
#ifdef _OPENMP
    return b->threads ? b->threads : omp_get_max_threads();
#else
    return 1;
#endif
}

int ct_default_threads(void)
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

int ct_bundle_threads(const ct_bundle *b)
{
#ifdef _OPENMP
    return b->threads ? b->threads : omp_get_max_threads();
#else
    (void)b;
    return 1;
#endif
}

int ct_bundle_team(const ct_bundle *b)
{
    return b->n < b->parallel_min ? 1 : ct_bundle_threads(b);
}

int ct_bundle_team_from(const ct_bundle *b, size_t factor)
{
    if ((double)b->n < (double)b->parallel_min * (double)factor)
        return 1;
    return ct_bundle_team(b);
}

/* What the system can give: MemAvailable (what the kernel can give without swapping). */
static size_t system_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        char line[256];
        unsigned long long kb;
        while (fgets(line, sizeof line, f)) {
            if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1) {
                fclose(f);
                return (size_t)(kb * 1024ULL);
            }
        }
        fclose(f);
    }
    long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0)
        return (size_t)pages * (size_t)page;
    return SIZE_MAX;
}

/* The address space the process maps now (VmSize), 0 if unknown. */
static size_t mapped_now(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    unsigned long long pages = 0;
    if (f) {
        if (fscanf(f, "%llu", &pages) != 1)
            pages = 0;
        fclose(f);
    }
    long page = sysconf(_SC_PAGESIZE);
    return page > 0 ? (size_t)pages * (size_t)page : 0;
}

size_t ct_available_memory(void)
{
    /* and no more than the process may still map (ulimit -v less what it maps: the limit
     * alone let a 2.9 GiB request pass under 3.4 GiB with 1.7 GiB mapped, and fail later) */
    size_t avail = system_available();
    struct rlimit r;
    if (!getrlimit(RLIMIT_AS, &r) && r.rlim_cur != RLIM_INFINITY) {
        const size_t limit = (size_t)r.rlim_cur, used = mapped_now(),
                     left = used < limit ? limit - used : 0;
        avail = left < avail ? left : avail;
    }
    return avail;
}

void ct_bundle_free(ct_bundle *b)
{
    if (!b)
        return;
    free(b->top);
    free(b->length);
    free(b->area);
    free(b->plastic_strain);
    if (b->kind && b->kind->free)
        b->kind->free(b->meta);
    free(b);
}

/* A rod array. Large ones are 2 MiB aligned and asked for transparent huge pages: on a
 * depth-26 bundle (4.3 GB) the kernel's page faults and page clearing otherwise cost more
 * than the whole computation. */
static double *rod_array(size_t n)
{
    const size_t huge = (size_t)2 << 20, bytes = n * sizeof(double);
    if (bytes < huge)
        return malloc(bytes);
    void *p = NULL;
    size_t rounded = (bytes + huge - 1) / huge * huge;
    if (posix_memalign(&p, huge, rounded))
        return NULL;
#ifdef MADV_HUGEPAGE
    madvise(p, rounded, MADV_HUGEPAGE); /* advice only: failure changes nothing */
#endif
    return p;
}

int ct_bundle_create(ct_bundle **out, const ct_layer *layer, size_t n, const char *what)
{
    int st;
    *out = NULL;
    if ((st = ct_layer_validate(layer)))
        return st;
    if (n > SIZE_MAX / CT_BYTES_PER_ROD / 2)
        return ct_error_set(CT_ENOMEM, "%s: %zu rods cannot be addressed", what, n);
    size_t need = n * CT_BYTES_PER_ROD,
           avail = (double)need < CT_MEMORY_CHECK_MIN ? SIZE_MAX : ct_available_memory();
    if (need > avail / 10 * 9)
        return ct_error_set(CT_ENOMEM,
                            "%s: %zu rods need %.3g GiB, more than the %.3g GiB of memory "
                            "available",
                            what, n, (double)need / 1073741824.0, (double)avail / 1073741824.0);
    ct_bundle *b = calloc(1, sizeof *b);
    if (!b)
        return ct_error_set(CT_ENOMEM, "%s: out of memory", what);
    b->layer = *layer;
    b->n = n;
    b->E = layer->E;
    b->eps_y = layer->sigma_y / layer->E;
    b->parallel_min = CT_PARALLEL_MIN_RODS;
    b->nblocks = (n + CT_BLOCK - 1) / CT_BLOCK;
    size_t m = n ? n : 1;
    b->top = rod_array(m);
    b->length = rod_array(m);
    b->area = rod_array(m);
    b->plastic_strain = rod_array(m);
    if (!b->top || !b->length || !b->area || !b->plastic_strain) {
        ct_bundle_free(b);
        return ct_error_set(CT_ENOMEM, "%s: %zu rods: out of memory", what, n);
    }
    *out = b;
    return CT_OK;
}

void ct_bundle_arrays(ct_bundle *b, double **top, double **length, double **area,
                      double **plastic_strain)
{
    *top = b->top;
    *length = b->length;
    *area = b->area;
    *plastic_strain = b->plastic_strain;
}

void ct_bundle_fill(ct_bundle *b, size_t k0, size_t count, double top, double length, double area)
{
    const int team = count >= b->parallel_min ? ct_default_threads() : 1;
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
    for (ptrdiff_t j = 0; j < (ptrdiff_t)count; j++) {
        b->top[k0 + (size_t)j] = top;
        b->length[k0 + (size_t)j] = length;
        b->area[k0 + (size_t)j] = area;
        b->plastic_strain[k0 + (size_t)j] = 0.0;
    }
}

void ct_bundle_parallel(const ct_bundle *b, size_t count, size_t chunk, ct_chunk_fn fn, void *ctx)
{
    const size_t nc = chunk ? (count + chunk - 1) / chunk : 0;
    const int team = count >= b->parallel_min ? ct_bundle_team(b) : 1;
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
    for (ptrdiff_t c = 0; c < (ptrdiff_t)nc; c++) {
        size_t i0 = (size_t)c * chunk, i1 = i0 + chunk < count ? i0 + chunk : count;
        fn(ctx, (size_t)c, i0, i1);
    }
}

void ct_bundle_set_surface(ct_bundle *b, const ct_rod_meta_kind *kind, void *meta, size_t omitted)
{
    if (b->kind && b->kind->free)
        b->kind->free(b->meta);
    b->kind = kind;
    b->meta = meta;
    b->omitted = omitted;
}

const void *ct_bundle_surface_meta(const ct_bundle *b, const ct_rod_meta_kind *kind)
{
    return b->kind == kind ? b->meta : NULL;
}

const char *ct_bundle_surface(const ct_bundle *b)
{
    return b->kind ? b->kind->name : "rods";
}

int ct_bundle_from_rods(ct_bundle **out, const ct_layer *layer, size_t n, const double *top,
                        const double *area)
{
    CT_NEED(out);
    CT_NEED(layer);
    int st;
    *out = NULL;
    if ((st = ct_layer_validate(layer)))
        return st;
    if (n && (!top || !area))
        return ct_error_set(CT_EINVAL, "rods: NULL arrays for %zu rods", n);
    for (size_t k = 0; k < n; k++) {
        if (!isfinite(top[k]) || !(top[k] >= 0.0) || !(top[k] < layer->Hstar))
            return ct_error_set(CT_EINVAL, "rod %zu: top = %g: must satisfy 0 <= top < H* = %g", k,
                                top[k], layer->Hstar);
        if (!isfinite(area[k]) || !(area[k] > 0.0))
            return ct_error_set(CT_EINVAL, "rod %zu: area = %g: must be finite and > 0", k,
                                area[k]);
    }
    ct_bundle *b;
    if ((st = ct_bundle_create(&b, layer, n, "rods")))
        return st;
    for (size_t k = 0; k < n; k++) {
        b->top[k] = top[k];
        b->length[k] = layer->Hstar - top[k];
        b->area[k] = area[k];
        b->plastic_strain[k] = 0.0;
    }
    *out = b;
    return CT_OK;
}

int ct_bundle_clone(ct_bundle **out, const ct_bundle *src)
{
    CT_NEED(out);
    CT_NEED(src);
    int st;
    ct_bundle *b;
    *out = NULL;
    if ((st = ct_bundle_create(&b, &src->layer, src->n, "bundle clone")))
        return st;
    memcpy(b->top, src->top, src->n * sizeof(double));
    memcpy(b->length, src->length, src->n * sizeof(double));
    memcpy(b->area, src->area, src->n * sizeof(double));
    memcpy(b->plastic_strain, src->plastic_strain, src->n * sizeof(double));
    b->threads = src->threads;
    b->parallel_min = src->parallel_min;
    if (src->kind) {
        void *meta = src->kind->clone ? src->kind->clone(src->meta) : NULL;
        if (src->meta && !meta) {
            ct_bundle_free(b);
            return ct_error_set(CT_ENOMEM, "bundle clone: out of memory");
        }
        ct_bundle_set_surface(b, src->kind, meta, src->omitted);
    }
    *out = b;
    return CT_OK;
}

void ct_bundle_reset(ct_bundle *b)
{
    const int team = ct_bundle_team(b);
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++)
        b->plastic_strain[k] = 0.0;
}

size_t ct_bundle_size(const ct_bundle *b)
{
    return b->n;
}

size_t ct_bundle_omitted(const ct_bundle *b)
{
    return b->omitted;
}

const ct_layer *ct_bundle_layer(const ct_bundle *b)
{
    return &b->layer;
}

double ct_bundle_reach(const ct_bundle *b, char *why, size_t len)
{
    if (len)
        why[0] = '\0';
    return b->kind && b->kind->reach ? b->kind->reach(b->meta, why, len) : INFINITY;
}

int ct_bundle_period(const ct_bundle *b, double *x, double *y)
{
    return b->kind && b->kind->period ? b->kind->period(b->meta, x, y) : 0;
}

int ct_bundle_rod(const ct_bundle *b, size_t k, ct_rod_info *info)
{
    CT_NEED(b);
    CT_NEED(info);
    if (k >= b->n)
        return ct_error_set(CT_EINVAL, "rod %zu: bundle holds %zu rods", k, b->n);
    memset(info, 0, sizeof *info); /* padding too: rods compare bytewise */
    info->top = b->top[k];
    info->length = b->length[k];
    info->area = b->area[k];
    info->plastic_strain = b->plastic_strain[k];
    info->stage = -1;
    info->x_left = info->x_right = NAN;
    info->footprint = (ct_footprint){CT_FOOTPRINT_NONE, NAN, NAN, NAN, NAN};
    if (b->kind && b->kind->rod_info)
        b->kind->rod_info(b->meta, k, info);
    /* a surface that gives an x-extent and no footprint of its own: the interval */
    if (info->footprint.shape == CT_FOOTPRINT_NONE && isfinite(info->x_left) &&
        isfinite(info->x_right))
        info->footprint =
            (ct_footprint){CT_FOOTPRINT_INTERVAL, info->x_left, info->x_right, NAN, NAN};
    return CT_OK;
}

/* ---- blocked sums ---- */

enum sum_kind { SUM_FORCE, SUM_WORK, SUM_ELASTIC };

/* The sum of one block, compensated (ct_add_comp): 2^i identical pieces of a stage then add up
 * to what the merged stage rod gives, to a few ulps. Force at ua of the state after being
 * taken to adv (-INFINITY: the current state); work from ua to ub, or the recoverable energy
 * at ua, of the current state. */
static double block_sum(const ct_bundle *b, enum sum_kind kind, double ua, double ub, double adv,
                        size_t k0, size_t k1)
{
    const double *top = b->top, *length = b->length, *area = b->area, *eps_p = b->plastic_strain;
    const double E = b->E, eps_y = b->eps_y;
    double s = 0.0, c = 0.0;
    switch (kind) {
    case SUM_FORCE:
        for (size_t k = k0; k < k1; k++) {
            double p = ct_rod_advance(adv, top[k], length[k], eps_p[k], eps_y);
            ct_add_comp(&s, &c, ct_rod_force(ua, top[k], length[k], area[k], p, E, eps_y));
        }
        break;
    case SUM_WORK:
        for (size_t k = k0; k < k1; k++)
            ct_add_comp(&s, &c,
                        ct_rod_work(ua, ub, top[k], length[k], area[k], eps_p[k], E, eps_y));
        break;
    case SUM_ELASTIC:
        for (size_t k = k0; k < k1; k++)
            ct_add_comp(&s, &c,
                        ct_rod_elastic_energy(ua, top[k], length[k], area[k], eps_p[k], E, eps_y));
        break;
    }
    return s + c;
}

/* The fixed pairwise tree over block sums: ws[i] += ws[i + stride] for stride 1, 2, 4, ...
 * A left-to-right binary counter (merge equal levels as they appear, then the remaining
 * levels right to left) adds exactly the same pairs, so the serial path needs no array. */
typedef struct {
    double v[64];
    int level[64];
    int sp;
} tree_counter;

static void counter_push(tree_counter *t, double x)
{
    t->v[t->sp] = x;
    t->level[t->sp++] = 0;
    while (t->sp >= 2 && t->level[t->sp - 1] == t->level[t->sp - 2]) {
        t->v[t->sp - 2] += t->v[t->sp - 1];
        t->level[t->sp - 2]++;
        t->sp--;
    }
}

static double counter_total(const tree_counter *t)
{
    if (t->sp == 0)
        return 0.0;
    double x = t->v[t->sp - 1];
    for (int j = t->sp - 2; j >= 0; j--)
        x = t->v[j] + x;
    return x;
}

static double blocked_total(const ct_bundle *b, enum sum_kind kind, double ua, double ub,
                            double adv)
{
    const ptrdiff_t nb = (ptrdiff_t)b->nblocks;
    const int team = ct_bundle_team(b);
    double *ws = team > 1 && nb > 0 ? malloc((size_t)nb * sizeof(double)) : NULL;
    if (!ws) { /* serial (or no memory for the block sums): the same tree as a counter */
        tree_counter t = {.sp = 0};
        for (ptrdiff_t j = 0; j < nb; j++) {
            size_t k0 = (size_t)j * CT_BLOCK;
            size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
            counter_push(&t, block_sum(b, kind, ua, ub, adv, k0, k1));
        }
        return counter_total(&t);
    }
#pragma omp parallel for schedule(static) num_threads(team)
    for (ptrdiff_t j = 0; j < nb; j++) {
        size_t k0 = (size_t)j * CT_BLOCK;
        size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
        ws[j] = block_sum(b, kind, ua, ub, adv, k0, k1);
    }
    for (ptrdiff_t stride = 1; stride < nb; stride *= 2)
        for (ptrdiff_t i = 0; i + stride < nb; i += 2 * stride)
            ws[i] += ws[i + stride];
    double total = ws[0];
    free(ws);
    return total;
}

/* Multi-node sums: one pass over the rods serves up to CT_NODE_CHUNK nodes. Each block
 * keeps one compensated sum per node, adding the rods in the same order as block_sum, and the
 * block sums meet in the same pairwise tree; the terms are rod.h's block form, bitwise its
 * scalar form, so every value is bitwise what the single-node call gives. The node loop is
 * innermost and branch-free (rod.h and ct_add_comp are selects), so it vectorises; on x86-64 an
 * AVX-512 or AVX2 clone is picked at load time when the CPU has it (the same IEEE operations
 * lane by lane, so the same bits; no FMA: contraction is off under -std=c11, and a fused
 * multiply-add would change the rounding). */
#define CT_NODE_CHUNK 64

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                             \
    !defined(__SANITIZE_ADDRESS__)
#define CT_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define CT_CLONES
#endif

CT_CLONES
static void block_sum_many(const ct_bundle *b, enum sum_kind kind, double ua, double adv,
                           const double *restrict ub, size_t m, size_t k0, size_t k1,
                           double *restrict out)
{
    const double *top = b->top, *length = b->length, *area = b->area, *eps_p = b->plastic_strain;
    const double E = b->E, eps_y = b->eps_y;
    double s[CT_NODE_CHUNK], c[CT_NODE_CHUNK];
    for (size_t i = 0; i < m; i++)
        s[i] = c[i] = 0.0;
    for (size_t k = k0; k < k1; k++) {
        const double tk = top[k], rl = 1.0 / length[k];
        const double pk = ct_rod_advanced(ct_rod_total_strain(adv, tk, rl), eps_p[k], eps_y);
        const double Es = E * area[k], EsL = E * area[k] * length[k];
        const double wa = ct_rod_work_density(ct_rod_strain(ua, tk, rl, pk), eps_y);
        if (kind == SUM_FORCE) {
            for (size_t i = 0; i < m; i++) {
                const double d = ct_rod_strain(ub[i], tk, rl, pk);
                ct_add_comp(&s[i], &c[i], ct_rod_force_of(d, Es, eps_y));
            }
        } else {
            for (size_t i = 0; i < m; i++) {
                const double d = ct_rod_strain(ub[i], tk, rl, pk);
                ct_add_comp(&s[i], &c[i], EsL * (ct_rod_work_density(d, eps_y) - wa));
            }
        }
    }
    for (size_t i = 0; i < m; i++)
        out[i] = s[i] + c[i];
}

/* The multi-node kernels behind one interface: a block [k0, k1) of rods, nodes
 * [i0, i0 + mc), `per_node` outputs per node written to out[j * CT_NODE_CHUNK + i]. */
typedef struct {
    enum sum_kind kind;
    double ua, adv;
    const double *ub;
} many_args;

static void many_kernel(const ct_bundle *b, const void *args, size_t i0, size_t mc, size_t k0,
                        size_t k1, double *out)
{
    const many_args *a = args;
    block_sum_many(b, a->kind, a->ua, a->adv, a->ub + i0, mc, k0, k1, out);
}

typedef void (*block_kernel)(const ct_bundle *b, const void *args, size_t i0, size_t mc, size_t k0,
                             size_t k1, double *out);

enum { NODE_WORK_FACTOR = 2048 };

/* Runs kernel over all blocks for m nodes and combines the block results in the fixed tree;
 * out[j * m + i] gets output j of node i. */
static int blocked_apply(const ct_bundle *b, block_kernel kernel, const void *args, size_t m,
                         int per_node, double *out, const volatile int *interrupt)
{
    const ptrdiff_t nb = (ptrdiff_t)b->nblocks;
    const size_t width = (size_t)per_node * CT_NODE_CHUNK;
    /* Two ways to share the work, bitwise the same (the same tree of blocks for every node):
     * with many nodes (a sweep's closed-form check) the chunks of nodes are independent
     * sums, each computed whole by one thread, in one parallel region; with few nodes (the
     * quadrature and u_max search on a deep bundle) the rod blocks of each chunk are shared.
     * Nodes are shared from two chunks per thread and NODE_WORK_FACTOR times the rod
     * threshold in rod-node terms (8.4 M): below, a team's start and its spinning cost the
     * rest of a short run more than it saves (a sweep of a small Cantor bundle); and the few
     * rod blocks of a measured profile of some thousand rods, shared unevenly by the team
     * in one parallel region per chunk of nodes, are slower than one thread
     * (docs/benchmarks.md has the figures). */
    const size_t nchunks = (m + CT_NODE_CHUNK - 1) / CT_NODE_CHUNK;
    const int avail = ct_bundle_threads(b);
    const int node_team =
        avail > 1 && nchunks >= 2 * (size_t)avail &&
                (double)b->n * (double)m >= (double)b->parallel_min * NODE_WORK_FACTOR
            ? avail
            : 1;
    const int team = node_team > 1 ? 1 : ct_bundle_team(b);
    double *ws = team > 1 && nb > 0 ? malloc((size_t)nb * width * sizeof(double)) : NULL;
    (void)node_team;
#pragma omp parallel for schedule(static) num_threads(node_team) if (node_team > 1)
    for (ptrdiff_t c = 0; c < (ptrdiff_t)nchunks; c++) {
        const size_t i0 = (size_t)c * CT_NODE_CHUNK;
        const size_t mc = m - i0 < CT_NODE_CHUNK ? m - i0 : CT_NODE_CHUNK;
        if (ct_interrupted(interrupt))
            continue; /* stopped: the rest is not computed, CT_EINTR below */
        if (!ws) {    /* serial: the same tree, one counter per output */
            double v[64][3 * CT_NODE_CHUNK], blk[3 * CT_NODE_CHUNK];
            int level[64], sp = 0;
            for (ptrdiff_t j = 0; j < nb && !ct_interrupted(interrupt); j++) {
                size_t k0 = (size_t)j * CT_BLOCK;
                size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
                kernel(b, args, i0, mc, k0, k1, blk);
                memcpy(v[sp], blk, width * sizeof(double));
                level[sp++] = 0;
                while (sp >= 2 && level[sp - 1] == level[sp - 2]) {
                    for (size_t i = 0; i < width; i++)
                        v[sp - 2][i] += v[sp - 1][i];
                    level[sp - 2]++;
                    sp--;
                }
            }
            for (int o = 0; o < per_node; o++)
                for (size_t i = 0; i < mc; i++) {
                    size_t q = (size_t)o * CT_NODE_CHUNK + i;
                    double x = sp ? v[sp - 1][q] : 0.0;
                    for (int j = sp - 2; j >= 0; j--)
                        x = v[j][q] + x;
                    out[(size_t)o * m + i0 + i] = x;
                }
            continue;
        }
#pragma omp parallel for schedule(static) num_threads(team)
        for (ptrdiff_t j = 0; j < nb; j++) {
            size_t k0 = (size_t)j * CT_BLOCK;
            size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
            if (!ct_interrupted(interrupt))
                kernel(b, args, i0, mc, k0, k1, ws + (size_t)j * width);
        }
        for (ptrdiff_t stride = 1; stride < nb; stride *= 2)
            for (ptrdiff_t j = 0; j + stride < nb; j += 2 * stride)
                for (size_t i = 0; i < width; i++)
                    ws[(size_t)j * width + i] += ws[(size_t)(j + stride) * width + i];
        for (int o = 0; o < per_node; o++)
            for (size_t i = 0; i < mc; i++)
                out[(size_t)o * m + i0 + i] = ws[(size_t)o * CT_NODE_CHUNK + i];
    }
    free(ws);
    return ct_interrupted(interrupt) ? ct_error_interrupted() : CT_OK;
}

static int blocked_many(const ct_bundle *b, enum sum_kind kind, double ua, double adv,
                        const double *ub, size_t m, double *out)
{
    many_args a = {kind, ua, adv, ub};
    return blocked_apply(b, many_kernel, &a, m, 1, out, NULL);
}

/* Closed forms of impacts, each from its own state (b advanced to adv[i]): per rod and node
 * rod.h's block form of ct_rod_advance, ct_rod_work, ct_rod_elastic_energy and ct_rod_force,
 * so each sum is bitwise what the single-node sums give on that state. */
typedef struct {
    const double *adv, *u0, *u1;
} closed_args;

/* The three terms of a rod: W_load from the work densities at u1 (db) and at u0 (w0), the
 * recoverable energy and the force at u1. */
static inline void closed_terms(double db, double w0, double EsL, double half, double Es,
                                double eps_y, double x[3])
{
    x[0] = EsL * (ct_rod_work_density(db, eps_y) - w0);
    x[1] = ct_rod_energy_of(db, half, eps_y);
    x[2] = ct_rod_force_of(db, Es, eps_y);
}

/* Whether the impacts of a chunk start from the virgin state at or before every rod's top
 * (a sweep's first impacts: adv = -inf, u0 the first contact): then no rod advances (the
 * plastic strain stays eps_p) and none is strained at u0 (its work density there is 0), so
 * both are left out, bitwise: (u0 - top) / L <= 0 and eps_p >= 0 give an elastic strain <= 0.
 * Needs every rod's 1/L finite and positive and eps_p >= 0 (no NaN). */
static int closed_from_virgin(const ct_bundle *b, const closed_args *a, size_t m, size_t k0,
                              size_t k1)
{
    double u0_max = -INFINITY;
    for (size_t i = 0; i < m; i++) {
        if (!(a->adv[i] == -INFINITY) || isnan(a->u0[i]))
            return 0;
        u0_max = a->u0[i] > u0_max ? a->u0[i] : u0_max;
    }
    int tame = 1;
    for (size_t k = k0; k < k1; k++) {
        const double rl = 1.0 / b->length[k];
        tame &=
            (rl > 0.0) & (rl < INFINITY) & (b->plastic_strain[k] >= 0.0) & (u0_max <= b->top[k]);
    }
    return tame;
}

CT_CLONES
static void closed_kernel(const ct_bundle *b, const void *args, size_t i0, size_t m, size_t k0,
                          size_t k1, double *restrict out)
{
    const closed_args *a = args;
    const double *restrict adv = a->adv + i0, *restrict u0 = a->u0 + i0, *restrict u1 = a->u1 + i0;
    const double *top = b->top, *length = b->length, *area = b->area, *eps_p = b->plastic_strain;
    const double E = b->E, eps_y = b->eps_y;
    const closed_args chunk = {adv, u0, u1};
    const int virgin = closed_from_virgin(b, &chunk, m, k0, k1);
    double s[3][CT_NODE_CHUNK], c[3][CT_NODE_CHUNK];
    for (size_t i = 0; i < m; i++)
        for (int o = 0; o < 3; o++)
            s[o][i] = c[o][i] = 0.0;
    for (size_t k = k0; k < k1; k++) {
        const double tk = top[k], pk = eps_p[k], rl = 1.0 / length[k];
        const double Es = E * area[k], EsL = E * area[k] * length[k],
                     half = 0.5 * E * area[k] * length[k];
        if (virgin) {
            for (size_t i = 0; i < m; i++) {
                double x[3];
                closed_terms(ct_rod_strain(u1[i], tk, rl, pk), 0.0, EsL, half, Es, eps_y, x);
                for (int o = 0; o < 3; o++)
                    ct_add_comp(&s[o][i], &c[o][i], x[o]);
            }
            continue;
        }
        for (size_t i = 0; i < m; i++) {
            const double p = ct_rod_advanced(ct_rod_total_strain(adv[i], tk, rl), pk, eps_y);
            const double da = ct_rod_strain(u0[i], tk, rl, p), db = ct_rod_strain(u1[i], tk, rl, p);
            double x[3];
            closed_terms(db, ct_rod_work_density(da, eps_y), EsL, half, Es, eps_y, x);
            for (int o = 0; o < 3; o++)
                ct_add_comp(&s[o][i], &c[o][i], x[o]);
        }
    }
    for (int o = 0; o < 3; o++)
        for (size_t i = 0; i < m; i++)
            out[(size_t)o * CT_NODE_CHUNK + i] = s[o][i] + c[o][i];
}

int ct_bundle_closed_many(const ct_bundle *b, const double *adv, const double *u0, const double *u1,
                          size_t m, double *W_load, double *W_unload, double *P,
                          const volatile int *interrupt)
{
    closed_args a = {adv, u0, u1};
    double *out = malloc(3 * (m ? m : 1) * sizeof(double));
    if (!out)
        return ct_error_set(CT_ENOMEM, "closed forms of %zu impacts: out of memory", m);
    int st = blocked_apply(b, closed_kernel, &a, m, 3, out, interrupt);
    memcpy(W_load, out, m * sizeof(double));
    memcpy(W_unload, out + m, m * sizeof(double));
    if (P)
        memcpy(P, out + 2 * m, m * sizeof(double));
    free(out);
    return st;
}

int ct_bundle_force_many(const ct_bundle *b, const double *u, size_t m, double *P)
{
    CT_NEED(b);
    if (m && !u)
        return ct_error_set(CT_EINVAL, "%s: u is NULL", __func__);
    if (m && !P)
        return ct_error_set(CT_EINVAL, "%s: P is NULL", __func__);
    return blocked_many(b, SUM_FORCE, 0.0, -INFINITY, u, m, P);
}

int ct_bundle_force_after(const ct_bundle *b, double u_adv, const double *u, size_t m, double *P)
{
    CT_NEED(b);
    if (m && !u)
        return ct_error_set(CT_EINVAL, "%s: u is NULL", __func__);
    if (m && !P)
        return ct_error_set(CT_EINVAL, "%s: P is NULL", __func__);
    return blocked_many(b, SUM_FORCE, 0.0, u_adv, u, m, P);
}

int ct_bundle_work_many(const ct_bundle *b, double u_a, const double *u_b, size_t m, double *W)
{
    CT_NEED(b);
    if (m && !u_b)
        return ct_error_set(CT_EINVAL, "%s: u_b is NULL", __func__);
    if (m && !W)
        return ct_error_set(CT_EINVAL, "%s: W is NULL", __func__);
    return blocked_many(b, SUM_WORK, u_a, -INFINITY, u_b, m, W);
}

double ct_bundle_force(const ct_bundle *b, double u)
{
    return blocked_total(b, SUM_FORCE, u, u, -INFINITY);
}

double ct_bundle_work(const ct_bundle *b, double u_a, double u_b)
{
    return blocked_total(b, SUM_WORK, u_a, u_b, -INFINITY);
}

double ct_bundle_elastic_energy(const ct_bundle *b, double u)
{
    return blocked_total(b, SUM_ELASTIC, u, u, -INFINITY);
}

void ct_bundle_advance(ct_bundle *b, double u)
{
    const double eps_y = b->eps_y;
    const int team = ct_bundle_team(b);
    (void)team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++)
        b->plastic_strain[k] =
            ct_rod_advance(u, b->top[k], b->length[k], b->plastic_strain[k], eps_y);
}

/* Minima are exact: any order, any thread count, the same value. */
double ct_bundle_release(const ct_bundle *b, double u_adv)
{
    double m = INFINITY;
    const double eps_y = b->eps_y;
    const int team = ct_bundle_team(b);
    (void)team;
#pragma omp parallel for schedule(static) reduction(min : m) num_threads(team) if (team > 1)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++) {
        double p = ct_rod_advance(u_adv, b->top[k], b->length[k], b->plastic_strain[k], eps_y);
        double c = ct_rod_contact(b->top[k], b->length[k], p);
        if (c < m)
            m = c;
    }
    return m;
}

double ct_bundle_first_contact(const ct_bundle *b)
{
    return ct_bundle_release(b, -INFINITY);
}

double ct_bundle_first_yield(const ct_bundle *b)
{
    double m = INFINITY;
    const double eps_y = b->eps_y;
    const int team = ct_bundle_team(b);
    (void)team;
#pragma omp parallel for schedule(static) reduction(min : m) num_threads(team) if (team > 1)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++) {
        double y = ct_rod_yield(b->top[k], b->length[k], b->plastic_strain[k], eps_y);
        if (y < m)
            m = y;
    }
    return m;
}
