/* Lucent base: status codes and error messages, logging, progress, thread pool,
 * RNG streams, atomic file writes. Everything else in Lucent builds on this. */
#ifndef LUCENT_BASE_H
#define LUCENT_BASE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define LUCENT_VERSION_MAJOR 0
#define LUCENT_VERSION_MINOR 1
#define LUCENT_VERSION_PATCH 0
#define LUCENT_VERSION_STRING "0.1.0"

#if defined(__GNUC__) || defined(__clang__)
#define LUCENT_PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#else
#define LUCENT_PRINTF(fmt, args)
#endif

/* ---- Status codes ------------------------------------------------------
 * One table, so codes and their texts cannot drift apart. */
#define LUCENT_STATUS_TABLE(X)                                                                                         \
    X(LUCENT_OK, "ok")                                                                                                 \
    X(LUCENT_ERR_INVALID_ARGUMENT, "invalid argument")                                                                 \
    X(LUCENT_ERR_OUT_OF_MEMORY, "out of memory")                                                                       \
    X(LUCENT_ERR_IO, "input/output error")                                                                             \
    X(LUCENT_ERR_PARSE, "malformed input")                                                                             \
    X(LUCENT_ERR_UNSUPPORTED, "unsupported")                                                                           \
    X(LUCENT_ERR_NOT_FOUND, "not found")                                                                               \
    X(LUCENT_ERR_NUMERIC, "numerical failure")                                                                         \
    X(LUCENT_ERR_GL, "OpenGL error")                                                                                   \
    X(LUCENT_ERR_INTERNAL, "internal error")

typedef enum lucent_status {
#define LUCENT_X_ENUM(code, text) code,
    LUCENT_STATUS_TABLE(LUCENT_X_ENUM)
#undef LUCENT_X_ENUM
        LUCENT_STATUS_COUNT
} lucent_status;

/* Returns a short constant text for a status code. */
const char *lucent_status_string(lucent_status status);

/* Sets this thread's error message (printf-style) and returns status, so that
 * `return lucent_error(LUCENT_ERR_PARSE, "%s: line %d: ...", file, line);` reads well. */
lucent_status lucent_error(lucent_status status, const char *fmt, ...) LUCENT_PRINTF(2, 3);
lucent_status lucent_error_v(lucent_status status, const char *fmt, va_list ap);

/* Prepends context ("<context>: ") to this thread's current message and returns status.
 * Used when an error travels up through a caller that knows more (the file name). */
