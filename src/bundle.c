/* Rod bundles (MODEL.md §4): rods as arrays, force assembly, state advance, energies and
 * breakpoints. This is the only file with OpenMP pragmas.
 *
 * Determinism: every sum over rods is split into fixed blocks of CT_BLOCK rods, each block
 * summed in rod order, and the block sums combined pairwise in a fixed tree. Threads only
 * decide who computes which block, so results are bitwise identical for any thread count,
 * and the serial path (small bundles) uses the very same blocks. */
#define _DEFAULT_SOURCE /* madvise(MADV_HUGEPAGE) */
#include "internal.h"
#include "rod.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#define CT_BLOCK 2048

struct ct_bundle {
    ct_params params;
    ct_representation rep;
    long depth;       /* prefractal depth N */
    long first_stage; /* stages below this were left out (never touched) */
    size_t first_rod; /* global index of rod 0 (segments: 2^first_stage - 1) */
    size_t n;         /* rods held */
    size_t omitted;   /* rods left out */
    double E, eps_y;
    double *top, *length, *area, *plastic_strain;
    size_t nblocks;
    double *block_sums;  /* workspace of the blocked sums */
    double *many_sums;   /* workspace of the multi-node sums: nblocks x CT_NODE_CHUNK */
    size_t parallel_min; /* sums of fewer rods run on one thread */
};

void ct_bundle_set_parallel_min(ct_bundle *b, size_t rods)
{
    b->parallel_min = rods;
}

int ct_set_threads(int threads)
{
#ifdef _OPENMP
    if (threads > 0)
        omp_set_num_threads(threads);
    return omp_get_max_threads();
#else
    (void)threads;
    return 1;
#endif
}

