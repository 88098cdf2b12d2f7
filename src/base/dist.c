/* The process group of a job (lucent/dist.h): MPI ranks, the parts of a job array, or a merge of
 * parts; one process when none of them. Built without MPI (LUCENT_HAVE_MPI undefined) it is the
 * one-process case plus parts and merges.
 *
 * Sums go in rank order: rank 0 adds rank 1's values, then rank 2's, ... and sends the sums back,
 * so even a sum that was not exact would not depend on MPI's reduction algorithm. (Lucent's tallies
 * are exact anyway: integer counters, or doubles that one chunk alone writes, 0 elsewhere.)
 *
 * Part file (native byte order, checked by the order mark):
 *   "LUCENT-PART v2\n\0" (16 bytes), u32 0x01020304, u32 k, u32 n, u32 argc,
 *   argc times: u32 length, the bytes; u32 tally count,
 *   per tally: u32 type (lucent_dist_type), u64 count, count values (8, 8 or 4 bytes each);
 *   u32 the CRC-32 (zlib's) of every byte before it, so that a damaged part is refused.
 * (v1, before issue 32, had no checksum: its parts are refused, naming the version.)
 * I64 tallies are counters (>= 0), F64 tallies finite; the merge refuses others, and sums that overflow. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "base/dist_internal.h"
#include "lucent/dist.h"

#ifdef LUCENT_HAVE_MPI
#include <mpi.h>
#include <time.h>
#endif

#define PART_MAGIC "LUCENT-PART v2\n"
#define PART_MAGIC_V1 "LUCENT-PART v1\n"
#define PART_ORDER 0x01020304u
enum { MAX_PARTS = 65536, MAX_ARGS = 4096, MAX_ARG_BYTES = 65536, MAX_TALLIES = 1 << 20, MESSAGE = 2048 };

typedef struct tally {
    lucent_dist_type type;
    uint64_t count;
    void *data;
} tally;

static struct {
    int rank, size;
    bool mpi;
    /* the agreed failure: once set, no process communicates again */
    bool failed;
    lucent_status status;
    char message[MESSAGE];
    uint64_t failed_chunk; /* UINT64_MAX: none noted */
    /* parts and merges */
    int part_k, part_n; /* part_n 0: not a part */
    int argc;
    char **argv;
    tally *tallies;
    size_t tally_count, tally_cap, merge_next;
    bool merge, writing_part;
    char *first_output;
} g = {.size = 1, .failed_chunk = UINT64_MAX};

static size_t type_size(lucent_dist_type t) { return t == LUCENT_DIST_U32 ? 4 : 8; }

bool lucent_dist_mpi_built(void)
{
#ifdef LUCENT_HAVE_MPI
    return true;
#else
    return false;
#endif
}

int lucent_dist_rank(void) { return g.rank; }
int lucent_dist_size(void) { return g.size; }

