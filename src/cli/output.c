#include "output.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int ct_out_open(ct_out *o, const char *path, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    /* stdout, and a path that exists but is no regular file (/dev/null, a FIFO, a
     * terminal): rows are held in memory and written there at commit. Renaming a temporary
     * file over such a path would replace the device itself. */
    struct stat st;
    int special = strcmp(path, "-") && stat(path, &st) == 0 && !S_ISREG(st.st_mode);
    if (special && S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: cannot write: is a directory", path);
        return -1;
    }
    if (!strcmp(path, "-") || special) {
        if (special && access(path, W_OK) != 0) {
            snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
            return -1;
        }
        if (special && !(o->special = strdup(path))) {
            snprintf(err, errlen, "out of memory");
            return -1;
        }
        o->f = open_memstream(&o->mem, &o->mem_size);
        if (!o->f) {
            snprintf(err, errlen, "cannot buffer output: %s", strerror(errno));
            free(o->special);
            o->special = NULL;
            return -1;
        }
        return 0;
    }
    size_t n = strlen(path);
    o->path = strdup(path);
    o->tmp_path = malloc(n + 16);
    if (!o->path || !o->tmp_path) {
        snprintf(err, errlen, "out of memory");
        ct_out_abort(o);
        return -1;
    }
    snprintf(o->tmp_path, n + 16, "%s.tmpXXXXXX", path);
    int fd = mkstemp(o->tmp_path);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        free(o->tmp_path);
        o->tmp_path = NULL;
        ct_out_abort(o);
        return -1;
    }
    o->f = fdopen(fd, "w");
    if (!o->f) {
        close(fd);
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        ct_out_abort(o);
        return -1;
    }
    return 0;
}

int ct_out_commit(ct_out *o, char *err, size_t errlen)
{
    int bad = ferror(o->f);
    if (fclose(o->f) != 0)
        bad = 1;
    o->f = NULL;
    if (o->special) { /* written in place: open(2) without O_CREAT or O_TRUNC */
        int fd = bad ? -1 : open(o->special, O_WRONLY | O_NOCTTY);
        size_t done = 0;
        while (fd >= 0 && done < o->mem_size) {
            ssize_t w = write(fd, o->mem + done, o->mem_size - done);
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0)
                break;
            done += (size_t)w;
        }
        if (fd < 0 || done < o->mem_size)
            bad = 1;
        if (fd >= 0 && close(fd) != 0)
            bad = 1;
        if (bad)
            snprintf(err, errlen, "%s: cannot write: %s", o->special, strerror(errno));
        free(o->mem);
        free(o->special);
        o->mem = o->special = NULL;
        return bad ? -1 : 0;
    }
    if (!o->path) {
        if (!bad && o->mem_size && fwrite(o->mem, 1, o->mem_size, stdout) != o->mem_size)
            bad = 1;
        if (fflush(stdout) != 0)
            bad = 1;
        free(o->mem);
        o->mem = NULL;
        if (bad)
            snprintf(err, errlen, "standard output: write failed");
        return bad ? -1 : 0;
    }
    if (bad || rename(o->tmp_path, o->path) != 0) {
        snprintf(err, errlen, "%s: cannot write: %s", o->path,
                 bad ? "write failed" : strerror(errno));
        ct_out_abort(o);
        return -1;
    }
    free(o->tmp_path);
    free(o->path);
    o->tmp_path = o->path = NULL;
    return 0;
}

void ct_out_abort(ct_out *o)
{
    if (o->f)
        fclose(o->f);
    o->f = NULL;
    if (o->tmp_path)
        unlink(o->tmp_path);
    free(o->tmp_path);
    free(o->path);
    free(o->mem);
    free(o->special);
    o->tmp_path = o->path = o->mem = o->special = NULL;
}

void ct_progress_start(ct_progress *p, size_t total)
{
    p->enabled = isatty(STDERR_FILENO) && total > 1;
    p->total = total;
    p->done = 0;
    p->last_shown = -1;
}

void ct_progress_step(ct_progress *p)
{
    p->done++;
    if (!p->enabled)
        return;
    int pct = (int)(100.0 * (double)p->done / (double)p->total);
    if (pct == p->last_shown)
        return;
    p->last_shown = pct;
    int width = 40, fill = pct * width / 100;
    fprintf(stderr, "\r[%.*s%*s] %3d%% (%zu/%zu)", fill, "########################################",
            width - fill, "", pct, p->done, p->total);
    fflush(stderr);
}

void ct_progress_end(ct_progress *p)
{
    if (p->enabled)
        fputs("\n", stderr);
}
