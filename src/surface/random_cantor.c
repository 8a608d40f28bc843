/* Random Cantor surfaces (docs/model.md §10): every split draws its own width and depth ratios
 * around f_x and f_z, so the pieces of one stage sit at different depths and every piece is
 * its own rod. A realisation is a pure function of (seed, realisation index): the ratios of
 * piece g are one Philox4x64-10 block (Random123, counter-based) with key (seed, realisation)
 * and counter (g, 0, 0, 0). No stream is ever advanced, so nothing depends on which thread or
 * process builds which piece, or in which order.
 *
 * Layout: the segments layout of the deterministic surface (src/surface/cantor.c): piece j of
 * stage i is rod g = 2^i - 1 + j, and its children (pieces 2j and 2j + 1 of stage i + 1) are
 * rods 2g + 1 (left) and 2g + 2 (right). A stage-i piece of width w and depth h keeps its
 * children at its two ends, child k of width w / (2 f_x,k) at depth h / f_z,k; its middle, of
 * width w - w/(2 f_x,1) - w/(2 f_x,2), stays at h. The 2^N tips of stage N carry their whole
 * width (the prefractal of depth N, docs/model.md §2).
 *
 * Spread 0 gives the deterministic surface's rods in the same order, each top and area equal
 * to a few ulps per stage (not bitwise: cantor.c computes h0 f^-i in one exp/log so that deep
 * stages do not drift, a random piece's depth is the product of its own i ratios). */
#include "kind.h"

#include <Random123/philox.h>
#include <stddef.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the ratios ---- */

/* (0, 1) from the top 53 bits: never 0, so log() below is finite. */
static double unit_open(uint64_t r)
{
    return ((double)(r >> 11) + 0.5) * 0x1p-53;
}

/* The nearest doubles inside the open valid ranges (docs/model.md §1): f_x > 1, 1 < f_z < 2. */
#define RATIO_LOW (1.0 + DBL_EPSILON)
#define FZ_HIGH (2.0 - DBL_EPSILON)

/* The generator's key for a realisation. */
static philox4x64_key_t key_of(const ct_random_cantor *rc, uint64_t realisation)
{
    const philox4x64_key_t key = {{rc->seed, realisation}};
    return key;
}

/* The two words of piece g's block that the ratios use (the other two are not needed). */
static void words_of(philox4x64_key_t key, uint64_t g, uint64_t *w0, uint64_t *w1)
{
    const philox4x64_ctr_t ctr = {{g, 0, 0, 0}};
    const philox4x64_ctr_t r = philox4x64(ctr, key);
    *w0 = r.v[0];
    *w1 = r.v[1];
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#include <immintrin.h>
#define CT_PHILOX_X8 1

/* The high word of a x m (64 x 64 bits) in every lane, from 32-bit products: m's halves
 * broadcast in m_lo and m_hi. */
__attribute__((target("avx512f,avx512dq"))) static inline __m512i mulhi_x8(__m512i a, __m512i m_lo,
                                                                           __m512i m_hi)
{
    const __m512i low32 = _mm512_set1_epi64(0xffffffffLL), a_hi = _mm512_srli_epi64(a, 32);
    const __m512i p00 = _mm512_mul_epu32(a, m_lo), p01 = _mm512_mul_epu32(a, m_hi),
                  p10 = _mm512_mul_epu32(a_hi, m_lo), p11 = _mm512_mul_epu32(a_hi, m_hi);
    const __m512i mid =
        _mm512_add_epi64(_mm512_add_epi64(_mm512_srli_epi64(p00, 32), _mm512_and_si512(p01, low32)),
                         _mm512_and_si512(p10, low32));
    return _mm512_add_epi64(
        _mm512_add_epi64(p11, _mm512_srli_epi64(p01, 32)),
        _mm512_add_epi64(_mm512_srli_epi64(p10, 32), _mm512_srli_epi64(mid, 32)));
}

/* words_of for pieces g0 .. g0 + 8 n - 1, eight at a time: Random123's Philox4x64-10 round
 * for round (the same integer operations, so the same words). */
__attribute__((target("avx512f,avx512dq"))) static void
words_x8(philox4x64_key_t key, uint64_t g0, size_t n, uint64_t *w0, uint64_t *w1)
{
    const __m512i m0 = _mm512_set1_epi64((long long)PHILOX_M4x64_0),
                  m1 = _mm512_set1_epi64((long long)PHILOX_M4x64_1),
                  m0_lo = _mm512_set1_epi64((long long)(PHILOX_M4x64_0 & 0xffffffffu)),
                  m0_hi = _mm512_set1_epi64((long long)(PHILOX_M4x64_0 >> 32)),
                  m1_lo = _mm512_set1_epi64((long long)(PHILOX_M4x64_1 & 0xffffffffu)),
                  m1_hi = _mm512_set1_epi64((long long)(PHILOX_M4x64_1 >> 32)),
                  lane = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0), zero = _mm512_setzero_si512();
    for (size_t b = 0; b < n; b++) {
        __m512i v0 = _mm512_add_epi64(_mm512_set1_epi64((long long)(g0 + 8 * b)), lane), v1 = zero,
                v2 = zero, v3 = zero;
        uint64_t k0 = key.v[0], k1 = key.v[1];
        for (int round = 0; round < 10; round++) {
            if (round) { /* bumpkey */
                k0 += PHILOX_W64_0;
                k1 += PHILOX_W64_1;
            }
            const __m512i lo0 = _mm512_mullo_epi64(v0, m0), hi0 = mulhi_x8(v0, m0_lo, m0_hi);
            const __m512i lo1 = _mm512_mullo_epi64(v2, m1), hi1 = mulhi_x8(v2, m1_lo, m1_hi);
            v0 = _mm512_xor_si512(_mm512_xor_si512(hi1, v1), _mm512_set1_epi64((long long)k0));
            v1 = lo1;
            v2 = _mm512_xor_si512(_mm512_xor_si512(hi0, v3), _mm512_set1_epi64((long long)k1));
            v3 = lo0;
        }
        _mm512_storeu_si512(w0 + 8 * b, v0);
        _mm512_storeu_si512(w1 + 8 * b, v1);
    }
}
#endif