lucent_status lucent_dist_init(int *argc, char ***argv)
{
#ifdef LUCENT_HAVE_MPI
    /* MPI only under a launcher: a plain `lucent ...` stays one process without MPI's start-up. */
    const char *launched[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"};
    bool under = false;
    for (size_t i = 0; i < sizeof launched / sizeof *launched; i++) under |= getenv(launched[i]) != NULL;
    if (under) {
        int provided = 0;
        if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
            return lucent_error(LUCENT_ERR_IO, "MPI: MPI_Init_thread failed");
        g.mpi = true;
        MPI_Comm_rank(MPI_COMM_WORLD, &g.rank);
        MPI_Comm_size(MPI_COMM_WORLD, &g.size);
    }
#else
    (void)argc, (void)argv;
    const char *sizes[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        if (getenv(sizes[i]) && atoi(getenv(sizes[i])) > 1)
            return lucent_error(LUCENT_ERR_UNSUPPORTED,
                                "started as one of %s processes by an MPI launcher, but built without MPI "
                                "(cmake -DLUCENT_MPI=ON, with libopenmpi-dev): every process would run the whole job",
                                getenv(sizes[i]));
#endif
    return LUCENT_OK;
}

bool lucent_dist_writes_outputs(void) { return g.writing_part || (g.rank == 0 && !g.part_n); }

bool dist_open_output(const char *path)
{
    if (lucent_dist_writes_outputs()) return true;
    if (!g.first_output && path) g.first_output = strdup(path);
    return false;
}

const char *lucent_dist_first_output(void) { return g.first_output; }

lucent_share lucent_dist_share(void)
{
    if (g.merge) return (lucent_share){0, 0};
    uint64_t n = g.part_n ? (uint64_t)g.part_n : 1, k = g.part_n ? (uint64_t)(g.part_k - 1) : 0;
    /* part k of n, rank r of N: chunks k + n (r + N j), so the ranks of a part split its chunks */
    return (lucent_share){k + n * (uint64_t)g.rank, n * (uint64_t)g.size};
}

bool lucent_dist_active(void) { return g.size > 1 || g.part_n || g.merge; }

void dist_note_failed_chunk(uint64_t chunk) { g.failed_chunk = chunk; }

/* ---- agreement ---- */

static lucent_status agreed_error(void) { return lucent_error(g.status, "%s", g.message); }

#ifdef LUCENT_HAVE_MPI
/* Waits for a request without spinning. Open MPI's blocking collectives busy-poll, so a rank that
 * has finished its share of a pass would burn a core while the others work: with more ranks than
 * free cores (a shared machine, oversubscription) the waiting ranks take the time of the working
 * ones. Naps of 50 us growing to 1 ms cost at most 1 ms per agreement (once per pass or sum). */
static void wait_gently(MPI_Request *request)
{
    int done = 0;
    struct timespec nap = {0, 50000};
    MPI_Test(request, &done, MPI_STATUS_IGNORE);
    while (!done) {
        nanosleep(&nap, NULL);
        if (nap.tv_nsec < 1000000) nap.tv_nsec *= 2;
        MPI_Test(request, &done, MPI_STATUS_IGNORE);
    }
}
#endif

lucent_status lucent_dist_agree(lucent_status status)
{
    if (g.failed) return agreed_error();
    uint64_t chunk = g.failed_chunk;
    g.failed_chunk = UINT64_MAX;
    if (!g.mpi) return status; /* one process: its own error, nothing to agree (and nothing latched) */
#ifdef LUCENT_HAVE_MPI
    /* The key of a failure: its chunk, or after every chunk for failures outside chunks; MINLOC
     * breaks ties by the lower rank. */
    struct {
        long key;
        int rank;
    } in = {LONG_MAX, g.rank}, out;
    if (status != LUCENT_OK) in.key = chunk < (uint64_t)LONG_MAX - 1 ? (long)chunk : LONG_MAX - 1;
    MPI_Request request;
    MPI_Iallreduce(&in, &out, 1, MPI_LONG_INT, MPI_MINLOC, MPI_COMM_WORLD, &request);
    wait_gently(&request);
    if (out.key == LONG_MAX) return LUCENT_OK;
    struct {
        int status;
        char message[MESSAGE];
    } m = {0};
    if (g.rank == out.rank) {
        m.status = (int)status;
        if (g.rank == 0)
            snprintf(m.message, sizeof m.message, "%s", lucent_last_error());
        else
            snprintf(m.message, sizeof m.message, "rank %d of %d failed: %s", g.rank, g.size, lucent_last_error());
    }
    MPI_Bcast(&m, (int)sizeof m, MPI_BYTE, out.rank, MPI_COMM_WORLD);
    g.failed = true, g.status = (lucent_status)m.status;
    snprintf(g.message, sizeof g.message, "%s", m.message);
    return agreed_error();
#else
    (void)chunk;
    return status;
#endif
}

int lucent_dist_finish(int rc)
{
    if (g.mpi && !g.failed) {
        if (rc != 0 && !lucent_last_error()[0]) lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "failed (exit %d)", rc);
        lucent_status s = lucent_dist_agree(rc == 0 ? LUCENT_OK : LUCENT_ERR_INVALID_ARGUMENT);
        if (s != LUCENT_OK && rc == 0) {
            /* this rank had finished, another had not: the job fails, with that rank's message */
            if (g.rank == 0) fprintf(stderr, "lucent: %s\n", g.message);
            rc = 1;
        }
    }
#ifdef LUCENT_HAVE_MPI
    if (g.mpi) MPI_Finalize();
#endif
    for (size_t i = 0; i < g.tally_count; i++) free(g.tallies[i].data);
    free(g.tallies);
    for (int i = 0; i < g.argc; i++) free(g.argv[i]);
    free(g.argv);
    free(g.first_output);
    g.tallies = NULL, g.tally_count = g.tally_cap = g.merge_next = 0;
    g.argv = NULL, g.argc = 0, g.first_output = NULL, g.merge = false; /* a later load starts afresh */
    return rc;
}

/* ---- sums ---- */

#ifdef LUCENT_HAVE_MPI
static MPI_Datatype mpi_type(lucent_dist_type t)
{
    return t == LUCENT_DIST_I64 ? MPI_INT64_T : t == LUCENT_DIST_F64 ? MPI_DOUBLE : MPI_UINT32_T;
}

/* Sums v over the ranks in rank order into every rank, in pieces of at most 2^26 values. */
static lucent_status mpi_sum(lucent_dist_type type, void *v, size_t n)
{
    const size_t piece = (size_t)1 << 26;
    size_t es = type_size(type), first = n < piece ? n : piece;
    void *tmp = g.rank == 0 ? malloc(first ? first * es : 1) : NULL;
    int ok = g.rank != 0 || tmp != NULL, all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (!all) {
        free(tmp);
        return lucent_dist_agree(lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "MPI: out of memory for a sum"));
    }
    for (size_t at = 0; at < n; at += piece) {
        size_t m = n - at < piece ? n - at : piece;
        char *base = (char *)v + at * es;
        if (g.rank == 0) {
            for (int r = 1; r < g.size; r++) {
                MPI_Recv(tmp, (int)m, mpi_type(type), r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
                if (type == LUCENT_DIST_I64)
                    for (size_t i = 0; i < m; i++) ((int64_t *)base)[i] += ((const int64_t *)tmp)[i];
                else if (type == LUCENT_DIST_F64)
                    for (size_t i = 0; i < m; i++) ((double *)base)[i] += ((const double *)tmp)[i];
                else
                    for (size_t i = 0; i < m; i++) ((uint32_t *)base)[i] += ((const uint32_t *)tmp)[i];
            }
        } else {
            MPI_Send(base, (int)m, mpi_type(type), 0, 0, MPI_COMM_WORLD);
        }
        MPI_Bcast(base, (int)m, mpi_type(type), 0, MPI_COMM_WORLD);
    }
    free(tmp);
    return LUCENT_OK;
}
#endif

static lucent_status record(lucent_dist_type type, const void *v, size_t n)
{
    if (g.tally_count == g.tally_cap) {
        size_t cap = g.tally_cap ? 2 * g.tally_cap : 8;
        tally *t = realloc(g.tallies, cap * sizeof *t);
        if (!t) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "part: out of memory");
        g.tallies = t, g.tally_cap = cap;
    }
    void *copy = malloc(n ? n * type_size(type) : 1);
    if (!copy) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "part: out of memory for a tally of %zu values", n);
    if (n) memcpy(copy, v, n * type_size(type));
    g.tallies[g.tally_count++] = (tally){type, n, copy};
    return LUCENT_OK;
}

