/* Atomic file writes (temporary beside the target, then rename), whole-file reads, mkdir -p. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <signal.h>
#include <stdatomic.h>
#include <time.h>

#include "base/dist_internal.h"
#include "base/file_internal.h"
#include "lucent/dist.h"
#include "lucent/output.h"

static bool g_create_parents;

void lucent_files_create_parents(bool on) { g_create_parents = on; }

/* mkdir -p of path's folder, when it is missing. */
static lucent_status make_parent(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash || slash == path) return LUCENT_OK;
    char *dir = strndup(path, (size_t)(slash - path));
    if (!dir) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    struct stat st;
    lucent_status s = stat(dir, &st) == 0 ? LUCENT_OK : lucent_mkdir_p(dir);
    free(dir);
    return s == LUCENT_OK ? s : lucent_error_context(s, "%s", path);
}

static void atomic_free(lucent_atomic_file *af)
{
    outputs_untrack(af->slot);
    outputs_release(af);
    free(af->path);
    free(af->tmp);
    free(af);
}

/* The writes of a process that writes no outputs (an MPI rank other than 0, a part): to /dev/null,
 * tmp NULL, so that commit and abort only close it. */
static lucent_status open_nowhere(const char *path, lucent_atomic_file **dest, FILE **out)
{
    lucent_atomic_file *af = calloc(1, sizeof *af);
    if (af) af->slot = -1, af->fp = fopen("/dev/null", "wb");
    if (!af || !af->fp) {
        free(af);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot open /dev/null", path);
    }
    *dest = af;
    *out = af->fp;
    return LUCENT_OK;
}

/* A fresh temporary name beside the target: path.tmpXXXXXX, from the process id, a counter and the clock. */
static void temp_name(lucent_atomic_file *af, size_t size)
{
    static atomic_uint counter;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    uint64_t h = ((uint64_t)getpid() << 32) ^ (uint64_t)ts.tv_nsec ^ ((uint64_t)atomic_fetch_add(&counter, 1) << 20);
    h *= 0x9e3779b97f4a7c15ull; /* Fibonacci hashing: mixes the bits into the top */
    static const char digits[] = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
    char suffix[7];
    for (int i = 0; i < 6; i++) suffix[i] = digits[(h >> (58 - 6 * i)) % 62];
    suffix[6] = '\0';
    snprintf(af->tmp, size, "%s.tmp%s", af->path, suffix);
}

/* Creates the temporary, named in the signal handler's table before it exists, so that a signal at any
 * moment finds it there (O_EXCL: a name in use is never reused). */
static int create_temp(lucent_atomic_file *af, size_t size)
{
    for (int attempt = 0; attempt < 100; attempt++) {
        temp_name(af, size);
        af->slot = outputs_track(af->tmp);
        int fd = open(af->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST) {
            int e = errno;
            if (fd < 0) outputs_untrack(af->slot), af->slot = -1;
            errno = e;
            return fd;
        }
        outputs_untrack(af->slot), af->slot = -1;
    }
    errno = EEXIST;
    return -1;
}

/* What an output path names, and so how it is written (docs/architecture.md, "Outputs"). */
typedef enum { TARGET_FILE, TARGET_THROUGH } target_kind;

/* Classifies path's target: nothing there or a regular file (TARGET_FILE, written as a temporary beside it and
 * renamed), a character device, FIFO or socket (TARGET_THROUGH: written through, never replaced); a symbolic
 * link is followed: to a regular file it is TARGET_FILE with *file the file's own path (malloc'd), so that
 * the file is replaced and the link kept. A folder, a block device or a link to nothing is refused. *file is
 * NULL when path itself is the file. */
static lucent_status classify_target(const char *path, target_kind *kind, char **file)
{
    *kind = TARGET_FILE;
    *file = NULL;
    struct stat st;
    if (lstat(path, &st) != 0) {
        if (errno == ENOENT || errno == ENOTDIR) return LUCENT_OK; /* the folder's check says more */
        return lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    }
    bool link = S_ISLNK(st.st_mode);
    if (link && stat(path, &st) != 0)
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write: a symbolic link to %s (%s)", path,
                            errno == ENOENT ? "nothing" : "what cannot be reached", strerror(errno));
    if (S_ISDIR(st.st_mode)) return lucent_error(LUCENT_ERR_IO, "%s: cannot write: is a directory", path);
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)) {
        *kind = TARGET_THROUGH;
        return LUCENT_OK;
    }
    if (!S_ISREG(st.st_mode))
        return lucent_error(LUCENT_ERR_IO,
                            "%s: cannot write: %s (outputs are regular files, or a character device or FIFO "
                            "written through)",
                            path, S_ISBLK(st.st_mode) ? "a block device" : "not a regular file");
    if (link && !(*file = realpath(path, NULL)))
        return lucent_error(LUCENT_ERR_IO, "%s: cannot resolve the symbolic link: %s", path, strerror(errno));
    return LUCENT_OK;
}

