/* The CLI's use of MPI (meson feature mpi): ranks share an ensemble's realisations and rank 0
 * gathers the samples in realisation order. Built without MPI, or run without a launcher,
 * everything here is a single process of rank 0. */
#ifndef CT_CLI_RANKS_H
#define CT_CLI_RANKS_H

#include "cantact.h"

/* MPI_Init when the process was started by an MPI launcher (mpirun sets OMPI_COMM_WORLD_SIZE,
 * PMI_SIZE or PMIX_RANK), nothing otherwise. MPI lives in the module cantact-mpi.so, loaded here
 * only then (beside the executable in the build tree, in <libdir>/cantact once installed; the
 * environment variable CANTACT_MPI_MODULE names another file). Returns 0, or -1 with a
 * one-line message on stderr when a launcher started the process but the module cannot be
 * loaded (or cantact was built without MPI: then every rank would write the whole output). */
int ct_mpi_init(int *argc, char ***argv);
void ct_mpi_finalize(void);
int ct_mpi_rank(void);
int ct_mpi_size(void);
/* Returns rank 0's value of v to every rank. */
int ct_mpi_bcast_int(int v);
/* Gathers every rank's samples (realisations in rank order, contiguous) into all (rank 0
 * only; allocated there for first .. first + count - 1, nrows rows each): the arrays, the clip
 * counts, the largest quadrature error, the lowest failure, and each rank's status with its message
 * (lowest rank first). mine may be NULL (an empty block). Returns on rank 0 the first
 * failed rank's status (its message in err), CT_OK elsewhere. */
int ct_mpi_gather(const ct_ensemble_samples *mine, int status, const char *message, uint64_t first,
                  uint64_t count, size_t nrows, ct_ensemble_samples **all, char *err,
                  size_t errlen);

/* The module's table (ranks_mpi.c exports it as ct_mpi_module_v1). */
typedef struct {
    void (*init)(int *argc, char ***argv);
    void (*finalize)(void);
    int (*rank)(void);
    int (*size)(void);
    int (*bcast_int)(int v);
    int (*gather)(const ct_ensemble_samples *mine, int status, const char *message, uint64_t first,
                  uint64_t count, size_t nrows, ct_ensemble_samples **all, char *err,
                  size_t errlen);
} ct_mpi_module;

#endif