static const char *type_name(lucent_dist_type t)
{
    return t == LUCENT_DIST_I64 ? "int64" : t == LUCENT_DIST_F64 ? "double" : "uint32";
}

static lucent_status merged(lucent_dist_type type, void *v, size_t n)
{
    size_t i = g.merge_next++;
    if (i >= g.tally_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "merge: the command needs more tallies than the parts hold (%zu): not the run "
                            "the parts come from (were its inputs changed?)",
                            g.tally_count);
    const tally *t = &g.tallies[i];
    if (t->type != type || t->count != n)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "merge: tally %zu of the parts holds %llu %s values, the command needs %zu %s values: "
                            "not the run the parts come from (were its inputs changed?)",
                            i + 1, (unsigned long long)t->count, type_name(t->type), n, type_name(type));
    if (n) memcpy(v, t->data, n * type_size(type));
    return LUCENT_OK;
}

lucent_status lucent_dist_sum(lucent_status status, lucent_dist_type type, void *v, size_t n)
{
    lucent_status s = lucent_dist_agree(status);
    if (s != LUCENT_OK) return s;
    if (g.merge) return lucent_dist_agree(merged(type, v, n));
#ifdef LUCENT_HAVE_MPI
    if (g.mpi && g.size > 1 && (s = mpi_sum(type, v, n)) != LUCENT_OK) return s;
#endif
    if (g.part_n) s = lucent_dist_agree(record(type, v, n));
    return s;
}

