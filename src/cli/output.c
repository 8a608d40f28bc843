#define _XOPEN_SOURCE 700 /* realpath */
#include "output.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- temporary files still to remove when the process dies ---- */

#define CT_MAX_LIVE 64
static char *volatile live[CT_MAX_LIVE];

static void remove_live(void)
{
    for (int k = 0; k < CT_MAX_LIVE; k++) {
        char *p = live[k];
        if (p)
            unlink(p); /* async-signal-safe */
    }
}

static void on_signal(int sig)
{
    remove_live();
    signal(sig, SIG_DFL);
    raise(sig); /* delivered when the handler returns (a fault: when it recurs), by default */
}

/* Every signal whose default action ends the process (SIGKILL and SIGSTOP aside, which no
 * handler sees), the real-time ones too; SIGXFSZ is not among them: it is ignored instead. */
static const int fatal_signals[] = {
    SIGHUP,    SIGINT,  SIGQUIT, SIGILL,  SIGTRAP, SIGABRT, SIGBUS, SIGFPE,    SIGSEGV,
    SIGUSR1,   SIGUSR2, SIGPIPE, SIGALRM, SIGTERM, SIGXCPU, SIGSYS, SIGVTALRM, SIGPROF,
#ifdef SIGSTKFLT
    SIGSTKFLT,
#endif
#ifdef SIGIO
    SIGIO,
#endif
#ifdef SIGPWR
    SIGPWR,
#endif
#ifdef SIGEMT
    SIGEMT,
#endif
#ifdef SIGLOST
    SIGLOST,
#endif
};
#define NFATAL (sizeof fatal_signals / sizeof fatal_signals[0])

/* The signals the handler was installed for (those at their default action then). */
static sigset_t handled;

static void handle(int sig)
{
    struct sigaction old, sa;
    /* ignored, or handled by someone else (a sanitizer, an MPI runtime): left as it is */
    if (sigaction(sig, NULL, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL)
        return;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(sig, &sa, NULL) == 0)
        sigaddset(&handled, sig);
}

/* The handlers, once, before the first output is opened: every signal that would end the
 * process at its default action unlinks what is live, then ends it as before (a killed run
 * leaves no temporary file); exit() (also libgomp's, when it cannot create a thread) unlinks
 * it too. SIGXFSZ (a file beyond ulimit -f) is ignored, so that the write fails with EFBIG and
 * the run says so (exit 2) rather than die without a word. Signals the caller ignores stay
 * ignored. */
static void install_cleanup(void)
{
    static int done;
    if (done)
        return;
    done = 1;
    atexit(remove_live);
    sigemptyset(&handled);
    for (size_t k = 0; k < NFATAL; k++)
        handle(fatal_signals[k]);
#if defined(SIGRTMIN) && defined(SIGRTMAX)
    for (int sig = SIGRTMIN; sig <= SIGRTMAX; sig++)
        handle(sig);
#endif
    struct sigaction old;
    if (sigaction(SIGXFSZ, NULL, &old) == 0 && !(old.sa_flags & SA_SIGINFO) &&
        old.sa_handler == SIG_DFL)
        signal(SIGXFSZ, SIG_IGN);
}

/* Holds the handled signals back while files are created or renamed, so that a signal
 * between two steps (a temporary file made but not yet registered, one output renamed and
 * the next not) finds everything either before or after: delivered at release. */
static void hold_signals(sigset_t *old)
{
    sigprocmask(SIG_BLOCK, &handled, old);
}

static void release_signals(const sigset_t *old)
{
    sigprocmask(SIG_SETMASK, old, NULL);
}

static void live_add(char *path)
{
    for (int k = 0; k < CT_MAX_LIVE; k++)
        if (!live[k]) {
            live[k] = path;
            return;
        }
}

static void live_remove(const char *path)
{
    for (int k = 0; k < CT_MAX_LIVE; k++)
        if (live[k] == path)
            live[k] = NULL;
}