/* A through output's bytes wait in an unlinked file of TMPDIR (or /tmp) until the output lands. */
static lucent_status open_through(lucent_atomic_file *af)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !*dir) dir = "/tmp";
    int fd = open(dir, O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd < 0) {
        size_t n = strlen(dir) + 24;
        char *name = malloc(n);
        if (!name) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", af->path);
        snprintf(name, n, "%s/lucent-XXXXXX", dir);
        fd = mkostemp(name, O_CLOEXEC);
        if (fd >= 0) unlink(name);
        free(name);
    }
    if (fd >= 0 && !(af->fp = fdopen(fd, "w+b"))) close(fd);
    if (!af->fp)
        return lucent_error(LUCENT_ERR_IO, "%s: cannot make the temporary in %s: %s", af->path, dir, strerror(errno));
    return LUCENT_OK;
}

lucent_status base_write_through(lucent_atomic_file *af)
{
    int in = fileno(af->fp);
    int out = open(af->path, O_WRONLY | O_NOCTTY | O_CLOEXEC);
    struct stat st;
    if (out < 0) return lucent_error(LUCENT_ERR_IO, "%s: cannot open: %s", af->path, strerror(errno));
    if (fstat(out, &st) != 0 || S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)) {
        close(out);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write: it is no longer a device or FIFO", af->path);
    }
    /* A reader that left gives EPIPE, not a SIGPIPE that would end the process with temporaries left. */
    struct sigaction ignore = {.sa_handler = SIG_IGN}, old;
    sigaction(SIGPIPE, &ignore, &old);
    char buf[1 << 16];
    int e = 0;
    for (off_t at = 0;;) {
        ssize_t got = pread(in, buf, sizeof buf, at);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
            e = got < 0 ? errno : 0;
            break;
        }
        at += got;
        for (ssize_t put = 0; put < got && !e;) {
            ssize_t w = write(out, buf + put, (size_t)(got - put));
            if (w > 0)
                put += w;
            else if (w < 0 && errno != EINTR)
                e = errno;
        }
        if (e) break;
    }
    sigaction(SIGPIPE, &old, NULL);
    if (close(out) != 0 && !e && errno != EINTR) e = errno;
    return e ? lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", af->path, strerror(e)) : LUCENT_OK;
}