lucent_status lucent_dist_max_f64(lucent_status status, double *v, size_t n)
{
    lucent_status s = lucent_dist_agree(status);
    if (s != LUCENT_OK || !g.mpi || g.size == 1) return s;
#ifdef LUCENT_HAVE_MPI
    const size_t piece = (size_t)1 << 26;
    for (size_t at = 0; at < n; at += piece)
        MPI_Allreduce(MPI_IN_PLACE, v + at, (int)(n - at < piece ? n - at : piece), MPI_DOUBLE, MPI_MAX,
                      MPI_COMM_WORLD);
#else
    (void)v, (void)n;
#endif
    return LUCENT_OK;
}

lucent_status lucent_dist_bcast_flag(lucent_status status, bool *flag)
{
    lucent_status s = lucent_dist_agree(status);
    if (s != LUCENT_OK || !g.mpi || g.size == 1) return s;
#ifdef LUCENT_HAVE_MPI
    int f = *flag;
    MPI_Bcast(&f, 1, MPI_INT, 0, MPI_COMM_WORLD);
    *flag = f != 0;
#else
    (void)flag;
#endif
    return LUCENT_OK;
}

/* ---- parts ---- */

static lucent_status copy_args(int argc, char **argv)
{
    g.argv = calloc((size_t)argc + 1, sizeof *g.argv);
    if (!g.argv) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < argc; i++) {
        if (!(g.argv[i] = strdup(argv[i]))) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        g.argc = i + 1;
    }
    return LUCENT_OK;
}

lucent_status lucent_dist_set_part(int k, int n, int argc, char **argv)
{
    if (n < 1 || n > MAX_PARTS || k < 1 || k > n)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--part K/N: need 1 <= K <= N <= %d, got %d/%d", MAX_PARTS, k,
                            n);
    if (argc > MAX_ARGS) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--part: at most %d arguments", MAX_ARGS);
    g.part_k = k, g.part_n = n;
    return copy_args(argc, argv);
}

bool lucent_dist_part(int *k, int *n)
{
    if (k) *k = g.part_k;
    if (n) *n = g.part_n;
    return g.part_n != 0;
}

/* The part writer: its file and the CRC-32 of what it has written. */
typedef struct part_out {
    FILE *fp;
    uLong crc;
} part_out;

static bool put(part_out *o, const void *p, size_t n)
{
    if (n == 0) return true;
    o->crc = crc32_z(o->crc, p, n);
    return fwrite(p, 1, n, o->fp) == n;
}

static bool put_u32(part_out *o, uint32_t v) { return put(o, &v, 4); }

lucent_status lucent_dist_part_write(const char *path)
{
    if (!g.part_n) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "part: not a part (--part K/N)");
    if (g.rank != 0) return LUCENT_OK;
    g.writing_part = true;
    lucent_atomic_file *af;
    FILE *fp;
    lucent_status s = lucent_atomic_open(path, &af, &fp);
    g.writing_part = false;
    if (s != LUCENT_OK) return s;
    char magic[16] = PART_MAGIC;
    part_out o = {fp, crc32_z(0, NULL, 0)};
    bool ok = put(&o, magic, 16) && put_u32(&o, PART_ORDER) && put_u32(&o, (uint32_t)g.part_k) &&
              put_u32(&o, (uint32_t)g.part_n) && put_u32(&o, (uint32_t)g.argc);
    for (int i = 0; ok && i < g.argc; i++) {
        size_t len = strlen(g.argv[i]);
        ok = len <= MAX_ARG_BYTES && put_u32(&o, (uint32_t)len) && put(&o, g.argv[i], len);
    }
    ok = ok && put_u32(&o, (uint32_t)g.tally_count);
    for (size_t i = 0; ok && i < g.tally_count; i++) {
        const tally *t = &g.tallies[i];
        ok = put_u32(&o, (uint32_t)t->type) && put(&o, &t->count, 8) &&
             put(&o, t->data, (size_t)t->count * type_size(t->type));
    }
    ok = ok && put_u32(&o, (uint32_t)o.crc);
    if (!ok) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}

