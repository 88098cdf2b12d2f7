/* A streaming byte source for the mesh readers (PLY, OBJ): a regular file or a memory block, gzip
 * inflated on the fly when it starts with the gzip magic, read through one fixed buffer. Written for
 * hostile input: zlib's errors are checked (a truncated .gz is an error naming the byte offset), lines
 * are bounded, and the caller learns a bound on the bytes still to come before it allocates. */
#ifndef LUCENT_MESH_READER_H
#define LUCENT_MESH_READER_H

#include <stddef.h>
#include <stdint.h>
#include <zlib.h>

#include "lucent/base.h"

/* Longest line the text readers accept (a PLY header line, an ASCII PLY row, an OBJ line). */
#define LUCENT_READER_MAX_LINE ((size_t)1 << 20)

typedef struct lucent_reader {
    const char *name; /* for messages */
    int fd;           /* -1 for memory */
    const unsigned char *mem;
    size_t mem_size, mem_pos;
    int gz;             /* inflating */
    z_stream zs;        /* when gz */
    unsigned char *in;  /* compressed input buffer (fd + gz) */
    int in_eof;         /* no more raw input */
    int stream_end;     /* inflate saw the end of the gzip stream */
    unsigned char *buf; /* decoded bytes: buf[pos..len) not yet consumed */
    size_t cap, len, pos;
    uint64_t base;     /* decoded offset of buf[0] */
    int eof;           /* no more decoded bytes after buf[len] */
    uint64_t raw_size; /* size of the file or memory block */
    uint64_t line;     /* current line (text readers; 1-based, counted by lucent_reader_line) */
} lucent_reader;

/* Opens a regular file (FIFOs, devices refused) or a memory block (path NULL; data, size). */
lucent_status lucent_reader_open(lucent_reader *r, const char *path);
lucent_status lucent_reader_open_memory(lucent_reader *r, const void *data, size_t size, const char *name);
void lucent_reader_close(lucent_reader *r);

/* Decoded offset of the next unread byte. */
static inline uint64_t lucent_reader_offset(const lucent_reader *r) { return r->base + r->pos; }

/* An upper bound on the decoded bytes left: exact for plain input, and for gzip the most that the
 * compressed bytes left can inflate to (deflate expands at most 1032:1). */
uint64_t lucent_reader_bound(const lucent_reader *r);

/* Makes at least n bytes available at buf + pos (fewer only at the end). LUCENT_OK or an error
 * (I/O, corrupt or truncated gzip). */
lucent_status lucent_reader_fill(lucent_reader *r, size_t n);

/* The next line without its '\n' (and '\r'), NUL-terminated in place: *line is NULL at the end of the
 * input. A line longer than LUCENT_READER_MAX_LINE is an error naming its number. Counts r->line. */
lucent_status lucent_reader_line(lucent_reader *r, char **line, size_t *length);

/* After the last byte a reader needs: for gzip input, inflates the rest of the stream (discarding it) so
 * that a truncated or corrupt file, the CRC and length trailer included, is an error; nothing for plain
 * input. */
lucent_status lucent_reader_finish(lucent_reader *r);

/* Copies n bytes to dest; LUCENT_ERR_PARSE "truncated" naming the offset when fewer remain. what names
 * the item being read in the message ("vertex 12 of 400"). */
lucent_status lucent_reader_bytes(lucent_reader *r, void *dest, size_t n, const char *what);

/* Fast decimal parsing for the text readers: a number at *p (leading blanks skipped) up to end; *p is
 * moved past it. Returns 0 when there is no number there. Exact (correctly rounded) for the usual
 * decimals; the rare others go through strtod. */
int lucent_parse_double(const char **p, const char *end, double *dest);

/* A decimal integer (optional sign) at *p; 0 when there is none or it does not fit an int64. */
int lucent_parse_int64(const char **p, const char *end, int64_t *dest);

#endif
