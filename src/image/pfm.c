/* PFM (portable float map): "PF" (RGB) or "Pf" (grey), width, height, scale; the sign of the scale
 * gives the byte order (negative: little endian), rows are stored bottom-to-top. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "image/internal.h"

typedef struct pfm_header {
    int channels;
    long long width, height;
    double scale;
} pfm_header;

/* Reads one whitespace-delimited token of at most size-1 characters; false at EOF or when longer. */
static bool read_token(FILE *fp, char *tok, size_t size)
{
    int ch = fgetc(fp);
    while (ch != EOF && isspace(ch)) ch = fgetc(fp);
    size_t n = 0;
    while (ch != EOF && !isspace(ch)) {
        if (n + 1 >= size) return false;
        tok[n++] = (char)ch;
        ch = fgetc(fp);
    }
    tok[n] = '\0';
    return n > 0; /* the single whitespace after the scale has been consumed */
}

static bool parse_int(const char *tok, long long *dest)
{
    char *end;
    errno = 0;
    long long v = strtoll(tok, &end, 10);
    if (*end || errno || v < 0) return false;
    *dest = v;
    return true;
}

static lucent_status read_header(const char *path, FILE *fp, pfm_header *h)
{
    char tok[64], w[64], hh[64];
    if (!read_token(fp, tok, sizeof tok) || (strcmp(tok, "PF") != 0 && strcmp(tok, "Pf") != 0))
        return lucent_error(LUCENT_ERR_PARSE, "%s: not a PFM file (expected \"PF\" or \"Pf\")", path);
    h->channels = tok[1] == 'F' ? 3 : 1;
    if (!read_token(fp, w, sizeof w) || !read_token(fp, hh, sizeof hh) || !parse_int(w, &h->width) ||
        !parse_int(hh, &h->height))
        return lucent_error(LUCENT_ERR_PARSE, "%s: PFM header: bad width or height", path);
    char *end;
    if (!read_token(fp, tok, sizeof tok) || (h->scale = strtod(tok, &end), *end) || !isfinite(h->scale) ||
        h->scale == 0.0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: PFM header: bad scale (a non-zero number; negative: little endian)",
                            path);
    return image_check_read(path, h->width, h->height, h->channels);
}

/* Checks that the file holds at least the pixel data the header announces. */
static lucent_status check_length(const char *path, FILE *fp, const pfm_header *h)
{
    struct stat st;
    long pos = ftell(fp);
    if (fstat(fileno(fp), &st) != 0 || pos < 0 || !S_ISREG(st.st_mode)) return LUCENT_OK;
    uint64_t need = (uint64_t)h->width * (uint64_t)h->height * (uint64_t)h->channels * 4u;
    uint64_t have = (uint64_t)st.st_size - (uint64_t)pos;
    if (have >= need) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_PARSE, "%s: truncated PFM data (%lldx%lld needs %llu bytes of pixels, found %llu)",
                        path, h->width, h->height, (unsigned long long)need, (unsigned long long)have);
}

static lucent_status read_pixels(const char *path, FILE *fp, const pfm_header *h, lucent_image *img)
{
    size_t row_values = (size_t)img->width * (size_t)img->channels;
    unsigned char *row = malloc(row_values * 4);
    if (!row) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    bool le = h->scale < 0;
    for (int y = img->height - 1; y >= 0; y--) { /* bottom row first */
        if (fread(row, 4, row_values, fp) != row_values) {
            free(row);
            return lucent_error(LUCENT_ERR_PARSE, "%s: truncated PFM data (row %d of %d missing)", path,
                                img->height - y, img->height);
        }
        float *p = lucent_image_pixel(img, 0, y);
        for (size_t i = 0; i < row_values; i++) p[i] = image_get_f32(row + 4 * i, le);
    }
    free(row);
    return LUCENT_OK;
}

lucent_status lucent_image_load_pfm(const char *path, lucent_image **dest)
{
    *dest = NULL;
    FILE *fp;
    lucent_status st = lucent_fopen_regular(path, &fp, NULL);
    if (st != LUCENT_OK) return st;
    pfm_header h = {0};
    lucent_status s = read_header(path, fp, &h);
    if (s == LUCENT_OK) s = check_length(path, fp, &h);
    lucent_image *img = NULL;
    if (s == LUCENT_OK) s = lucent_image_create((int)h.width, (int)h.height, h.channels, &img);
    if (s == LUCENT_OK) s = read_pixels(path, fp, &h, img);
    fclose(fp);
    if (s != LUCENT_OK) {
        lucent_image_destroy(img);
        return s;
    }
    *dest = img;
    return LUCENT_OK;
}

static bool write_pixels(FILE *fp, const lucent_image *img)
{
    size_t row_values = (size_t)img->width * (size_t)img->channels;
    unsigned char *row = malloc(row_values * 4);
    bool ok = row != NULL;
    for (int y = img->height - 1; ok && y >= 0; y--) {
        const float *p = lucent_image_pixel(img, 0, y);
        for (size_t i = 0; i < row_values; i++) image_put_le32(row + 4 * i, p[i]);
        ok = fwrite(row, 4, row_values, fp) == row_values;
    }
    free(row);
    return ok;
}

lucent_status lucent_image_write_pfm(const char *path, const lucent_image *img)
{
    lucent_status s = image_check_size(path, img->width, img->height, img->channels, LUCENT_ERR_INVALID_ARGUMENT);
    if (s != LUCENT_OK) return s;
    if (img->channels == 4)
        return lucent_error(LUCENT_ERR_UNSUPPORTED,
                            "%s: PFM holds 1 or 3 channels, not 4 (drop the alpha channel first)", path);
    lucent_atomic_file *af;
    FILE *fp;
    s = lucent_atomic_open(path, &af, &fp);
    if (s != LUCENT_OK) return s;
    fprintf(fp, "%s\n%d %d\n-1.0\n", img->channels == 3 ? "PF" : "Pf", img->width, img->height);
    if (!write_pixels(fp, img)) {
        int e = errno;
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed: %s", path, strerror(e));
    }
    return lucent_atomic_commit(af);
}
