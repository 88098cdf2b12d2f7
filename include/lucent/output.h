/* Lucent outputs: how the library's writers (lucent_atomic_open and all that use it: images,
 * tables, meshes, reports) treat the folder of a file they write. */
#ifndef LUCENT_OUTPUT_H
#define LUCENT_OUTPUT_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Whether lucent_atomic_open (lucent/base.h), and so every writer of the library, creates the
 * missing folders above its target (mkdir -p) before writing. Off by default: a missing folder
 * fails, naming the path. The `lucent` command turns it on, so that every command creates the
 * folder of its outputs. Set it before writing starts (it is not synchronised). */
void lucent_files_create_parents(bool on);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_OUTPUT_H */
