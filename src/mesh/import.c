/* Mesh import. PLY (ASCII/binary, .ply.gz) and OBJ go through Lucent's own readers (ply.c, obj.c),
 * written for hostile input. The other formats (glTF/GLB, STL, OFF) go through assimp's C API, which
 * is not: its file system is restricted to the mesh's own bytes (a custom aiFileIO refusing any other
 * name, so a reference to /etc/passwd or ../../x.mtl reads nothing), post-processing is kept to
 * triangulation and flattening the node transforms, and the import runs in a child process under CPU
 * and time limits, so that a crash or a hang there becomes an error naming the file. */
#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "mesh/internal.h"
#include "mesh/reader.h"

lucent_status lucent_mesh_obj_read(lucent_reader *r, lucent_mesh **dest);

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

/* The format from a file name: "ply" for x.ply and x.ply.gz, etc. */
static lucent_status format_from_path(const char *path, char *dest, size_t size)
{
    char name[4096];
    snprintf(name, sizeof name, "%s", path);
    if (has_suffix(name, ".gz")) name[strlen(name) - 3] = '\0';
    const char *dot = strrchr(name, '.');
    static const char *const known[] = {"ply", "obj", "gltf", "glb", "stl", "off"};
    for (size_t i = 0; dot && i < sizeof known / sizeof known[0]; i++)
        if (strcasecmp(dot + 1, known[i]) == 0) {
            snprintf(dest, size, "%s", known[i]);
            return LUCENT_OK;
        }
    return lucent_error(LUCENT_ERR_UNSUPPORTED,
                        "%s: unknown mesh format (expected .ply, .ply.gz, .obj, .gltf, .glb, .stl or .off)", path);
}

/* ---- PLY ------------------------------------------------------------------------ */

static lucent_status mesh_from_ply(lucent_ply *ply, const char *name, lucent_mesh **dest)
{
    static const char *const xyz[] = {"x", "y", "z"};
    lucent_ply_data d;
    lucent_status s =
        lucent_ply_read(ply, &(lucent_ply_read_desc){.names = xyz, .count = 3, .faces = LUCENT_PLY_FACES_REQUIRED}, &d);
    if (s != LUCENT_OK) return s;
    if (d.triangle_count == 0) s = lucent_error(LUCENT_ERR_PARSE, "%s: no faces in the file", name);
    if (d.triangle_count > UINT32_MAX / 3)
        s = lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: %zu triangles: too many", name, d.triangle_count);
    if (s == LUCENT_OK) s = lucent_mesh_create(0, 0, dest);
    if (s == LUCENT_OK) {
        /* Hand the arrays over instead of copying them. */
        lucent_mesh *m = *dest;
        free(m->positions), free(m->normals), free(m->faces);
        m->vertex_count = d.vertex_count, m->face_count = d.triangle_count;
        m->positions = d.values, m->faces = d.triangles;
        m->normals = calloc(3 * d.vertex_count + 1, sizeof *m->normals);
        mesh_advise_large(m->normals, 3 * d.vertex_count * sizeof *m->normals);
        d.values = NULL, d.triangles = NULL;
        if (!m->normals) {
            lucent_mesh_destroy(m), *dest = NULL;
            s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
        }
    }
    lucent_ply_data_free(&d);
    return s;
}

/* ---- assimp, in a child, on a closed file system ------------------------------------ */

typedef struct memfile {
    const unsigned char *data;
    size_t size, pos;
} memfile;

static const char k_import_name[] = "lucent-mesh-input";

static size_t mem_read(struct aiFile *f, char *dest, size_t size, size_t count)
{
    memfile *m = (memfile *)f->UserData;
    if (size == 0) return 0;
    size_t items = (m->size - m->pos) / size;
    if (items > count) items = count;
    memcpy(dest, m->data + m->pos, items * size);
    m->pos += items * size;
    return items;
}

static size_t mem_write(struct aiFile *f, const char *src, size_t size, size_t count)
{
    (void)f, (void)src, (void)size, (void)count;
    return 0;
}

