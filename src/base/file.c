/* Atomic file writes (temporary beside the target, then rename), whole-file reads, mkdir -p. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/dist_internal.h"
#include "lucent/dist.h"
#include "lucent/output.h"

struct lucent_atomic_file {
    FILE *fp;
    char *path;
    char *tmp;
};

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

static mode_t current_umask(void)
{
    mode_t m = umask(022);
    umask(m);
    return m;
}

static void atomic_free(lucent_atomic_file *af)
{
    free(af->path);
    free(af->tmp);
    free(af);
}

/* The writes of a process that writes no outputs (an MPI rank other than 0, a part): to /dev/null,
 * tmp NULL, so that commit and abort only close it. */
static lucent_status open_nowhere(const char *path, lucent_atomic_file **dest, FILE **out)
{
    lucent_atomic_file *af = calloc(1, sizeof *af);
    if (af) af->fp = fopen("/dev/null", "wb");
    if (!af || !af->fp) {
        free(af);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot open /dev/null", path);
    }
    *dest = af;
    *out = af->fp;
    return LUCENT_OK;
}

lucent_status lucent_atomic_open(const char *path, lucent_atomic_file **dest, FILE **out)
{
    *dest = NULL;
    *out = NULL;
    if (!path || !*path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "empty output path");
    if (!dist_open_output(path)) return open_nowhere(path, dest, out);
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write: is a directory", path);
    if (g_create_parents) {
        lucent_status ps = make_parent(path);
        if (ps != LUCENT_OK) return ps;
    }
    lucent_atomic_file *af = calloc(1, sizeof *af);
    size_t n = strlen(path);
    if (af) af->path = strdup(path);
    if (af) af->tmp = malloc(n + 12);
    if (!af || !af->path || !af->tmp) {
        if (af) atomic_free(af);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    snprintf(af->tmp, n + 12, "%s.tmpXXXXXX", path);
    int fd = mkstemp(af->tmp);
    if (fd < 0) {
        int e = errno;
        atomic_free(af);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s", path, strerror(e));
    }
    fchmod(fd, 0666 & ~current_umask());
    af->fp = fdopen(fd, "wb");
    if (!af->fp) {
        int e = errno;
        close(fd);
        unlink(af->tmp);
        atomic_free(af);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot create: %s", path, strerror(e));
    }
    *dest = af;
    *out = af->fp;
    return LUCENT_OK;
}

lucent_status lucent_atomic_commit(lucent_atomic_file *af)
{
    bool ok = fflush(af->fp) == 0 && !ferror(af->fp);
    int e = errno;
    if (ok && fsync(fileno(af->fp)) != 0 && errno != EINVAL) ok = false, e = errno;
    if (fclose(af->fp) != 0 && ok) ok = false, e = errno;
    af->fp = NULL;
    if (!af->tmp) { /* nowhere */
        atomic_free(af);
        return LUCENT_OK;
    }
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

lucent_status lucent_write_file(const char *path, const void *data, size_t size)
{
    lucent_atomic_file *af;
    FILE *fp;
    lucent_status s = lucent_atomic_open(path, &af, &fp);
    if (s != LUCENT_OK) return s;
    if (size && fwrite(data, 1, size, fp) != size) {
        int e = errno;
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", path, strerror(e));
    }
    return lucent_atomic_commit(af);
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
    while (buf) {
        len += fread(buf + len, 1, cap - len, fp);
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
        return lucent_error(LUCENT_ERR_IO, "%s: read failed (is it a directory?)", path);
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
