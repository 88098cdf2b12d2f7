/* PNG files through libpng. libpng reports errors by longjmp: every call that may fail runs
 * inside one function that sets the jump point, and all state lives in a png_job owned by the
 * caller, so nothing local to the jumping function changes between setjmp and longjmp. */
#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "image/internal.h"

typedef struct png_job {
    const char *path;
    FILE *fp;
    png_structp png;
    png_infop info;
    unsigned char *buf; /* decoded rows (read) or one row (write) */
    png_bytep *rows;
    float *lut; /* sample code -> linear value (read) */
    lucent_image *img;
    char msg[200]; /* libpng's error text */
} png_job;

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_job *job = png_get_error_ptr(png);
    snprintf(job->msg, sizeof job->msg, "%s", msg);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png, (void)msg; /* the library never prints; warnings do not change the result */
}

static void on_png_read(png_structp png, png_bytep data, size_t size)
{
    png_job *job = png_get_io_ptr(png);
    if (fread(data, 1, size, job->fp) != size)
        png_error(png, ferror(job->fp) ? "read error" : "unexpected end of file");
}

static void job_free(png_job *job, bool reading)
{
    if (job->png && reading) png_destroy_read_struct(&job->png, &job->info, NULL);
    if (job->png && !reading) png_destroy_write_struct(&job->png, &job->info);
    free(job->buf);
    free(job->rows);
    free(job->lut);
}

/* ---- reading ---- */

/* The transfer curve of the file's colour samples: 0 for sRGB, else the decoding exponent. */
static double file_decoding_exponent(png_job *job)
{
    if (png_get_valid(job->png, job->info, PNG_INFO_sRGB)) return 0.0;
    png_fixed_point g;
    if (!png_get_gAMA_fixed(job->png, job->info, &g) || g <= 0) return 0.0;
    return 100000.0 / (double)g; /* PNG 1.2, 11.3.3.2: sample = linear^gamma */
}

static bool build_lut(png_job *job, int bits)
{
    size_t n = (size_t)1 << bits;
    job->lut = malloc((n * 2) * sizeof(float)); /* [0, n): colour; [n, 2n): alpha (linear) */
    if (!job->lut) return false;
    double expo = file_decoding_exponent(job);
    for (size_t i = 0; i < n; i++) {
        float e = (float)((double)i / (double)(n - 1));
        job->lut[i] = expo == 0.0 ? lucent_srgb_decode(e) : (float)pow(e, expo);
        job->lut[n + i] = e;
    }
    return true;
}