/* ---- merges ---- */

typedef struct part_file {
    const char *path;
    char *data;
    size_t size, at;
    uint32_t k, n, argc;
    char **argv;
    uint32_t tally_count;
    tally *tallies; /* data point into the file's bytes */
} part_file;

static lucent_status take(part_file *p, void *dest, size_t n, const char *where)
{
    if (p->size - p->at < n) return lucent_error(LUCENT_ERR_PARSE, "%s: %s: the file ends early", p->path, where);
    memcpy(dest, p->data + p->at, n);
    p->at += n;
    return LUCENT_OK;
}

static lucent_status read_args(part_file *p)
{
    if (p->argc < 1 || p->argc > MAX_ARGS)
        return lucent_error(LUCENT_ERR_PARSE, "%s: header: %u arguments (1 to %d)", p->path, p->argc, MAX_ARGS);
    p->argv = calloc(p->argc, sizeof *p->argv);
    if (!p->argv) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", p->path);
    for (uint32_t i = 0; i < p->argc; i++) {
        uint32_t len = 0;
        char where[48];
        snprintf(where, sizeof where, "argument %u", i + 1);
        lucent_status s = take(p, &len, 4, where);
        if (s == LUCENT_OK && len > MAX_ARG_BYTES)
            s = lucent_error(LUCENT_ERR_PARSE, "%s: %s: %u bytes (at most %d)", p->path, where, len, MAX_ARG_BYTES);
        if (s == LUCENT_OK && !(p->argv[i] = calloc(len + 1, 1)))
            s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", p->path);
        if (s == LUCENT_OK) s = take(p, p->argv[i], len, where);
        if (s == LUCENT_OK && strlen(p->argv[i]) != len)
            s = lucent_error(LUCENT_ERR_PARSE, "%s: %s: holds a NUL byte", p->path, where);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

static lucent_status read_tallies(part_file *p)
{
    lucent_status s = take(p, &p->tally_count, 4, "tally count");
    if (s == LUCENT_OK && p->tally_count > MAX_TALLIES)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: tally count: %u (at most %d)", p->path, p->tally_count, MAX_TALLIES);
    if (s == LUCENT_OK && !(p->tallies = calloc(p->tally_count ? p->tally_count : 1, sizeof *p->tallies)))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", p->path);
    for (uint32_t i = 0; s == LUCENT_OK && i < p->tally_count; i++) {
        char where[48];
        snprintf(where, sizeof where, "tally %u", i + 1);
        uint32_t type = 0;
        uint64_t count = 0;
        if ((s = take(p, &type, 4, where)) != LUCENT_OK || (s = take(p, &count, 8, where)) != LUCENT_OK) break;
        if (type > LUCENT_DIST_U32)
            return lucent_error(LUCENT_ERR_PARSE, "%s: %s: unknown type %u", p->path, where, type);
        size_t es = type_size((lucent_dist_type)type);
        if (count > (p->size - p->at) / es)
            return lucent_error(LUCENT_ERR_PARSE, "%s: %s: %llu values, more than the file holds", p->path, where,
                                (unsigned long long)count);
        p->tallies[i] = (tally){(lucent_dist_type)type, count, p->data + p->at};
        for (uint64_t j = 0; j < count && type != LUCENT_DIST_U32; j++) {
            int64_t v;
            double d;
            memcpy(&v, p->data + p->at + j * 8, 8), memcpy(&d, p->data + p->at + j * 8, 8);
            if (type == LUCENT_DIST_I64 && v < 0)
                return lucent_error(LUCENT_ERR_PARSE, "%s: %s: value %llu is negative (%lld): a damaged part file",
                                    p->path, where, (unsigned long long)j, (long long)v);
            if (type == LUCENT_DIST_F64 && !isfinite(d))
                return lucent_error(LUCENT_ERR_PARSE, "%s: %s: value %llu is not finite: a damaged part file", p->path,
                                    where, (unsigned long long)j);
        }
        p->at += (size_t)count * es;
    }
    if (s == LUCENT_OK && p->at != p->size)
        s = lucent_error(LUCENT_ERR_PARSE, "%s: %zu bytes after the last tally", p->path, p->size - p->at);
    return s;
}

/* The part's last 4 bytes: the CRC-32 of the others (then left out of p->size). */
static lucent_status check_sum(part_file *p)
{
    uint32_t stored;
    if (p->size < 20 + 4) return lucent_error(LUCENT_ERR_PARSE, "%s: header: the file ends early", p->path);
    memcpy(&stored, p->data + p->size - 4, 4);
    p->size -= 4;
    if ((uint32_t)crc32_z(crc32_z(0, NULL, 0), (const Bytef *)p->data, p->size) != stored)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: the part's checksum does not match its contents: a damaged part file (write it "
                            "again with lucent ... --part K/N)",
                            p->path);
    return LUCENT_OK;
}

static lucent_status read_part(part_file *p)
{
    lucent_status s = lucent_read_file(p->path, &p->data, &p->size);
    if (s != LUCENT_OK) return s;
    char magic[16];
    uint32_t order = 0;
    if (p->size >= 16 && memcmp(p->data, PART_MAGIC_V1, 16) == 0)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: header: a part file of format v1 (before checksums, Lucent 0.1 of 2026-12-06): "
                            "run its part again with this lucent",
                            p->path);
    if (p->size < 16 || memcmp(p->data, PART_MAGIC, 16) != 0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: header: not a Lucent part file (lucent ... --part K/N)", p->path);
    s = take(p, magic, 16, "header");
    if (s == LUCENT_OK) s = take(p, &order, 4, "header");
    if (s == LUCENT_OK && order != PART_ORDER) /* before the checksum, itself in the writer's byte order */
        s = lucent_error(LUCENT_ERR_PARSE, "%s: header: written on a machine of another byte order", p->path);
    if (s == LUCENT_OK) s = check_sum(p);
    if (s == LUCENT_OK) s = take(p, &p->k, 4, "header");
    if (s == LUCENT_OK) s = take(p, &p->n, 4, "header");
    if (s == LUCENT_OK && (p->n < 1 || p->n > MAX_PARTS || p->k < 1 || p->k > p->n))
        s = lucent_error(LUCENT_ERR_PARSE, "%s: header: part %u of %u", p->path, p->k, p->n);
    if (s == LUCENT_OK) s = take(p, &p->argc, 4, "header");
    if (s == LUCENT_OK) s = read_args(p);
    if (s == LUCENT_OK) s = read_tallies(p);
    return s;
}

static void free_part(part_file *p)
{
    for (uint32_t i = 0; p->argv && i < p->argc; i++) free(p->argv[i]);
    free(p->argv);
    free(p->tallies);
    free(p->data);
}

/* The parts agree with the first one: the same command, the same tallies. */
static lucent_status check_same(const part_file *a, const part_file *b)
{
    if (b->n != a->n)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: %s is a part of %u, %s of %u", b->path, b->n, a->path,
                            a->n);
    bool same = a->argc == b->argc;
    for (uint32_t i = 0; same && i < a->argc; i++) same = strcmp(a->argv[i], b->argv[i]) == 0;
    if (!same)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: %s and %s are parts of different commands", a->path,
                            b->path);
    if (a->tally_count != b->tally_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: %s holds %u tallies, %s %u", a->path, a->tally_count,
                            b->path, b->tally_count);
    for (uint32_t i = 0; i < a->tally_count; i++)
        if (a->tallies[i].type != b->tallies[i].type || a->tallies[i].count != b->tallies[i].count)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: tally %u of %s and of %s differ in size", i + 1,
                                a->path, b->path);
    return LUCENT_OK;
}