static size_t mem_tell(struct aiFile *f) { return ((memfile *)f->UserData)->pos; }
static size_t mem_size(struct aiFile *f) { return ((memfile *)f->UserData)->size; }
static void mem_flush(struct aiFile *f) { (void)f; }

static enum aiReturn mem_seek(struct aiFile *f, size_t offset, enum aiOrigin origin)
{
    memfile *m = (memfile *)f->UserData;
    size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? m->pos : m->size;
    /* assimp passes negative offsets from the end as size_t: wraps modulo 2^64 as intended. */
    size_t to = base + offset;
    if (to > m->size) return aiReturn_FAILURE;
    m->pos = to;
    return aiReturn_SUCCESS;
}

/* Opens only the mesh's own bytes (under the name given to assimp); every other name is refused. */
static struct aiFile *mem_open(struct aiFileIO *io, const char *path, const char *mode)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    if (strncmp(base, k_import_name, sizeof k_import_name - 1) != 0 || strchr(mode, 'w') || strchr(mode, 'a'))
        return NULL;
    const memfile *src = (const memfile *)io->UserData;
    struct aiFile *f = calloc(1, sizeof *f);
    memfile *m = calloc(1, sizeof *m);
    if (!f || !m) {
        free(f), free(m);
        return NULL;
    }
    *m = (memfile){src->data, src->size, 0};
    f->ReadProc = mem_read, f->WriteProc = mem_write, f->TellProc = mem_tell, f->FileSizeProc = mem_size;
    f->SeekProc = mem_seek, f->FlushProc = mem_flush, f->UserData = (aiUserData)m;
    return f;
}

static void mem_close(struct aiFileIO *io, struct aiFile *f)
{
    (void)io;
    if (!f) return;
    free(f->UserData);
    free(f);
}

/* What the child sends: a header, then positions (3 doubles per vertex) and faces (3 uint32 each), or an
 * error message of `message_len` bytes. */
typedef struct child_header {
    uint32_t magic;
    int32_t status;
    uint64_t vertex_count, face_count, message_len;
} child_header;

#define CHILD_MAGIC 0x4c4d4553u

static int write_all(int fd, const void *data, size_t n)
{
    const char *p = data;
    while (n > 0) {
        ssize_t k = write(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return 0;
        p += k, n -= (size_t)k;
    }
    return 1;
}

static int read_all(int fd, void *data, size_t n)
{
    char *p = data;
    while (n > 0) {
        ssize_t k = read(fd, p, n);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) return 0;
        p += k, n -= (size_t)k;
    }
    return 1;
}

static void child_fail(int fd, lucent_status status, const char *message)
{
    size_t n = strlen(message);
    if (n > 900) n = 900;
    child_header h = {CHILD_MAGIC, (int32_t)status, 0, 0, n};
    write_all(fd, &h, sizeof h);
    write_all(fd, message, n);
}

/* True when every face index of every mesh names one of its vertices. */
static int scene_valid(const struct aiScene *sc)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        if (!am || (am->mNumFaces && !am->mFaces) || (am->mNumVertices && !am->mVertices)) return 0;
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices && !face->mIndices) return 0;
            for (unsigned j = 0; j < face->mNumIndices; j++)
                if (face->mIndices[j] >= am->mNumVertices) return 0;
        }
    }
    return 1;
}

#if defined(__SANITIZE_ADDRESS__)
#define IMPORT_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IMPORT_SANITIZED 1
#endif
#endif

/* Under a sanitizer: the callback it runs before dying of an error it found. libFuzzer sets one that saves
 * the input as a finding of its own; in the child, an error of assimp's must end the child only (the
 * parent reports it), so the child replaces it. Weak: absent (NULL) without a sanitizer. */
extern void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

static void child_death(void) { _exit(70); }

enum { CHILD_OUT_OF_MEMORY = 71, CHILD_MEMORY_MB = 48 };

