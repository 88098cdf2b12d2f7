/* Lucent dist: the Monte Carlo work of one job shared by several processes (MPI ranks, or the
 * parts of a scheduler's job array), with results identical to one process's (docs/scale.md).
 *
 * The work of a Monte Carlo run is already cut into fixed chunks with one RNG stream each, so
 * that results depend on the seed only, never on the thread count (lucent_parallel_for). The same
 * chunks are shared out between processes: process p of P runs the chunks c with c % P == p
 * (lucent_dist_share), threads inside each process as before. The tallies of the chunks (integer
 * fixed-point counters, or doubles that each chunk writes into slots of its own) are then summed
 * over the processes in rank order (lucent_dist_sum), which is exact for both kinds, so every
 * process ends with the single run's tallies, bit for bit, and computes the same result from them.
 *
 * Three ways to be one of several processes:
 *   - MPI (built with -DLUCENT_MPI=ON, started by mpirun): rank r of N; only rank 0 writes files.
 *   - a part (--part K/N): the chunks of part K only; the tallies are written as a part file
 *     instead of the outputs (lucent_dist_part_*), and `lucent merge` sums the parts.
 *   - a merge: no chunk runs here; each tally is replaced by the sum of the parts' tallies.
 * Without any of them everything is one process and these functions cost nothing.
 *
 * Errors: every collective step first agrees on failure. When any process failed, every process
 * gets the same error: the message of the lowest failing chunk (or, for failures outside chunks,
 * of the lowest failing rank), and no further communication happens. */
#ifndef LUCENT_DIST_H
#define LUCENT_DIST_H

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Starts the process group: MPI when built with it and started by an MPI launcher (mpirun,
 * srun), otherwise one process. Call once, first thing in main. */
lucent_status lucent_dist_init(int *argc, char ***argv);

/* Ends it: agrees on the exit code (a failure on any rank fails every rank, rc 1, or the largest
 * rc) and returns it; shuts MPI down. Call once, last thing in main. */
int lucent_dist_finish(int rc);

/* True when built with MPI support. */
bool lucent_dist_mpi_built(void);

int lucent_dist_rank(void);
int lucent_dist_size(void);

/* Only rank 0 of a group writes outputs, and a part writes none (lucent_atomic_open sends the
 * others' writes nowhere); a part writes its part file instead. */
bool lucent_dist_writes_outputs(void);

/* Which chunks run in this process: those with chunk % stride == offset; stride 0: none (merge). */
typedef struct lucent_share {
    uint64_t offset, stride;
} lucent_share;

lucent_share lucent_dist_share(void);

/* True when more than one process shares chunks (ranks or parts), or the chunks ran elsewhere
 * (merge): then callers with state across several steps keep what each process owns apart. */
bool lucent_dist_active(void);

/* lucent_parallel_for over the chunks of `share` only (chunk numbers stay global). */
lucent_status lucent_parallel_for_share(lucent_pool *pool, uint64_t count, uint64_t chunk_size, lucent_chunk_fn fn,
                                        void *ctx, lucent_share share);

typedef enum lucent_dist_type { LUCENT_DIST_I64, LUCENT_DIST_F64, LUCENT_DIST_U32 } lucent_dist_type;

/* A tally: agrees on `status` (every process's), then sums v[0 .. n) over the processes in rank
 * order into every process. Under --part the sums are kept for the part file; in a merge v is
 * replaced by the sum of the parts'. Returns the agreed status. */
lucent_status lucent_dist_sum(lucent_status status, lucent_dist_type type, void *v, size_t n);

/* Between ranks only (no part file, nothing in a merge): agrees on status, then sets v[i] to the
 * largest v[i] of every rank (exact, in any order). */
lucent_status lucent_dist_max_f64(lucent_status status, double *v, size_t n);

/* Between ranks only: agrees on status, then every rank gets rank 0's flag. */
lucent_status lucent_dist_bcast_flag(lucent_status status, bool *flag);

/* Agrees on status alone. */
lucent_status lucent_dist_agree(lucent_status status);

/* ---- parts ---- */

/* Sets this process to be part k (1-based) of n (checked: 1 <= k <= n <= 65536), for the command
 * argv[0 .. argc) (kept in the part file, so that a merge can run the same command). */
lucent_status lucent_dist_set_part(int k, int n, int argc, char **argv);

/* True in part mode (--part K/N), and which part. */
bool lucent_dist_part(int *k, int *n);

/* The first output the command tried to write (NULL if none): the part file goes beside it. */
const char *lucent_dist_first_output(void);

/* Writes the part file (tallies and the command) at path. */
lucent_status lucent_dist_part_write(const char *path);

/* Reads part files paths[0 .. count): checks they are the parts 1..N of one command, sums their
 * tallies in part order, and enters merge mode with them. Returns in *argc / *argv the command
 * (owned by the dist module until lucent_dist_finish). */
lucent_status lucent_dist_merge_load(const char *const *paths, int count, int *argc, char ***argv);

/* In a merge: OK when every merged tally was used by the command (else: it is not the same run). */
lucent_status lucent_dist_merge_check_used(void);

#ifdef __cplusplus
}
#endif

#endif