/* ---- opening ---- */

/* A path for a one-line message: long ones keep their head and tail. */
static void short_path(char *buf, size_t n, const char *path)
{
    size_t len = strlen(path);
    if (len <= 120)
        snprintf(buf, n, "%s", path);
    else
        snprintf(buf, n, "%.60s...%s (%zu characters)", path, path + len - 40, len);
}

static int fail(ct_out *o, char *err, size_t errlen, const char *what, int errnum)
{
    char shown[200];
    short_path(shown, sizeof shown, o->shown ? o->shown : "output");
    snprintf(err, errlen, "%s: cannot write: %s", shown, what ? what : strerror(errnum));
    ct_out_abort(o);
    return -1;
}

/* An unlinked spool file in $TMPDIR (or /tmp). */
static FILE *spool(void)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir)
        dir = "/tmp";
    size_t n = strlen(dir) + 32;
    char *name = malloc(n);
    if (!name)
        return NULL;
    snprintf(name, n, "%s/cantact-spool-XXXXXX", dir);
    int fd = mkstemp(name);
    if (fd >= 0)
        unlink(name);
    free(name);
    if (fd < 0)
        return NULL;
    FILE *f = fdopen(fd, "w+");
    if (!f)
        close(fd);
    return f;
}

/* A larger buffer for o->f (stdio's is 4 KiB: a system call per 4 KiB of rows); without
 * memory for it, stdio's own. 64 KiB: a 2000-speed sweep's 544 KB of rows in 9 writes; a
 * 1 MiB buffer wrote them in one but took 117 more page faults (about 1.5 us each on the CI
 * machine) than the 9 calls cost. */
static void big_buffer(ct_out *o)
{
    enum { SIZE = 1 << 16 };
    if (o->f && (o->buf = malloc(SIZE)) && setvbuf(o->f, o->buf, _IOFBF, SIZE) != 0) {
        free(o->buf);
        o->buf = NULL;
    }
}

/* A name for mkstemp in path's directory (a rename stays in one filesystem): path's own name,
 * cut where needed so that with `tag` and six random characters it stays within the
 * directory's longest name (a 250-byte name has room for the output but not for
 * NAME.tmpXXXXXX) and the whole within PATH_MAX, never inside a UTF-8 character. malloc'ed;
 * NULL when out of memory. */
static char *name_beside(const char *path, const char *tag)
{
    const char *slash = strrchr(path, '/');
    const size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0, tail = strlen(tag) + 6;
    const char *base = path + dirlen;
    char *dir = dirlen ? strndup(path, dirlen) : strdup(".");
    if (!dir)
        return NULL;
    long name_max = 255;
    errno = 0;
    const long m = pathconf(dir, _PC_NAME_MAX);
    free(dir);
    if (m > (long)tail && m < name_max)
        name_max = m;
    /* and the whole path within PATH_MAX (a legal path of a short name near it) */
    size_t room = (size_t)name_max - tail;
    if (dirlen + tail < PATH_MAX && PATH_MAX - 1 - dirlen - tail < room)
        room = PATH_MAX - 1 - dirlen - tail;
    size_t keep = strlen(base);
    if (keep > room) {
        keep = room;
        while (keep > 0 && ((unsigned char)base[keep] & 0xC0) == 0x80)
            keep--; /* base[keep] continues a character: cut before it */
    }
    char *name = malloc(dirlen + keep + tail + 1);
    if (name)
        sprintf(name, "%.*s%.*s%sXXXXXX", (int)dirlen, path, (int)keep, base, tag);
    return name;
}

static int stdout_closed;

void ct_out_guard_std(void)
{
    for (int fd = 0; fd <= 2; fd++) {
        if (fcntl(fd, F_GETFD) != -1 || errno != EBADF)
            continue;
        stdout_closed |= fd == 1;
        int n = open("/dev/null", O_RDONLY); /* read-only: a write to it fails, as it should */
        if (n >= 0 && n != fd) { /* a lower descriptor was closed too: filled in order */
            dup2(n, fd);
            close(n);
        }
    }
}