static void set_read_transforms(png_job *job)
{
    int type = png_get_color_type(job->png, job->info);
    if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(job->png);
    if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(job->png, job->info) < 8)
        png_set_expand_gray_1_2_4_to_8(job->png);
    if (png_get_valid(job->png, job->info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(job->png);
    png_set_interlace_handling(job->png);
    png_read_update_info(job->png, job->info);
}

/* Converts the decoded rows (in_ch samples of `bits` bits) to the float image. */
static void rows_to_image(png_job *job, int in_ch, int bits)
{
    lucent_image *img = job->img;
    size_t n = (size_t)1 << bits, bps = (size_t)bits / 8;
    for (int y = 0; y < img->height; y++) {
        const unsigned char *row = job->rows[y];
        for (int x = 0; x < img->width; x++) {
            float v[4];
            for (int c = 0; c < in_ch; c++) {
                const unsigned char *s = row + ((size_t)x * (size_t)in_ch + (size_t)c) * bps;
                size_t code = bps == 2 ? ((size_t)s[0] << 8 | s[1]) : s[0];
                bool alpha = in_ch % 2 == 0 && c == in_ch - 1;
                v[c] = job->lut[(alpha ? n : 0) + code];
            }
            float *p = lucent_image_pixel(img, x, y);
            if (in_ch == 2)
                p[0] = p[1] = p[2] = v[0], p[3] = v[1];
            else
                memcpy(p, v, (size_t)in_ch * sizeof(float));
        }
    }
}

static lucent_status read_body(png_job *job)
{
    if (setjmp(png_jmpbuf(job->png)))
        return lucent_error(LUCENT_ERR_PARSE, "%s: truncated or corrupt PNG data (%s)", job->path, job->msg);
    png_set_read_fn(job->png, job, on_png_read);
    png_set_sig_bytes(job->png, 8);
    png_set_user_limits(job->png, LUCENT_IMAGE_MAX_SIDE, LUCENT_IMAGE_MAX_SIDE);
    png_read_info(job->png, job->info);
    set_read_transforms(job);
    png_uint_32 w = png_get_image_width(job->png, job->info);
    png_uint_32 h = png_get_image_height(job->png, job->info);
    int in_ch = png_get_channels(job->png, job->info);
    int bits = png_get_bit_depth(job->png, job->info);
    lucent_status s = image_check_read(job->path, w, h, in_ch == 1 ? 1 : in_ch == 3 ? 3 : 4);
    if (s != LUCENT_OK) return s;
    size_t rowbytes = png_get_rowbytes(job->png, job->info);
    job->buf = malloc(rowbytes * h);
    job->rows = malloc(h * sizeof *job->rows);
    if (!job->buf || !job->rows || !build_lut(job, bits))
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", job->path);
    for (png_uint_32 y = 0; y < h; y++) job->rows[y] = job->buf + y * rowbytes;
    png_read_image(job->png, job->rows);
    png_read_end(job->png, NULL);
    s = lucent_image_create((int)w, (int)h, in_ch == 1 ? 1 : in_ch == 3 ? 3 : 4, &job->img);
    if (s != LUCENT_OK) return lucent_error_context(s, "%s", job->path);
    rows_to_image(job, in_ch, bits);
    return LUCENT_OK;
}

static lucent_status check_signature(png_job *job)
{
    unsigned char sig[8];
    size_t got = fread(sig, 1, 8, job->fp);
    if (got == 0 && ferror(job->fp))
        return lucent_error(LUCENT_ERR_IO, "%s: cannot read: %s", job->path, strerror(errno));
    if (got == 0) return lucent_error(LUCENT_ERR_PARSE, "%s: not a PNG file (empty file)", job->path);
    if (png_sig_cmp(sig, 0, got) != 0)
        return lucent_error(LUCENT_ERR_PARSE, "%s: not a PNG file (bad signature)", job->path);
    if (got < 8) return lucent_error(LUCENT_ERR_PARSE, "%s: truncated or corrupt PNG data (%zu bytes)", job->path, got);
    return LUCENT_OK;
}

lucent_status lucent_image_load_png(const char *path, lucent_image **dest)
{
    *dest = NULL;
    png_job job = {.path = path};
    lucent_status st = lucent_fopen_regular(path, &job.fp, NULL);
    if (st != LUCENT_OK) return st;
    lucent_status s = check_signature(&job);
    if (s == LUCENT_OK) {
        job.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &job, on_png_error, on_png_warning);
        job.info = job.png ? png_create_info_struct(job.png) : NULL;
        s = job.info ? read_body(&job) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    fclose(job.fp);
    job_free(&job, true);
    if (s == LUCENT_OK)
        *dest = job.img;
    else
        lucent_image_destroy(job.img);
    return s;
}

/* ---- writing ---- */

static unsigned quantise(float v, unsigned max)
{
    float c = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN -> 0 */
    return (unsigned)((double)c * max + 0.5);
}

static void fill_row(png_job *job, const lucent_image *img, int y, const lucent_image_write_desc *d)
{
    unsigned max = d->png_bits == 16 ? 65535u : 255u;
    const float *p = lucent_image_pixel(img, 0, y);
    size_t n = (size_t)img->width * (size_t)img->channels;
    for (size_t i = 0; i < n; i++) {
        bool alpha = img->channels == 4 && i % 4 == 3;
        unsigned q = quantise(alpha || d->png_linear ? p[i] : lucent_srgb_encode(p[i]), max);
        if (max == 255u)
            job->buf[i] = (unsigned char)q;
        else
            job->buf[2 * i] = (unsigned char)(q >> 8), job->buf[2 * i + 1] = (unsigned char)q;
    }
}

static lucent_status write_body(png_job *job, const lucent_image *img, const lucent_image_write_desc *d)
{
    if (setjmp(png_jmpbuf(job->png)))
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write PNG (%s)", job->path, job->msg);
    png_init_io(job->png, job->fp);
    int type = img->channels == 1   ? PNG_COLOR_TYPE_GRAY
               : img->channels == 3 ? PNG_COLOR_TYPE_RGB
                                    : PNG_COLOR_TYPE_RGB_ALPHA;
    png_set_IHDR(job->png, job->info, (png_uint_32)img->width, (png_uint_32)img->height, d->png_bits, type,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (d->png_linear)
        png_set_gAMA_fixed(job->png, job->info, PNG_GAMMA_LINEAR);
    else
        png_set_sRGB_gAMA_and_cHRM(job->png, job->info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(job->png, job->info);
    for (int y = 0; y < img->height; y++) {
        fill_row(job, img, y, d);
        png_write_row(job->png, job->buf);
    }
    png_write_end(job->png, job->info);
    return LUCENT_OK;
}

lucent_status lucent_image_write_png(const char *path, const lucent_image *img, const lucent_image_write_desc *desc)
{
    lucent_image_write_desc d = image_resolve_desc(desc);
    if (d.png_bits != 8 && d.png_bits != 16)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: PNG bit depth %d (expected 8 or 16)", path, d.png_bits);
    lucent_status s = image_check_size(path, img->width, img->height, img->channels, LUCENT_ERR_INVALID_ARGUMENT);
    if (s != LUCENT_OK) return s;
    png_job job = {.path = path};
    lucent_atomic_file *af;
    s = lucent_atomic_open(path, &af, &job.fp);
    if (s != LUCENT_OK) return s;
    job.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &job, on_png_error, on_png_warning);
    job.info = job.png ? png_create_info_struct(job.png) : NULL;
    job.buf = malloc((size_t)img->width * (size_t)img->channels * 2);
    if (!job.info || !job.buf)
        s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    else
        s = write_body(&job, img, &d);
    job_free(&job, false);
    if (s != LUCENT_OK) {
        lucent_atomic_abort(af);
        return s;
    }
    return lucent_atomic_commit(af);
}
