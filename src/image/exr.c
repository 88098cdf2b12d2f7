/* OpenEXR files through OpenEXR's C core API (libOpenEXRCore): reading scanline and tiled parts
 * with the decode pipeline, writing scanline parts with the encode pipeline into the FILE* of an
 * atomic output (custom write function), so a failed write leaves nothing behind. */
#include <errno.h>
#include <openexr.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/internal.h"

/* OpenEXR reports the text of an error through a callback, on the failing thread. */
static _Thread_local char t_exr_msg[256];

static void on_exr_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    snprintf(t_exr_msg, sizeof t_exr_msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static const char *exr_message(exr_result_t rv) { return t_exr_msg[0] ? t_exr_msg : exr_get_default_error_message(rv); }

static exr_context_initializer_t exr_init(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = on_exr_error;
    init.max_image_width = LUCENT_IMAGE_MAX_SIDE;
    init.max_image_height = LUCENT_IMAGE_MAX_SIDE;
    init.max_tile_width = LUCENT_IMAGE_MAX_SIDE;
    init.max_tile_height = LUCENT_IMAGE_MAX_SIDE;
    return init;
}

/* ---- reading ---- */

typedef struct exr_reader {
    const char *path;
    exr_context_t ctx;
    exr_decode_pipeline_t dec;
    bool dec_ready;
    exr_attr_box2i_t dw;
    int target[64];  /* file channel index -> image channel, -1: skipped */
    bool grey_alpha; /* Y and A: replicate Y into G and B afterwards */
    lucent_image *img;
    float *scratch; /* one decoded chunk, a plane per image channel */
    uint64_t file_size;
    size_t scratch_size;
} exr_reader;

static lucent_status corrupt(exr_reader *r, exr_result_t rv)
{
    return lucent_error(LUCENT_ERR_PARSE, "%s: truncated or corrupt OpenEXR data (%s)", r->path, exr_message(rv));
}

static int find_channel(const exr_attr_chlist_t *cl, const char *name)
{
    for (int i = 0; i < cl->num_channels; i++)
        if (strcmp(cl->entries[i].name.str, name) == 0) return i;
    return -1;
}

/* Chooses which file channels fill which image channels; returns the image channel count. */
static lucent_status map_channels(exr_reader *r, const exr_attr_chlist_t *cl, int *channels)
{
    int R = find_channel(cl, "R"), G = find_channel(cl, "G"), B = find_channel(cl, "B");
    int A = find_channel(cl, "A"), Y = find_channel(cl, "Y");
    int n = cl->num_channels < 64 ? cl->num_channels : 64;
    for (int i = 0; i < n; i++) r->target[i] = -1;
    if (R >= 0 && G >= 0 && B >= 0) {
        r->target[R] = 0, r->target[G] = 1, r->target[B] = 2;
        *channels = 3;
    } else if (Y >= 0 || cl->num_channels == 1) {
        r->target[Y >= 0 ? Y : 0] = 0;
        *channels = 1;
    } else {
        return lucent_error(LUCENT_ERR_UNSUPPORTED,
                            "%s: no R, G, B or Y channels (%d channels, the first named \"%s\")", r->path,
                            cl->num_channels, cl->num_channels ? cl->entries[0].name.str : "");
    }
    if (A >= 0 && *channels != 4 && (*channels == 3 || Y >= 0)) {
        r->grey_alpha = *channels == 1;
        r->target[A] = 3;
        *channels = 4;
    }
    for (int i = 0; i < n; i++)
        if (r->target[i] >= 0 && (cl->entries[i].x_sampling != 1 || cl->entries[i].y_sampling != 1))
            return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: channel %s is subsampled", r->path,
                                cl->entries[i].name.str);
    return LUCENT_OK;
}

/* Points the decode pipeline's channels at planes of the scratch buffer, one per image channel.
 * (Planes, not the interleaved image: OpenEXR 3.1's fast path for interleaved half -> float
 * output writes the channels in reverse order, seen with 3.1.5.) */