int ct_out_open(ct_out *o, const char *path, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    install_cleanup();
    if (!(o->shown = strdup(path)))
        return fail(o, err, errlen, "out of memory", 0);
    if (!strcmp(path, "-") && stdout_closed)
        return fail(o, err, errlen, "standard output is closed: give -o FILE", 0);
    if (!strcmp(path, "-")) {
        o->spooled = 1;
        if (!(o->f = spool()))
            return fail(o, err, errlen, NULL, errno);
        big_buffer(o);
        return 0;
    }
    if (!*path)
        return fail(o, err, errlen, "empty path", 0);
    /* a symbolic link: the rows go to its target, which is what gets replaced */
    struct stat st;
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
        struct stat target_st;
        if (stat(path, &target_st) != 0)
            return fail(o, err, errlen,
                        errno == ENOENT ? "a symbolic link whose target does not exist" : NULL,
                        errno);
        /* a link to a regular file: the file is replaced; to anything else (/dev/stdout to
         * a pipe, whose target has no name to resolve): written in place through the link */
        char *target = S_ISREG(target_st.st_mode) ? realpath(path, NULL) : strdup(path);
        if (!target)
            return fail(o, err, errlen, NULL, errno);
        o->path = target;
    } else if (!(o->path = strdup(path))) {
        return fail(o, err, errlen, "out of memory", 0);
    }
    if (stat(o->path, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return fail(o, err, errlen, "is a directory", 0);
        if (access(o->path, W_OK) != 0)
            return fail(o, err, errlen, NULL, errno);
        if (!S_ISREG(st.st_mode)) {
            /* a device or a FIFO: written in place at commit, never renamed over (as root,
             * renaming over /dev/null would replace the device with a file) */
            o->spooled = 1;
            if (!(o->f = spool()))
                return fail(o, err, errlen, NULL, errno);
            big_buffer(o);
            return 0;
        }
        o->mode = st.st_mode & 07777;
    } else if (errno != ENOENT) {
        return fail(o, err, errlen, NULL, errno);
    } else {
        mode_t mask = umask(0); /* read the umask (the CLI is single-threaded here) */
        umask(mask);
        o->mode = 0666 & ~mask;
    }
    if (!(o->tmp_path = name_beside(o->path, ".tmp")))
        return fail(o, err, errlen, "out of memory", 0);
    sigset_t held;
    hold_signals(&held);
    int fd = mkstemp(o->tmp_path);
    if (fd >= 0)
        live_add(o->tmp_path);
    release_signals(&held);
    if (fd < 0) {
        int e = errno;
        free(o->tmp_path);
        o->tmp_path = NULL;
        return fail(o, err, errlen, NULL, e);
    }
    if (fchmod(fd, o->mode) != 0 || !(o->f = fdopen(fd, "w"))) {
        int e = errno;
        close(fd);
        return fail(o, err, errlen, NULL, e);
    }
    big_buffer(o);
    return 0;
}

/* ---- committing ---- */

/* Phase 1: everything written and closed (regular files) or flushed (spools). */
static int finish(ct_out *o, char *err, size_t errlen)
{
    errno = 0;
    int bad = fflush(o->f) != 0 || ferror(o->f), e = errno;
    if (!o->spooled) {
        if (!bad && fsync(fileno(o->f)) != 0 && errno != EINVAL)
            bad = 1, e = errno;
        if (fclose(o->f) != 0 && !bad)
            bad = 1, e = errno;
        o->f = NULL;
        free(o->buf);
        o->buf = NULL;
    }
    /* an earlier write failed and the last flush had nothing left to say why */
    if (bad)
        snprintf(err, errlen, "%s: cannot write: %s",
                 o->spooled && !o->path ? "standard output" : o->shown,
                 e ? strerror(e) : "a write failed (disk full, or a file size limit)");
    return bad ? -1 : 0;
}

