/* The mesh readers' byte source (reader.h): plain or gzip, file or memory, one bounded buffer. */
#include "mesh/reader.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lucent/mesh.h"

#define BUF_CAP (2 * LUCENT_READER_MAX_LINE)
#define IN_CAP ((size_t)1 << 18)
/* Deflate's largest expansion: a 258-byte match per 2 bits at best, about 1032:1 (zlib's FAQ). */
#define DEFLATE_MAX_RATIO 1032u
/* What gzip input may inflate to: LUCENT_MESH_MAX_INFLATE_RATIO times the compressed bytes, plus this (so
 * that a small file's header and first rows, whatever their ratio, are never refused). */
#define INFLATE_SLACK ((uint64_t)1 << 20)

static _Atomic uint64_t g_read_limit;

void lucent_mesh_set_read_limit(uint64_t elements) { g_read_limit = elements; }

uint64_t lucent_mesh_read_limit(void)
{
    uint64_t l = g_read_limit;
    if (l) return l;
    const char *env = getenv("LUCENT_MESH_MAX_ELEMENTS");
    char *end;
    unsigned long long v = env ? strtoull(env, &end, 10) : 0;
    if (env && *env && !*end && v > 0) return v;
    return LUCENT_MESH_DEFAULT_READ_ELEMENTS;
}

/* The most inflated bytes gzip input of `compressed` bytes may give. */
static uint64_t inflate_cap(uint64_t compressed) { return compressed * LUCENT_MESH_MAX_INFLATE_RATIO + INFLATE_SLACK; }