static lucent_status point_channels(exr_reader *r, const exr_chunk_info_t *ci)
{
    size_t plane = (size_t)ci->width * (size_t)ci->height;
    if (plane * 4 > r->scratch_size) {
        free(r->scratch);
        r->scratch_size = plane * 4;
        r->scratch = malloc(r->scratch_size * sizeof(float));
        if (!r->scratch) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", r->path);
    }
    memset(r->scratch, 0, plane * 4 * sizeof(float)); /* what a codec leaves undecoded is 0, never old bytes */
    const exr_attr_chlist_t *cl;
    exr_get_channels(r->ctx, 0, &cl);
    for (int i = 0; i < r->dec.channel_count; i++) {
        exr_coding_channel_info_t *ch = &r->dec.channels[i];
        int idx = find_channel(cl, ch->channel_name);
        int t = idx >= 0 && idx < 64 ? r->target[idx] : -1;
        ch->decode_to_ptr = t < 0 ? NULL : (uint8_t *)(r->scratch + (size_t)t * plane);
        ch->user_pixel_stride = (int32_t)sizeof(float);
        ch->user_line_stride = ci->width * (int32_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
    }
    return LUCENT_OK;
}

/* Copies the decoded planes into the image, the chunk starting at (x0, y0). */
static void planes_to_image(exr_reader *r, const exr_chunk_info_t *ci, int x0, int y0)
{
    size_t plane = (size_t)ci->width * (size_t)ci->height;
    int channels = r->grey_alpha ? 4 : r->img->channels;
    for (int y = 0; y < ci->height; y++)
        for (int x = 0; x < ci->width; x++) {
            float *p = lucent_image_pixel(r->img, x0 + x, y0 + y);
            size_t k = (size_t)y * (size_t)ci->width + (size_t)x;
            for (int c = 0; c < channels; c++)
                if (!r->grey_alpha || c == 0 || c == 3) p[c] = r->scratch[(size_t)c * plane + k];
        }
}

static lucent_status decode_chunk(exr_reader *r, const exr_chunk_info_t *ci, int x0, int y0)
{
    if (x0 < 0 || y0 < 0 || ci->width < 1 || ci->height < 1 || x0 + ci->width > r->img->width ||
        y0 + ci->height > r->img->height)
        return lucent_error(LUCENT_ERR_PARSE, "%s: corrupt OpenEXR data (chunk outside the image)", r->path);
    exr_result_t rv =
        r->dec_ready ? exr_decoding_update(r->ctx, 0, ci, &r->dec) : exr_decoding_initialize(r->ctx, 0, ci, &r->dec);
    if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
    r->dec_ready = true;
    lucent_status s = point_channels(r, ci);
    if (s != LUCENT_OK) return s;
    rv = exr_decoding_choose_default_routines(r->ctx, 0, &r->dec);
    if (rv == EXR_ERR_SUCCESS) rv = exr_decoding_run(r->ctx, 0, &r->dec);
    if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
    planes_to_image(r, ci, x0, y0);
    return LUCENT_OK;
}

static lucent_status read_scanlines(exr_reader *r)
{
    int32_t lines;
    exr_result_t rv = exr_get_scanlines_per_chunk(r->ctx, 0, &lines);
    if (rv != EXR_ERR_SUCCESS || lines < 1) return corrupt(r, rv);
    for (int64_t y = r->dw.min.y; y <= r->dw.max.y; y += lines) {
        exr_chunk_info_t ci;
        rv = exr_read_scanline_chunk_info(r->ctx, 0, (int)y, &ci);
        if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
        lucent_status s = decode_chunk(r, &ci, ci.start_x - r->dw.min.x, ci.start_y - r->dw.min.y);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

static lucent_status read_tiles(exr_reader *r)
{
    uint32_t tw, th;
    exr_tile_level_mode_t lm;
    exr_tile_round_mode_t rm;
    exr_result_t rv = exr_get_tile_descriptor(r->ctx, 0, &tw, &th, &lm, &rm);
    if (rv != EXR_ERR_SUCCESS || tw < 1 || th < 1) return corrupt(r, rv);
    int nx = (int)((r->img->width + tw - 1) / tw), ny = (int)((r->img->height + th - 1) / th);
    for (int ty = 0; ty < ny; ty++) {
        for (int tx = 0; tx < nx; tx++) {
            exr_chunk_info_t ci;
            rv = exr_read_tile_chunk_info(r->ctx, 0, tx, ty, 0, 0, &ci);
            if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
            lucent_status s = decode_chunk(r, &ci, tx * (int)tw, ty * (int)th);
            if (s != LUCENT_OK) return s;
        }
    }
    return LUCENT_OK;
}

/* One chunk's entry (line y, or tile tx, ty): inside the file, and its unpacked size one that its packed
 * bytes can give: equal to it without compression, else no more than 2048 times it (no EXR codec expands more
 * than deflate's 1032:1; 2048 leaves room). A chunk shorter than its lines would leave pixels undecoded. */
static lucent_status check_chunk(exr_reader *r, const exr_chunk_info_t *ci, exr_compression_t comp, const char *what,
                                 long long a, long long b)
{
    char where[64];
    snprintf(where, sizeof where, b < 0 ? "%s %lld" : "%s %lld, %lld", what, a, b);
    if (ci->data_offset > r->file_size || ci->packed_size > r->file_size - ci->data_offset ||
        ci->unpacked_size > 2048 * ci->packed_size + 4096)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: corrupt OpenEXR chunk table (the chunk at %s claims %llu bytes at offset %llu, "
                            "%llu unpacked, in a %llu-byte file)",
                            r->path, where, (unsigned long long)ci->packed_size, (unsigned long long)ci->data_offset,
                            (unsigned long long)ci->unpacked_size, (unsigned long long)r->file_size);
    if (comp == EXR_COMPRESSION_NONE && ci->packed_size != ci->unpacked_size)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: truncated or corrupt OpenEXR data (the uncompressed chunk at %s holds %llu bytes, its "
                            "%d x %d pixels need %llu)",
                            r->path, where, (unsigned long long)ci->packed_size, ci->width, ci->height,
                            (unsigned long long)ci->unpacked_size);
    return LUCENT_OK;
}

/* Before anything is allocated for the pixels: the chunk table must fit the file (8 bytes an entry), and
 * every chunk that the reader decodes (each scanline block; each tile of level 0) must pass check_chunk, so
 * that a 379-byte file cannot make the reader allocate gigabytes nor a short chunk leave pixels undecoded. */
static lucent_status check_chunk_table(exr_reader *r, exr_storage_t storage)
{
    int32_t count = 0;
    exr_compression_t comp = EXR_COMPRESSION_NONE;
    exr_result_t rv = exr_get_chunk_count(r->ctx, 0, &count);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_compression(r->ctx, 0, &comp);
    if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
    if (count < 1 || (uint64_t)count * 8 > r->file_size)
        return lucent_error(LUCENT_ERR_PARSE,
                            "%s: corrupt OpenEXR data (a chunk table of %d entries in a %llu-byte file)", r->path,
                            count, (unsigned long long)r->file_size);
    exr_chunk_info_t ci;
    lucent_status s = LUCENT_OK;
    if (storage == EXR_STORAGE_TILED) {
        uint32_t tw, th;
        exr_tile_level_mode_t lm;
        exr_tile_round_mode_t rm;
        rv = exr_get_tile_descriptor(r->ctx, 0, &tw, &th, &lm, &rm);
        if (rv != EXR_ERR_SUCCESS || tw < 1 || th < 1) return corrupt(r, rv);
        int64_t w = (int64_t)r->dw.max.x - r->dw.min.x + 1, h = (int64_t)r->dw.max.y - r->dw.min.y + 1;
        int64_t nx = (w + tw - 1) / tw, ny = (h + th - 1) / th;
        if (nx * ny > count)
            return lucent_error(LUCENT_ERR_PARSE, "%s: corrupt OpenEXR data (%lld tiles, a chunk table of %d)", r->path,
                                (long long)(nx * ny), count);
        for (int64_t ty = 0; s == LUCENT_OK && ty < ny; ty++)
            for (int64_t tx = 0; s == LUCENT_OK && tx < nx; tx++) {
                rv = exr_read_tile_chunk_info(r->ctx, 0, (int)tx, (int)ty, 0, 0, &ci);
                s = rv != EXR_ERR_SUCCESS ? lucent_error(LUCENT_ERR_PARSE, "%s: corrupt OpenEXR chunk table (%s)",
                                                         r->path, exr_message(rv))
                                          : check_chunk(r, &ci, comp, "tile", tx, ty);
            }
        return s;
    }
    int32_t lines;
    rv = exr_get_scanlines_per_chunk(r->ctx, 0, &lines);
    if (rv != EXR_ERR_SUCCESS || lines < 1) return corrupt(r, rv);
    for (int64_t y = r->dw.min.y; s == LUCENT_OK && y <= r->dw.max.y; y += lines) {
        rv = exr_read_scanline_chunk_info(r->ctx, 0, (int)y, &ci);
        s = rv != EXR_ERR_SUCCESS
                ? lucent_error(LUCENT_ERR_PARSE, "%s: corrupt OpenEXR chunk table (%s)", r->path, exr_message(rv))
                : check_chunk(r, &ci, comp, "line", y, -1);
    }
    return s;
}

/* Reads the header facts of part 0 and allocates the image. */
static lucent_status prepare(exr_reader *r, exr_storage_t *storage)
{
    const exr_attr_chlist_t *cl;
    exr_result_t rv = exr_get_storage(r->ctx, 0, storage);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_data_window(r->ctx, 0, &r->dw);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_channels(r->ctx, 0, &cl);
    if (rv != EXR_ERR_SUCCESS) return corrupt(r, rv);
    if (*storage != EXR_STORAGE_SCANLINE && *storage != EXR_STORAGE_TILED)
        return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: deep OpenEXR images are not supported", r->path);
    int channels = 0;
    lucent_status s = map_channels(r, cl, &channels);
    int64_t w = (int64_t)r->dw.max.x - r->dw.min.x + 1, h = (int64_t)r->dw.max.y - r->dw.min.y + 1;
    if (s == LUCENT_OK) s = image_check_read(r->path, w, h, channels);
    if (s == LUCENT_OK) s = check_chunk_table(r, *storage);
    if (s == LUCENT_OK) s = lucent_image_create((int)w, (int)h, channels, &r->img);
    return s;
}

static void replicate_grey(lucent_image *img)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++) img->data[4 * i + 1] = img->data[4 * i + 2] = img->data[4 * i];
}

/* Opens the file to tell a missing file and a wrong magic number from a corrupt header. */
static lucent_status probe_magic(const char *path, uint64_t *size)
{
    FILE *fp;
    lucent_status st = lucent_fopen_regular(path, &fp, size);
    if (st != LUCENT_OK) return st;
    unsigned char m[4] = {0};
    size_t got = fread(m, 1, 4, fp);
    fclose(fp);
    static const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01}; /* 20000630, little endian */
    if (got == 4 && memcmp(m, magic, 4) == 0) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_PARSE, "%s: not an OpenEXR file (%s)", path,
                        got == 0 ? "empty file" : "bad magic number");
}