/* Copies a spool to standard output or to its special file, in place. */
static int copy_spool(ct_out *o, char *err, size_t errlen)
{
    int fd = o->path ? open(o->path, O_WRONLY | O_NOCTTY) : STDOUT_FILENO;
    int bad = fd < 0 || fseek(o->f, 0, SEEK_SET) != 0;
    char buf[1 << 16];
    size_t got;
    if (!o->path)
        fflush(stdout);
    while (!bad && (got = fread(buf, 1, sizeof buf, o->f)) > 0) {
        size_t done = 0;
        while (done < got) {
            ssize_t w = write(fd, buf + done, got - done);
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0) {
                bad = 1;
                break;
            }
            done += (size_t)w;
        }
    }
    if (ferror(o->f))
        bad = 1;
    if (o->path && fd >= 0 && close(fd) != 0)
        bad = 1;
    if (bad)
        snprintf(err, errlen, "%s: cannot write: %s", o->path ? o->shown : "standard output",
                 strerror(errno ? errno : EIO));
    return bad ? -1 : 0;
}

/* A second name (a hard link) for the file at path, beside it: what a rename over path would
 * drop, kept until every output has landed. NULL when the file system gives none (no hard
 * links there, or path is no longer a file). */
static char *backup_of(const char *path)
{
    for (int tries = 0; tries < 16; tries++) {
        char *name = name_beside(path, ".old");
        int fd = name ? mkstemp(name) : -1; /* a fresh name, then the link takes it */
        if (fd < 0) {
            free(name);
            return NULL;
        }
        close(fd);
        unlink(name);
        if (link(path, name) == 0)
            return name;
        const int e = errno;
        free(name);
        if (e != EEXIST)
            return NULL;
    }
    return NULL;
}

/* Phase 3: the regular outputs renamed into place, all or none. With several, each existing
 * file gets a backup link first; should a rename fail (a directory made where an output
 * goes, a temporary file removed), the outputs already renamed are put back: the old file
 * from its backup, a new one removed. A file that has no backup (a file system without hard
 * links) is renamed last, where no later failure can leave it replaced. */