static size_t available_memory(void)
{
    /* MemAvailable is what the kernel can give without swapping. */
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

/* Stage of segment rod with global index g: g = 2^i - 1 + j, 0 <= j < 2^i. */
static long segment_stage(size_t g)
{
    long i = 0;
    while (((size_t)1 << (i + 1)) - 1 <= g)
        i++;
    return i;
}

void ct_bundle_free(ct_bundle *b)
{
    if (!b)
        return;
    free(b->top);
    free(b->length);
    free(b->area);
    free(b->plastic_strain);
    free(b->block_sums);
    free(b->many_sums);
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

static int bundle_arrays(ct_bundle *b)
{
    size_t n = b->n ? b->n : 1;
    b->nblocks = (b->n + CT_BLOCK - 1) / CT_BLOCK;
    b->top = rod_array(n);
    b->length = rod_array(n);
    b->area = rod_array(n);
    b->plastic_strain = rod_array(n);
    b->block_sums = malloc((b->nblocks ? b->nblocks : 1) * sizeof(double));
    if (!b->top || !b->length || !b->area || !b->plastic_strain || !b->block_sums)
        return ct_error_set(CT_ENOMEM, "bundle of %zu rods: out of memory", b->n);
    return CT_OK;
}

int ct_bundle_alloc(ct_bundle **out, const ct_params *p, ct_representation rep, long depth,
                    double u_reach)
{
    int st;
    *out = NULL;
    if ((st = ct_params_validate(p)))
        return st;
    if (rep != CT_REP_STAGES && rep != CT_REP_SEGMENTS)
        return ct_error_set(CT_EINVAL, "representation %d: must be stages or segments", rep);
    long max_depth = rep == CT_REP_STAGES ? CT_MAX_STAGES_DEPTH : CT_MAX_SEGMENTS_DEPTH;
    if (depth < 0 || depth > max_depth)
        return ct_error_set(CT_EINVAL, "depth = %ld: must satisfy 0 <= depth <= %ld for %s", depth,
                            max_depth, rep == CT_REP_STAGES ? "stages" : "segments");
    if (isnan(u_reach))
        return ct_error_set(CT_EINVAL, "u_reach is NaN");

    /* Stages whose top lies deeper than u_reach can never be touched. Tops decrease with
     * the stage index, so these are the first stages. */
    long first = 0;
    while (first < depth + 1 && ct_stage_depth(p, (double)first) > u_reach)
        first++;

    size_t total, first_rod;
    if (rep == CT_REP_STAGES) {
        total = (size_t)depth + 1;
        first_rod = (size_t)first;
    } else {
        total = ((size_t)1 << (depth + 1)) - 1;
        first_rod = ((size_t)1 << first) - 1;
    }
    size_t n = total - first_rod;
    size_t need = n * CT_BYTES_PER_ROD + (n / CT_BLOCK + 1) * sizeof(double);
    size_t avail = available_memory();
    if (need > avail / 10 * 9) /* depth <= 40 keeps need far from overflow */
        return ct_error_set(CT_ENOMEM,
                            "depth %ld %s: %zu rods need %.3g GiB, more than the %.3g GiB "
                            "of memory available",
                            depth, rep == CT_REP_STAGES ? "stages" : "segments", n,
                            (double)need / 1073741824.0, (double)avail / 1073741824.0);

    ct_bundle *b = calloc(1, sizeof *b);
    if (!b)
        return ct_error_set(CT_ENOMEM, "bundle: out of memory");
    b->params = *p;
    b->rep = rep;
    b->depth = depth;
    b->first_stage = first;
    b->first_rod = first_rod;
    b->n = n;
    b->omitted = first_rod;
    b->E = p->E;
    b->eps_y = p->sigma_y / p->E;
    b->parallel_min = CT_PARALLEL_MIN_RODS;
    if ((st = bundle_arrays(b))) {
        ct_bundle_free(b);
        return st;
    }

    if (rep == CT_REP_STAGES) {
        for (long i = first; i <= depth; i++) {
            size_t k = (size_t)(i - first);
            double top = ct_stage_depth(p, (double)i);
            b->top[k] = top;
            b->length[k] = p->Hstar - top;
            b->area[k] = i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i);
            b->plastic_strain[k] = 0.0;
        }
    } else {
        for (long i = first; i <= depth; i++) {
            size_t pieces = (size_t)1 << i;
            size_t k0 = pieces - 1 - first_rod;
            double top = ct_stage_depth(p, (double)i);
            double length = p->Hstar - top;
            /* middles carry s_i / 2^i, the tips l_N / 2^N */
            double area =
                (i < depth ? ct_stage_area(p, (double)i) : ct_stage_length(p, (double)i)) *
                ldexp(1.0, (int)-i);
            /* first touch in parallel, so pages land where the threads will read them */
#pragma omp parallel for schedule(static) if (pieces >= CT_PARALLEL_MIN_RODS)
            for (ptrdiff_t j = 0; j < (ptrdiff_t)pieces; j++) {
                b->top[k0 + (size_t)j] = top;
                b->length[k0 + (size_t)j] = length;
                b->area[k0 + (size_t)j] = area;
                b->plastic_strain[k0 + (size_t)j] = 0.0;
            }
        }
    }
    *out = b;
    return CT_OK;
}

int ct_bundle_clone(ct_bundle **out, const ct_bundle *src)
{
    int st;
    *out = NULL;
    ct_bundle *b = calloc(1, sizeof *b);
    if (!b)
        return ct_error_set(CT_ENOMEM, "bundle: out of memory");
    *b = *src;
    b->top = b->length = b->area = b->plastic_strain = b->block_sums = b->many_sums = NULL;
    if ((st = bundle_arrays(b))) {
        ct_bundle_free(b);
        return st;
    }
    memcpy(b->top, src->top, src->n * sizeof(double));
    memcpy(b->length, src->length, src->n * sizeof(double));
    memcpy(b->area, src->area, src->n * sizeof(double));
    memcpy(b->plastic_strain, src->plastic_strain, src->n * sizeof(double));
    *out = b;
    return CT_OK;
}

void ct_bundle_reset(ct_bundle *b)
{
#pragma omp parallel for schedule(static) if (b->n >= b->parallel_min)
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

long ct_bundle_depth(const ct_bundle *b)
{
    return b->depth;
}

ct_representation ct_bundle_representation(const ct_bundle *b)
{
    return b->rep;
}

const ct_params *ct_bundle_params(const ct_bundle *b)
{
    return &b->params;
}

int ct_bundle_rod(const ct_bundle *b, size_t k, ct_rod_info *info)
{
    if (k >= b->n)
        return ct_error_set(CT_EINVAL, "rod %zu: bundle holds %zu rods", k, b->n);
    info->top = b->top[k];
    info->length = b->length[k];
    info->area = b->area[k];
    info->plastic_strain = b->plastic_strain[k];
    if (b->rep == CT_REP_STAGES) {
        info->stage = (long)(k + b->first_rod);
        info->x_left = info->x_right = NAN; /* merged pieces have no single position */
        return CT_OK;
    }
    size_t g = k + b->first_rod;
    long i = segment_stage(g);
    info->stage = i;
    return ct_piece_extent(&b->params, b->depth, i, g - (((size_t)1 << i) - 1), &info->x_left,
                           &info->x_right);
}

enum sum_kind { SUM_FORCE, SUM_WORK, SUM_ELASTIC };

/* Neumaier-compensated sum of one block: 2^i identical pieces of a stage then add up to
 * what the merged stage rod gives, to a few ulps. */
#define CT_ADD(term)                                                                               \
    do {                                                                                           \
        double x_ = (term), t_ = s + x_;                                                           \
        c += fabs(s) >= fabs(x_) ? (s - t_) + x_ : (x_ - t_) + s;                                  \
        s = t_;                                                                                    \
    } while (0)

static double block_sum(const ct_bundle *b, enum sum_kind kind, double ua, double ub, size_t k0,
                        size_t k1)
{
    const double *top = b->top, *length = b->length, *area = b->area, *eps_p = b->plastic_strain;
    const double E = b->E, eps_y = b->eps_y;
    double s = 0.0, c = 0.0;
    switch (kind) {
    case SUM_FORCE:
        for (size_t k = k0; k < k1; k++)
            CT_ADD(ct_rod_force(ua, top[k], length[k], area[k], eps_p[k], E, eps_y));
        break;
    case SUM_WORK:
        for (size_t k = k0; k < k1; k++)
            CT_ADD(ct_rod_work(ua, ub, top[k], length[k], area[k], eps_p[k], E, eps_y));
        break;
    case SUM_ELASTIC:
        for (size_t k = k0; k < k1; k++)
            CT_ADD(ct_rod_elastic_energy(ua, top[k], length[k], area[k], eps_p[k], E, eps_y));
        break;
    }
    return s + c;
}

static double blocked_total(ct_bundle *b, enum sum_kind kind, double ua, double ub)
{
    const ptrdiff_t nb = (ptrdiff_t)b->nblocks;
    double *ws = b->block_sums;
    if (nb == 0)
        return 0.0;
#pragma omp parallel for schedule(static) if (b->n >= b->parallel_min)
    for (ptrdiff_t j = 0; j < nb; j++) {
        size_t k0 = (size_t)j * CT_BLOCK;
        size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
        ws[j] = block_sum(b, kind, ua, ub, k0, k1);
    }
    /* fixed pairwise tree */
    for (ptrdiff_t stride = 1; stride < nb; stride *= 2)
        for (ptrdiff_t i = 0; i + stride < nb; i += 2 * stride)
            ws[i] += ws[i + stride];
    return ws[0];
}

/* Multi-node sums: one pass over the rods serves up to CT_NODE_CHUNK nodes. Each block
 * keeps one Neumaier sum per node, adding the rods in the same order as block_sum, and the
 * block sums meet in the same pairwise tree, so every value is bitwise what the single-node
 * call gives. The node loop is innermost and branch-free, so it vectorises; on x86-64 an
 * AVX2 clone is picked at load time when the CPU has it (no FMA: contraction is off under
 * -std=c11, and a fused multiply-add would change the rounding). */
#define CT_NODE_CHUNK 64

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                             \
    !defined(__SANITIZE_ADDRESS__)
#define CT_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CT_CLONES
#endif

CT_CLONES
static void block_sum_many(const ct_bundle *b, enum sum_kind kind, double ua,
                           const double *restrict ub, size_t m, size_t k0, size_t k1,
                           double *restrict out)
{
    const double *top = b->top, *length = b->length, *area = b->area, *eps_p = b->plastic_strain;
    const double E = b->E, eps_y = b->eps_y;
    double s[CT_NODE_CHUNK], c[CT_NODE_CHUNK];
    for (size_t i = 0; i < m; i++)
        s[i] = c[i] = 0.0;
    for (size_t k = k0; k < k1; k++) {
        const double tk = top[k], lk = length[k], ak = area[k], pk = eps_p[k], rl = 1.0 / lk;
        const double Ea = E * ak, EaL = E * ak * lk;
        const double wa = ct_rod_work_density(ct_rod_elastic_strain(ua, tk, lk, pk), eps_y);
        if (kind == SUM_FORCE) {
            for (size_t i = 0; i < m; i++) {
                double d = (ub[i] - tk) * rl - pk;
                d = d > 0.0 ? d : 0.0;
                d = d > eps_y ? eps_y : d;
                double x = Ea * d, t = s[i] + x;
                double big_s = (s[i] - t) + x, big_x = (x - t) + s[i]; /* both: a select */
                c[i] += fabs(s[i]) >= fabs(x) ? big_s : big_x;
                s[i] = t;
            }
        } else {
            for (size_t i = 0; i < m; i++) {
                double d = (ub[i] - tk) * rl - pk;
                double plateau = eps_y * (d - 0.5 * eps_y), elastic = 0.5 * d * d;
                double w = d > eps_y ? plateau : elastic;
                w = d > 0.0 ? w : 0.0;
                double x = EaL * (w - wa), t = s[i] + x;
                double big_s = (s[i] - t) + x, big_x = (x - t) + s[i];
                c[i] += fabs(s[i]) >= fabs(x) ? big_s : big_x;
                s[i] = t;
            }
        }
    }
    for (size_t i = 0; i < m; i++)
        out[i] = s[i] + c[i];
}

static int blocked_many(ct_bundle *b, enum sum_kind kind, double ua, const double *ub, size_t m,
                        double *out)
{
    const ptrdiff_t nb = (ptrdiff_t)b->nblocks;
    if (nb == 0) {
        for (size_t i = 0; i < m; i++)
            out[i] = 0.0;
        return CT_OK;
    }
    if (!b->many_sums && !(b->many_sums = malloc((size_t)nb * CT_NODE_CHUNK * sizeof(double))))
        return ct_error_set(CT_ENOMEM, "multi-node sum over %zu rods: out of memory", b->n);
    double *ws = b->many_sums;
    for (size_t i0 = 0; i0 < m; i0 += CT_NODE_CHUNK) {
        const size_t mc = m - i0 < CT_NODE_CHUNK ? m - i0 : CT_NODE_CHUNK;
#pragma omp parallel for schedule(static) if (b->n >= b->parallel_min)
        for (ptrdiff_t j = 0; j < nb; j++) {
            size_t k0 = (size_t)j * CT_BLOCK;
            size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
            block_sum_many(b, kind, ua, ub + i0, mc, k0, k1, ws + (size_t)j * CT_NODE_CHUNK);
        }
        for (ptrdiff_t stride = 1; stride < nb; stride *= 2)
            for (ptrdiff_t j = 0; j + stride < nb; j += 2 * stride)
                for (size_t i = 0; i < mc; i++)
                    ws[(size_t)j * CT_NODE_CHUNK + i] +=
                        ws[(size_t)(j + stride) * CT_NODE_CHUNK + i];
        for (size_t i = 0; i < mc; i++)
            out[i0 + i] = ws[i];
    }
    return CT_OK;
}

int ct_bundle_force_many(ct_bundle *b, const double *u, size_t m, double *P)
{
    return blocked_many(b, SUM_FORCE, 0.0, u, m, P);
}

int ct_bundle_work_many(ct_bundle *b, double u_a, const double *u_b, size_t m, double *W)
{
    return blocked_many(b, SUM_WORK, u_a, u_b, m, W);
}

double ct_bundle_force(ct_bundle *b, double u)
{
    return blocked_total(b, SUM_FORCE, u, u);
}

double ct_bundle_work(ct_bundle *b, double u_a, double u_b)
{
    return blocked_total(b, SUM_WORK, u_a, u_b);
}

double ct_bundle_elastic_energy(ct_bundle *b, double u)
{
    return blocked_total(b, SUM_ELASTIC, u, u);
}

void ct_bundle_advance(ct_bundle *b, double u)
{
    const double eps_y = b->eps_y;
#pragma omp parallel for schedule(static) if (b->n >= b->parallel_min)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++)
        b->plastic_strain[k] =
            ct_rod_advance(u, b->top[k], b->length[k], b->plastic_strain[k], eps_y);
}

double ct_bundle_first_contact(const ct_bundle *b)
{
    double m = INFINITY;
#pragma omp parallel for schedule(static) reduction(min : m) if (b->n >= b->parallel_min)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++) {
        double c = ct_rod_contact(b->top[k], b->length[k], b->plastic_strain[k]);
        if (c < m)
            m = c;
    }
    return m;
}

double ct_bundle_first_yield(const ct_bundle *b)
{
    double m = INFINITY;
    const double eps_y = b->eps_y;
#pragma omp parallel for schedule(static) reduction(min : m) if (b->n >= b->parallel_min)
    for (ptrdiff_t k = 0; k < (ptrdiff_t)b->n; k++) {
        double y = ct_rod_yield(b->top[k], b->length[k], b->plastic_strain[k], eps_y);
        if (y < m)
            m = y;
    }
    return m;
}

typedef struct {
    double *v;
    size_t n, cap;
    int oom;
} point_list;

static void point_push(point_list *l, double x)
{
    if (l->oom)
        return;
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        double *grown = realloc(l->v, cap * sizeof(double));
        if (!grown) {
            l->oom = 1;
            return;
        }
        l->v = grown;
        l->cap = cap;
    }
    l->v[l->n++] = x;
}

