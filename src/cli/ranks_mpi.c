/* The MPI half of the CLI (see ranks.h), built as the module cantact-mpi and loaded by ranks.c
 * only when the process was started by an MPI launcher: linking libmpi into cantact itself
 * loaded OpenMPI, hwloc, libevent and their dependencies at every start (about a millisecond of
 * every run, MPI or not). The module exports one symbol, ct_mpi_module_v1, a table of the
 * functions below. */
#include "ranks.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <mpi.h>
#include <limits.h>

static int mpi_on; /* MPI_Init was called (the CLI's process state, not the library's) */

static void m_init(int *argc, char ***argv)
{
    MPI_Init(argc, argv);
    mpi_on = 1;
}

static void m_finalize(void)
{
    if (mpi_on)
        MPI_Finalize();
    mpi_on = 0;
}

static int m_rank(void)
{
    int r = 0;
    if (mpi_on)
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
    return r;
}

static int m_size(void)
{
    int n = 1;
    if (mpi_on)
        MPI_Comm_size(MPI_COMM_WORLD, &n);
    return n;
}

static int m_bcast_int(int v)
{
    if (mpi_on)
        MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v;
}

/* What every rank sends besides the arrays. */
typedef struct {
    int status;
    char message[300];
    uint64_t failed_realisation;
    uint64_t failed_row;
    double quad_error_max;
    char failed_message[240];
} rank_report;

/* MPI_Gatherv of `per` elements per realisation of one array. */
static int gather_array(const void *mine, uint64_t my_count, void *all, const int *counts,
                        const int *displs, MPI_Datatype type, int rank)
{
    (void)rank;
    return MPI_Gatherv(mine, (int)my_count, type, all, counts, displs, type, 0, MPI_COMM_WORLD);
}

/* This rank's report: its status and message, and its samples' failure and quadrature error. */
static void report_of(rank_report *rep, const ct_ensemble_samples *mine, int status,
                      const char *message)
{
    memset(rep, 0, sizeof *rep);
    rep->status = status;
    snprintf(rep->message, sizeof rep->message, "%s", message ? message : "");
    rep->failed_realisation = UINT64_MAX;
    rep->quad_error_max = NAN;
    if (mine) {
        rep->failed_realisation = mine->failed_realisation;
        rep->failed_row = mine->failed_row;
        rep->quad_error_max = mine->quad_error_max;
        snprintf(rep->failed_message, sizeof rep->failed_message, "%s", mine->message);
    }
}

/* Rank 0, from every rank's report: whether the gather goes on (CT_OK: *all allocated), or the
 * first failed rank's status, or a gather larger than MPI's int counts carry (the message in
 * err). */
static int gather_status(const rank_report *reps, int size, uint64_t first, uint64_t count,
                         size_t nrows, ct_ensemble_samples **all, char *err, size_t errlen)
{
    int st = CT_OK;
    for (int k = 0; k < size && !st; k++)
        if (reps[k].status) {
            st = reps[k].status;
            snprintf(err, errlen, "%s", reps[k].message);
        }
    if (!st && (double)count * (double)nrows > INT_MAX) {
        st = CT_EINVAL;
        snprintf(err, errlen,
                 "MPI: %llu realisations x %zu rows exceed what one gather carries (2^31 - 1 "
                 "values): use fewer realisations per run and cantact merge",
                 (unsigned long long)count, nrows);
    }
    if (!st && (st = ct_ensemble_samples_alloc(all, first, count, nrows)))
        snprintf(err, errlen, "%s", ct_error_message());
    return st;
}

/* Rank 0: where every rank's block lands, the same split as the caller's: four arrays of size
 * ints, [counts | displs] in values (nrows per realisation), then [counts | displs] in
 * realisations. */
static int *block_layout(uint64_t first, uint64_t count, size_t nrows, int size)
{
    int *counts = malloc(4 * (size_t)size * sizeof(int));
    int *displs = counts + size, *counts_r = displs + size, *displs_r = counts_r + size;
    for (int k = 0; k < size; k++) {
        uint64_t a = first + count * (uint64_t)k / (uint64_t)size;
        uint64_t b = first + count * (uint64_t)(k + 1) / (uint64_t)size;
        counts_r[k] = (int)(b - a);
        displs_r[k] = (int)(a - first);
        counts[k] = (int)((b - a) * nrows);
        displs[k] = (int)((a - first) * nrows);
    }
    return counts;
}

