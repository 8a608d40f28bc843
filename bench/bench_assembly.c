/* Force assembly against the memory-bandwidth limit (issue 6). For segment bundles of
 * 2^20 - 1 ... 2^27 - 1 rods (depths 19 ... 26), one force evaluation P(u) with 1 and 2
 * threads: rods/s and bytes/s (32 bytes read per rod), beside a STREAM-like triad
 * a[i] = b[i] + s c[i] measured in the same run on arrays far larger than the last-level
 * cache (24 bytes per element, the STREAM convention). Also the multi-node pass the
 * quadrature uses (64 nodes per pass over the rods).
 *
 * Usage: bench_assembly [--quick] [--runs N]   (--quick: 2^20 ... 2^24 rods)
 * CSV on stdout, '#' lines are comments. */
#define _DEFAULT_SOURCE /* madvise */
#include "cantact.h"
#include "common.h"

#include <sys/mman.h>

#include <math.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int runs = 7;

/* Median seconds of one call of fn over `runs` timed runs after a warm-up. */
#define MEDIAN_OF(result, stmt)                                                                    \
    do {                                                                                           \
        double t_[64];                                                                             \
        stmt;                                                                                      \
        for (int r_ = 0; r_ < runs; r_++) {                                                        \
            double t0_ = bench_now();                                                              \
            stmt;                                                                                  \
            t_[r_] = bench_now() - t0_;                                                            \
        }                                                                                          \
        (result) = bench_median(t_, runs);                                                         \
    } while (0)

static void triad_once(double *a, const double *b, const double *c, size_t n, int threads)
{
    const double s = 3.0;
    (void)threads;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (ptrdiff_t i = 0; i < (ptrdiff_t)n; i++)
        a[i] = b[i] + s * c[i];
}

/* The assembly's own access pattern without its arithmetic: four arrays read, nothing
 * written (32 bytes per element). */
static double read4_once(const double *a, const double *b, const double *c, const double *d,
                         size_t n, int threads)
{
    double s = 0.0;
    (void)threads;
#pragma omp parallel for simd schedule(static) num_threads(threads) reduction(+ : s)
    for (ptrdiff_t i = 0; i < (ptrdiff_t)n; i++)
        s += a[i] + b[i] + c[i] + d[i];
    return s;
}

static double read4(const double *a, const double *b, const double *c, const double *d, size_t n,
                    int threads, double *sink)
{
    double t;
    MEDIAN_OF(t, *sink += read4_once(a, b, c, d, n, threads));
    return 32.0 * (double)n / t;
}

static double triad(double *a, const double *b, const double *c, size_t n, int threads)
{
    double t;
    MEDIAN_OF(t, triad_once(a, b, c, n, threads));
    return 24.0 * (double)n / t;
}

/* Arrays as the bundle gets them: 2 MiB aligned, transparent huge pages advised, so the
 * triad and the assembly see the same TLB behaviour. */
static double *huge_array(size_t n)
{
    void *p = NULL;
    size_t bytes =
        (n * sizeof(double) + ((size_t)2 << 20) - 1) / ((size_t)2 << 20) * ((size_t)2 << 20);
    if (posix_memalign(&p, (size_t)2 << 20, bytes))
        return NULL;
#ifdef MADV_HUGEPAGE
    madvise(p, bytes, MADV_HUGEPAGE);
#endif
    return p;
}

static long llc_bytes(void)
{
    long best = 0;
    for (int idx = 0; idx < 8; idx++) {
        char path[96], buf[64];
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", idx);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        if (fgets(buf, sizeof buf, f)) {
            char *end;
            long v = strtol(buf, &end, 10);
            if (*end == 'K')
                v *= 1024;
            else if (*end == 'M')
                v *= 1024 * 1024;
            best = v > best ? v : best;
        }
        fclose(f);
    }
    return best;
}