static lucent_status overflow(uint32_t tally, uint64_t j, const part_file *p)
{
    return lucent_error(LUCENT_ERR_PARSE,
                        "merge: tally %u value %llu overflows when %s is added: damaged parts (no run counts so many)",
                        tally + 1, (unsigned long long)j, p->path);
}

/* Sums the parts' tallies in part order (byparts[0] is part 1), refusing sums that overflow. */
static lucent_status sum_parts(part_file **byparts, uint32_t n)
{
    const part_file *first = byparts[0];
    for (uint32_t i = 0; i < first->tally_count; i++) {
        const tally *t0 = &first->tallies[i];
        size_t es = type_size(t0->type);
        void *sum = calloc(t0->count ? (size_t)t0->count : 1, es);
        if (!sum) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "merge: out of memory");
        bool over = false;
        for (uint32_t k = 0; k < n && !over; k++) {
            const char *src = byparts[k]->tallies[i].data; /* unaligned in the file: copy values */
            for (uint64_t j = 0; j < t0->count && !over; j++) {
                if (t0->type == LUCENT_DIST_I64) {
                    int64_t x;
                    memcpy(&x, src + j * 8, 8);
                    over = __builtin_add_overflow(((int64_t *)sum)[j], x, &((int64_t *)sum)[j]);
                } else if (t0->type == LUCENT_DIST_F64) {
                    double x;
                    memcpy(&x, src + j * 8, 8);
                    ((double *)sum)[j] += x;
                    over = !isfinite(((double *)sum)[j]);
                } else {
                    uint32_t x;
                    memcpy(&x, src + j * 4, 4);
                    over = __builtin_add_overflow(((uint32_t *)sum)[j], x, &((uint32_t *)sum)[j]);
                }
                if (over) {
                    free(sum);
                    return overflow(i, j, byparts[k]);
                }
            }
        }
        if (g.tally_count == g.tally_cap) {
            size_t cap = g.tally_cap ? 2 * g.tally_cap : 8;
            tally *tt = realloc(g.tallies, cap * sizeof *tt);
            if (!tt) {
                free(sum);
                return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "merge: out of memory");
            }
            g.tallies = tt, g.tally_cap = cap;
        }
        g.tallies[g.tally_count++] = (tally){t0->type, t0->count, sum};
    }
    return LUCENT_OK;
}