/* Every rank's arrays into A (rank 0; NULL and layout NULL elsewhere). */
static void gather_samples(const ct_ensemble_samples *mine, ct_ensemble_samples *A,
                           const int *layout, int size, int rank)
{
    const int *counts = layout, *displs = layout ? layout + size : NULL;
    const int *counts_r = layout ? layout + 2 * size : NULL;
    const int *displs_r = layout ? layout + 3 * size : NULL;
    const uint64_t my_n = mine ? mine->count * mine->nrows : 0, my_r = mine ? mine->count : 0;
    gather_array(mine ? mine->e : NULL, my_n, A ? A->e : NULL, counts, displs, MPI_DOUBLE, rank);
    gather_array(mine ? mine->u_max : NULL, my_n, A ? A->u_max : NULL, counts, displs, MPI_DOUBLE,
                 rank);
    gather_array(mine ? mine->V_star_crit : NULL, my_n, A ? A->V_star_crit : NULL, counts, displs,
                 MPI_DOUBLE, rank);
    gather_array(mine ? mine->status : NULL, my_n, A ? A->status : NULL, counts, displs, MPI_INT,
                 rank);
    gather_array(mine ? mine->fx_clipped : NULL, my_r, A ? A->fx_clipped : NULL, counts_r, displs_r,
                 MPI_UINT64_T, rank);
    gather_array(mine ? mine->fz_clipped : NULL, my_r, A ? A->fz_clipped : NULL, counts_r, displs_r,
                 MPI_UINT64_T, rank);
    gather_array(mine ? mine->x : NULL, my_r, A ? A->x : NULL, counts_r, displs_r, MPI_DOUBLE,
                 rank);
    gather_array(mine ? mine->y : NULL, my_r, A ? A->y : NULL, counts_r, displs_r, MPI_DOUBLE,
                 rank);
}

/* Rank 0: the lowest failure of all (ranks hold increasing realisations, so the first rank
 * that failed has it) and the largest quadrature error (a maximum, exact in any order). */
static void combine_reports(ct_ensemble_samples *A, const rank_report *reps, int size)
{
    A->failed_realisation = UINT64_MAX;
    A->quad_error_max = NAN;
    A->message[0] = '\0';
    for (int k = 0; k < size; k++) {
        const rank_report *r = &reps[k];
        if (r->quad_error_max > A->quad_error_max ||
            (isnan(A->quad_error_max) && !isnan(r->quad_error_max)))
            A->quad_error_max = r->quad_error_max;
        if (r->failed_realisation < A->failed_realisation) {
            A->failed_realisation = r->failed_realisation;
            A->failed_row = (size_t)r->failed_row;
            snprintf(A->message, sizeof A->message, "%s", r->failed_message);
        }
    }
}

static int m_gather(const ct_ensemble_samples *mine, int status, const char *message,
                    uint64_t first, uint64_t count, size_t nrows, ct_ensemble_samples **all,
                    char *err, size_t errlen)
{
    const int rank = m_rank(), size = m_size();
    rank_report rep;
    report_of(&rep, mine, status, message);
    rank_report *reps = rank == 0 ? calloc((size_t)size, sizeof *reps) : NULL;
    MPI_Gather(&rep, (int)sizeof rep, MPI_BYTE, reps, (int)sizeof rep, MPI_BYTE, 0, MPI_COMM_WORLD);
    /* from here every rank knows whether the gather goes on: rank 0 decides */
    int st = rank == 0 ? gather_status(reps, size, first, count, nrows, all, err, errlen) : CT_OK;
    st = m_bcast_int(st);
    if (st) {
        free(reps);
        return rank == 0 ? st : CT_OK;
    }
    int *layout = rank == 0 ? block_layout(first, count, nrows, size) : NULL;
    ct_ensemble_samples *A = rank == 0 ? *all : NULL;
    gather_samples(mine, A, layout, size, rank);
    if (rank == 0)
        combine_reports(A, reps, size);
    free(layout);
    free(reps);
    return CT_OK;
}

const ct_mpi_module ct_mpi_module_v1 = {
    .init = m_init,
    .finalize = m_finalize,
    .rank = m_rank,
    .size = m_size,
    .bcast_int = m_bcast_int,
    .gather = m_gather,
};