lucent_status lucent_image_load_exr(const char *path, lucent_image **dest)
{
    *dest = NULL;
    uint64_t size = 0;
    lucent_status s = probe_magic(path, &size);
    if (s != LUCENT_OK) return s;
    exr_reader r = {.path = path, .file_size = size};
    exr_context_initializer_t init = exr_init();
    t_exr_msg[0] = '\0';
    exr_result_t rv = exr_start_read(&r.ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        exr_finish(&r.ctx);
        return lucent_error(LUCENT_ERR_PARSE, "%s: truncated or corrupt OpenEXR header (%s)", path, exr_message(rv));
    }
    exr_storage_t storage;
    s = prepare(&r, &storage);
    if (s == LUCENT_OK) s = storage == EXR_STORAGE_TILED ? read_tiles(&r) : read_scanlines(&r);
    if (r.dec_ready) exr_decoding_destroy(r.ctx, &r.dec);
    exr_finish(&r.ctx);
    free(r.scratch);
    if (s != LUCENT_OK) {
        lucent_image_destroy(r.img);
        return s;
    }
    if (r.grey_alpha) replicate_grey(r.img);
    *dest = r.img;
    return LUCENT_OK;
}

/* ---- writing ---- */

static int64_t write_to_fd(exr_const_context_t ctxt, void *user, const void *buf, uint64_t size, uint64_t offset,
                           exr_stream_error_func_ptr_t error_cb)
{
    int fd = *(const int *)user;
    uint64_t done = 0;
    while (done < size) {
        ssize_t n = pwrite(fd, (const char *)buf + done, size - done, (off_t)(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error_cb(ctxt, EXR_ERR_WRITE_IO, "%s", strerror(n < 0 ? errno : EIO));
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)size;
}

static exr_compression_t exr_compression_of(lucent_exr_compression c)
{
    switch (c) {
    case LUCENT_EXR_COMPRESSION_NONE: return EXR_COMPRESSION_NONE;
    case LUCENT_EXR_COMPRESSION_RLE: return EXR_COMPRESSION_RLE;
    case LUCENT_EXR_COMPRESSION_ZIPS: return EXR_COMPRESSION_ZIPS;
    case LUCENT_EXR_COMPRESSION_PIZ: return EXR_COMPRESSION_PIZ;
    default: return EXR_COMPRESSION_ZIP;
    }
}

static const char *const k_names[4][4] = {{"Y"}, {0}, {"R", "G", "B"}, {"R", "G", "B", "A"}};

static exr_result_t define_part(exr_context_t ctx, const lucent_image *img, const lucent_image_write_desc *d)
{
    int part;
    exr_result_t rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, img->width, img->height,
                                                 exr_compression_of(d->exr_compression));
    exr_pixel_type_t pt = d->exr_pixel == LUCENT_EXR_PIXEL_HALF ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    for (int c = 0; c < img->channels && rv == EXR_ERR_SUCCESS; c++)
        rv = exr_add_channel(ctx, part, k_names[img->channels - 1][c], pt,
                             c == 3 ? EXR_PERCEPTUALLY_LINEAR : EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    return rv;
}

static int channel_index(const lucent_image *img, const char *name)
{
    for (int c = 0; c < img->channels; c++)
        if (strcmp(k_names[img->channels - 1][c], name) == 0) return c;
    return 0;
}

static exr_result_t encode_chunk(exr_context_t ctx, exr_encode_pipeline_t *enc, bool first, int y,
                                 const lucent_image *img)
{
    exr_chunk_info_t ci;
    exr_result_t rv = exr_write_scanline_chunk_info(ctx, 0, y, &ci);
    if (rv == EXR_ERR_SUCCESS)
        rv = first ? exr_encoding_initialize(ctx, 0, &ci, enc) : exr_encoding_update(ctx, 0, &ci, enc);
    if (rv != EXR_ERR_SUCCESS) return rv;
    for (int i = 0; i < enc->channel_count; i++) {
        exr_coding_channel_info_t *ch = &enc->channels[i];
        ch->encode_from_ptr = (const uint8_t *)(lucent_image_pixel(img, 0, y) + channel_index(img, ch->channel_name));
        ch->user_pixel_stride = img->channels * (int32_t)sizeof(float);
        ch->user_line_stride = img->width * img->channels * (int32_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = (int16_t)sizeof(float);
    }
    if (first) rv = exr_encoding_choose_default_routines(ctx, 0, enc);
    return rv == EXR_ERR_SUCCESS ? exr_encoding_run(ctx, 0, enc) : rv;
}

static exr_result_t write_parts(exr_context_t ctx, const lucent_image *img, const lucent_image_write_desc *d)
{
    exr_result_t rv = define_part(ctx, img, d);
    int32_t lines = 1;
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool first = true;
    for (int y = 0; rv == EXR_ERR_SUCCESS && y < img->height; y += lines, first = false)
        rv = encode_chunk(ctx, &enc, first, y, img);
    if (!first) exr_encoding_destroy(ctx, &enc);
    return rv;
}

lucent_status lucent_image_write_exr(const char *path, const lucent_image *img, const lucent_image_write_desc *desc)
{
    lucent_image_write_desc d = image_resolve_desc(desc);
    lucent_status s = image_check_size(path, img->width, img->height, img->channels, LUCENT_ERR_INVALID_ARGUMENT);
    if (s != LUCENT_OK) return s;
    lucent_atomic_file *af;
    FILE *fp;
    s = lucent_atomic_open(path, &af, &fp);
    if (s != LUCENT_OK) return s;
    int fd = fileno(fp);
    exr_context_initializer_t init = exr_init();
    init.user_data = &fd;
    init.write_fn = write_to_fd;
    t_exr_msg[0] = '\0';
    exr_context_t ctx = NULL;
    exr_result_t rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = write_parts(ctx, img, &d);
    exr_result_t fin = ctx ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    if (rv == EXR_ERR_SUCCESS) rv = fin;
    if (rv != EXR_ERR_SUCCESS) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: cannot write OpenEXR (%s)", path, exr_message(rv));
    }
    return lucent_atomic_commit(af);
}

const char *lucent_image_openexr_version(void)
{
    static char text[48];
    int major = 0, minor = 0, patch = 0;
    const char *extra = NULL;
    exr_get_library_version(&major, &minor, &patch, &extra);
    snprintf(text, sizeof text, "%d.%d.%d%s", major, minor, patch, extra ? extra : "");
    return text;
}