#ifdef IMPORT_SANITIZED
/* Under a sanitizer the address-space limit cannot bound the child (the shadow memory alone exceeds any
 * sensible one), so the child measures its resident set every 5 ms of CPU time and ends itself past its
 * budget: CHILD_MEMORY_MB plus 64 bytes per input byte above what it started with (fuzz_mesh: a 127-byte
 * glTF on which assimp allocates without end). Async-signal-safe: open, read, _exit. */
static long child_rss_limit; /* pages */

static long resident_pages(void)
{
    char buf[96];
    int fd = open("/proc/self/statm", O_RDONLY);
    if (fd < 0) return -1;
    ssize_t n = read(fd, buf, sizeof buf - 1);
    close(fd);
    if (n <= 0) return -1;
    buf[n] = '\0';
    const char *p = buf;
    while (*p && *p != ' ') p++; /* the second field: resident pages */
    while (*p == ' ') p++;
    long pages = 0;
    while (*p >= '0' && *p <= '9') pages = pages * 10 + (*p++ - '0');
    return pages;
}

static void child_rss_check(int sig)
{
    (void)sig;
    if (resident_pages() > child_rss_limit) _exit(CHILD_OUT_OF_MEMORY);
}

static void child_bound_memory(size_t size)
{
    long page = sysconf(_SC_PAGESIZE);
    child_rss_limit = resident_pages() + (long)((((size_t)CHILD_MEMORY_MB << 20) + size * 64) / (size_t)page);
    struct sigaction sa = {.sa_handler = child_rss_check};
    sigaction(SIGPROF, &sa, NULL);
    struct itimerval every = {.it_interval = {0, 5000}, .it_value = {0, 5000}};
    setitimer(ITIMER_PROF, &every, NULL);
}
#endif

/* The child: import, then stream the triangles to fd. Never returns. */
static void assimp_child(int fd, const void *data, size_t size, const char *format)
{
    /* A crash kills the child plainly: the parent's handlers (a sanitizer's, a fuzzer's) must not report it
     * as their own. A hang becomes SIGALRM / SIGXCPU; memory is bounded where no sanitizer reserves shadow
     * memory. */
    static const int crashes[] = {
        SIGSEGV, SIGBUS,  SIGFPE, SIGILL,  SIGABRT, SIGTRAP,
        SIGALRM, SIGXCPU, SIGINT, SIGTERM, SIGHUP}; /* the parent's output cleanup is the parent's */
    for (size_t i = 0; i < sizeof crashes / sizeof crashes[0]; i++) signal(crashes[i], SIG_DFL);
    /* assimp prints (assertions, its logger): nothing of it reaches the user's terminal. */
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, 1), dup2(null, 2), close(null);
    /* Time in proportion to the input: assimp reads tens of MB a second, so 0.7 s plus 1 s per 2 MiB is
     * ample; fuzz_mesh found a 127-byte glTF on which assimp's importer spins (it ran into the 60 s of before). */
    unsigned secs = (unsigned)(size >> 21);
    struct itimerval timer = {.it_value = {.tv_sec = secs, .tv_usec = 700000}};
    setitimer(ITIMER_REAL, &timer, NULL);
    struct rlimit cpu = {secs + 1, secs + 2};
    setrlimit(RLIMIT_CPU, &cpu);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(child_death);
#ifdef IMPORT_SANITIZED
    child_bound_memory(size);
#else
    struct rlimit as = {((rlim_t)4 << 30) + (rlim_t)size * 64, ((rlim_t)4 << 30) + (rlim_t)size * 64};
    setrlimit(RLIMIT_AS, &as);