static int rename_all(ct_out *const *outs, size_t n, char *err, size_t errlen)
{
    size_t regular = 0;
    for (size_t k = 0; k < n; k++)
        regular += !outs[k]->spooled;
    char **bak = calloc(n ? n : 1, sizeof *bak);
    unsigned char *state = calloc(n ? n : 1, 1); /* 1: existed, 2: renamed */
    if (!bak || !state) {
        free(bak);
        free(state);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    sigset_t held;
    hold_signals(&held);
    struct stat st;
    for (size_t k = 0; k < n && regular > 1; k++)
        if (!outs[k]->spooled && lstat(outs[k]->path, &st) == 0) {
            state[k] = 1;
            bak[k] = backup_of(outs[k]->path);
        }
    int bad = 0;
    for (int last = 0; last < 2 && !bad; last++)
        for (size_t k = 0; k < n && !bad; k++) {
            ct_out *o = outs[k];
            if (o->spooled || (state[k] == 1 && !bak[k]) != last)
                continue;
            if (rename(o->tmp_path, o->path) != 0) {
                snprintf(err, errlen, "%s: cannot write: %s", o->shown, strerror(errno));
                bad = 1;
                break;
            }
            state[k] |= 2;
            live_remove(o->tmp_path);
            free(o->tmp_path);
            o->tmp_path = NULL;
        }
    size_t lost = n; /* an output replaced that could not be put back */
    for (size_t k = 0; k < n && bad; k++) {
        if (!(state[k] & 2))
            continue;
        int back;
        if (bak[k])
            back = rename(bak[k], outs[k]->path) == 0;
        else if (state[k] & 1)
            back = 0; /* an old file without a backup: renamed last, so only before another */
        else
            back = unlink(outs[k]->path) == 0;
        if (!back)
            lost = k;
        else if (bak[k]) {
            free(bak[k]);
            bak[k] = NULL;
        }
    }
    if (bad && regular > 1) {
        size_t len = strlen(err);
        if (lost == n)
            snprintf(err + len, errlen - len, " (no output was replaced)");
        else if (bak[lost])
            snprintf(err + len, errlen - len, " (%s was replaced; its old content is in %s)",
                     outs[lost]->shown, bak[lost]);
        else
            snprintf(err + len, errlen - len, " (%s was replaced)", outs[lost]->shown);
    }
    for (size_t k = 0; k < n; k++) {
        if (bak[k] && !(bad && k == lost))
            unlink(bak[k]);
        free(bak[k]);
    }
    release_signals(&held);
    free(bak);
    free(state);
    return bad ? -1 : 0;
}

int ct_out_commit_all(ct_out *const *outs, size_t n, char *err, size_t errlen)
{
    int bad = 0;
    for (size_t k = 0; k < n && !bad; k++)
        bad = finish(outs[k], err, errlen) != 0;
    /* special files first (what reaches a device cannot be taken back, so nothing is renamed
     * into place unless they all took their rows), then the renames */
    for (size_t k = 0; k < n && !bad; k++)
        if (outs[k]->spooled)
            bad = copy_spool(outs[k], err, errlen) != 0;
    if (!bad)
        bad = rename_all(outs, n, err, errlen) != 0;
    for (size_t k = 0; k < n; k++)
        ct_out_abort(outs[k]); /* frees; what was published stays */
    return bad ? -1 : 0;
}

int ct_out_commit(ct_out *o, char *err, size_t errlen)
{
    return ct_out_commit_all(&o, 1, err, errlen);
}

void ct_out_abort(ct_out *o)
{
    if (o->f)
        fclose(o->f);
    o->f = NULL;
    free(o->buf);
    o->buf = NULL;
    if (o->tmp_path) {
        unlink(o->tmp_path);
        live_remove(o->tmp_path);
    }
    free(o->tmp_path);
    free(o->path);
    free(o->shown);
    o->tmp_path = o->path = o->shown = NULL;
}

int ct_out_is_input(const char *output, const char *input)
{
    struct stat si;
    if (!strcmp(input, "-") || stat(input, &si) != 0 || !S_ISREG(si.st_mode))
        return 0; /* standard input, a device or a pipe is read, never replaced */
    return ct_out_same_file(output, input);
}

int ct_out_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (!strcmp(a, "-") || !strcmp(b, "-") || stat(a, &sa) != 0 || stat(b, &sb) != 0)
        return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

void ct_progress_start(ct_progress *p, size_t total)
{
    p->enabled = isatty(STDERR_FILENO) && total > 1;
    p->total = total;
    p->done = 0;
    p->last_shown = -1;
    p->unit = NULL;
}

void ct_progress_to(ct_progress *p, size_t done, size_t total)
{
    const int grew = total != p->total;
    p->done = done;
    p->total = total;
    if (!p->enabled || !total)
        return;
    int pct = (int)(100.0 * (double)done / (double)total);
    if (pct == p->last_shown && !grew)
        return;
    p->last_shown = pct;
    int width = 40, fill = pct * width / 100;
    if (p->unit) /* a total that grows: the counts, no bar that would fill and empty again */
        fprintf(stderr, "\r%zu of %zu %s", p->done, p->total, p->unit);
    else
        fprintf(stderr, "\r[%.*s%*s] %3d%% (%zu/%zu)", fill,
                "########################################", width - fill, "", pct, p->done,
                p->total);
    fflush(stderr);
}

void ct_progress_step(ct_progress *p)
{
    ct_progress_to(p, p->done + 1, p->total);
}

void ct_progress_end(ct_progress *p)
{
    if (p->enabled)
        fputs("\n", stderr);
}