lucent_status lucent_dist_merge_load(const char *const *paths, int count, int *argc, char ***argv)
{
    if (count < 1) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: no part files");
    part_file *parts = calloc((size_t)count, sizeof *parts);
    part_file **byparts = NULL;
    if (!parts) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "merge: out of memory");
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < count && s == LUCENT_OK; i++) {
        parts[i].path = paths[i];
        s = read_part(&parts[i]);
        if (s == LUCENT_OK && i > 0) s = check_same(&parts[0], &parts[i]);
    }
    uint32_t n = parts[0].n;
    if (s == LUCENT_OK && !(byparts = calloc(n, sizeof *byparts)))
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "merge: out of memory");
    for (int i = 0; i < count && s == LUCENT_OK; i++) {
        part_file **slot = &byparts[parts[i].k - 1];
        if (*slot)
            s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: part %u of %u given twice (%s and %s)", parts[i].k, n,
                             (*slot)->path, parts[i].path);
        *slot = &parts[i];
    }
    for (uint32_t k = 0; k < n && s == LUCENT_OK; k++)
        if (!byparts[k])
            s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "merge: part %u of %u is missing (parts given: %d)", k + 1, n,
                             count);
    if (s == LUCENT_OK) s = sum_parts(byparts, n);
    if (s == LUCENT_OK) s = copy_args((int)parts[0].argc, parts[0].argv);
    if (s == LUCENT_OK) {
        g.merge = true, g.merge_next = 0;
        *argc = g.argc, *argv = g.argv;
    }
    for (int i = 0; i < count; i++) free_part(&parts[i]);
    free(parts);
    free(byparts);
    return s;
}

lucent_status lucent_dist_merge_check_used(void)
{
    if (g.merge && g.merge_next != g.tally_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "merge: the command used %zu of the parts' %zu tallies: not the run the parts come from "
                            "(were its inputs changed?)",
                            g.merge_next, g.tally_count);
    return LUCENT_OK;
}