static lucent_status atomic_open(const char *path, bool direct, lucent_atomic_file **dest, FILE **out)
{
    *dest = NULL;
    *out = NULL;
    if (!path || !*path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "empty output path");
    if (!dist_open_output(path)) return open_nowhere(path, dest, out);
    target_kind kind;
    char *file;
    lucent_status ks = classify_target(path, &kind, &file);
    if (ks != LUCENT_OK) return ks;
    if (file) path = file; /* a link to a regular file: the file is replaced, not the link */
    if (g_create_parents && kind == TARGET_FILE) {
        lucent_status ps = make_parent(path);
        if (ps != LUCENT_OK) return free(file), ps;
    }
    lucent_atomic_file *af = calloc(1, sizeof *af);
    size_t n = strlen(path);
    if (af) af->slot = -1, af->direct = direct, af->path = strdup(path), af->through = kind == TARGET_THROUGH;
    free(file);
    if (af && !af->through) af->tmp = malloc(n + 12);
    if (!af || !af->path || (!af->through && !af->tmp)) {
        if (af) atomic_free(af);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    if (af->through) {
        lucent_status ts = open_through(af);
        if (ts != LUCENT_OK) return atomic_free(af), ts;
        *dest = af;
        *out = af->fp;
        return LUCENT_OK;
    }
    lucent_status cs = direct ? LUCENT_OK : outputs_claim(af);
    if (cs != LUCENT_OK) {
        atomic_free(af);
        return cs;
    }
    int fd = create_temp(af, n + 12);
    if (fd < 0) {
        int e = errno;
        lucent_status err = lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s", af->path, strerror(e));
        atomic_free(af);
        return err;
    }
    af->fp = fdopen(fd, "wb");
    if (!af->fp) {
        int e = errno;
        close(fd);
        unlink(af->tmp);
        lucent_status err = lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s", af->path, strerror(e));
        atomic_free(af);
        return err;
    }
    *dest = af;
    *out = af->fp;
    return LUCENT_OK;
}

lucent_status lucent_atomic_open(const char *path, lucent_atomic_file **dest, FILE **out)
{
    return atomic_open(path, false, dest, out);
}

/* A through output's commit: its bytes are complete; written now, or when the open set lands. */
static lucent_status commit_through(lucent_atomic_file *af)
{
    bool ok = fflush(af->fp) == 0 && !ferror(af->fp);
    int e = errno;
    lucent_status s = ok ? LUCENT_OK : lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", af->path, strerror(e));
    if (s == LUCENT_OK && outputs_defer(af)) return LUCENT_OK; /* written by lucent_outputs_end */
    if (s == LUCENT_OK) s = base_write_through(af);
    fclose(af->fp);
    af->fp = NULL;
    atomic_free(af);
    return s;
}

lucent_status lucent_atomic_commit(lucent_atomic_file *af)
{
    if (af->through) return commit_through(af);
    bool ok = fflush(af->fp) == 0 && !ferror(af->fp);
    int e = errno;
    if (ok && fsync(fileno(af->fp)) != 0 && errno != EINVAL) ok = false, e = errno;
    if (fclose(af->fp) != 0 && ok) ok = false, e = errno;
    af->fp = NULL;
    if (!af->tmp) { /* nowhere */
        atomic_free(af);
        return LUCENT_OK;
    }
    if (ok && !af->direct && outputs_defer(af)) return LUCENT_OK; /* renamed by lucent_outputs_end */
    if (ok && rename(af->tmp, af->path) != 0) ok = false, e = errno;
    if (!ok) {
        unlink(af->tmp);
        lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", af->path, e ? strerror(e) : "I/O error");
    }
    atomic_free(af);
    return ok ? LUCENT_OK : LUCENT_ERR_IO;
}

void lucent_atomic_abort(lucent_atomic_file *af)
{
    if (!af) return;
    if (af->fp) fclose(af->fp);
    if (af->tmp) unlink(af->tmp);
    atomic_free(af);
}

/* dir (where an output of `what` goes) can be written: its nearest existing ancestor is a folder this process
 * may create files in, and the missing ones below it will be made (lucent_files_create_parents). */
static lucent_status check_folder(const char *what, const char *dir)
{
    char *d = strdup(*dir ? dir : ".");
    if (!d) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", what);
    lucent_status s = LUCENT_OK;
    for (bool missing = false;; missing = true) {
        struct stat st;
        if (stat(d, &st) == 0) {
            if (!S_ISDIR(st.st_mode))
                s = lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s is not a folder", what, d);
            else if (missing && !g_create_parents)
                s = lucent_error(LUCENT_ERR_IO, "%s: cannot create: a folder above it is missing", what);
            else if (faccessat(AT_FDCWD, d, W_OK | X_OK, AT_EACCESS) != 0)
                s = lucent_error(LUCENT_ERR_IO, "%s: cannot create: the folder %s is not writable (%s)", what, d,
                                 strerror(errno));
            break;
        }
        if (errno != ENOENT && errno != ENOTDIR) { /* ENOTDIR: the one above says which is not a folder */
            s = lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s: %s", what, d, strerror(errno));
            break;
        }
        char *slash = strrchr(d, '/');
        while (slash && slash > d && slash[-1] == '/') slash--; /* "a//b" */
        if (!slash)
            strcpy(d, ".");
        else if (slash == d)
            d[1] = '\0';
        else
            *slash = '\0';
    }
    free(d);
    return s;
}

lucent_status lucent_output_check(const char *path)
{
    if (!path || !*path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "empty output path");
    if (lucent_dist_rank() != 0) return LUCENT_OK; /* rank 0 writes */
    target_kind kind;
    char *file;
    lucent_status s = classify_target(path, &kind, &file);
    if (s != LUCENT_OK) return s;
    const char *target = file ? file : path;
    struct stat st;
    if (kind == TARGET_THROUGH) {
        if (faccessat(AT_FDCWD, target, W_OK, AT_EACCESS) != 0)
            s = lucent_error(LUCENT_ERR_IO, "%s: cannot write: %s", path, strerror(errno));
    } else {
        const char *slash = strrchr(target, '/');
        char *dir = slash ? strndup(target, (size_t)(slash == target ? 1 : slash - target)) : strdup(".");
        s = dir ? check_folder(path, dir) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
        free(dir);
        if (s == LUCENT_OK && stat(target, &st) == 0) outputs_plan(&st);
    }
    free(file);
    return s;
}

lucent_status lucent_output_check_folder(const char *dir)
{
    if (!dir || !*dir) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "empty output folder");
    if (lucent_dist_rank() != 0) return LUCENT_OK;
    return check_folder(dir, dir);
}