/* words_of for pieces g0 .. g0 + n - 1, eight lanes at a time where the CPU has AVX-512. */
static void words_many(philox4x64_key_t key, uint64_t g0, size_t n, uint64_t *w0, uint64_t *w1)
{
    size_t done = 0;
#ifdef CT_PHILOX_X8
    if (n >= 8 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")) {
        words_x8(key, g0, n / 8, w0, w1);
        done = n / 8 * 8;
    }
#endif
    for (size_t i = done; i < n; i++)
        words_of(key, g0 + i, &w0[i], &w1[i]);
}

/* The ratios of a piece from its two words; returns which were clipped (1: fx, 2: fz). */
static int ratios_of(const ct_random_cantor *rc, uint64_t w0, uint64_t w1, double *fx_k,
                     double *fz_k)
{
    const double u0 = unit_open(w0), u1 = unit_open(w1);
    double x, z;
    if (rc->dist == CT_RATIO_UNIFORM) {
        /* spread 0: 1 + 0 (2u - 1) is exactly 1, so the centre itself */
        x = rc->params.fx * (1.0 + rc->fx_spread * (2.0 * u0 - 1.0));
        z = rc->params.fz * (1.0 + rc->fz_spread * (2.0 * u1 - 1.0));
    } else {
        /* Box-Muller: the pair (rad cos, rad sin) is two independent standard normals;
         * spread 0: exp(0) is exactly 1 */
        const double rad = sqrt(-2.0 * log(u0)), ang = 6.283185307179586 * u1;
        x = rc->params.fx * exp(rc->fx_spread * (rad * cos(ang)));
        z = rc->params.fz * exp(rc->fz_spread * (rad * sin(ang)));
    }
    int clipped = 0;
    if (!(x >= RATIO_LOW)) {
        x = RATIO_LOW;
        clipped |= 1;
    } else if (!(x <= DBL_MAX)) { /* f_x 1.7e308 (1 + 0.5 ...) or 1e300 exp(10 Z): inf */
        x = DBL_MAX;
        clipped |= 1;
    }
    if (!(z >= RATIO_LOW)) {
        z = RATIO_LOW;
        clipped |= 2;
    } else if (!(z <= FZ_HIGH)) {
        z = FZ_HIGH;
        clipped |= 2;
    }
    *fx_k = x;
    *fz_k = z;
    return clipped;
}

static int draw(const ct_random_cantor *rc, uint64_t realisation, uint64_t g, double *fx_k,
                double *fz_k)
{
    uint64_t w0, w1;
    words_of(key_of(rc, realisation), g, &w0, &w1);
    return ratios_of(rc, w0, w1, fx_k, fz_k);
}

int ct_random_cantor_validate(const ct_random_cantor *rc)
{
    int st;
    if (!rc)
        return ct_error_set(CT_EINVAL, "random cantor surface: NULL");
    if ((st = ct_params_validate(&rc->params)))
        return st;
    if (rc->dist != CT_RATIO_UNIFORM && rc->dist != CT_RATIO_LOGNORMAL)
        return ct_error_set(CT_EINVAL, "ratio distribution %d: must be uniform or lognormal",
                            (int)rc->dist);
    /* uniform: f (1 - spread) must stay positive; log-normal: exp(spread z) stays finite for
     * every z the generator can give (|z| < 8.6) */
    const double max_spread = rc->dist == CT_RATIO_UNIFORM ? 1.0 : 10.0;
    const char *range = rc->dist == CT_RATIO_UNIFORM ? "0 <= spread < 1 (uniform)"
                                                     : "0 <= spread <= 10 (lognormal)";
    const double sp[2] = {rc->fx_spread, rc->fz_spread};
    for (int k = 0; k < 2; k++)
        if (!isfinite(sp[k]) || !(sp[k] >= 0.0) ||
            (rc->dist == CT_RATIO_UNIFORM ? !(sp[k] < max_spread) : !(sp[k] <= max_spread)))
            return ct_error_set(CT_EINVAL, "%s_spread = %g: must satisfy %s", k ? "fz" : "fx",
                                sp[k], range);
    if (rc->depth < 0 || rc->depth > CT_MAX_RANDOM_DEPTH)
        return ct_error_set(CT_EINVAL, "depth = %ld: must satisfy 0 <= depth <= %d", rc->depth,
                            CT_MAX_RANDOM_DEPTH);
    return CT_OK;
}