static lucent_status start(lucent_reader *r)
{
    /* The buffer starts small (a small file or a fuzzer's input needs no more) and grows to BUF_CAP for
     * long lines and large reads. */
    r->cap = r->raw_size < ((uint64_t)1 << 16) && r->fd < 0 ? (size_t)1 << 14 : (size_t)1 << 18;
    r->buf = malloc(r->cap + 1);
    if (!r->buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
    r->line = 0;
    /* Peek at the first two bytes for the gzip magic (1f 8b). */
    unsigned char magic[2] = {0, 0};
    size_t got = 0;
    if (r->fd >= 0) {
        while (got < 2) {
            ssize_t n = read(r->fd, magic + got, 2 - got);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            got += (size_t)n;
        }
    } else {
        got = r->mem_size < 2 ? r->mem_size : 2;
        memcpy(magic, r->mem, got);
    }
    r->gz = got == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
    if (!r->gz) {
        memcpy(r->buf, magic, got);
        r->len = got;
        if (r->fd < 0) r->mem_pos = got;
        return LUCENT_OK;
    }
    r->in = r->fd >= 0 ? malloc(IN_CAP) : NULL;
    if (r->fd >= 0 && !r->in) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
    memset(&r->zs, 0, sizeof r->zs);
    if (inflateInit2(&r->zs, 16 + MAX_WBITS) != Z_OK) {
        r->gz = 0;
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: cannot start zlib", r->name);
    }
    if (r->fd >= 0) {
        memcpy(r->in, magic, 2);
        r->zs.next_in = r->in, r->zs.avail_in = 2;
    } else {
        r->zs.next_in = (unsigned char *)r->mem;
        r->zs.avail_in = r->mem_size > UINT_MAX ? UINT_MAX : (unsigned)r->mem_size;
        r->mem_pos = r->zs.avail_in;
        r->in_eof = r->mem_pos == r->mem_size;
    }
    return LUCENT_OK;
}

lucent_status lucent_reader_open(lucent_reader *r, const char *path)
{
    memset(r, 0, sizeof *r);
    r->name = path, r->fd = -1;
    int fd;
    uint64_t size;
    lucent_status s = lucent_open_regular(path, &fd, &size);
    if (s != LUCENT_OK) return s;
    r->fd = fd, r->raw_size = size;
    s = start(r);
    if (s != LUCENT_OK) lucent_reader_close(r);
    return s;
}

lucent_status lucent_reader_open_memory(lucent_reader *r, const void *data, size_t size, const char *name)
{
    memset(r, 0, sizeof *r);
    r->name = name, r->fd = -1;
    r->mem = data, r->mem_size = size, r->raw_size = size;
    lucent_status s = start(r);
    if (s != LUCENT_OK) lucent_reader_close(r);
    return s;
}

void lucent_reader_close(lucent_reader *r)
{
    if (r->gz) inflateEnd(&r->zs);
    if (r->fd >= 0) close(r->fd);
    free(r->buf);
    free(r->in);
    memset(r, 0, sizeof *r);
    r->fd = -1;
}

uint64_t lucent_reader_bound(const lucent_reader *r)
{
    uint64_t buffered = r->len - r->pos;
    if (!r->gz) return buffered + (r->fd >= 0 ? r->raw_size - (r->base + r->len) : r->mem_size - r->mem_pos);
    if (r->stream_end) return buffered;
    uint64_t raw_left = r->raw_size - r->zs.total_in, cap = inflate_cap(r->raw_size), out = r->zs.total_out;
    uint64_t left = raw_left * DEFLATE_MAX_RATIO + 65536, allowed = cap > out ? cap - out : 0;
    return buffered + (left < allowed ? left : allowed);
}

/* Reads raw bytes into r->in for inflate. */
static lucent_status feed(lucent_reader *r)
{
    if (r->fd < 0) {
        size_t left = r->mem_size - r->mem_pos;
        unsigned n = left > UINT_MAX ? UINT_MAX : (unsigned)left;
        r->zs.next_in = (unsigned char *)r->mem + r->mem_pos, r->zs.avail_in = n;
        r->mem_pos += n;
        r->in_eof = r->mem_pos == r->mem_size;
        return LUCENT_OK;
    }
    for (;;) {
        ssize_t n = read(r->fd, r->in, IN_CAP);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return lucent_error(LUCENT_ERR_IO, "%s: read failed: %s", r->name, strerror(errno));
        if (n == 0) r->in_eof = 1;
        r->zs.next_in = r->in, r->zs.avail_in = (unsigned)n;
        return LUCENT_OK;
    }
}

/* Appends decoded bytes to buf[len..cap). */
static lucent_status decode_more(lucent_reader *r)
{
    size_t room = r->cap - r->len;
    if (!r->gz) {
        if (r->fd < 0) {
            size_t n = r->mem_size - r->mem_pos < room ? r->mem_size - r->mem_pos : room;
            memcpy(r->buf + r->len, r->mem + r->mem_pos, n);
            r->mem_pos += n, r->len += n;
            if (r->mem_pos == r->mem_size) r->eof = 1;
            return LUCENT_OK;
        }
        for (;;) {
            ssize_t n = read(r->fd, r->buf + r->len, room);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) return lucent_error(LUCENT_ERR_IO, "%s: read failed: %s", r->name, strerror(errno));
            if (n == 0) r->eof = 1;
            r->len += (size_t)n;
            return LUCENT_OK;
        }
    }
    while (room > 0 && !r->eof) {
        if (r->zs.avail_in == 0 && !r->in_eof) {
            lucent_status s = feed(r);
            if (s != LUCENT_OK) return s;
        }
        r->zs.next_out = r->buf + r->len;
        r->zs.avail_out = room > UINT_MAX ? UINT_MAX : (unsigned)room;
        int z = inflate(&r->zs, Z_NO_FLUSH);
        size_t made = (size_t)(r->zs.next_out - (r->buf + r->len));
        r->len += made, room -= made;
        if ((uint64_t)r->zs.total_out > inflate_cap(r->zs.total_in))
            return lucent_error(LUCENT_ERR_PARSE,
                                "%s: gzip data inflating more than %d times its size (%llu bytes from %llu): refused "
                                "as a decompression bomb (gunzip it to read it whole)",
                                r->name, LUCENT_MESH_MAX_INFLATE_RATIO, (unsigned long long)r->zs.total_out,
                                (unsigned long long)r->zs.total_in);
        if (z == Z_STREAM_END) {
            r->stream_end = r->eof = 1; /* anything after the first gzip member is ignored */
        } else if (z == Z_OK || z == Z_BUF_ERROR) {
            if (made == 0 && r->zs.avail_in == 0 && r->in_eof)
                return lucent_error(LUCENT_ERR_PARSE,
                                    "%s: truncated gzip data: the compressed stream ends after %llu inflated "
                                    "bytes",
                                    r->name, (unsigned long long)(r->base + r->len));
        } else {
            return lucent_error(LUCENT_ERR_PARSE, "%s: corrupt gzip data after %llu inflated bytes: %s", r->name,
                                (unsigned long long)(r->base + r->len), r->zs.msg ? r->zs.msg : zError(z));
        }
        if (made > 0) break;
    }
    return LUCENT_OK;
}

lucent_status lucent_reader_fill(lucent_reader *r, size_t n)
{
    if (n > r->cap && r->cap < BUF_CAP) {
        size_t cap = 2 * r->cap;
        while (cap < n && cap < BUF_CAP) cap *= 2;
        if (cap > BUF_CAP) cap = BUF_CAP;
        unsigned char *grown = realloc(r->buf, cap + 1);
        if (!grown) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->name);
        r->buf = grown, r->cap = cap;
    }
    if (n > r->cap) n = r->cap;
    if (r->len - r->pos >= n) return LUCENT_OK;
    if (r->pos > 0) {
        memmove(r->buf, r->buf + r->pos, r->len - r->pos);
        r->base += r->pos, r->len -= r->pos, r->pos = 0;
    }
    while (r->len < n && !r->eof) {
        lucent_status s = decode_more(r);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

lucent_status lucent_reader_finish(lucent_reader *r)
{
    while (r->gz && !r->stream_end) {
        r->base += r->len, r->pos = r->len = 0; /* what is left is not needed, only checked */
        lucent_status s = decode_more(r);
        if (s != LUCENT_OK) return s;
        if (r->eof && !r->stream_end) break;
    }
    return LUCENT_OK;
}

lucent_status lucent_reader_line(lucent_reader *r, char **line, size_t *length)
{
    *line = NULL;
    if (length) *length = 0;
    size_t scanned = 0;
    for (;;) {
        unsigned char *start = r->buf + r->pos;
        size_t have = r->len - r->pos;
        unsigned char *nl = have > scanned ? memchr(start + scanned, '\n', have - scanned) : NULL;
        if (nl || r->eof) {
            if (!nl && have == 0) return LUCENT_OK;
            size_t n = nl ? (size_t)(nl - start) : have;
            if (n > LUCENT_READER_MAX_LINE)
                return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: longer than %zu bytes", r->name,
                                    (unsigned long long)(r->line + 1), LUCENT_READER_MAX_LINE);
            r->pos += nl ? n + 1 : n;
            if (n > 0 && start[n - 1] == '\r') n--;
            start[n] = '\0'; /* buf has one spare byte past cap for a last line without '\n' */
            r->line++;
            *line = (char *)start;
            if (length) *length = n;
            return LUCENT_OK;
        }
        if (have > LUCENT_READER_MAX_LINE)
            return lucent_error(LUCENT_ERR_PARSE, "%s: line %llu: longer than %zu bytes", r->name,
                                (unsigned long long)(r->line + 1), LUCENT_READER_MAX_LINE);
        scanned = have;
        lucent_status s = lucent_reader_fill(r, have + 1);
        if (s != LUCENT_OK) return s;
    }
}