#endif
    memfile src = {data, size, 0};
    struct aiFileIO io = {mem_open, mem_close, (aiUserData)&src};
    char name[64];
    snprintf(name, sizeof name, "%s.%s", k_import_name, format);
    const struct aiScene *sc = aiImportFileEx(name, 0, &io);
    if (sc && sc->mNumMeshes && !scene_valid(sc)) {
        child_fail(fd, LUCENT_ERR_PARSE, "truncated or malformed: a face refers to a missing vertex");
        _exit(0);
    }
    if (sc && sc->mNumMeshes) sc = aiApplyPostProcessing(sc, aiProcess_Triangulate | aiProcess_PreTransformVertices);
    if (!sc || !sc->mNumMeshes || !scene_valid(sc)) {
        child_fail(fd, LUCENT_ERR_PARSE, sc ? "no meshes" : aiGetErrorString());
        _exit(0);
    }
    uint64_t nv = 0, nf = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        nv += sc->mMeshes[i]->mNumVertices;
        for (unsigned f = 0; f < sc->mMeshes[i]->mNumFaces; f++) nf += sc->mMeshes[i]->mFaces[f].mNumIndices == 3;
    }
    if (nv > UINT32_MAX) {
        child_fail(fd, LUCENT_ERR_UNSUPPORTED, "more than 4294967295 vertices");
        _exit(0);
    }
    int uvs = 1; /* texture coordinates when every part has them (message_len 1: 6 doubles per face follow) */
    for (unsigned i = 0; i < sc->mNumMeshes; i++) uvs = uvs && sc->mMeshes[i]->mTextureCoords[0];
    child_header h = {CHILD_MAGIC, LUCENT_OK, nv, nf, (uint64_t)uvs};
    if (!write_all(fd, &h, sizeof h)) _exit(0);
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            double p[3] = {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z};
            if (!write_all(fd, p, sizeof p)) _exit(0);
        }
    }
    uint64_t v0 = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices != 3) continue;
            uint32_t t[3];
            for (int j = 0; j < 3; j++) t[j] = (uint32_t)(v0 + face->mIndices[j]);
            if (!write_all(fd, t, sizeof t)) _exit(0);
        }
        v0 += am->mNumVertices;
    }
    for (unsigned i = 0; uvs && i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices != 3) continue;
            double c[6];
            for (int j = 0; j < 3; j++)
                c[2 * j] = am->mTextureCoords[0][face->mIndices[j]].x,
                      c[2 * j + 1] = am->mTextureCoords[0][face->mIndices[j]].y;
            if (!write_all(fd, c, sizeof c)) _exit(0);
        }
    }
    _exit(0);
}