int ct_random_cantor_ratios(const ct_random_cantor *rc, uint64_t realisation, uint64_t g,
                            double *fx_k, double *fz_k, int *clipped)
{
    int st;
    if ((st = ct_random_cantor_validate(rc)))
        return st;
    if (g == 0 || g >= ((uint64_t)2 << rc->depth) - 1)
        return ct_error_set(CT_EINVAL, "piece %llu: must satisfy 1 <= g < 2^(depth + 1) - 1 = %llu",
                            (unsigned long long)g,
                            (unsigned long long)(((uint64_t)2 << rc->depth) - 1));
    int c = draw(rc, realisation, g, fx_k, fz_k);
    if (clipped)
        *clipped = c;
    return CT_OK;
}

/* ---- metadata: stage and x-extent, derived again from the draws ---- */

typedef struct {
    ct_random_cantor rc;
    uint64_t realisation;
    uint64_t fx_clipped, fz_clipped;
    size_t n;
    uint32_t *piece; /* rod k is piece piece[k] (heap index g) */
    uint64_t *key;   /* the sort's scratch, kept by bundles that are refilled (NULL: none) */
    uint32_t *tmp;
} random_meta;

/* Stage of rod g = 2^i - 1 + j. */
static long rod_stage(uint64_t g)
{
    long i = 0;
    while ((((uint64_t)1 << (i + 1)) - 1) <= g)
        i++;
    return i;
}

/* The child of a piece of width w at left: its width and left end, by the very operations
 * of the builder (so a rod's extent matches its area bit for bit). */
static void child_extent(double w, double left, double fx_k, int right, double *w_child,
                         double *left_child)
{
    *w_child = w / (2.0 * fx_k);
    *left_child = right ? left + (w - *w_child) : left;
}

static void random_rod_info(const void *meta, size_t rod, ct_rod_info *info)
{
    const random_meta *m = meta;
    const uint64_t k = m->piece[rod];
    const long stage = rod_stage(k);
    /* walk from the root down the path to rod k, redrawing each split */
    double w = m->rc.params.l0, left = 0.0, fx_k, fz_k;
    uint64_t g = 0;
    for (long s = stage - 1; s >= 0; s--) {
        int right = (int)(((k + 1) >> s) & 1u);
        g = 2 * g + 1 + (uint64_t)right;
        draw(&m->rc, m->realisation, g, &fx_k, &fz_k);
        child_extent(w, left, fx_k, right, &w, &left);
    }
    info->stage = stage;
    if (stage < m->rc.depth) { /* the middle, between its two children */
        double fl, fr, wl, wr, ll, lr;
        draw(&m->rc, m->realisation, 2 * k + 1, &fl, &fz_k);
        draw(&m->rc, m->realisation, 2 * k + 2, &fr, &fz_k);
        child_extent(w, left, fl, 0, &wl, &ll);
        child_extent(w, left, fr, 1, &wr, &lr);
        info->x_left = ll + wl;
        info->x_right = lr;
    } else {
        info->x_left = left;
        info->x_right = left + w;
    }
}

static void random_free(void *meta)
{
    random_meta *m = meta;
    if (m) {
        free(m->piece);
        free(m->key);
        free(m->tmp);
    }
    free(m);
}

static void *random_clone(const void *meta)
{
    const random_meta *src = meta;
    random_meta *m = malloc(sizeof *m);
    uint32_t *piece = malloc((src->n ? src->n : 1) * sizeof *piece);
    if (!m || !piece) {
        free(m);
        free(piece);
        return NULL;
    }
    *m = *src;
    memcpy(piece, src->piece, src->n * sizeof *piece);
    m->piece = piece;
    m->key = NULL;
    m->tmp = NULL;
    return m;
}

static const ct_rod_meta_kind random_kind = {
    "random_cantor", random_rod_info, random_clone, random_free, NULL, NULL};

int ct_random_cantor_piece(const ct_bundle *b, size_t k, uint64_t *g)
{
    const random_meta *m = b ? ct_bundle_surface_meta(b, &random_kind) : NULL;
    if (!m)
        return ct_error_set(CT_EINVAL, "bundle: not made by ct_random_cantor_bundle");
    if (k >= m->n)
        return ct_error_set(CT_EINVAL, "rod %zu: bundle holds %zu rods", k, m->n);
    *g = m->piece[k];
    return CT_OK;
}