lucent_status lucent_error_context(lucent_status status, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* Returns this thread's last error message ("" when none). Valid until the next error call. */
const char *lucent_last_error(void);

/* Returns this thread's last error status (LUCENT_OK when none). */
lucent_status lucent_last_status(void);

/* Forgets this thread's error. */
void lucent_clear_error(void);

/* ---- Logging ------------------------------------------------------------
 * The library never prints: log lines go to a sink the application installs. */
typedef enum lucent_log_level {
    LUCENT_LOG_DEBUG = 0,
    LUCENT_LOG_INFO = 1,
    LUCENT_LOG_WARN = 2,
    LUCENT_LOG_ERROR = 3,
    LUCENT_LOG_OFF = 4
} lucent_log_level;

typedef void (*lucent_log_fn)(lucent_log_level level, const char *message, void *user);

/* Installs the log sink (NULL: drop everything) and the lowest level passed to it. */
void lucent_log_set_sink(lucent_log_fn fn, void *user, lucent_log_level min_level);

/* Writes one formatted line to the sink, if the level passes. Thread-safe. */
void lucent_log(lucent_log_level level, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* A ready-made sink that writes "lucent: [level] message\n" to the FILE* in user. */
void lucent_log_stderr_sink(lucent_log_level level, const char *message, void *user);

/* ---- Progress -----------------------------------------------------------
 * A bar with rate and ETA. Silent unless the application names an output
 * (the CLI does so when stderr is a terminal and --quiet is absent). */
typedef struct lucent_progress lucent_progress;

/* Sets where progress bars are drawn (NULL: nowhere, the default). */
void lucent_progress_set_output(FILE *out);

/* Starts a task of `total` units named `label`. Returns NULL only when out of memory;
 * every progress function accepts NULL and then does nothing. */
lucent_progress *lucent_progress_begin(const char *label, uint64_t total);

/* Names the task's unit ("frame"): the bar then also says which unit is under way, "frame k of n"
 * (NULL or "": none, the default). */
void lucent_progress_set_unit(lucent_progress *p, const char *unit);

/* Makes the bar also follow a time limit of `seconds` from the task's start (<= 0: none): it shows
 * the larger of the units' fraction and the elapsed time's, and the ETA of whichever ends first. */
void lucent_progress_set_deadline(lucent_progress *p, double seconds);

/* Adds n finished units. Thread-safe, cheap (redraws at most ten times per second). */
void lucent_progress_add(lucent_progress *p, uint64_t n);

/* Returns the units finished so far. */
uint64_t lucent_progress_done(const lucent_progress *p);

/* Draws the final state, ends the line, and frees p. */
void lucent_progress_end(lucent_progress *p);

/* ---- Thread pool ----------------------------------------------------------
 * Work is cut into fixed chunks (independent of the thread count), so results that
 * depend on the chunk index are identical whatever the number of threads. */
typedef struct lucent_pool lucent_pool;

/* The most threads a pool has. */
#define LUCENT_POOL_MAX_THREADS 256

/* Creates a pool of `threads` workers (0: LUCENT_THREADS from the environment, else all cores).
 * The calling thread works too, so a pool of 1 runs everything on the caller. More than
 * LUCENT_POOL_MAX_THREADS, or a LUCENT_THREADS that is not a whole number from 1 to it, is said in a
 * warning (lucent_log) and replaced: by the maximum, or by all cores. */
lucent_pool *lucent_pool_create(int threads);
void lucent_pool_destroy(lucent_pool *pool);

/* Returns the number of threads that execute work (callers included). */
int lucent_pool_threads(const lucent_pool *pool);

/* Returns the number of cores the system reports (at least 1). */
int lucent_cpu_count(void);

/* Body of a parallel loop: process items [begin, end) of chunk `chunk` on thread `thread`
 * (0 <= thread < lucent_pool_threads). Returns LUCENT_OK or an error (set with lucent_error). */
typedef lucent_status (*lucent_chunk_fn)(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread);

/* Runs fn over [0, count) cut into chunks of chunk_size items (the last may be shorter).
 * Blocks until all chunks are done. If chunks fail, the error of the lowest failing chunk
 * is returned and its message is set on the calling thread; chunks not yet started are skipped.
 * pool may be NULL: then everything runs on the caller. */
lucent_status lucent_parallel_for(lucent_pool *pool, uint64_t count, uint64_t chunk_size, lucent_chunk_fn fn,
                                  void *ctx);

/* ---- SIMD paths -----------------------------------------------------------------
 * Hot kernels (the photon Monte Carlo) have a path per instruction set, chosen at run time from
 * the CPU's features; the scalar path is the reference. Results are identical for any thread or
 * process count on each path, and agree statistically (not bit for bit) between paths. */
typedef enum lucent_isa {
    LUCENT_ISA_AUTO = 0, /* the best path this CPU supports */
    LUCENT_ISA_SCALAR,   /* portable C, the reference */
    LUCENT_ISA_AVX2,     /* x86-64 AVX2 + FMA: 8 lanes */
    LUCENT_ISA_AVX512,   /* x86-64 AVX-512 F/DQ/BW/VL: 16 lanes */
    LUCENT_ISA_COUNT
} lucent_isa;

/* Whether this CPU (and this build) can run the path; AUTO and SCALAR always can. */
bool lucent_isa_supported(lucent_isa isa);

/* Chooses the path for the whole process (AUTO: the best supported, or LUCENT_ISA from the
 * environment when it is set); fails, naming the path, when the CPU lacks it. */
lucent_status lucent_isa_set(lucent_isa isa);

/* The path in use, never AUTO: the one set, else LUCENT_ISA (scalar, avx2, avx512, auto) from the
 * environment, else the best supported. An unknown or unsupported LUCENT_ISA is logged once as a
 * warning and the best supported path is used. */
lucent_isa lucent_isa_active(void);

/* "auto", "scalar", "avx2", "avx512" (NULL for other values). */
const char *lucent_isa_name(lucent_isa isa);

/* Parses one of lucent_isa_name's names; the message lists them. */
lucent_status lucent_isa_parse(const char *name, lucent_isa *dest);

/* ---- Random numbers -------------------------------------------------------
 * xoshiro256** (Blackman & Vigna 2018). Each (seed, stream) pair gives an independent,
 * reproducible sequence: the state is derived by hashing seed and stream with SplitMix64,
 * so stream k of seed s does not depend on how many streams exist or which thread runs it. */
typedef struct lucent_rng {
    uint64_t s[4];
} lucent_rng;

/* Initialises dest for the given seed and stream. */
void lucent_rng_init(uint64_t seed, uint64_t stream, lucent_rng *dest);

/* Returns the next 64 random bits. */
static inline uint64_t lucent_rng_next(lucent_rng *r)
{
    uint64_t *s = r->s;
    uint64_t x = s[1] * 5u;
    uint64_t result = ((x << 7) | (x >> 57)) * 9u;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = (s[3] << 45) | (s[3] >> 19);
    return result;
}

/* Returns a uniform double in [0, 1) with 53 random bits. */
static inline double lucent_rng_uniform(lucent_rng *r)
{
    return (double)(lucent_rng_next(r) >> 11) * (1.0 / 9007199254740992.0); /* 2^-53 */
}

/* Returns a uniform float in [0, 1) with 24 random bits. */
static inline float lucent_rng_uniformf(lucent_rng *r)
{
    return (float)(lucent_rng_next(r) >> 40) * 5.9604644775390625e-8f; /* 2^-24 */
}

/* Advances r by 2^128 steps (the xoshiro256 jump), giving a non-overlapping subsequence. */
void lucent_rng_jump(lucent_rng *r);

/* ---- Files --------------------------------------------------------------------
 * Outputs are never half-written: data goes to a temporary file beside the target,
 * which is renamed over the target only once complete. */
typedef struct lucent_atomic_file lucent_atomic_file;

/* Opens a temporary file beside `path` for writing; *out receives its FILE*.
 * Fails (with a message naming path) when the directory is missing or not writable. A path that
 * names a character device, a FIFO or a socket is written through instead (the bytes wait in an
 * unlinked file of $TMPDIR and are copied into it on commit, or when the output set lands; it is
 * never replaced by a file); a symbolic link to a regular file is followed (the file is replaced,
 * the link kept); a folder, a block device or a link to nothing is refused (lucent/output.h). */
lucent_status lucent_atomic_open(const char *path, lucent_atomic_file **dest, FILE **out);

/* Flushes, syncs and renames the temporary file onto its target, then frees af.
 * On failure the temporary is removed and the target is left as it was. */
lucent_status lucent_atomic_commit(lucent_atomic_file *af);

/* Removes the temporary file and frees af (af may be NULL). */
void lucent_atomic_abort(lucent_atomic_file *af);

/* Writes size bytes to path atomically. */
lucent_status lucent_write_file(const char *path, const void *data, size_t size);

/* Opens path for reading when it is a regular file: a FIFO, a device (/dev/urandom), a socket or a
 * directory is refused up front (LUCENT_ERR_IO naming the file), since reading one can block or never
 * end. *size receives the file's size. The descriptor is blocking and close-on-exec. */
lucent_status lucent_open_regular(const char *path, int *fd, uint64_t *size);

/* The same as a FILE* ("rb"). */
lucent_status lucent_fopen_regular(const char *path, FILE **dest, uint64_t *size);

/* Reads a whole file; *dest is NUL-terminated (not counted in *size) and freed with free(). */
lucent_status lucent_read_file(const char *path, char **dest, size_t *size);

/* Reads a whole text file (LUCENT_ERR_PARSE "not a text file" when it holds a NUL byte); free with free(). */
lucent_status lucent_read_text_file(const char *path, char **dest);

/* Creates directory `dir` and any missing parents (mkdir -p; mode 0777 less the umask). Succeeds
 * when they exist already; fails, naming the component, when one cannot be made or is not a
 * directory. */
lucent_status lucent_mkdir_p(const char *dir);

/* ---- Clocks ---------------------------------------------------------------------
 * For measuring intervals (timings, time limits, progress rates); never for results. */

/* Seconds on the monotonic clock (CLOCK_MONOTONIC), from an arbitrary origin. */
double lucent_clock_seconds(void);

/* The same clock in milliseconds. */
double lucent_clock_ms(void);

/* CPU seconds used so far by the process, all threads together (CLOCK_PROCESS_CPUTIME_ID): unlike
 * the wall clock, not inflated by other work on a shared machine. */
double lucent_cpu_seconds(void);

/* ---- The disk cache of computed results ---------------------------------------------
 * Monte Carlo results that take seconds (sigma0 fits, slab transmittances) kept between runs: one
 * JSON file per result, DIR/PREFIX-<FNV-1a of the key>.json, holding the full key, so that a changed
 * material, setting or photon count misses. Entries are written atomically; a file that cannot be
 * read, or holds another key, is a miss; failures to write are logged warnings, never errors. */
typedef struct lucent_cache lucent_cache;

/* A cache in dir (created when the first entry is written). */
lucent_status lucent_cache_create(const char *dir, lucent_cache **dest);
void lucent_cache_destroy(lucent_cache *cache);

/* Reads count numbers of field from the entry of (prefix, key) into dest; false on a miss. */
bool lucent_cache_get(const lucent_cache *cache, const char *prefix, const char *key, const char *field, int count,
                      double *dest);

/* A named array of numbers of an entry. */
typedef struct lucent_cache_field {
    const char *name;
    const double *values;
    int count;
} lucent_cache_field;

/* Writes the entry of (prefix, key) with its fields (a warning is logged when it cannot be written). */
void lucent_cache_put(lucent_cache *cache, const char *prefix, const char *key, const lucent_cache_field *fields,
                      int count);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_BASE_H */