static lucent_status write_file(const char *path, bool direct, const void *data, size_t size)
{
    lucent_atomic_file *af;
    FILE *fp;
    lucent_status s = atomic_open(path, direct, &af, &fp);
    if (s != LUCENT_OK) return s;
    if (size && fwrite(data, 1, size, fp) != size) {
        int e = errno;
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", path, strerror(e));
    }
    return lucent_atomic_commit(af);
}

lucent_status lucent_write_file(const char *path, const void *data, size_t size)
{
    return write_file(path, false, data, size);
}

lucent_status base_write_file_direct(const char *path, const void *data, size_t size)
{
    return write_file(path, true, data, size);
}

lucent_status lucent_write_file_now(const char *path, const void *data, size_t size)
{
    return base_write_file_direct(path, data, size);
}

lucent_status lucent_open_regular(const char *path, int *fd, uint64_t *size)
{
    *fd = -1;
    if (size) *size = 0;
    /* O_NONBLOCK so that opening a FIFO with no writer does not block; cleared after the check. */
    int f = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (f < 0) return lucent_error(LUCENT_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat st;
    if (fstat(f, &st) != 0 || !S_ISREG(st.st_mode)) {
        const char *what = S_ISDIR(st.st_mode)                          ? "a directory"
                           : S_ISFIFO(st.st_mode)                       ? "a FIFO"
                           : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                                        : "not a regular file";
        close(f);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot read: %s (only regular files are read)", path, what);
    }
    lucent_status ns = outputs_note_input(path, &st);
    if (ns != LUCENT_OK) return close(f), ns;
    int flags = fcntl(f, F_GETFL);
    if (flags >= 0) fcntl(f, F_SETFL, flags & ~O_NONBLOCK);
    *fd = f;
    if (size) *size = (uint64_t)st.st_size;
    return LUCENT_OK;
}

lucent_status lucent_fopen_regular(const char *path, FILE **dest, uint64_t *size)
{
    *dest = NULL;
    int fd;
    lucent_status s = lucent_open_regular(path, &fd, size);
    if (s != LUCENT_OK) return s;
    *dest = fdopen(fd, "rb");
    if (!*dest) {
        close(fd);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    return LUCENT_OK;
}

lucent_status lucent_read_file(const char *path, char **dest, size_t *size)
{
    *dest = NULL;
    if (size) *size = 0;
    FILE *fp;
    lucent_status st = lucent_fopen_regular(path, &fp, NULL);
    if (st != LUCENT_OK) return st;
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap + 1);
    int read_errno = 0;
    while (buf) {
        errno = 0;
        len += fread(buf + len, 1, cap - len, fp);
        read_errno = errno;
        if (len < cap) break;
        char *bigger = realloc(buf, 2 * cap + 1);
        if (!bigger) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = bigger;
        cap *= 2;
    }
    bool bad = ferror(fp);
    fclose(fp);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    if (bad) {
        free(buf);
        return lucent_error(LUCENT_ERR_IO, "%s: read failed: %s", path,
                            read_errno ? strerror(read_errno) : "I/O error");
    }
    buf[len] = '\0';
    *dest = buf;
    if (size) *size = len;
    return LUCENT_OK;
}

/* One component of lucent_mkdir_p: made now, or there already as a directory. */
static lucent_status make_one(const char *p)
{
    if (mkdir(p, 0777) == 0) return LUCENT_OK;
    int e = errno;
    struct stat st;
    if (e == EEXIST && stat(p, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return LUCENT_OK;
        e = ENOTDIR;
    }
    return lucent_error(LUCENT_ERR_IO, "%s: cannot create the folder: %s", p, strerror(e));
}

lucent_status lucent_mkdir_p(const char *dir)
{
    if (!dir || !*dir) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "empty folder path");
    char *p = strdup(dir);
    if (!p) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", dir);
    lucent_status s = LUCENT_OK;
    for (char *q = p + 1; s == LUCENT_OK; q++) { /* each prefix that ends before a '/', then all */
        if (*q != '/' && *q != '\0') continue;
        char c = *q;
        *q = '\0';
        s = make_one(p);
        *q = c;
        if (!c) break;
    }
    free(p);
    return s;
}

lucent_status lucent_read_text_file(const char *path, char **dest)
{
    size_t size;
    lucent_status s = lucent_read_file(path, dest, &size);
    if (s == LUCENT_OK && strlen(*dest) != size) {
        free(*dest);
        *dest = NULL;
        s = lucent_error(LUCENT_ERR_PARSE, "%s: not a text file", path);
    }
    return s;
}
