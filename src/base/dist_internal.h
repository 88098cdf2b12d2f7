/* Internal to src/base: what the pool and the atomic writer tell the dist module (dist.c). */
#ifndef LUCENT_SRC_BASE_DIST_INTERNAL_H
#define LUCENT_SRC_BASE_DIST_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

/* The lowest chunk that failed in the last lucent_parallel_for_share (its message is the
 * thread's error): the key of this process's failure when the group agrees. */
void dist_note_failed_chunk(uint64_t chunk);

/* lucent_atomic_open's question for path: write it (true), or send it nowhere (false; the path
 * is remembered as the first output when it is the first). */
bool dist_open_output(const char *path);

#endif
