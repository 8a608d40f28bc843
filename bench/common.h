/* Helpers of the benchmark programs: a monotonic clock, medians, the machine's description. */
#ifndef CT_BENCH_COMMON_H
#define CT_BENCH_COMMON_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static inline double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline int bench_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static inline double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof(double), bench_cmp);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Prints "# machine: <cpu model>, <n> cores" from /proc/cpuinfo. */
static inline void bench_machine(FILE *out)
{
    char line[512], model[256] = "unknown cpu";
    int cores = 0;
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (f) {
        while (fgets(line, sizeof line, f)) {
            if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
                snprintf(model, sizeof model, "%s", strchr(line, ':') + 2);
                model[strcspn(model, "\n")] = '\0';
            }
            if (!strncmp(line, "processor", 9))
                cores++;
        }
        fclose(f);
    }
    fprintf(out, "# machine: %s, %d logical cores\n", model, cores);
}

#endif