int ct_random_cantor_clipped(const ct_bundle *b, uint64_t *fx_clipped, uint64_t *fz_clipped,
                             uint64_t *draws)
{
    const random_meta *m = b ? ct_bundle_surface_meta(b, &random_kind) : NULL;
    if (!m)
        return ct_error_set(CT_EINVAL, "bundle: not made by ct_random_cantor_bundle");
    *fx_clipped = m->fx_clipped;
    *fz_clipped = m->fz_clipped;
    *draws = ((uint64_t)2 << m->rc.depth) - 2;
    return CT_OK;
}

/* ---- the builder ---- */

#define SPLIT_CHUNK 4096 /* pieces per chunk of one stage's splits */

typedef struct {
    const ct_random_cantor *rc;
    uint64_t realisation;
    size_t stage_first; /* rod of piece 0 of the stage being split */
    double *top, *area; /* area holds a piece's width until the piece is split */
    uint64_t *clipped;  /* per chunk: fx clipped in [3c], fz clipped in [3c + 1], widths
                           below the smallest normal double in [3c + 2] */
} split_ctx;

#define SPLIT_BATCH 256 /* pieces whose children's words are drawn together */

/* Splits pieces [i0, i1) of a stage: the children's widths and depths, then the middle's
 * area. Everything written for piece g depends on g alone. The children of consecutive
 * pieces are consecutive pieces, so their words are drawn a batch at a time. */
static void split_chunk(void *ctx, size_t c, size_t i0, size_t i1)
{
    split_ctx *s = ctx;
    uint64_t nx = 0, nz = 0, nw = 0;
    const philox4x64_key_t key = key_of(s->rc, s->realisation);
    uint64_t w0[2 * SPLIT_BATCH], w1[2 * SPLIT_BATCH];
    for (size_t b0 = i0; b0 < i1; b0 += SPLIT_BATCH) {
        const size_t b1 = b0 + SPLIT_BATCH < i1 ? b0 + SPLIT_BATCH : i1;
        words_many(key, 2 * (s->stage_first + b0) + 1, 2 * (b1 - b0), w0, w1);
        for (size_t j = b0; j < b1; j++) {
            const size_t g = s->stage_first + j, gl = 2 * g + 1, gr = 2 * g + 2, q = 2 * (j - b0);
            const double w = s->area[g], h = s->top[g];
            double fl, zl, fr, zr, wl, wr, ll, lr;
            int cl = ratios_of(s->rc, w0[q], w1[q], &fl, &zl);
            int cr = ratios_of(s->rc, w0[q + 1], w1[q + 1], &fr, &zr);
            nx += (uint64_t)(cl & 1) + (uint64_t)(cr & 1);
            nz += (uint64_t)(cl >> 1) + (uint64_t)(cr >> 1);
            child_extent(w, 0.0, fl, 0, &wl, &ll);
            child_extent(w, 0.0, fr, 1, &wr, &lr);
            s->area[gl] = wl;
            s->area[gr] = wr;
            s->top[gl] = h / zl;
            s->top[gr] = h / zr;
            /* the middle: w (1 - 1/(2 f_l) - 1/(2 f_r)) as w ((f_l - 1)/f_l + (f_r - 1)/f_r) / 2,
             * which does not cancel as the ratios approach 1 (f - 1 is exact for f in [1, 2]) */
            s->area[g] = w * (0.5 * ((fl - 1.0) / fl + (fr - 1.0) / fr));
            nw += !(wl >= DBL_MIN) + !(wr >= DBL_MIN) + !(s->area[g] >= DBL_MIN);
        }
    }
    s->clipped[3 * c] = nx;
    s->clipped[3 * c + 1] = nz;
    s->clipped[3 * c + 2] = nw;
}

typedef struct {
    double *top, *area;
    double *tree_top, *tree_area; /* become length and plastic strain */
    const uint32_t *piece;
    double Hstar;
} finish_ctx;

/* areas in sorted order from the pieces in tree order (the tops come sorted) */
static void gather_chunk(void *ctx, size_t c, size_t i0, size_t i1)
{
    finish_ctx *f = ctx;
    (void)c;
    for (size_t k = i0; k < i1; k++)
        f->area[k] = f->tree_area[f->piece[k]];
}

static void finish_chunk(void *ctx, size_t c, size_t i0, size_t i1)
{
    finish_ctx *f = ctx;
    (void)c;
    for (size_t k = i0; k < i1; k++) {
        f->tree_top[k] = f->Hstar - f->top[k]; /* the length */
        f->tree_area[k] = 0.0;                 /* virgin */
    }
}

