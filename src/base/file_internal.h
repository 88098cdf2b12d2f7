/* Internal to src/base: the atomic writer (file.c) and the output set (outputs.c) share the open file. */
#ifndef LUCENT_SRC_BASE_FILE_INTERNAL_H
#define LUCENT_SRC_BASE_FILE_INTERNAL_H

#include <stdbool.h>
#include <stdio.h>
#include <sys/stat.h>

#include "lucent/base.h"

struct lucent_atomic_file {
    FILE *fp;
    char *path;
    char *tmp;                /* NULL: an output sent nowhere (dist_open_output), or written through */
    int slot;                 /* tmp's slot in the signal handler's table, -1 none */
    bool direct;              /* not an output of the command (the disk cache): renamed at once */
    bool claimed;             /* path is claimed in the open output set */
    bool through;             /* path is a device, FIFO or socket: fp is an unlinked file in TMPDIR whose bytes
                                 are written through to path (base_write_through) when the output lands */
    lucent_atomic_file *next; /* the output set's completed temporaries */
};

/* Writes size bytes to path atomically at once, outside the output set (for the disk cache: an entry is
 * not an output of the command and may be read back before the command ends). */
lucent_status base_write_file_direct(const char *path, const void *data, size_t size);

/* Writes the bytes of a through output's fp into its target (opened without O_CREAT, so a target gone since
 * is never made a regular file). */
lucent_status base_write_through(lucent_atomic_file *af);

/* ---- outputs.c ---- */

/* Takes tmp into the signal handler's table before the file exists: its slot, or -1 when the table is full. */
int outputs_track(const char *tmp);
void outputs_untrack(int slot);

/* When an output set is open: refuses a path the set already holds, or one naming a file read since the set
 * began; claims it otherwise (af->claimed). */
lucent_status outputs_claim(lucent_atomic_file *af);
void outputs_release(lucent_atomic_file *af);

/* When an output set is open: keeps af's completed temporary for lucent_outputs_end (true), else false. */
bool outputs_defer(lucent_atomic_file *af);

/* lucent_open_regular's note of a file it opened for reading (kept while an output set is open); refuses
 * (naming path) a file planned as an output of the set (outputs_plan). */
lucent_status outputs_note_input(const char *path, const struct stat *st);

/* Notes an existing regular file as an output of the open set before it is written (lucent_output_check). */
void outputs_plan(const struct stat *st);

#endif