static lucent_status assimp_load(const void *data, size_t size, const char *name, const char *format,
                                 lucent_mesh **dest)
{
    if (size > UINT32_MAX) return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: file larger than 4 GiB", name);
    int fds[2];
    if (pipe(fds) != 0) return lucent_error(LUCENT_ERR_IO, "%s: cannot start the importer: %s", name, strerror(errno));
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]), close(fds[1]);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot start the importer: %s", name, strerror(errno));
    }
    if (pid == 0) {
        close(fds[0]);
        signal(SIGPIPE, SIG_IGN);
        assimp_child(fds[1], data, size, format);
    }
    close(fds[1]);
    child_header h;
    lucent_status s = LUCENT_OK;
    int got = read_all(fds[0], &h, sizeof h) && h.magic == CHILD_MAGIC;
    /* What the child may claim is bounded by what the input can describe: each vertex and face takes some
     * bytes of the file (STL: 50 per triangle and 3 vertices; glTF at least 12 per vertex, 2 per index). */
    uint64_t limit = 64 * (uint64_t)size + 4096;
    if (got && h.status != LUCENT_OK) {
        char msg[1024] = {0};
        size_t n = h.message_len < sizeof msg - 1 ? (size_t)h.message_len : sizeof msg - 1;
        read_all(fds[0], msg, n);
        /* assimp's message may quote bytes of the input: keep printable ASCII only. */
        for (size_t i = 0; i < n; i++)
            if (msg[i] < 32 || msg[i] > 126) msg[i] = '?';
        s = lucent_error((lucent_status)h.status == LUCENT_ERR_UNSUPPORTED ? LUCENT_ERR_UNSUPPORTED : LUCENT_ERR_PARSE,
                         "%s: not a readable %s mesh (%s)", name, format, msg);
    } else if (got && (h.vertex_count > limit || h.face_count > limit)) {
        s = lucent_error(LUCENT_ERR_PARSE, "%s: the importer claims more vertices or faces than the file can hold",
                         name);
    } else if (got) {
        s = lucent_mesh_create((size_t)h.vertex_count, (size_t)h.face_count, dest);
        if (s == LUCENT_OK && (!read_all(fds[0], (*dest)->positions, (size_t)h.vertex_count * 3 * sizeof(double)) ||
                               !read_all(fds[0], (*dest)->faces, (size_t)h.face_count * 3 * sizeof(uint32_t)))) {
            lucent_mesh_destroy(*dest), *dest = NULL;
            got = 0;
        }
        if (s == LUCENT_OK && got && h.message_len == 1) { /* the corners' texture coordinates */
            size_t n = (size_t)h.face_count * 6;
            (*dest)->uvs = malloc(n * sizeof(double) + 1);
            if (!(*dest)->uvs) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", name);
            if (s == LUCENT_OK && !read_all(fds[0], (*dest)->uvs, n * sizeof(double))) got = 0;
            for (size_t i = 0; s == LUCENT_OK && got && i < n; i++)
                if (!isfinite((*dest)->uvs[i]))
                    s = lucent_error(LUCENT_ERR_PARSE, "%s: face %zu: texture coordinate not finite", name, i / 6);
        }
    }
    close(fds[0]);
    int wstatus = 0;
    while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
    }
    if (s == LUCENT_OK && (!got || !WIFEXITED(wstatus))) {
        lucent_mesh_destroy(*dest), *dest = NULL;
        if (WIFSIGNALED(wstatus))
            s = lucent_error(
                LUCENT_ERR_PARSE, "%s: malformed %s mesh: the importer (assimp) %s on it (signal %d)", name, format,
                WTERMSIG(wstatus) == SIGALRM || WTERMSIG(wstatus) == SIGXCPU ? "ran out of time" : "crashed",
                WTERMSIG(wstatus));
        else if (WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == CHILD_OUT_OF_MEMORY)
            s = lucent_error(LUCENT_ERR_PARSE,
                             "%s: malformed %s mesh: the importer (assimp) needed more than %zu MB for %zu bytes", name,
                             format, (size_t)CHILD_MEMORY_MB + (size * 64 >> 20), size);
        else
            s = lucent_error(LUCENT_ERR_PARSE, "%s: malformed %s mesh: the importer (assimp) failed", name, format);
    }
    if (s != LUCENT_OK && *dest) lucent_mesh_destroy(*dest), *dest = NULL;
    return s;
}

/* ---- Entry points ---------------------------------------------------------------------- */

/* After reading: finite positions, weld (or normals), no face left. */
static lucent_status finish(lucent_status s, const char *name, const lucent_mesh_load_desc *desc, lucent_mesh **dest)
{
    if (s == LUCENT_OK && (*dest)->face_count == 0)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: no triangles in the file", name);
    for (size_t i = 0; s == LUCENT_OK && i < 3 * (*dest)->vertex_count; i++)
        if (!isfinite((*dest)->positions[i]))
            s = lucent_error(LUCENT_ERR_PARSE, "%s: vertex %zu is not finite", name, i / 3);
    if (s == LUCENT_OK && !(desc && desc->keep_duplicates))
        s = lucent_mesh_weld(*dest);
    else if (s == LUCENT_OK)
        lucent_mesh_compute_normals(*dest);
    if (s == LUCENT_OK && (*dest)->face_count == 0)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: every face is degenerate", name);
    if (s != LUCENT_OK) lucent_mesh_destroy(*dest), *dest = NULL;
    return s;
}