/* Rods sorted by top, shallowest first (ties in piece order): the load curve's events are
 * then two monotone runs, merged in O(n) (src/curve.c), where pieces in tree order would
 * cost a full merge sort per realisation. LSD radix sort, stable, on the tops' bit patterns
 * (positive doubles order as their bits) less the smallest: only the bits where the keys can
 * differ are sorted, in as few digits of at most RADIX_BITS bits as they need (seven for
 * depth 16, of which the top three are sorted first: below), each pass from one buffer to the
 * other; digits that all keys share are skipped.
 * Bytes, not wider digits: a pass then scatters to 256 places per array, which the L1 cache
 * holds (11-bit digits, five passes, took a quarter longer: docs/benchmarks.md). The
 * permutation goes to m->piece, the sorted tops to `sorted`. */
#define RADIX_BITS 8

/* The top HIGH_DIGITS digits sort first; keys that share them (few: tops spread over their
 * range) are put in order by a stable insertion sort within each such group, which together
 * is the stable sort by the whole key; a group longer than FIXUP_MAX and out of order (near-
 * ties in their thousands: a spread so small that tops agree to 24 bits) sends the sort back
 * to all the digits, so the cost stays linear (ties alone, spread 0, are in order already).
 * Depth 16: three passes and a scan instead of seven passes. */
#define HIGH_DIGITS 3
#define FIXUP_MAX 64

/* Puts each run of keys equal in their bits from `shift` up in order of the whole key (stable:
 * a key moves only past larger ones), the permutation alongside. Returns 0 when a run longer
 * than FIXUP_MAX is out of order (nothing moved). */
static int fix_groups(uint64_t *key, uint32_t *perm, size_t n, int shift)
{
    for (size_t a = 0, b; a < n; a = b) { /* the runs first: a long one must be in order */
        int in_order = 1;
        for (b = a + 1; b < n && key[b] >> shift == key[a] >> shift; b++)
            in_order &= key[b] >= key[b - 1];
        if (b - a > FIXUP_MAX && !in_order)
            return 0;
    }
    for (size_t k = 1; k < n; k++) {
        if (key[k] >= key[k - 1] || key[k] >> shift != key[k - 1] >> shift)
            continue;
        const uint64_t kk = key[k];
        const uint32_t pk = perm[k];
        size_t q = k;
        for (; q > 0 && key[q - 1] > kk; q--) { /* within the run: its first key is <= kk */
            key[q] = key[q - 1];
            perm[q] = perm[q - 1];
        }
        key[q] = kk;
        perm[q] = pk;
    }
    return 1;
}

static int sort_by_top(random_meta *m, const double *top, double *sorted, int keep)
{
    const size_t n = m->n;
    uint64_t *key = m->key ? m->key : malloc(2 * (n ? n : 1) * sizeof *key);
    uint32_t *tmp = m->tmp ? m->tmp : malloc((n ? n : 1) * sizeof *tmp);
    uint32_t(*count)[1 << RADIX_BITS] = NULL;
    m->key = key;
    m->tmp = tmp;
    uint64_t low = UINT64_MAX, high = 0;
    for (size_t k = 0; k < n; k++) {
        uint64_t bits;
        memcpy(&bits, &top[k], sizeof bits);
        low = bits < low ? bits : low;
        high = bits > high ? bits : high;
    }
    int span = 0; /* bits of the largest key less the smallest */
    while (span < 64 && ((high - low) >> span))
        span++;
    const int digits = (span + RADIX_BITS - 1) / RADIX_BITS;
    const int width = digits ? (span + digits - 1) / digits : 0;
    const uint64_t mask = ((uint64_t)1 << width) - 1;
    if (key && tmp && digits)
        count = calloc((size_t)digits, sizeof *count);
    if (!key || !tmp || (digits && !count)) {
        free(count);
        return ct_error_set(CT_ENOMEM, "random cantor surface: sorting %zu rods: out of memory", n);
    }
    uint64_t *src, *dst;
    uint32_t *perm, *perm_dst;
    /* first the high digits alone (then the groups), else every digit */
    for (int first = digits > HIGH_DIGITS ? digits - HIGH_DIGITS : 0;; first = 0) {
        src = key, dst = key + n;
        perm = NULL, perm_dst = m->piece; /* NULL: the identity */
        if (digits)
            memset(count, 0, (size_t)digits * sizeof *count);
        for (size_t k = 0; k < n; k++) {
            uint64_t bits;
            memcpy(&bits, &top[k], sizeof bits);
            src[k] = bits - low;
            for (int d = first; d < digits; d++)
                count[d][(src[k] >> (width * d)) & mask]++;
        }
        for (int d = first; d < digits; d++) {
            uint32_t sum = 0;
            int shared = 0;
            for (size_t v = 0; v <= mask; v++)
                shared |= count[d][v] == n;
            if (shared)
                continue;
            for (size_t v = 0; v <= mask; v++) {
                uint32_t c = count[d][v];
                count[d][v] = sum;
                sum += c;
            }
            uint32_t *at = count[d];
            const int shift = width * d;
            for (size_t k = 0; k < n; k++) {
                const uint32_t q = at[(src[k] >> shift) & mask]++;
                dst[q] = src[k];
                perm_dst[q] = perm ? perm[k] : (uint32_t)k;
            }
            uint64_t *t = src;
            src = dst;
            dst = t;
            perm = perm_dst;
            perm_dst = perm == m->piece ? tmp : m->piece;
        }
        if (first == 0 || (perm && fix_groups(src, perm, n, width * first)))
            break;
    }
    free(count);
    if (!perm) /* already in order */
        for (size_t k = 0; k < n; k++)
            m->piece[k] = (uint32_t)k;
    else if (perm != m->piece) { /* the last pass wrote the scratch: it becomes the pieces */
        m->tmp = m->piece;
        m->piece = perm;
    }
    for (size_t k = 0; k < n; k++) {
        const uint64_t bits = src[k] + low;
        memcpy(&sorted[k], &bits, sizeof bits);
    }
    if (!keep) {
        free(m->key);
        free(m->tmp);
        m->key = NULL;
        m->tmp = NULL;
    }
    return CT_OK;
}

