/* MPI for the CLI (see ranks.h). The library knows nothing of MPI: a realisation is a pure
 * function of (seed, realisation), so ranks only need to agree on who builds which ones and
 * to send rank 0 the samples, whose statistics it computes in realisation order exactly as a
 * single process would: the output is the same bytes for any number of ranks.
 *
 * This file is the front: without a launcher (or a module) everything is one process of rank 0,
 * and cantact does not load MPI at all; under a launcher it loads the module cantact-mpi
 * (ranks_mpi.c), which links libmpi, and forwards every call to it. */
#define _POSIX_C_SOURCE 200809L /* readlink, dlopen */
#include "ranks.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const ct_mpi_module *mod; /* the loaded module, NULL: one process */

static int launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK");
}

#ifdef CT_HAVE_MPI
/* dlopen one candidate; RTLD_GLOBAL because OpenMPI's own components, loaded by MPI_Init,
 * resolve symbols of libmpi and libopen-pal from the global scope */
static const ct_mpi_module *try_load(const char *path, char *why, size_t len)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    if (!h) {
        snprintf(why, len, "%s", dlerror());
        return NULL;
    }
    const ct_mpi_module *m = dlsym(h, "ct_mpi_module_v1");
    if (!m) {
        snprintf(why, len, "%s has no ct_mpi_module_v1", path);
        dlclose(h);
    }
    return m;
}
#endif

int ct_mpi_init(int *argc, char ***argv)
{
    if (!launched())
        return 0;
#ifdef CT_HAVE_MPI
    char why[PATH_MAX + 200] = "";
    const char *env = getenv("CANTACT_MPI_MODULE");
    if (env && *env) {
        mod = try_load(env, why, sizeof why);
    } else {
        /* beside the executable (the build tree), then the installed module */
        char exe[PATH_MAX];
        ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
        if (n > 0) {
            exe[n] = '\0';
            char *slash = strrchr(exe, '/');
            if (slash && (size_t)(slash - exe) + sizeof "/cantact-mpi.so" < sizeof exe) {
                strcpy(slash, "/cantact-mpi.so");
                if (access(exe, R_OK) == 0)
                    mod = try_load(exe, why, sizeof why);
            }
        }
        if (!mod && !why[0])
            mod = try_load(CT_MPI_MODULE_DIR "/cantact-mpi.so", why, sizeof why);
    }
    if (!mod) {
        fprintf(stderr,
                "cantact: started by an MPI launcher, but the MPI module cannot be "
                "loaded: %s\n",
                why);
        return -1;
    }
    mod->init(argc, argv);
    return 0;
#else
    (void)argc, (void)argv;
    fputs("cantact: started by an MPI launcher, but built without MPI (meson option mpi): every "
          "rank would compute and write the whole output\n",
          stderr);
    return -1;
#endif
}

void ct_mpi_finalize(void)
{
    if (mod)
        mod->finalize();
}

int ct_mpi_rank(void)
{
    return mod ? mod->rank() : 0;
}

int ct_mpi_size(void)
{
    return mod ? mod->size() : 1;
}

int ct_mpi_bcast_int(int v)
{
    return mod ? mod->bcast_int(v) : v;
}

int ct_mpi_gather(const ct_ensemble_samples *mine, int status, const char *message, uint64_t first,
                  uint64_t count, size_t nrows, ct_ensemble_samples **all, char *err, size_t errlen)
{
    if (mod)
        return mod->gather(mine, status, message, first, count, nrows, all, err, errlen);
    (void)mine, (void)first, (void)count, (void)nrows, (void)all;
    if (status)
        snprintf(err, errlen, "%s", message ? message : "");
    return status;
}