int main(int argc, char **argv)
{
    int quick = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_assembly [--quick] [--runs N]\n");
            return 2;
        }
    }
    if (runs < 5 || runs > 64) {
        fprintf(stderr, "bench_assembly: need 5 <= runs <= 64\n");
        return 2;
    }
    const long max_depth = quick ? 23 : 26;
    long llc = llc_bytes();
    /* triad arrays: 3 x 2^25 doubles = 768 MiB, far beyond any last-level cache */
    size_t n = (size_t)1 << (quick ? 24 : 25);
    double *a = huge_array(n), *bb = huge_array(n), *cc = huge_array(n), *dd = huge_array(n),
           sink = 0.0;
    if (!a || !bb || !cc || !dd) {
        fprintf(stderr, "bench_assembly: out of memory for the triad\n");
        return 1;
    }
#pragma omp parallel for schedule(static)
    for (ptrdiff_t i = 0; i < (ptrdiff_t)n; i++) {
        a[i] = 0.0;
        bb[i] = 1.0;
        cc[i] = 2.0;
        dd[i] = 4.0;
    }
    double bw[3] = {0, 0, 0}, rd[3] = {0, 0, 0};
    for (int t = 1; t <= 2; t++) {
        bw[t] = triad(a, bb, cc, n, t);
        rd[t] = read4(a, bb, cc, dd, n, t, &sink);
    }
    free(a);
    free(bb);
    free(cc);
    free(dd);

    bench_machine(stdout);
    printf("# last-level cache %ld bytes; triad (%zu elements, 24 B each): 1 thread %.3g GB/s, "
           "2 threads %.3g GB/s; read of 4 arrays (32 B each): 1 thread %.3g GB/s, 2 threads "
           "%.3g GB/s\n",
           llc, n, bw[1] / 1e9, bw[2] / 1e9, rd[1] / 1e9, rd[2] / 1e9);
    printf("rods,bytes,threads,seconds,rods_per_s,bytes_per_s,triad_bytes_per_s,fraction_of_triad,"
           "read_bytes_per_s,fraction_of_read,speedup,many64_core_ns_per_rod_node\n");
    ct_params p = {.fx = 1.5, .fz = 1.3, .l0 = 1, .h0 = 1, .Hstar = 10, .E = 500, .sigma_y = 1};
    for (long depth = 19; depth <= max_depth; depth++) {
        ct_bundle *b;
        if (ct_cantor_bundle(&b, &p, CT_REP_SEGMENTS, depth, INFINITY)) {
            fprintf(stderr, "bench_assembly: %s\n", ct_error_message());
            return 1;
        }
        ct_bundle_advance(b, 0.3); /* a mixed state: some rods yielded, some elastic, some free */
        size_t rods = ct_bundle_size(b);
        double t1 = 0.0;
        for (int t = 1; t <= 2; t++) {
            ct_bundle_set_threads(b, t);
            double sec, many;
            MEDIAN_OF(sec, sink += ct_bundle_force(b, 0.25));
            double u[64], P[64];
            for (int i = 0; i < 64; i++)
                u[i] = 0.01 * (i + 1);
            MEDIAN_OF(many, sink += ct_bundle_force_many(b, u, 64, P) + P[63]);
            if (t == 1)
                t1 = sec;
            double rate = (double)rods / sec;
            printf("%zu,%zu,%d,%.6g,%.4g,%.4g,%.4g,%.3f,%.4g,%.3f,%.3f,%.4g\n", rods,
                   rods * CT_BYTES_PER_ROD, t, sec, rate, rate * CT_BYTES_PER_ROD, bw[t],
                   rate * CT_BYTES_PER_ROD / bw[t], rd[t], rate * CT_BYTES_PER_ROD / rd[t],
                   t1 / sec, 1e9 * many / ((double)rods * 64.0) * t);
            fflush(stdout);
        }
        ct_bundle_free(b);
    }
    printf("# checksum %g\n", sink);
    return 0;
}
