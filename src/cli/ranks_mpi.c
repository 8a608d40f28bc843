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

static int m_gather(const ct_ensemble_samples *mine, int status, const char *message,
                    uint64_t first, uint64_t count, size_t nrows, ct_ensemble_samples **all,
                    char *err, size_t errlen)
{
    const int rank = m_rank(), size = m_size();
    rank_report rep;
    memset(&rep, 0, sizeof rep);
    rep.status = status;
    snprintf(rep.message, sizeof rep.message, "%s", message ? message : "");
    rep.failed_realisation = UINT64_MAX;
    rep.quad_error_max = NAN;
    if (mine) {
        rep.failed_realisation = mine->failed_realisation;
        rep.failed_row = mine->failed_row;
        rep.quad_error_max = mine->quad_error_max;
        snprintf(rep.failed_message, sizeof rep.failed_message, "%s", mine->message);
    }
    rank_report *reps = rank == 0 ? calloc((size_t)size, sizeof *reps) : NULL;
    MPI_Gather(&rep, (int)sizeof rep, MPI_BYTE, reps, (int)sizeof rep, MPI_BYTE, 0, MPI_COMM_WORLD);
    /* from here every rank knows whether the gather goes on: rank 0 decides */
    int st = CT_OK;
    if (rank == 0) {
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
    }
    st = m_bcast_int(st);
    if (st) {
        free(reps);
        return rank == 0 ? st : CT_OK;
    }
    /* every rank's block: the same split as the caller's */
    int *counts = NULL, *displs = NULL, *counts_r = NULL, *displs_r = NULL;
    if (rank == 0) {
        counts = malloc(4 * (size_t)size * sizeof(int));
        displs = counts + size;
        counts_r = displs + size;
        displs_r = counts_r + size;
        for (int k = 0; k < size; k++) {
            uint64_t a = first + count * (uint64_t)k / (uint64_t)size;
            uint64_t b = first + count * (uint64_t)(k + 1) / (uint64_t)size;
            counts_r[k] = (int)(b - a);
            displs_r[k] = (int)(a - first);
            counts[k] = (int)((b - a) * nrows);
            displs[k] = (int)((a - first) * nrows);
        }
    }
    const uint64_t my_n = mine ? mine->count * mine->nrows : 0, my_r = mine ? mine->count : 0;
    ct_ensemble_samples *A = rank == 0 ? *all : NULL;
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
    if (rank == 0) {
        /* the lowest failure of all: ranks hold increasing realisations, so the first rank
         * that failed has it; the largest quadrature error: a maximum, exact in any order */
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
    free(counts);
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