/* Draws and lays out realisation `realisation` in b's arrays (b made for meta's depth). */
static int fill(ct_bundle *b, random_meta *meta, uint64_t realisation, int keep_scratch)
{
    const ct_random_cantor *rc = &meta->rc;
    const ct_params *p = &rc->params;
    const size_t total = meta->n;
    /* per chunk clip counts of the widest stage, summed after each stage (integers: exact) */
    const size_t widest = (size_t)1 << (rc->depth ? rc->depth - 1 : 0);
    const size_t nchunks = (widest + SPLIT_CHUNK - 1) / SPLIT_CHUNK;
    uint64_t *clipped = malloc(3 * nchunks * sizeof *clipped), tiny = 0;
    if (!clipped)
        return ct_error_set(CT_ENOMEM, "random cantor surface: out of memory");
    meta->realisation = realisation;
    meta->fx_clipped = meta->fz_clipped = 0;
    /* the pieces in tree order go to the arrays that hold length and plastic strain at the
     * end: they are the sort's source */
    double *top, *length, *area, *eps_p;
    ct_bundle_arrays(b, &top, &length, &area, &eps_p);
    double *tree_top = length, *tree_area = eps_p;
    tree_top[0] = p->h0;
    tree_area[0] = p->l0;
    split_ctx s = {rc, realisation, 0, tree_top, tree_area, clipped};
    for (long i = 0; i < rc->depth; i++) {
        const size_t pieces = (size_t)1 << i;
        s.stage_first = pieces - 1;
        ct_bundle_parallel(b, pieces, SPLIT_CHUNK, split_chunk, &s);
        for (size_t c = 0; c < (pieces + SPLIT_CHUNK - 1) / SPLIT_CHUNK; c++) {
            meta->fx_clipped += clipped[3 * c];
            meta->fz_clipped += clipped[3 * c + 1];
            tiny += clipped[3 * c + 2];
        }
        if (tiny) { /* the first such piece, named: a serial scan of this stage's splits */
            free(clipped);
            size_t g = 0;
            for (size_t k = 0; k < 3 * pieces && !g; k++) {
                size_t q = pieces - 1 + k / 3, at = k % 3 ? 2 * q + k % 3 : q;
                g = !(tree_area[at] >= DBL_MIN) ? at + 1 : 0;
            }
            return ct_error_set(
                CT_ERANGE,
                "random cantor realisation %llu: piece %zu (stage %ld) is %g wide (in l0 = "
                "%g), below the smallest normal double %g: width ratios this large (fx = %g, "
                "spread %g) leave what doubles hold within %ld stages; lower fx, its spread or "
                "the depth",
                (unsigned long long)realisation, g ? g - 1 : 0, g ? rod_stage(g - 1) : i + 1,
                g ? tree_area[g - 1] : 0.0, p->l0, DBL_MIN, p->fx, rc->fx_spread, i + 1);
        }
    }
    free(clipped);
    int st = sort_by_top(meta, tree_top, top, keep_scratch);
    if (st)
        return st;
    finish_ctx f = {top, area, tree_top, tree_area, meta->piece, p->Hstar};
    ct_bundle_parallel(b, total, SPLIT_CHUNK, gather_chunk, &f);
    ct_bundle_parallel(b, total, SPLIT_CHUNK, finish_chunk, &f);
    return CT_OK;
}