/* Reads the whole (inflated) input for assimp, bounded to 1 GiB. */
static lucent_status slurp(lucent_reader *r, unsigned char **dest, size_t *size)
{
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    lucent_status s = buf ? LUCENT_OK : LUCENT_ERR_OUT_OF_MEMORY;
    while (s == LUCENT_OK) {
        if ((s = lucent_reader_fill(r, r->cap)) != LUCENT_OK) break;
        size_t k = r->len - r->pos;
        if (k == 0) break;
        if (n + k > ((size_t)1 << 30)) {
            s = lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: more than 1 GiB of mesh data", r->name);
            break;
        }
        if (n + k > cap) {
            while (cap < n + k) cap *= 2;
            unsigned char *g = realloc(buf, cap);
            if (!g) {
                s = LUCENT_ERR_OUT_OF_MEMORY;
                break;
            }
            buf = g;
        }
        memcpy(buf + n, r->buf + r->pos, k);
        n += k, r->pos += k;
    }
    if (s == LUCENT_ERR_OUT_OF_MEMORY) lucent_error(s, "%s: out of memory", r->name);
    if (s != LUCENT_OK) {
        free(buf);
        return s;
    }
    *dest = buf, *size = n;
    return LUCENT_OK;
}

static lucent_status load_reader(lucent_reader *r, const char *format, const lucent_mesh_load_desc *desc,
                                 lucent_mesh **dest)
{
    lucent_status s;
    if (strcmp(format, "obj") == 0 && !(desc && desc->use_assimp)) {
        s = lucent_mesh_obj_read(r, dest);
    } else {
        unsigned char *data;
        size_t size;
        s = slurp(r, &data, &size);
        if (s == LUCENT_OK && size == 0) s = lucent_error(LUCENT_ERR_PARSE, "%s: empty file", r->name);
        if (s == LUCENT_OK) {
            s = assimp_load(data, size, r->name, format, dest);
            free(data);
        }
    }
    return finish(s, r->name, desc, dest);
}

lucent_status lucent_mesh_load_memory(const void *data, size_t size, const char *name,
                                      const lucent_mesh_load_desc *desc, lucent_mesh **dest)
{
    *dest = NULL;
    const char *format = desc && desc->format ? desc->format : NULL;
    if (!format) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: no mesh format given", name);
    if (size == 0) return lucent_error(LUCENT_ERR_PARSE, "%s: empty file", name);
    lucent_status s;
    if (strcmp(format, "ply") == 0 && !(desc && desc->use_assimp)) {
        lucent_ply *ply;
        s = lucent_ply_open_memory(data, size, name, &ply);
        if (s == LUCENT_OK) s = mesh_from_ply(ply, name, dest), lucent_ply_close(ply);
        return finish(s, name, desc, dest);
    }
    lucent_reader r;
    if ((s = lucent_reader_open_memory(&r, data, size, name)) != LUCENT_OK) return s;
    s = load_reader(&r, format, desc, dest);
    lucent_reader_close(&r);
    return s;
}

lucent_status lucent_mesh_load(const char *path, const lucent_mesh_load_desc *desc, lucent_mesh **dest)
{
    *dest = NULL;
    if (!path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "mesh: no file given (NULL path)");
    char format[16];
    const char *fmt = desc && desc->format ? desc->format : NULL;
    lucent_status s = LUCENT_OK;
    if (!fmt) {
        if ((s = format_from_path(path, format, sizeof format)) != LUCENT_OK) return s;
        fmt = format;
    }
    if (strcmp(fmt, "ply") == 0 && !(desc && desc->use_assimp)) {
        lucent_ply *ply;
        s = lucent_ply_open(path, &ply);
        if (s == LUCENT_OK) s = mesh_from_ply(ply, path, dest), lucent_ply_close(ply);
        return finish(s, path, desc, dest);
    }
    lucent_reader r;
    if ((s = lucent_reader_open(&r, path)) != LUCENT_OK) return s;
    s = load_reader(&r, fmt, desc, dest);
    lucent_reader_close(&r);
    return s;
}