int ct_bundle_breakpoints(const ct_bundle *b, double lo, double hi, double **points, size_t *count)
{
    *points = NULL;
    *count = 0;
    if (!(lo <= hi))
        return ct_error_set(CT_EINVAL, "breakpoints: interval [%g, %g] is empty", lo, hi);
    int nt = 1;
#ifdef _OPENMP
    if (b->n >= b->parallel_min)
        nt = omp_get_max_threads();
#endif
    /* per thread: contacts, then yields; each list is one monotone run on a virgin stage
     * bundle, which is what lets the sort below merge instead of sorting */
    point_list *lists = calloc(2 * (size_t)nt, sizeof *lists);
    if (!lists)
        return ct_error_set(CT_ENOMEM, "breakpoints: out of memory");
    const ptrdiff_t nb = (ptrdiff_t)b->nblocks;
    /* Each thread gathers its blocks' points; the sort below makes the order irrelevant. */
#pragma omp parallel num_threads(nt) if (nt > 1)
    {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
#endif
        point_list *lc = &lists[2 * t], *ly = &lists[2 * t + 1];
#pragma omp for schedule(static)
        for (ptrdiff_t j = 0; j < nb; j++) {
            size_t k0 = (size_t)j * CT_BLOCK;
            size_t k1 = k0 + CT_BLOCK < b->n ? k0 + CT_BLOCK : b->n;
            /* Rods of one stage share their state through any common history; skipping a
             * value equal to the previous one of its kind keeps segment lists short. */
            double last_c = NAN, last_y = NAN;
            for (size_t k = k0; k < k1; k++) {
                double c = ct_rod_contact(b->top[k], b->length[k], b->plastic_strain[k]);
                double y = ct_rod_yield(b->top[k], b->length[k], b->plastic_strain[k], b->eps_y);
                if (c != last_c && c > lo && c < hi)
                    point_push(lc, c);
                if (y != last_y && y > lo && y < hi)
                    point_push(ly, y);
                last_c = c;
                last_y = y;
            }
        }
    }
    size_t n = 2;
    int oom = 0;
    for (int t = 0; t < 2 * nt; t++) {
        n += lists[t].n;
        oom |= lists[t].oom;
    }
    double *pts = oom ? NULL : malloc(n * sizeof(double));
    if (pts) {
        pts[0] = lo;
        pts[1] = hi;
        n = 2;
        for (int t = 0; t < 2 * nt; t++) {
            if (lists[t].n)
                memcpy(pts + n, lists[t].v, lists[t].n * sizeof(double));
            n += lists[t].n;
        }
    }
    for (int t = 0; t < 2 * nt; t++)
        free(lists[t].v);
    free(lists);
    if (!pts)
        return ct_error_set(CT_ENOMEM, "breakpoints: out of memory");
    *points = pts;
    *count = ct_sort_unique(pts, n);
    return CT_OK;
}