int ct_random_cantor_bundle(ct_bundle **out, const ct_random_cantor *rc, uint64_t realisation,
                            int threads)
{
    int st;
    *out = NULL;
    if ((st = ct_random_cantor_validate(rc)))
        return st;
    const size_t total = ((size_t)2 << rc->depth) - 1;
    /* the rods (32 bytes), each rod's piece (4) and the sort's keys and permutation (20,
     * while building): refused up front, with the figure, when it would not fit */
    const double need = (double)total * (CT_BYTES_PER_ROD + 4 + 20);
    const double avail = (double)ct_available_memory();
    if (need > 0.9 * avail)
        return ct_error_set(CT_ENOMEM,
                            "random cantor depth %ld: %zu rods need %.3g GiB while built, more "
                            "than the %.3g GiB of memory available",
                            rc->depth, total, need / 1073741824.0, avail / 1073741824.0);
    random_meta *meta = calloc(1, sizeof *meta);
    uint32_t *piece = malloc(total * sizeof *piece);
    if (!meta || !piece) {
        free(meta);
        free(piece);
        return ct_error_set(CT_ENOMEM, "random cantor surface: out of memory");
    }
    *meta = (random_meta){*rc, realisation, 0, 0, total, piece, NULL, NULL};
    char what[96];
    snprintf(what, sizeof what, "random cantor depth %ld", rc->depth);
    ct_layer layer;
    ct_cantor_layer(&rc->params, &layer);
    ct_bundle *b;
    if ((st = ct_bundle_create(&b, &layer, total, what))) {
        random_free(meta);
        return st;
    }
    ct_bundle_set_surface(b, &random_kind, meta, 0);
    ct_bundle_set_threads(b, threads);
    if ((st = fill(b, meta, realisation, 0))) {
        ct_bundle_free(b);
        return st;
    }
    *out = b;
    return CT_OK;
}

int ct_random_cantor_refill(ct_bundle *b, const ct_random_cantor *rc, uint64_t realisation)
{
    int st;
    random_meta *meta = b ? (random_meta *)ct_bundle_surface_meta(b, &random_kind) : NULL;
    if ((st = ct_random_cantor_validate(rc)))
        return st;
    if (!meta || meta->rc.depth != rc->depth)
        return ct_error_set(CT_EINVAL, "refill: not a random cantor bundle of depth %ld",
                            rc->depth);
    ct_layer layer;
    ct_cantor_layer(&rc->params, &layer);
    if (memcmp(ct_bundle_layer(b), &layer, sizeof layer))
        return ct_error_set(CT_EINVAL, "refill: the layer differs from the bundle's");
    meta->rc = *rc;
    return fill(b, meta, realisation, 1);
}

/* ---- the kind (src/surface/kind.h) ---- */

typedef struct {
    ct_cantor_keys k; /* fx, fz (the centres of the ratio distributions), H, h0, l0; E, sigma_y */
    long depth;
    int distribution; /* ct_ratio_dist */
    double fx_spread, fz_spread;
    uint64_t seed, realisation;
    ct_random_cantor rc; /* computed: dimensionless (l0 = h0 = sigma_y = 1) */
    ct_params physical;  /* as given */
} random_config;

#define AT(field) offsetof(random_config, field)
static const ct_key random_keys[] = {
    CT_CANTOR_SURFACE_ROWS(random_config, k, "centre of the width ratios fx_k",
                           "centre of the depth ratios fz_k"),
    {"surface", "depth", CT_KEY_INTEGER, 0.0, CT_MAX_RANDOM_DEPTH, CT_KEY_REQUIRED, NULL,
     "type = random_cantor needs an integer 0 <= depth <= 30", "",
     "stages 0..depth, every piece its own rod (2^(depth+1) - 1 rods)", AT(depth)},
    {"surface", "distribution", CT_KEY_WORD, 0, 0, 0, "uniform|lognormal",
     "must be uniform or lognormal", "lognormal",
     "the ratios' distribution: f (1 + spread (2U - 1)) or f exp(spread Z)", AT(distribution)},
    {"surface", "fx_spread", CT_KEY_NUMBER, -INFINITY, INFINITY, 0, NULL,
     "0 <= spread < 1 (uniform), 0 <= spread <= 10 (lognormal)", "0", "spread of the width ratios",
     AT(fx_spread)},
    {"surface", "fz_spread", CT_KEY_NUMBER, -INFINITY, INFINITY, 0, NULL,
     "0 <= spread < 1 (uniform), 0 <= spread <= 10 (lognormal)", "0", "spread of the depth ratios",
     AT(fz_spread)},
    {"surface", "seed", CT_KEY_COUNT, 0, 0, 0, NULL, "must be an integer 0 <= n < 2^64", "0",
     "the generator's key with the realisation (Philox4x64)", AT(seed)},
    {"surface", "realisation", CT_KEY_COUNT, 0, 0, 0, NULL, "must be an integer 0 <= n < 2^64", "0",
     "the one realisation of a run without [ensemble]", AT(realisation)},
    CT_CANTOR_MATERIAL_ROWS(random_config, k),
};
#undef AT

static void random_defaults(void *config)
{
    random_config *c = config;
    ct_cantor_keys_defaults(&c->k);
    c->distribution = CT_RATIO_LOGNORMAL;
}