lucent_status lucent_reader_bytes(lucent_reader *r, void *dest, size_t n, const char *what)
{
    unsigned char *d = dest;
    while (n > 0) {
        if (r->pos == r->len) {
            lucent_status s = lucent_reader_fill(r, n < r->cap ? n : r->cap);
            if (s != LUCENT_OK) return s;
            if (r->pos == r->len)
                return lucent_error(LUCENT_ERR_PARSE, "%s: truncated at byte %llu: the data ends in %s", r->name,
                                    (unsigned long long)lucent_reader_offset(r), what);
        }
        size_t k = r->len - r->pos < n ? r->len - r->pos : n;
        memcpy(d, r->buf + r->pos, k);
        r->pos += k, d += k, n -= k;
    }
    return LUCENT_OK;
}

/* ---- Numbers ---------------------------------------------------------------- */

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

static const double k_pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                   1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

int lucent_parse_double(const char **pp, const char *end, double *dest)
{
    const char *p = *pp;
    while (p < end && is_blank(*p)) p++;
    const char *start = p;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) neg = *p == '-', p++;
    uint64_t m = 0;
    int digits = 0, exp10 = 0, any = 0;
    for (; p < end && *p >= '0' && *p <= '9'; p++, any = 1)
        if (digits < 19)
            m = m * 10 + (uint64_t)(*p - '0'), digits += m > 0;
        else
            exp10++;
    if (p < end && *p == '.') {
        for (p++; p < end && *p >= '0' && *p <= '9'; p++, any = 1)
            if (digits < 19) m = m * 10 + (uint64_t)(*p - '0'), digits += m > 0, exp10--;
    }
    if (!any) goto slow; /* "nan", "inf", or no number */
    if (p < end && (*p == 'e' || *p == 'E')) {
        const char *q = p + 1;
        int eneg = 0, e = 0, edig = 0;
        if (q < end && (*q == '-' || *q == '+')) eneg = *q == '-', q++;
        for (; q < end && *q >= '0' && *q <= '9'; q++, edig++)
            if (e < 100000) e = e * 10 + (*q - '0');
        if (!edig) return 0;
        exp10 += eneg ? -e : e;
        p = q;
    }
    if (p < end && !is_blank(*p) && *p != '\0') return 0;
    /* Clinger's fast path: m and 10^|e| are exact doubles, so one multiplication or division rounds
     * correctly. Otherwise strtod. */
    if (m <= ((uint64_t)1 << 53) && exp10 >= -22 && exp10 <= 22) {
        double v = (double)m;
        v = exp10 < 0 ? v / k_pow10[-exp10] : v * k_pow10[exp10];
        *dest = neg ? -v : v;
        *pp = p;
        return 1;
    }
slow:;
    /* The text readers NUL-terminate their lines, so strtod stops within [start, end]. */
    if (start >= end) return 0;
    char *stop;
    double v = strtod(start, &stop);
    if (stop == start || stop > end || (stop < end && !is_blank(*stop) && *stop != '\0')) return 0;
    *dest = v;
    *pp = stop;
    return 1;
}

int lucent_parse_int64(const char **pp, const char *end, int64_t *dest)
{
    const char *p = *pp;
    while (p < end && is_blank(*p)) p++;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) neg = *p == '-', p++;
    uint64_t v = 0;
    int any = 0;
    for (; p < end && *p >= '0' && *p <= '9'; p++, any = 1) {
        if (v > (uint64_t)INT64_MAX / 10) return 0;
        v = v * 10 + (uint64_t)(*p - '0');
        if (v > (uint64_t)INT64_MAX) return 0;
    }
    if (!any || (p < end && !is_blank(*p) && *p != '\0')) return 0;
    *dest = neg ? -(int64_t)v : (int64_t)v;
    *pp = p;
    return 1;
}
