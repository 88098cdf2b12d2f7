/* Lucent outputs: how the library's writers (lucent_atomic_open and all that use it: images,
 * tables, meshes, reports) treat the folder of a file they write. */
#ifndef LUCENT_OUTPUT_H
#define LUCENT_OUTPUT_H

#include <stdbool.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Whether lucent_atomic_open (lucent/base.h), and so every writer of the library, creates the
 * missing folders above its target (mkdir -p) before writing. Off by default: a missing folder
 * fails, naming the path. The `lucent` command turns it on, so that every command creates the
 * folder of its outputs. Set it before writing starts (it is not synchronised). */
void lucent_files_create_parents(bool on);

/* Checks, before any work, that path can be written as an output (what lucent_atomic_open would refuse, said
 * up front): a regular file or nothing is replaced by a temporary renamed over it, so the nearest existing
 * folder above it must be a folder this process may write in (the missing ones below are created when
 * lucent_files_create_parents is on); a symbolic link to a regular file is followed (the file is replaced, the
 * link kept); a character device, a FIFO or a socket is written through (no temporary, no rename: the bytes
 * wait until the output lands) and must be writable; a folder, a block device or a link to nothing is
 * refused. While an output set is open, an existing file so checked is also refused as an input afterwards
 * (a scene's material named as the command's --json). Other MPI ranks than 0 check nothing. */
lucent_status lucent_output_check(const char *path);

/* The same for a folder a command writes its outputs into: it is a folder this process may write in, or
 * can be created. */
lucent_status lucent_output_check_folder(const char *dir);

/* The output set: from lucent_outputs_begin until lucent_outputs_end, lucent_atomic_commit completes each
 * output's temporary (written, flushed, synced, closed) and leaves its target as it was; lucent_outputs_end
 * (true) then renames every one of them onto its target, lucent_outputs_end(false) removes them all. A
 * command that fails part-way (a full disk, an input found bad late, a signal) so leaves its previous
 * outputs as they were, never a mix of new and old. While the set is open, an output naming a file the set
 * already holds is refused, and so is one naming a file read (lucent_open_regular) since it began. The
 * `lucent` command runs each command in a set (except `view`, whose saves land when made). Writes of the
 * disk cache are not outputs: they land at once. */
void lucent_outputs_begin(void);
lucent_status lucent_outputs_end(bool commit);

/* Handles SIGINT, SIGTERM and SIGHUP: removes the temporaries of every output being written or waiting in
 * the set (their targets keep their previous contents), then ends the process by the same signal. A signal
 * that comes while lucent_outputs_end renames is held until the last rename, so the set lands whole. */
void lucent_outputs_handle_signals(void);

/* Writes size bytes to path atomically and at once, outside the output set: for a working file the
 * command hands to another program while it runs (a peer renderer's scene), never for an output. */
lucent_status lucent_write_file_now(const char *path, const void *data, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_OUTPUT_H */