static int random_check(ct_surface *s, const char *scene)
{
    random_config *c = s->config;
    int st;
    const int uniform = c->distribution == CT_RATIO_UNIFORM;
    const char *range = uniform ? "must satisfy 0 <= spread < 1 (distribution = uniform)"
                                : "must satisfy 0 <= spread <= 10 (distribution = lognormal)";
    static const char *const keys[2] = {"fx_spread", "fz_spread"};
    const double v[2] = {c->fx_spread, c->fz_spread};
    for (int k = 0; k < 2; k++)
        if (!(v[k] >= 0.0) || (uniform ? !(v[k] < 1.0) : !(v[k] <= 10.0)))
            return ct_surface_key_error(s, "surface", keys[k], CT_EINVAL, "%s", range);
    ct_params p;
    if ((st = ct_cantor_keys_check(s, &c->k, scene, &c->physical, &p)))
        return st;
    c->rc = (ct_random_cantor){.params = p,
                               .dist = (ct_ratio_dist)c->distribution,
                               .fx_spread = c->fx_spread,
                               .fz_spread = c->fz_spread,
                               .depth = c->depth,
                               .seed = c->seed};
    if ((st = ct_random_cantor_validate(&c->rc)))
        return ct_error_set(st, "%s: %s", scene, ct_error_message());
    return CT_OK;
}

static int random_prepare(ct_surface *s, const char *dir)
{
    (void)dir;
    const random_config *c = s->config;
    ct_layer built, given;
    ct_cantor_layer(&c->rc.params, &built);
    ct_cantor_layer(&c->physical, &given);
    ct_scales_of(&s->scales, &built, &given);
    return CT_OK;
}

static int random_build(const ct_surface *s, const ct_build_request *r, ct_bundle **out,
                        ct_plan_info *info)
{
    const random_config *c = s->config;
    int st = ct_random_cantor_bundle(out, &c->rc, c->realisation, r->threads);
    if (st)
        return st;
    info->depth = c->depth;
    info->bound = 0.0;
    info->rods = ct_bundle_size(*out);
    info->omitted = 0;
    info->u_reach = INFINITY;
    return CT_OK;
}

int ct_surface_random_cantor(const ct_surface *s, ct_random_cantor *rc, uint64_t *realisation)
{
    CT_NEED(s);
    if (s->kind != &ct_kind_random_cantor || !s->checked)
        return ct_error_set(CT_EINVAL, "surface %s: not a checked random_cantor surface",
                            s->kind->name);
    const random_config *c = s->config;
    if (rc)
        *rc = c->rc;
    if (realisation)
        *realisation = c->realisation;
    return CT_OK;
}

static void random_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    (void)s;
    snprintf(buf, len,
             "random cantor rods, depth %ld (given), %zu rods, %zu left out as never "
             "touched",
             info->depth, info->rods, info->omitted);
}

static void random_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len)
{
    const random_config *c = s->config;
    const ct_params *p = &c->rc.params;
    snprintf(buf, len,
             "random_cantor: fx = %.17g, fz = %.17g, H*/h0 = %.17g, E/sigma_y = %.17g, depth %ld, "
             "%zu rods, seed %llu, realisation %llu, spreads %.17g %.17g",
             p->fx, p->fz, p->Hstar / p->h0, p->E / p->sigma_y, info->depth, info->rods,
             (unsigned long long)c->seed, (unsigned long long)c->realisation, c->fx_spread,
             c->fz_spread);
}

/* One row per piece, in piece order (stage, then x), with its top and residual top. */
static int random_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f)
{
    (void)s;
    const size_t n = ct_bundle_size(b);
    const ct_layer *L = ct_bundle_layer(b);
    size_t *rod_of = malloc((n ? n : 1) * sizeof *rod_of);
    if (!rod_of)
        return ct_error_set(CT_ENOMEM, "profile: out of memory");
    for (size_t k = 0; k < n; k++) {
        uint64_t g;
        if (ct_random_cantor_piece(b, k, &g) || g >= n) {
            free(rod_of);
            return ct_error_set(CT_EINVAL, "profile: a rod without its piece");
        }
        rod_of[g] = k;
    }
    fputs("stage,x_left_over_l0,x_right_over_l0,top_over_h0,residual_top_over_h0\n", f);
    for (size_t g = 0; g < n; g++) {
        ct_rod_info info;
        ct_bundle_rod(b, rod_of[g], &info);
        fprintf(f, "%ld,%.17g,%.17g,%.17g,%.17g\n", info.stage, info.x_left / L->l0,
                info.x_right / L->l0, info.top / L->h0,
                (info.top + info.plastic_strain * info.length) / L->h0);
    }
    free(rod_of);
    return CT_OK;
}

const ct_kind ct_kind_random_cantor = {
    .name = "random_cantor",
    .summary = "a random Cantor surface: every split draws its own ratios (Philox, seeded)",
    .keys = random_keys,
    .nkeys = sizeof random_keys / sizeof random_keys[0],
    .config_size = sizeof(random_config),
    .defaults = random_defaults,
    .realisations = 1,
    .check = random_check,
    .prepare = random_prepare,
    .build = random_build,
    .describe = random_describe,
    .table_line = random_table_line,
    .write_profile = random_write_profile,
    .profile_shows_state = 1,
};
